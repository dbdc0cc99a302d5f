// SPDX-License-Identifier: MIT
// Inverse-time feed (G93): the feed that makes a move take 1/F minutes, from its exact length.
//
// LinuxCNC (interp_inverse.cc) turns an inverse-time move into a feed rate: the move's length
// times F, at least 0.1 program units per minute. A line's length is the distance from start to
// end; an arc's is find_arc_length's: the start radius times the swept angle (find_turn: end equal
// to start is a whole turn, each extra turn adds 2π), and for a helix the hypotenuse of that and
// the rise along the plane's normal. Lengths here are in millimetres, so the feed comes out in
// mm/min whatever the program's units; the lower bound is 0.1 of the program's unit per minute.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

#include <curvestep/core/curve/circular_arc.hpp>

namespace curvestep::gcode {

/// LinuxCNC's least inverse-time feed, program units per minute (interp_inverse.cc: MAX(0.1, ...)).
inline constexpr double inverse_time_min_feed_units_per_min = 0.1;

/// The angle an arc sweeps (radians, not negative) from start angle `start_rad` to end angle
/// `end_rad` about its centre, in `direction`, with `extra_turns` whole turns more; an end at the
/// start angle is a whole turn (LinuxCNC's find_turn).
[[nodiscard]] inline double arc_swept_angle_rad(double start_rad, double end_rad, ArcDirection direction,
                                                std::uint32_t extra_turns) noexcept {
  constexpr double turn = 2 * std::numbers::pi;
  double swept = direction == ArcDirection::CounterClockwise ? end_rad - start_rad : start_rad - end_rad;
  if (swept <= 0) swept += turn;
  return swept + turn * static_cast<double>(extra_turns);
}

/// The length of an arc or helix, mm: `radius_mm` (the start's distance from the centre) times the
/// swept angle, combined with the rise `normal_rise_mm` along the plane's normal (find_arc_length).
[[nodiscard]] inline double helix_length_mm(double radius_mm, double swept_rad, double normal_rise_mm) noexcept {
  return std::hypot(radius_mm * swept_rad, normal_rise_mm);
}

/// The feed of an inverse-time move, mm/min: `length_mm` × F (per minute), at least 0.1 program
/// unit per minute (`mm_per_unit`: 25.4 under G20, 1 under G21).
[[nodiscard]] inline double inverse_time_feed_mm_per_min(double length_mm, double f_per_min, double mm_per_unit) noexcept {
  return std::fmax(inverse_time_min_feed_units_per_min * mm_per_unit, length_mm * f_per_min);
}

}  // namespace curvestep::gcode
