// SPDX-License-Identifier: MIT
// Corner blending: a corner between two segments replaced by a quintic Bézier with continuous
// curvature (G2) that stays within a tolerance of the programmed corner.
//
// Why a quintic: a curve that joins a segment with the same position, tangent and curvature vector
// must match p, p' and p'' at both ends: six conditions, a quintic Hermite. With the blend's own
// speeds λ_A, λ_B at its ends (p'(0) = λ_A T_A, p''(0) = λ_A² κ_A N_A, the same at the end) its
// control points are
//     b0 = P_A, b1 = P_A + λ_A T_A/5, b2 = P_A + 2λ_A T_A/5 + λ_A² κ_A N_A/20,
//     b3 = P_B − 2λ_B T_B/5 + λ_B² κ_B N_B/20, b4 = P_B − λ_B T_B/5, b5 = P_B,
// and its curvature at the ends equals the neighbours' (κ = |p'×p''|/|p'|³ = λ²κ/λ²), whatever λ.
// P_A lies d_A before the corner on the incoming segment, P_B d_B after it on the outgoing one
// (arc lengths); λ = β d with β from a small set, the one whose blend the planner can pass fastest
// (its speed cap from the largest curvature and curvature rate, as plan_segment computes it).
// d is the largest (bisection) whose blend deviates at most the tolerance from the programmed
// path both ways: every blend point near the corner's two pieces, and every programmed point
// (the corner itself above all) near the blend. For two lines this is Sencer and Shamoto's
// setting (a G2 corner with an analytic cornering error); the same construction serves lines,
// arcs and curves, in 3-D.
#pragma once

#include <optional>

#include <curvestep/core/motion/path_segment.hpp>

namespace curvestep::host::smoothing {

/// A corner to blend: the end of `incoming` meets the start of `outgoing`.
struct CornerRequest {
  const PathSegment* incoming = nullptr;
  double incoming_length_mm = 0;      ///< arc length of `incoming`
  double incoming_available_mm = 0;   ///< how much of its end the blend may take
  const PathSegment* outgoing = nullptr;
  double outgoing_length_mm = 0;
  double outgoing_available_mm = 0;   ///< how much of its start the blend may take
  double tolerance_mm = 0;            ///< largest deviation from the programmed corner
  double a_max_mm_per_s2 = 1000;      ///< the machine's limits, to pick the fastest shape
  double j_max_mm_per_s3 = 10000;
};

/// A blend: the curve, where it leaves and joins the neighbours, its deviation and speed cap.
struct CornerBlend {
  PathSegment curve;             ///< quintic Bézier on the Q16.16 grid, rapid if the outgoing segment is (no feed: the caller sets it)
  double incoming_u = 1;         ///< the incoming segment now ends at this parameter
  double outgoing_u = 0;         ///< the outgoing segment now starts at this parameter
  double incoming_cut_mm = 0;    ///< arc length taken from the incoming segment's end
  double outgoing_cut_mm = 0;    ///< arc length taken from the outgoing segment's start
  double deviation_mm = 0;       ///< largest distance between blend and programmed path (both ways)
  double speed_cap_mm_per_s = 0; ///< the curvature speed cap used to choose the shape
};

/// The blend of a corner, or nullopt where none fits (degenerate pieces, off the grid).
[[nodiscard]] std::optional<CornerBlend> blend_corner(const CornerRequest& request);

}  // namespace curvestep::host::smoothing
