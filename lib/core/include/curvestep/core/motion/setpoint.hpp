// SPDX-License-Identifier: MIT
// Setpoint: one tick of the interpolator's output (time, position on every axis, path speed).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/core/result.hpp>
#include <curvestep/core/scalar.hpp>

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

/// The setpoint of `tick` at the unrounded point `p` (x, y, z in mm), each coordinate rounded to S
/// by from_double (the one rounding of every interpolator's output); its error, with `segment`
/// as the index, if a coordinate does not fit S.
template <class S, class Point>
[[nodiscard]] constexpr Result<Setpoint<S>> make_setpoint(const Point& p, std::uint64_t tick, double speed,
                                                          std::uint32_t segment) noexcept {
  Setpoint<S> sp;
  sp.tick = tick;
  sp.speed_mm_per_s = speed;
  sp.segment = segment;
  for (std::size_t axis = 0; axis < motion_axes; ++axis) {
    auto c = from_double<S>(p[axis]);
    if (!c) return fail(c.error(), segment);
    sp.position[axis] = c.value();
  }
  return sp;
}

}  // namespace curvestep
