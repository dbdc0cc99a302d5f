// SPDX-License-Identifier: MIT
// CountingOutput: the StepOutput `curvestep gpio` hands to the host board. It counts steps per axis
// (signed by the direction level) and passes every edge on to an inner output (GpiodStepOutput,
// or none in a dry run), keeping the inner output's edge clock on time.
//
// Why the clock needs keeping: boards::host::run_device sets the output's epoch (step-timer time
// 0 in CLOCK_MONOTONIC) once, when the device starts, but the firmware's step generator counts
// only the control ticks spent moving since the last machine configuration. After the upload, or
// any pause, every edge would lie in the past and be written at once, losing pulse widths and the
// spacing of steps within a tick. So an edge more than one control period late re-bases the epoch:
// that edge's time becomes now, and the edges after it are again written at their times.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <ctime>

#include <curvestep/core/motion/machine_limits.hpp>

namespace curvestep::host {

template <class Inner>
class CountingOutput {
 public:
  /// Edges go to `inner` (may be null); step-timer ticks at `timer_hz`, control ticks at `rate_hz`.
  CountingOutput(Inner* inner, std::uint32_t timer_hz, double rate_hz) noexcept
      : inner_(inner),
        ns_per_timer_tick_(1e9 / static_cast<double>(timer_hz)),
        late_limit_ns_(static_cast<std::int64_t>(1e9 / rate_hz)) {}

  void set_direction(std::uint64_t time_ticks, std::uint8_t axis, bool positive) noexcept {
    if (axis < motion_axes) positive_[axis] = positive;
    keep_on_time(time_ticks);
    if (inner_ != nullptr) inner_->set_direction(time_ticks, axis, positive);
  }
  void set_step(std::uint64_t time_ticks, std::uint8_t axis, bool high) noexcept {
    if (high && axis < motion_axes) {
      ++steps_[axis];
      net_[axis] += positive_[axis] ? 1 : -1;
    }
    keep_on_time(time_ticks);
    if (inner_ != nullptr) inner_->set_step(time_ticks, axis, high);
  }
  void fault_stop() noexcept {
    if constexpr (requires(Inner& i) { i.fault_stop(); }) {
      if (inner_ != nullptr) inner_->fault_stop();
    }
  }
  /// Called by run_device at start: step-timer time 0 is `epoch`; fast: no waiting (tests).
  void set_epoch(const timespec& epoch, bool fast) noexcept {
    epoch_ns_ = nanoseconds(epoch);
    fast_ = fast;
    if constexpr (requires(Inner& i) { i.set_epoch(epoch, fast); }) {
      if (inner_ != nullptr) inner_->set_epoch(epoch, fast);
    }
  }

  /// Rising step edges per axis.
  [[nodiscard]] const std::array<std::uint64_t, motion_axes>& steps() const noexcept { return steps_; }
  /// Steps per axis, positive minus negative: the distance moved in steps.
  [[nodiscard]] const std::array<std::int64_t, motion_axes>& net_steps() const noexcept { return net_; }
  /// Times the epoch was re-based (1 at the start of a job; more if the loop fell behind).
  [[nodiscard]] std::size_t rebases() const noexcept { return rebases_; }

 private:
  static std::int64_t nanoseconds(const timespec& t) noexcept { return std::int64_t{t.tv_sec} * 1000000000 + t.tv_nsec; }

  void keep_on_time(std::uint64_t time_ticks) noexcept {
    if constexpr (requires(Inner& i, const timespec& e) { i.set_epoch(e, false); }) {
      if (inner_ == nullptr || fast_) return;
      timespec now{};
      clock_gettime(CLOCK_MONOTONIC, &now);
      const auto offset_ns = static_cast<std::int64_t>(static_cast<double>(time_ticks) * ns_per_timer_tick_);
      if (nanoseconds(now) - (epoch_ns_ + offset_ns) <= late_limit_ns_) return;
      epoch_ns_ = nanoseconds(now) - offset_ns;
      timespec epoch{};
      epoch.tv_sec = static_cast<time_t>(epoch_ns_ / 1000000000);
      epoch.tv_nsec = static_cast<long>(epoch_ns_ % 1000000000);
      if (epoch.tv_nsec < 0) {
        epoch.tv_nsec += 1000000000;
        --epoch.tv_sec;
      }
      inner_->set_epoch(epoch, false);
      ++rebases_;
    }
  }

  Inner* inner_;
  double ns_per_timer_tick_;
  std::int64_t late_limit_ns_;
  std::int64_t epoch_ns_ = 0;
  bool fast_ = false;
  std::size_t rebases_ = 0;
  std::array<bool, motion_axes> positive_{true, true, true};
  std::array<std::uint64_t, motion_axes> steps_{};
  std::array<std::int64_t, motion_axes> net_{};
};

}  // namespace curvestep::host
