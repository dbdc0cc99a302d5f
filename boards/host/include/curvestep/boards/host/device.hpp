// SPDX-License-Identifier: MIT
// run_device: the host board's main loop around firmware::App (what `curvestep device` runs).
//
// Real time (default): control ticks on absolute CLOCK_MONOTONIC deadlines at the configured
// rate; between ticks the loop waits for serial input (ppoll) and then sleeps to the exact
// deadline (clock_nanosleep, TIMER_ABSTIME). poll() and on_tick() run in this one thread, as
// App requires.
//
// Fast mode (tests; DeviceOptions::fast, `curvestep device --fast`): ticks run as fast as the
// link allows instead of on the clock. The link is the flow control:
//   * no tick while the setpoint stream is backed up (App::ready_to_tick: the host has not
//     acknowledged enough batches) or the serial line is (the host is not reading); the stream's
//     stall timeout is off, so a slow host only slows the device down, it never loses a setpoint;
//   * otherwise fast_tick_allowed (fast_mode.hpp): no tick while the queue is shallower than the
//     planner's look-ahead window needs, or (without a planner, `curvestep device --executor`)
//     before the piece the next setpoint needs has arrived; held or starved, it waits for the
//     host instead of spinning. A fast device thus never plans a segment with fewer segments
//     ahead than a real-time device fed in time, nor starves, and its setpoints equal
//     `curvestep sim`'s.
// Real time: a tick whose setpoint cannot be streamed does not advance (App::on_tick), and a
// stream backed up for longer than the link timeout is a Fault (LinkTimeout). Every tick is timed
// on the board's microsecond clock (App::tick_watch): overruns are counted and logged with the
// state changes, never a fault here.
// Wall-clock time still drives the link (timeouts, heartbeats), so link loss is detected alike.
//
// The tick path (App::on_tick and the Output's set_step/set_direction) does not allocate, throw
// or block, except the GPIO output's deliberate wait for each edge's time.
#pragma once

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <poll.h>
#include <span>

#include <curvestep/boards/host/board.hpp>
#include <curvestep/boards/host/fast_mode.hpp>
#include <curvestep/boards/host/tick_clock.hpp>
#include <curvestep/core/error_text.hpp>
#include <curvestep/firmware/app.hpp>
#include <curvestep/protocol/frame_decoder.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::boards::host {

/// How the device runs.
struct DeviceOptions {
  bool fast = false;               ///< ticks as fast as the link allows (tests), not real time
  firmware::AppSettings app{};     ///< link timeout, heartbeat, setpoint streaming
  MachineOutputHooks* machine_outputs = nullptr;  ///< spindle, coolant, outputs, pen lines (null: events only logged)
};

/// Serves the firmware on the non-blocking descriptor `fd` until `stop` is set. State changes
/// are logged to `log` (one line each, may be null). Returns 0.
/// Lookahead 0 runs the App without a planner (it replays host-planned pieces).
template <StepOutput Output, std::size_t Lookahead = 16>
int run_device(int fd, Output& output, const DeviceOptions& options, const std::atomic<bool>& stop, std::FILE* log) {
  using Board = HostBoard<Output>;
  using Application = firmware::App<Board, Q16_16, 32, Lookahead>;
  Board board(fd, output, options.machine_outputs);
  firmware::AppSettings settings = options.app;
  // Ticks are timed against the clock in real time only; a late tick is counted, not a fault: the
  // tick clock and the edge clock re-base after a pause (tick_clock.hpp, edge_clock.hpp), which
  // this board tolerates (a device stopped for seconds finishes its job).
  settings.watch_ticks = !options.fast;
  settings.tick_deadline_periods = 0;
  if (options.fast) settings.stall_timeout_ms = 0;  // a slow host slows a fast device down, nothing else
  else if (settings.stall_timeout_ms == 0 || settings.stall_timeout_ms > settings.link_timeout_ms) {
    settings.stall_timeout_ms = settings.link_timeout_ms;  // real time: a stream stalled as long as a lost link is a fault
  }
  auto app = std::make_unique<Application>(board, settings);  // large: queue, plans, buffers
  if constexpr (requires { output.set_epoch(TickClock::now(), options.fast); }) output.set_epoch(TickClock::now(), options.fast);
  TickClock clock;
  protocol::MachineState reported = app->state();
  std::uint8_t reported_error = 0;
  std::uint32_t last_index = 0;
  const auto wait_for = [&](short events, int timeout_ms) {
    pollfd p{fd, events, 0};
    ::poll(&p, 1, timeout_ms);
  };
  while (!stop.load(std::memory_order_relaxed)) {
    app->poll();
    if (log != nullptr && (app->state() != reported || app->last_error() != reported_error)) {
      reported = app->state();
      reported_error = app->last_error();
      std::fprintf(log, "curvestep device: %s at tick %u", protocol::machine_state_name(reported), static_cast<unsigned>(last_index));
      if (reported_error != 0) {
        const auto code = static_cast<Error>(reported_error);
        std::fprintf(log, " (last error: %s, %s)", describe(code).data(), error_name(code).data());
      }
      if (app->tick_watch().overruns() != 0) {
        std::fprintf(log, " (tick overruns: %u, worst tick %u us)", static_cast<unsigned>(app->tick_watch().overruns()),
                     static_cast<unsigned>(app->tick_watch().worst_cycles()));
      }
      std::fprintf(log, "\n");
      std::fflush(log);
    }
    const std::uint32_t rate = app->control_rate_hz();
    if (!app->moving() || rate == 0) {
      clock.stop();
      wait_for(POLLIN, 2);
      continue;
    }
    if (options.fast) {
      if (board.backed_up()) {
        wait_for(POLLOUT, 2);
        board.clear_backed_up();
        continue;
      }
      if (!fast_tick_allowed(*app)) {
        wait_for(POLLIN, 2);  // for the host: acknowledgements, pieces, segments, a resume
        continue;
      }
      app->on_tick();
    } else {
      if (!clock.running()) clock.start(rate);
      const std::int64_t remaining = clock.remaining_ns();
      if (remaining > 1500000) {
        wait_for(POLLIN, static_cast<int>((remaining - 1000000) / 1000000));
        continue;  // serve what arrived, then come back for the tick
      }
      clock.sleep_until_due();
      app->on_tick();
      clock.advance();
    }
    last_index = app->controller().tick() > 0 ? static_cast<std::uint32_t>(app->controller().tick() - 1) : 0;
  }
  return 0;
}

}  // namespace curvestep::boards::host
