// SPDX-License-Identifier: MIT
// Limit points and limit-curve Bézier pieces of the four subdivision schemes of seed 001.
//
// Three of the schemes converge to uniform B-splines whose control points are the initial
// polygon's vertices P_k (seed 001 §8.3, §9 notes), so their limits are known in closed form:
//   cubic B-spline:        the point belonging to P_k is (P_{k−1} + 4P_k + P_{k+1})/6 and the
//                          piece between P_j and P_{j+1} has Bézier points
//                          (P_{j−1}+4P_j+P_{j+1})/6, (2P_j+P_{j+1})/3, (P_j+2P_{j+1})/3, (P_j+4P_{j+1}+P_{j+2})/6;
//   Chaikin and ternary:   the quadratic B-spline; the piece around P_j is
//                          (P_{j−1}+P_j)/2, P_j, (P_j+P_{j+1})/2 and the point belonging to P_k is its
//                          middle (P_{k−1} + 6P_k + P_{k+1})/8 (for the ternary scheme the limit of
//                          the refined vertex p_{3k}; Chaikin replaces vertices, so for it this is the
//                          limit curve's point at P_k's parameter);
//   four-point:            interpolating: the limit passes through every P_k (and every vertex
//                          ever inserted); its limit curve has no polynomial closed form, so no
//                          Bézier pieces (InvalidArgument).
// Neighbours follow the boundary rule: cyclic for Closed, replicated ends for PseudoFinite; the
// Finite rule has no limit at P_0 and P_K (InvalidArgument) except for the four-point scheme.
// Every value is an exact integer combination rounded once (Fixed): exact for dyadic weights.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/core/curve/bezier.hpp>
#include <curvestep/core/subdivision/refine.hpp>

