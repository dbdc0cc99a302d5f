// SPDX-License-Identifier: MIT
// The box a path segment sweeps: what the controller checks against its travel range and the host
// checks against the Q16.16 range and the machine file's travel before a job starts (one
// implementation for both).
#pragma once

#include <cstddef>

#include <curvestep/core/motion/deterministic_math.hpp>
#include <curvestep/core/motion/path_segment.hpp>

namespace curvestep {

/// Smallest and largest coordinates a segment can reach.
struct SegmentBounds {
  MachinePoint low{};   ///< per-axis minimum
  MachinePoint high{};  ///< per-axis maximum
};

/// Bounds of a segment: Bézier kinds by their control points (the curve lies in their convex hull,
/// for rational ones too since the weights are positive: conservative); arcs exactly, from the end
/// points and the extreme points of the circle (at the larger of the two radii) that the sweep passes.
[[nodiscard]] inline SegmentBounds segment_bounds(const PathSegment& s) noexcept {
  SegmentBounds b;
  const auto include = [&b](const MachinePoint& p) {
    for (std::size_t a = 0; a < motion_axes; ++a) {
      if (p[a] < b.low[a]) b.low[a] = p[a];
      if (p[a] > b.high[a]) b.high[a] = p[a];
    }
  };
  b.low = s.start();
  b.high = s.start();
  include(s.end());
  if (s.kind() == SegmentKind::Line || s.kind() == SegmentKind::Bezier) {
    for (const auto& p : s.polynomial().control_points()) include(p);
  } else if (s.kind() == SegmentKind::RationalBezier) {
    for (const auto& p : s.rational().control_points()) include(p);
  } else {
    const MachinePoint c = s.arc_center();
    const MachinePoint a = s.start();
    const MachinePoint e = s.end();
    const double end_radius = std::sqrt((e[0] - c[0]) * (e[0] - c[0]) + (e[1] - c[1]) * (e[1] - c[1]));
    const double r = end_radius > s.arc_radius() ? end_radius : s.arc_radius();
    const double start_angle = detail::atan2(a[1] - c[1], a[0] - c[0]);
    const double sweep = s.arc_sweep_rad();
    for (int k = 0; k < 4; ++k) {
      const double direction = k * (detail::pi / 2);
      double delta = sweep >= 0 ? direction - start_angle : start_angle - direction;
      while (delta < 0) delta += 2 * detail::pi;
      while (delta >= 2 * detail::pi) delta -= 2 * detail::pi;
      if (delta > (sweep >= 0 ? sweep : -sweep)) continue;
      MachinePoint extreme = c;
      extreme[2] = a[2];
      if (k == 0) extreme[0] += r;
      if (k == 1) extreme[1] += r;
      if (k == 2) extreme[0] -= r;
      if (k == 3) extreme[1] -= r;
      include(extreme);
    }
  }
  return b;
}

}  // namespace curvestep
