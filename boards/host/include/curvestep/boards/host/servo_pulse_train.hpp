// SPDX-License-Identifier: MIT
// ServoPulseTrain: a hobby servo's 50 Hz signal in software on one output line (a servo pen on the
// host board). Every 20 ms period starts at an absolute deadline, t0 + k x 20 ms, so sleeping late
// never accumulates: the line goes high at the period's start and low `pulse_us` later, both by
// sleeping to absolute CLOCK_MONOTONIC deadlines (clock_nanosleep, TIMER_ABSTIME); the pulse ends
// its width after the rising edge was written, so a late wake-up shifts a pulse but never
// shortens it. The width is read once per period: a new width starts with the next period, a
// pulse is never cut short. Width 0: no pulses (the line stays low). A period whose start passed
// more than half a period ago (the thread was not scheduled) is skipped, not crammed in.
//
// Lines: set(std::size_t line, bool high) (GpiodLineSet, or a recording stand-in in tests);
// Clock: std::int64_t now_ns(), void sleep_until_ns(std::int64_t) (MonotonicClock, or a fake).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>

#include <curvestep/boards/host/monotonic_time.hpp>

namespace curvestep::boards::host {

/// CLOCK_MONOTONIC and absolute sleeps (the real clock of the pulse train).
struct MonotonicClock {
  [[nodiscard]] std::int64_t now_ns() const noexcept { return to_nanoseconds(monotonic_now()); }
  void sleep_until_ns(std::int64_t deadline_ns) const noexcept { sleep_until(to_timespec(deadline_ns)); }
};

/// The pulse train of one servo line.
template <class Lines, class Clock = MonotonicClock>
class ServoPulseTrain {
 public:
  static constexpr std::int64_t period_ns = 20'000'000;  ///< 50 Hz
  static constexpr std::uint32_t max_pulse_us = 2500;    ///< widest pulse sent (servo range)
  static constexpr std::int64_t late_limit_ns = period_ns / 2;  ///< a period begun later than this is skipped

  /// Pulses on `line` of `lines`, timed by `clock`.
  ServoPulseTrain(Lines& lines, std::size_t line, Clock clock = Clock{}) noexcept : lines_(lines), line_(line), clock_(clock) {}

  /// The width of the pulses from the next period on, µs (0: none; above max_pulse_us: max_pulse_us).
  void set_pulse_us(std::uint32_t pulse_us) noexcept {
    pulse_us_.store(pulse_us > max_pulse_us ? max_pulse_us : pulse_us, std::memory_order_relaxed);
  }
  /// The width in force, µs.
  [[nodiscard]] std::uint32_t pulse_us() const noexcept { return pulse_us_.load(std::memory_order_relaxed); }

  /// Sends periods until `stop` is set (checked once per period); the line ends low.
  void run(const std::atomic<bool>& stop) noexcept {
    std::int64_t start = clock_.now_ns();
    while (!stop.load(std::memory_order_relaxed)) {
      const std::int64_t now = clock_.now_ns();
      if (now - start >= late_limit_ns) {  // woke too late for this period: wait for the next start ahead
        start += ((now - start) / period_ns + 1) * period_ns;
        clock_.sleep_until_ns(start);
        continue;
      }
      const std::uint32_t width = pulse_us();
      if (width != 0) {
        lines_.set(line_, true);
        clock_.sleep_until_ns(now + std::int64_t{width} * 1000);  // the width from the rising edge
        lines_.set(line_, false);
      }
      start += period_ns;
      clock_.sleep_until_ns(start);
    }
    lines_.set(line_, false);
  }

 private:
  Lines& lines_;
  std::size_t line_;
  Clock clock_;
  std::atomic<std::uint32_t> pulse_us_{0};
};

}  // namespace curvestep::boards::host
