// SPDX-License-Identifier: MIT
// The firmware main loop shared by the STM32 boards: App<Board>::poll() in the main loop and
// App::on_tick() paced by SysTick at the configured control rate (never concurrently: see app.hpp).
#pragma once

#include <cstdint>

#include <curvestep/boards/stm32/mmio.hpp>

namespace curvestep::stm32 {

namespace detail {
inline volatile std::uint32_t ticks_due = 0;
inline void count_tick(void*) { ticks_due = ticks_due + 1; }
}  // namespace detail

/// Runs `app` on `board` for ever. Each SysTick interrupt makes one on_tick() due; late ticks are
/// all run (the setpoint stream stays complete and identical, only later). Until a
/// MachineConfiguration arrives SysTick runs at 1 kHz for the millisecond clock.
template <class Board, class App>
[[noreturn]] void run_firmware(Board& board, App& app) noexcept {
  std::uint32_t rate = 0;
  std::uint32_t ticks_done = 0;
  board.start_tick(1000, detail::count_tick, nullptr);
  board.start_steps(1000);
  for (;;) {
    app.poll();
    if (app.control_rate_hz() != rate && app.control_rate_hz() != 0) {
      rate = app.control_rate_hz();
      board.start_tick(rate, detail::count_tick, nullptr);
      board.start_steps(rate);
      ticks_done = detail::ticks_due;
    }
    if (rate != 0) {
      while (ticks_done != detail::ticks_due) {
        app.on_tick();
        ++ticks_done;
        app.poll();
      }
    } else {
      ticks_done = detail::ticks_due;
    }
    wait_for_interrupt();
  }
}

}  // namespace curvestep::stm32
