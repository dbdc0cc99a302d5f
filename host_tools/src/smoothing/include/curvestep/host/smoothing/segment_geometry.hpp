// SPDX-License-Identifier: MIT
// Geometry of one PathSegment for the host's path smoothing: arc length between parameters, the
// parameter at an arc length, tangent and curvature, a piece of a segment, the Q16.16 grid, and the
// distance from a point to a sampled curve. Host code (double, std::vector); not run on a board.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include <curvestep/core/motion/path_segment.hpp>

namespace curvestep::host::smoothing {

/// `p` with every coordinate rounded to the Q16.16 grid (as job files are), or nullopt outside Q16.16.
[[nodiscard]] std::optional<MachinePoint> on_grid(const MachinePoint& p);

/// Arc length of `segment` between parameters u0 <= u1 (composite Gauss-Legendre, 1e-12 relative).
[[nodiscard]] double length_between(const PathSegment& segment, double u0, double u1);

/// Arc length as a function of u, tabulated once (64 Gauss-Legendre pieces) for fast inversion.
class LengthMap {
 public:
  explicit LengthMap(const PathSegment& segment);
  /// Total arc length, mm.
  [[nodiscard]] double total() const noexcept { return cumulative_.back(); }
  /// The parameter at arc length s from the start (0 <= s <= total), to ~1e-12 in u.
  [[nodiscard]] double parameter_at(double s_mm) const;

 private:
  const PathSegment* segment_;
  std::vector<double> cumulative_;  ///< length from 0 to k/64
};

/// Unit tangent and curvature vector κN at u (zero vectors where the derivative vanishes).
struct LocalFrame {
  MachinePoint tangent{};
  MachinePoint curvature{};
};
[[nodiscard]] LocalFrame local_frame(const PathSegment& segment, double u);

/// Whether piece_between() can cut this segment: lines, Béziers, rational Béziers, arcs of at most one turn.
[[nodiscard]] bool can_cut(const PathSegment& segment);

/// The piece of `segment` on [u0, u1] (0 <= u0 < u1 <= 1) whose end points are exactly `start` and
/// `end` (points on the grid near p(u0), p(u1)); control points on the Q16.16 grid, weights on the
/// wire's grid. Keeps rapid and feed. nullopt if the piece degenerates.
[[nodiscard]] std::optional<PathSegment> piece_between(const PathSegment& segment, double u0, double u1,
                                                       const MachinePoint& start, const MachinePoint& end);

/// Points of the segment at `samples` + 1 equal parameter steps.
[[nodiscard]] std::vector<MachinePoint> sample(const PathSegment& segment, double u0, double u1, std::size_t samples);

/// Distance from p to the polyline through `points`.
[[nodiscard]] double distance_to_polyline(const MachinePoint& p, const std::vector<MachinePoint>& points);

/// Distance from p to the segment [a, b].
[[nodiscard]] double distance_to_chord(const MachinePoint& p, const MachinePoint& a, const MachinePoint& b);

}  // namespace curvestep::host::smoothing
