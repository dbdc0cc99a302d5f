// SPDX-License-Identifier: MIT
// TickClock: control ticks on absolute CLOCK_MONOTONIC deadlines (clock_nanosleep with
// TIMER_ABSTIME), so the rate does not drift with the time the loop takes.
#pragma once

#include <cstdint>
#include <ctime>

namespace curvestep::boards::host {

/// Absolute-deadline tick pacing.
class TickClock {
 public:
  /// Starts a train of ticks at `rate_hz`, the first one due now.
  void start(std::uint32_t rate_hz) noexcept;
  /// True while a train runs.
  [[nodiscard]] bool running() const noexcept { return rate_hz_ != 0; }
  /// Ends the train.
  void stop() noexcept { rate_hz_ = 0; }
  /// Nanoseconds until the next tick is due (<= 0: due now).
  [[nodiscard]] std::int64_t remaining_ns() const noexcept;
  /// Sleeps until the next deadline (clock_nanosleep, TIMER_ABSTIME).
  void sleep_until_due() const noexcept;
  /// The tick was run: moves the deadline one period on. If the loop fell more than 100 periods
  /// behind, the deadline restarts from now and the overrun is counted.
  void advance() noexcept;
  /// Times the loop fell far behind real time.
  [[nodiscard]] std::uint64_t overruns() const noexcept { return overruns_; }
  /// The current monotonic time.
  [[nodiscard]] static timespec now() noexcept;

 private:
  timespec deadline_{};
  std::uint32_t rate_hz_ = 0;
  std::uint64_t ticks_ = 0;
  std::uint64_t overruns_ = 0;
  timespec origin_{};
};

}  // namespace curvestep::boards::host
