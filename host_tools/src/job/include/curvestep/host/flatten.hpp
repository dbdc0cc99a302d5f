// SPDX-License-Identifier: MIT
// Flattening: a polyline that stays within a tolerance of every segment of a path.
//
// Béziers (polynomial and rational with positive weights) lie in the convex hull of their control
// points. The distance to the chord P0-Pn is a convex function, so over that hull it is largest
// at a control point: max_i dist(P_i, [P0, Pn]) bounds the distance of the whole curve to its
// chord. A piece is emitted as one chord when that bound is within the tolerance, otherwise it is
// split at t = 1/2 (de Casteljau) and both halves are flattened in turn. Each halving shrinks
// the bound about 4×, so the depth grows like log4(size / tolerance); it is capped at 48.
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
