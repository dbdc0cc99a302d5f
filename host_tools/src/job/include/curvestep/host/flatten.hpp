// SPDX-License-Identifier: MIT
// Flattening: a polyline that stays within a tolerance of every segment of a path.
//
// Béziers (polynomial and rational) go through the core's flatten (sampling/flatten.hpp): with
// positive weights a piece lies in the convex hull of its control points, so the farthest control
// point of its halves from the chord bounds the curve's distance from that chord; pieces are
// chosen greedily as long as that bound stays within the tolerance. The last vertex is set to
// the segment's exact end so that consecutive segments share it.
//
// Arcs use the sagitta: a chord spanning Δθ of a circle of radius r stays within
// r(1 − cos(Δθ/2)) of the arc, so Δθ = 2 acos(1 − tol/r) (at most π/2) and n = ⌈|θ|/Δθ⌉ equal
// steps. On a helix (z linear in the angle) the 3D distance to the chord adds at most
// r·φ³/8 (φ = Δθ/2) along the chord's y–z plane; n grows until both parts together fit.
#pragma once

#include <span>
#include <vector>

#include <curvestep/core/motion/path_segment.hpp>

namespace curvestep::host {

/// Appends points of `segment` after its start (the start itself is not appended) so that the
/// polyline start, points... stays within `tolerance_mm` of the segment.
/// std::invalid_argument for a tolerance that is not positive or too small to reach.
void flatten_segment(const PathSegment& segment, double tolerance_mm, std::vector<MachinePoint>& out);

/// The polyline of a whole path: the first segment's start, then every segment's points; a
/// segment that does not start at the last point adds its start first.
[[nodiscard]] std::vector<MachinePoint> flatten_path(std::span<const PathSegment> segments, double tolerance_mm);

}  // namespace curvestep::host
