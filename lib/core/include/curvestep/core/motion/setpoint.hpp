// SPDX-License-Identifier: MIT
// Setpoint: one tick of the interpolator's output (time, position on every axis, path speed).
#pragma once

#include <array>
#include <cstdint>

#include <curvestep/core/motion/machine_limits.hpp>

namespace curvestep {

/// The commanded state at one control tick.
template <class S>
struct Setpoint {
  std::uint64_t tick = 0;                    ///< tick number since the start of the job (time = tick / rate)
  std::array<S, motion_axes> position{};     ///< x, y, z in mm (the position scalar: Q16.16 or float/double)
  double speed_mm_per_s = 0;                 ///< planned path speed at this tick
  std::uint32_t segment = 0;                 ///< index of the job segment being followed

  friend constexpr bool operator==(const Setpoint&, const Setpoint&) = default;
};

}  // namespace curvestep
