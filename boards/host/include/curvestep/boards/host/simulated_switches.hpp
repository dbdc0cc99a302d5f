// SPDX-License-Identifier: MIT
// SimulatedSwitches<Output>: a test board's limit switches at given positions
// (`curvestep device --machine M.json --switch x-:POS`).
//
// It wraps any StepOutput, passes every edge on, and counts the steps the drivers would take (a
// rising step edge moves one step in the direction last set), so the switches see the machine
// where its step pulses put it, not where the planner wanted it. The machine starts where the App
// first declared it (position_declared: the first setpoint after the device started); later
// declarations (a new session) do not move a real machine and are ignored here too.
//
// A min switch at POS mm is closed while the step position is at or below POS × steps_per_mm, a
// max switch while it is at or above. limit_switches() returns them as the mask of
// firmware/limit_switches.hpp (bit 2 × axis min, 2 × axis + 1 max). Nothing here allocates; the
// tick path is a few additions and comparisons.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

#include <curvestep/core/motion/step_output.hpp>

namespace curvestep::boards::host {

/// One simulated switch: its axis (0 x, 1 y, 2 z), side and position in mm.
struct SimulatedSwitch {
  std::uint8_t axis = 0;     ///< 0 x, 1 y, 2 z
  bool max_side = false;     ///< false: the min switch (closed at or below), true: the max switch
  double position_mm = 0;    ///< where it closes
};

/// Where the switches sit, in steps, per switch bit (2 × axis + side); empty: no switch there.
using SwitchThresholds = std::array<std::optional<double>, 6>;

/// The thresholds in steps of `switches` on a machine with `steps_per_mm`.
[[nodiscard]] inline SwitchThresholds switch_thresholds(const SimulatedSwitch* switches, std::size_t count,
                                                        const std::array<double, 3>& steps_per_mm) noexcept {
  SwitchThresholds thresholds{};
  for (std::size_t k = 0; k < count; ++k) {
    const SimulatedSwitch& s = switches[k];
    if (s.axis >= 3) continue;
    thresholds[std::size_t{2} * s.axis + (s.max_side ? 1u : 0u)] = s.position_mm * steps_per_mm[s.axis];
  }
  return thresholds;
}

/// A StepOutput that forwards to `Output` and simulates limit switches at fixed step positions.
template <StepOutput Output>
class SimulatedSwitches {
 public:
  /// Switches at `thresholds` (steps) in front of `output` (not owned).
  SimulatedSwitches(Output& output, const SwitchThresholds& thresholds) noexcept : output_(output), thresholds_(thresholds) {}

  /// Latches the direction and forwards the edge.
  void set_direction(std::uint64_t time_ticks, std::uint8_t axis, bool positive) noexcept {
    if (axis < 3) direction_[axis] = positive ? 1 : -1;
    output_.set_direction(time_ticks, axis, positive);
  }
  /// Counts a rising edge in the latched direction and forwards the edge.
  void set_step(std::uint64_t time_ticks, std::uint8_t axis, bool high) noexcept {
    if (high && axis < 3) steps_[axis] += direction_[axis];
    output_.set_step(time_ticks, axis, high);
  }
  /// Forwards the emergency stop.
  void fault_stop() noexcept {
    if constexpr (requires { output_.fault_stop(); }) output_.fault_stop();
  }
  /// Forwards the epoch to an output that keeps time (GPIO).
  template <class Time>
  void set_epoch(const Time& epoch, bool fast) noexcept
    requires requires(Output& o) { o.set_epoch(epoch, fast); }
  {
    output_.set_epoch(epoch, fast);
  }
  /// The first declaration places the machine; later ones are the host's, not a movement.
  void position_declared(const std::array<std::int32_t, 3>& steps) noexcept {
    if (placed_) return;
    placed_ = true;
    for (std::size_t axis = 0; axis < 3; ++axis) steps_[axis] += steps[axis];
  }
  /// The switches closed at the current step position.
  [[nodiscard]] std::uint8_t limit_switches() const noexcept {
    std::uint8_t closed = 0;
    for (std::size_t axis = 0; axis < 3; ++axis) {
      const auto position = static_cast<double>(steps_[axis]);
      const auto& min = thresholds_[2 * axis];
      const auto& max = thresholds_[2 * axis + 1];
      if (min && position <= *min) closed = static_cast<std::uint8_t>(closed | (1u << (2 * axis)));
      if (max && position >= *max) closed = static_cast<std::uint8_t>(closed | (1u << (2 * axis + 1)));
    }
    return closed;
  }
  /// The machine's position in steps as the switches see it.
  [[nodiscard]] std::int64_t steps(std::size_t axis) const noexcept { return steps_[axis]; }

 private:
  Output& output_;
  SwitchThresholds thresholds_;
  std::array<std::int64_t, 3> steps_{};
  std::array<std::int8_t, 3> direction_{};
  bool placed_ = false;
};

}  // namespace curvestep::boards::host