namespace curvestep {

/// The four schemes of seed 001 §8.3.
enum class SubdivisionScheme : std::uint8_t {
  CubicBSpline,      ///< [1,4,6,4,1]/8, limit: uniform cubic B-spline (C2)
  Chaikin,           ///< [1,3,3,1]/4, limit: uniform quadratic B-spline (C1)
  TernaryQuadratic,  ///< [1,3,6,7,6,3,1]/9, limit: uniform quadratic B-spline (C1)
  FourPoint,         ///< [−1,0,9,16,9,0,−1]/16, interpolating (C1)
};

/// The mask of a scheme.
[[nodiscard]] constexpr SubdivisionMask scheme_mask(SubdivisionScheme scheme) noexcept {
  switch (scheme) {
    case SubdivisionScheme::CubicBSpline:
      return cubic_bspline_mask();
    case SubdivisionScheme::Chaikin:
      return chaikin_mask();
    case SubdivisionScheme::TernaryQuadratic:
      return ternary_quadratic_mask();
    case SubdivisionScheme::FourPoint:
      break;
  }
  return four_point_mask();
}

namespace detail {
/// Vertex k + offset under the boundary rule (cyclic or clamped); false if it does not exist.
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr bool boundary_vertex(std::span<const Vec<S, Dim>> polygon, std::int64_t k, Boundary boundary,
                                       Vec<S, Dim>& out) noexcept {
  const auto n = static_cast<std::int64_t>(polygon.size());
  if (boundary == Boundary::Closed) {
    k = k - n * floor_divide_positive(k, n);
  } else if (k < 0 || k >= n) {
    if (boundary == Boundary::Finite) return false;
    k = k < 0 ? 0 : n - 1;
  }
  out = polygon[static_cast<std::size_t>(k)];
  return true;
}

/// Σ weights[r]·P_{first + r} / denominator with boundary-resolved indices.
template <Scalar S, std::size_t Dim, std::size_t Count>
[[nodiscard]] constexpr Result<Vec<S, Dim>> limit_stencil(std::span<const Vec<S, Dim>> polygon, std::int64_t first, Boundary boundary,
                                                    const std::array<std::int64_t, Count>& weights, std::int64_t denominator,
                                                    std::size_t index) noexcept {
  std::array<Vec<S, Dim>, Count> points{};
  for (std::size_t r = 0; r < Count; ++r) {
    if (weights[r] == 0) continue;
    if (!boundary_vertex(polygon, first + static_cast<std::int64_t>(r), boundary, points[r])) {
      return fail(Error::InvalidArgument, index);
    }
  }
  const auto p = exact_combination<S, Dim>(std::span<const Vec<S, Dim>>(points), std::span<const std::int64_t>(weights), denominator);
  if (!p) return fail(p.error(), index);
  return p.value();
}
}  // namespace detail

/// The limit-curve point belonging to old vertex k (see the header essay). InvalidArgument
/// (index = k) if k is not a vertex or, under the Finite rule, an end vertex without one.
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr Result<Vec<S, Dim>> limit_point(SubdivisionScheme scheme, std::span<const Vec<S, Dim>> polygon,
                                                        std::size_t k, Boundary boundary) noexcept {
  if (k >= polygon.size()) return fail(Error::InvalidArgument, k);
  const auto first = static_cast<std::int64_t>(k) - 1;
  switch (scheme) {
    case SubdivisionScheme::CubicBSpline:
      return detail::limit_stencil<S, Dim, 3>(polygon, first, boundary, {1, 4, 1}, 6, k);
    case SubdivisionScheme::Chaikin:
    case SubdivisionScheme::TernaryQuadratic:
      return detail::limit_stencil<S, Dim, 3>(polygon, first, boundary, {1, 6, 1}, 8, k);
    case SubdivisionScheme::FourPoint:
      break;
  }
  return polygon[k];
}

/// The Bézier piece of the limit curve: cubic between P_j and P_{j+1} (cubic B-spline scheme),
/// quadratic around P_j (Chaikin, ternary). InvalidArgument (index = j) for the four-point scheme,
/// j out of range, or neighbours missing under the Finite rule; FixedOverflow from the combination.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree = 3>
  requires(MaxDegree >= 3)
[[nodiscard]] constexpr Result<Bezier<S, Dim, MaxDegree>> limit_bezier(SubdivisionScheme scheme, std::span<const Vec<S, Dim>> polygon,
                                                                       std::size_t j, Boundary boundary) noexcept {
  if (j >= polygon.size() || scheme == SubdivisionScheme::FourPoint) return fail(Error::InvalidArgument, j);
  const auto k = static_cast<std::int64_t>(j);
  std::array<Vec<S, Dim>, 4> control{};
  if (scheme == SubdivisionScheme::CubicBSpline) {
    if (boundary != Boundary::Closed && j + 1 >= polygon.size()) return fail(Error::InvalidArgument, j);
    CURVESTEP_TRY(control[0], (detail::limit_stencil<S, Dim, 3>(polygon, k - 1, boundary, {1, 4, 1}, 6, j)));
    CURVESTEP_TRY(control[1], (detail::limit_stencil<S, Dim, 2>(polygon, k, boundary, {2, 1}, 3, j)));
    CURVESTEP_TRY(control[2], (detail::limit_stencil<S, Dim, 2>(polygon, k, boundary, {1, 2}, 3, j)));
    CURVESTEP_TRY(control[3], (detail::limit_stencil<S, Dim, 3>(polygon, k, boundary, {1, 4, 1}, 6, j)));
    return Bezier<S, Dim, MaxDegree>::create(std::span<const Vec<S, Dim>>(control.data(), 4));
  }
  CURVESTEP_TRY(control[0], (detail::limit_stencil<S, Dim, 2>(polygon, k - 1, boundary, {1, 1}, 2, j)));
  control[1] = polygon[j];
  CURVESTEP_TRY(control[2], (detail::limit_stencil<S, Dim, 2>(polygon, k, boundary, {1, 1}, 2, j)));
  return Bezier<S, Dim, MaxDegree>::create(std::span<const Vec<S, Dim>>(control.data(), 3));
}

}  // namespace curvestep
