// SPDX-License-Identifier: MIT
// Fuzz checks shared by the job, G-code and SVG harnesses: points inside a bound, and every number
// the wire carries (host_tools/src/link/wire.cpp) of a loaded job finite and on the Q16.16 grid.
#pragma once

#include <cmath>
#include <cstddef>

#include <curvestep/host/job.hpp>

namespace curvestep::fuzz {

/// Every coordinate finite and within ±limit.
inline bool inside(const curvestep::MachinePoint& p, double limit) {
  for (std::size_t a = 0; a < curvestep::motion_axes; ++a) {
    if (!std::isfinite(p[a]) || std::fabs(p[a]) > limit) return false;
  }
  return true;
}

/// Finite and on the Q16.16 grid (value · 65536, exact in double, is an integer): a number the
/// wire carries without rounding.
inline bool on_wire_grid(double value) { return std::isfinite(value) && value * 65536.0 == std::nearbyint(value * 65536.0); }

inline bool on_wire_grid(const curvestep::MachinePoint& p) {
  for (std::size_t a = 0; a < curvestep::motion_axes; ++a) {
    if (!on_wire_grid(p[a])) return false;
  }
  return true;
}

/// Every number of `s` that the wire carries (host_tools/src/link/wire.cpp): control points (the
/// end points and the XY centre of an arc), weights and the feed.
inline bool wire_exact(const curvestep::PathSegment& s) {
  if (!on_wire_grid(s.start()) || !on_wire_grid(s.end()) || !on_wire_grid(s.feed_mm_per_s())) return false;
  switch (s.kind()) {
    case curvestep::SegmentKind::Line:
    case curvestep::SegmentKind::Bezier:
      for (const auto& p : s.polynomial().control_points()) {
        if (!on_wire_grid(p)) return false;
      }
      return true;
    case curvestep::SegmentKind::RationalBezier:
      for (std::size_t k = 0; k <= s.rational().degree(); ++k) {
        if (!on_wire_grid(s.rational().control_points()[k]) || !on_wire_grid(s.rational().weight(k))) return false;
      }
      return true;
    case curvestep::SegmentKind::Arc: return on_wire_grid(s.arc_center()[0]) && on_wire_grid(s.arc_center()[1]);
  }
  return false;
}

/// The file's segments as loaded: points, weights and feed on the grid (knots never travel).
inline bool wire_exact(const curvestep::host::SourceSegment& source) {
  for (const auto& p : source.points) {
    if (!on_wire_grid(p)) return false;
  }
  for (const double w : source.weights) {
    if (!on_wire_grid(w)) return false;
  }
  return on_wire_grid(source.feed_mm_per_s);
}

}  // namespace curvestep::fuzz
