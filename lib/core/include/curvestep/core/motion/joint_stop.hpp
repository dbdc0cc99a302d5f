// SPDX-License-Identifier: MIT
// JointStop: how the motion enters a segment. Normally the planner passes the joint from the
// previous segment at its junction speed; a job event that needs the machine at rest there (a
// G4 dwell, an M0 pause, an M6 tool change, a plotter's layer change) makes the joint an exact
// stop, and a dwell adds a rest of whole control ticks at the joint (MotionController::try_push).
// During a rest the setpoints stay at the joint (speed 0) and the controller's clock is
// frozen, so the motion after it is exactly the motion without it, shifted by rest_ticks ticks.
#pragma once

#include <cstdint>

namespace curvestep {

/// The entry into a queued segment: an exact stop at its joint, and a rest there.
struct JointStop {
  bool stop = false;             ///< come to rest at the joint into the segment (exit speed 0)
  std::uint32_t rest_ticks = 0;  ///< then stay there this many control ticks (> 0 implies stop)

  /// True if the joint is passed at rest.
  [[nodiscard]] constexpr bool at_rest() const noexcept { return stop || rest_ticks > 0; }
  friend constexpr bool operator==(const JointStop&, const JointStop&) = default;
};

}  // namespace curvestep
