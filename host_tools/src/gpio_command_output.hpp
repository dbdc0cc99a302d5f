// SPDX-License-Identifier: MIT
// CountingOutput: the StepOutput `curvestep gpio` hands to the host board. It counts steps per axis
// (signed by the direction level) and passes every edge on to an inner output (GpiodStepOutput,
// or none in a dry run), and the inner output's limit switches back. Keeping the edges on time is the inner output's job (its EdgeClock).
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
  /// Edges go to `inner` (may be null: a dry run).
  explicit CountingOutput(Inner* inner) noexcept : inner_(inner) {}

  void set_direction(std::uint64_t time_ticks, std::uint8_t axis, bool positive) noexcept {
    if (axis < motion_axes) positive_[axis] = positive;
    if (inner_ != nullptr) inner_->set_direction(time_ticks, axis, positive);
  }
  void set_step(std::uint64_t time_ticks, std::uint8_t axis, bool high) noexcept {
    if (high && axis < motion_axes) {
      ++steps_[axis];
      net_[axis] += positive_[axis] ? 1 : -1;
    }
    if (inner_ != nullptr) inner_->set_step(time_ticks, axis, high);
  }
  void fault_stop() noexcept {
    if constexpr (requires(Inner& i) { i.fault_stop(); }) {
      if (inner_ != nullptr) inner_->fault_stop();
    }
  }
  /// The inner output's limit switches (none in a dry run).
  [[nodiscard]] std::uint8_t limit_switches() noexcept
    requires requires(Inner& i) { i.limit_switches(); }
  {
    return inner_ != nullptr ? inner_->limit_switches() : std::uint8_t{0};
  }
  /// Called by run_device at start: step-timer time 0 is `epoch`; fast: no waiting (tests).
  void set_epoch(const timespec& epoch, bool fast) noexcept {
    if constexpr (requires(Inner& i) { i.set_epoch(epoch, fast); }) {
      if (inner_ != nullptr) inner_->set_epoch(epoch, fast);
    }
  }

  /// Rising step edges per axis.
  [[nodiscard]] const std::array<std::uint64_t, motion_axes>& steps() const noexcept { return steps_; }
  /// Steps per axis, positive minus negative: the distance moved in steps.
  [[nodiscard]] const std::array<std::int64_t, motion_axes>& net_steps() const noexcept { return net_; }

 private:
  Inner* inner_;
  std::array<bool, motion_axes> positive_{true, true, true};
  std::array<std::uint64_t, motion_axes> steps_{};
  std::array<std::int64_t, motion_axes> net_{};
};

}  // namespace curvestep::host
