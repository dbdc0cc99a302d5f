// SPDX-License-Identifier: MIT
// Runs of short lines replaced by a C2 cubic B-spline within a tolerance of the programmed polyline.
//
// Why: CAM posts and plotter polylines approximate smooth curves by many short lines. Followed as
// lines, every vertex is a corner: the machine either slows at each (the velocity jump of a corner
// must fit the jerk limit within one tick) or, blended, runs a path whose curvature jumps between
// zero on the lines and a peak at each vertex. A cubic B-spline through the same points has
// continuous curvature and far fewer pieces: the planner follows it at the speed its true
// curvature allows, with fewer queue entries.
//
// How: chord-length parameters t_i of the vertices; a clamped cubic B-spline whose end control
// points are the run's end points; the inner control points by least squares over the vertices
// and the lines' midpoints, with a small second-difference term so that spans without data stay
// well posed (banded normal equations, Cholesky). Knots start with one span; each span where the
// spline strays more than the tolerance from a vertex or a line, or a line from the spline, is
// halved, and the fit repeats (knot placement by refinement, as in the B-spline fitting of the
// seeds). The spline is then cut into its Bézier pieces (blossoms), put on the Q16.16 grid.
// No fit is returned when it would need as many pieces as there are lines, or the spline would
// have a cusp.
#pragma once

#include <optional>
#include <vector>

#include <curvestep/core/motion/path_segment.hpp>

namespace curvestep::host::smoothing {

/// A fitted run: the cubic Bézier pieces (connected, first start = first vertex, last end = last
/// vertex) and the largest distance from the programmed polyline, both ways.
struct LineRunFit {
  std::vector<PathSegment> pieces;
  double deviation_mm = 0;
};

/// Fits the polyline through `vertices` (on the Q16.16 grid, at least 3 lines) within
/// `tolerance_mm`; the pieces carry `feed_mm_per_s`. nullopt if no useful fit exists.
[[nodiscard]] std::optional<LineRunFit> fit_line_run(const std::vector<MachinePoint>& vertices, double tolerance_mm,
                                                     double feed_mm_per_s);

}  // namespace curvestep::host::smoothing
