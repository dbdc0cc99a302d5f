// SPDX-License-Identifier: MIT
// C1 Hermite splines with given tangents, and Catmull–Rom splines (tangents from the neighbours).
//
// With a tangent v_i prescribed at every point, each segment is the Hermite cubic of its two end
// points and tangents (seed 000 §3.3.1, seed 002 exercise after Thm 3.3): the curve interpolates
// and is C1 by construction, with no system to solve. The Catmull–Rom choice on uniform knots
// u_i = i is v_j = ½(p_{j+1} − p_{j−1}) (seed 000, with its misprint corrected), local: moving one
// point changes only the four segments around it. Open curves take v_0 and v_n from the caller;
// closed curves use the cyclic neighbours. Curvature jumps at the knots (only C1); use
// cubic_spline.hpp when C2 is required.
// Error: one rounding for ½(p_{j+1} − p_{j−1}) (exact in Fixed for dyadic data) and the Bézier
// conversion's roundings (hermite.hpp).
#pragma once

#include <array>
#include <cstddef>
#include <span>

#include <curvestep/core/interpolation/detail/spline_input.hpp>

namespace curvestep {

/// The C1 cubic spline through `points` at `knots` with s'(u_i) = tangents[i] (all the same count).
/// TooFewPoints, CapacityExceeded, InvalidArgument (a count), InvalidInterval, NotFinite, FixedOverflow.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxSegments>
  requires(MaxDegree >= 3)
[[nodiscard]] constexpr Result<void> interpolate_hermite(std::span<const Vec<S, Dim>> points, std::span<const Vec<S, Dim>> tangents,
                                                         std::span<const S> knots,
                                                         CompositeBezier<S, Dim, MaxDegree, MaxSegments>& out) noexcept {
  const std::size_t n = points.size();
  if (n < 2) return fail(Error::TooFewPoints, n);
  if (n - 1 > MaxSegments) return fail(Error::CapacityExceeded, n - 1);
  if (tangents.size() != n) return fail(Error::InvalidArgument, tangents.size());
  CURVESTEP_CHECK(detail::check_interpolation_points(points));
  CURVESTEP_CHECK(detail::check_interpolation_points(tangents));
  CURVESTEP_CHECK(detail::check_interpolation_knots(knots, n));
  return detail::assemble_hermite(points, tangents, knots, n - 1, out);
}

namespace detail {
/// ½(p_{j+1} − p_{j−1}), checked.
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr Result<Vec<S, Dim>> central_tangent(const Vec<S, Dim>& previous, const Vec<S, Dim>& next,
                                                            std::size_t index) noexcept {
  Vec<S, Dim> v;
  for (std::size_t axis = 0; axis < Dim; ++axis) {
    const auto c = ((Checked<S>(next[axis]) - Checked<S>(previous[axis])) / Checked<S>(from_int<S>(2))).result();
    if (!c) return fail(c.error(), index);
    v[axis] = c.value();
  }
  return v;
}
}  // namespace detail

/// The open Catmull–Rom spline on knots 0, 1, …, n − 1: interior tangents ½(p_{j+1} − p_{j−1}),
/// end tangents from the caller. Errors as interpolate_hermite.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxSegments>
  requires(MaxDegree >= 3)
[[nodiscard]] constexpr Result<void> interpolate_catmull_rom(std::span<const Vec<S, Dim>> points, const Vec<S, Dim>& start_tangent,
                                                             const Vec<S, Dim>& end_tangent,
                                                             CompositeBezier<S, Dim, MaxDegree, MaxSegments>& out) noexcept {
  const std::size_t n = points.size();
  if (n < 2) return fail(Error::TooFewPoints, n);
  if (n - 1 > MaxSegments) return fail(Error::CapacityExceeded, n - 1);
  CURVESTEP_CHECK(detail::check_interpolation_points(points));
  std::array<Vec<S, Dim>, MaxSegments + 1> tangents{};
  std::array<S, MaxSegments + 1> knots{};
  tangents[0] = start_tangent;
  tangents[n - 1] = end_tangent;
  for (std::size_t j = 0; j < n; ++j) {
    CURVESTEP_TRY(knots[j], detail::uniform_knot<S>(j));
    if (j > 0 && j + 1 < n) {
      CURVESTEP_TRY(tangents[j], detail::central_tangent(points[j - 1], points[j + 1], j));
    }
  }
  return interpolate_hermite(points, std::span<const Vec<S, Dim>>(tangents.data(), n), std::span<const S>(knots.data(), n), out);
}

/// The closed Catmull–Rom spline through m >= 3 points (do not repeat the first) on knots
/// 0, 1, …, m: every tangent from the cyclic neighbours.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxSegments>
  requires(MaxDegree >= 3)
[[nodiscard]] constexpr Result<void> interpolate_closed_catmull_rom(std::span<const Vec<S, Dim>> points,
                                                                    CompositeBezier<S, Dim, MaxDegree, MaxSegments>& out) noexcept {
  const std::size_t m = points.size();
  if (m < 3) return fail(Error::TooFewPoints, m);
  if (m > MaxSegments) return fail(Error::CapacityExceeded, m);
  CURVESTEP_CHECK(detail::check_interpolation_points(points));
  std::array<Vec<S, Dim>, MaxSegments> tangents{};
  std::array<S, MaxSegments + 1> knots{};
  for (std::size_t j = 0; j <= m; ++j) {
    CURVESTEP_TRY(knots[j], detail::uniform_knot<S>(j));
    if (j < m) {
      CURVESTEP_TRY(tangents[j], detail::central_tangent(points[(j + m - 1) % m], points[(j + 1) % m], j));
    }
  }
  return detail::assemble_hermite(points, std::span<const Vec<S, Dim>>(tangents.data(), m), std::span<const S>(knots.data(), m + 1),
                                  m, out);
}

}  // namespace curvestep
