// SPDX-License-Identifier: MIT
// The firmware main loop shared by the STM32 boards: App<Board>::poll() in the main loop and
// App::on_tick() paced by SysTick at the configured control rate (never concurrently: see app.hpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include <curvestep/boards/stm32/mmio.hpp>
#include <curvestep/boards/stm32/tick_profile.hpp>
#include <curvestep/firmware/app_settings.hpp>

namespace curvestep::stm32 {

/// The App's settings on `board`: in an emulator, whose clock is not real time, tick overruns are
/// counted but a late tick is no fault (firmware::TickWatch).
template <class Board>
[[nodiscard]] firmware::AppSettings firmware_settings(const Board& board) noexcept {
  firmware::AppSettings settings;
  if (board.clocks().emulated) settings.tick_deadline_periods = 0;
  return settings;
}

namespace detail {
inline volatile std::uint32_t ticks_due = 0;
inline void count_tick(void*) { ticks_due = ticks_due + 1; }
}  // namespace detail

#if CURVESTEP_TICK_PROFILE
/// The benchmark builds' profile (read from the emulator's memory by the benchmark).
extern "C" {
inline TickProfile curvestep_tick_profile{};
}
#endif

/// app.poll(); profiled builds record the cycles of a poll that accepted segments or pieces.
template <class Board, class App>
void poll_app(Board& board, App& app) noexcept {
#if CURVESTEP_TICK_PROFILE
  const std::size_t queued = app.controller().queued();
  const std::uint32_t start = board.cycle_count();
  app.poll();
  const std::uint32_t cycles = board.cycle_count() - start;
  if (app.controller().queued() > queued) {
    curvestep_tick_profile.accept(cycles, static_cast<std::uint32_t>(app.controller().queued() - queued));
  }
#else
  static_cast<void>(board);
  app.poll();
#endif
}

/// app.on_tick(); profiled builds record its cycles while the App moves.
template <class Board, class App>
void tick_app(Board& board, App& app) noexcept {
#if CURVESTEP_TICK_PROFILE
  const bool moving = app.moving();
  const std::size_t queued = app.controller().queued();
  const std::uint32_t start = board.cycle_count();
  app.on_tick();
  const std::uint32_t cycles = board.cycle_count() - start;
  if (moving) curvestep_tick_profile.tick(cycles, app.controller().queued() < queued);
  curvestep_tick_profile.overruns = app.tick_watch().overruns();
  curvestep_tick_profile.cycles_per_second = board.cycles_per_second();
#else
  static_cast<void>(board);
  app.on_tick();
#endif
}

/// Runs `app` on `board` for ever. Each SysTick interrupt makes one on_tick() due; late ticks are
/// all run (the setpoint stream stays complete and identical, only later). Until a
/// MachineConfiguration arrives SysTick runs at 1 kHz for the millisecond clock. With
/// CURVESTEP_TICK_PROFILE (the real-time benchmark's builds) every tick and poll is timed into
/// curvestep_tick_profile (tick_profile.hpp).
template <class Board, class App>
[[noreturn]] void run_firmware(Board& board, App& app) noexcept {
  std::uint32_t rate = 0;
  std::uint32_t ticks_done = 0;
  board.start_tick(1000, detail::count_tick, nullptr);
  board.start_steps(1000);
  for (;;) {
    poll_app(board, app);
    if (app.control_rate_hz() != rate && app.control_rate_hz() != 0) {
      rate = app.control_rate_hz();
      board.start_tick(rate, detail::count_tick, nullptr);
      board.start_steps(rate);
      ticks_done = detail::ticks_due;
    }
    if (rate != 0) {
      while (ticks_done != detail::ticks_due) {
        tick_app(board, app);
        ++ticks_done;
        poll_app(board, app);
      }
    } else {
      ticks_done = detail::ticks_due;
    }
    wait_for_interrupt();
  }
}

}  // namespace curvestep::stm32
