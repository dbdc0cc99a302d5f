// SPDX-License-Identifier: MIT
// EdgeClock: when, in CLOCK_MONOTONIC, a step/dir edge of step-timer time t is due.
//
// The firmware's step generator counts step-timer time only while the machine moves (it starts at
// 0 with each machine configuration and stands still through uploads, holds and starved queues),
// so a fixed epoch set when the device starts puts every edge after the first pause in the past:
// an output waiting for epoch + t would write them all at once, losing pulse widths and the
// spacing of steps within a tick. EdgeClock re-bases instead: an edge more than `late_limit`
// behind its deadline moves the epoch so that this edge is due now; the edges after it keep their
// spacing again. Times are integers (ns), so an epoch is exact however long the device runs.
#pragma once

#include <cstddef>
#include <cstdint>

namespace curvestep::boards::host {

/// Step-timer time to CLOCK_MONOTONIC deadlines, re-based when an edge comes too late.
class EdgeClock {
 public:
  /// How late an edge may be before the clock re-bases: 0.5 ms, longer than the wake-up latency
  /// of a loop that keeps up (re-basing on that would make every edge later than the last and
  /// slow the machine down), shorter than one stalled tick at 1 kHz (1 ms), an upload or a hold.
  /// A caller that knows the control period P passes min(0.5 ms, P / 2).
  static constexpr std::int64_t default_late_limit_ns = 500'000;

  /// Step-timer ticks at `timer_hz` (> 0).
  explicit EdgeClock(std::uint32_t timer_hz, std::int64_t late_limit_ns = default_late_limit_ns) noexcept
      : timer_hz_(timer_hz), late_limit_ns_(late_limit_ns) {}

  /// Step-timer time 0 is `epoch_ns` (CLOCK_MONOTONIC, ns).
  void set_epoch(std::int64_t epoch_ns) noexcept { epoch_ns_ = epoch_ns; }

  /// When the edge at `time_ticks` is due, given that it is `now_ns`: epoch + time, or now if
  /// that lies more than the late limit in the past (then the epoch moves there: a re-base).
  [[nodiscard]] std::int64_t deadline_ns(std::uint64_t time_ticks, std::int64_t now_ns) noexcept {
    const std::int64_t offset = offset_ns(time_ticks);
    if (now_ns - (epoch_ns_ + offset) > late_limit_ns_) {
      epoch_ns_ = now_ns - offset;
      ++rebases_;
    }
    return epoch_ns_ + offset;
  }

  /// The epoch in use (ns).
  [[nodiscard]] std::int64_t epoch_ns() const noexcept { return epoch_ns_; }
  /// Times the epoch moved because an edge came late (after a pause, or a loop that fell behind).
  [[nodiscard]] std::size_t rebases() const noexcept { return rebases_; }

 private:
  /// time_ticks / timer_hz in ns, exact to the nanosecond and free of overflow for any run.
  [[nodiscard]] std::int64_t offset_ns(std::uint64_t time_ticks) const noexcept {
    const std::uint64_t seconds = time_ticks / timer_hz_;
    const std::uint64_t rest = time_ticks % timer_hz_;
    return static_cast<std::int64_t>(seconds * 1'000'000'000ull + rest * 1'000'000'000ull / timer_hz_);
  }

  std::uint32_t timer_hz_;
  std::int64_t late_limit_ns_;
  std::int64_t epoch_ns_ = 0;
  std::size_t rebases_ = 0;
};

}  // namespace curvestep::boards::host
