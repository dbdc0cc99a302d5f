// SPDX-License-Identifier: MIT
// C1 quadratic interpolating splines (seed 002 Thm 3.2, seed 001 §6.2) as composite Bézier curves.
//
// Segment i runs from p_i through the inner control point q_i to p_{i+1} on [u_i, u_{i+1}],
// h_i = u_{i+1} − u_i. Its end derivatives in u are 2(q_i − p_i)/h_i and 2(p_{i+1} − q_i)/h_i, so
// C1 at p_{i+1} is (p_{i+1} − q_i)/h_i = (q_{i+1} − p_{i+1})/h_{i+1}, i.e. the reflection
//   q_{i+1} = p_{i+1} + (h_{i+1}/h_i)·(p_{i+1} − q_i).
// One inner point fixes all the others, so the spline has one free vector:
//   * open, start tangent given (any dimension): q_0 = p_0 + h_0·v_0/2, then the recursion;
//   * open, end tangent DIRECTIONS t_0, t_n given (plane, seed 002 Thm 3.2): with s_i =
//     (q_i − p_i)/h_i and δ_i = (p_{i+1} − p_i)/h_i the recursion is s_{i+1} = δ_i − s_i, hence
//       μ·t_n − (−1)^n·λ·t_0 = Σ_{j<n} (−1)^j δ_{n−1−j},
//     a 2×2 system for λ, μ (Cramer's rule); parallel t_0, t_n make it singular: SingularSystem;
//   * closed through m points (seed 001 (20)): going once round the loop gives
//     q_0 = A + (−1)^m·(Π h_{i+1}/h_i)·q_0 = A + (−1)^m q_0, where A is the loop's value started from
//     q_0 = 0 (the ratios telescope to 1). For odd m, q_0 = A/2 is the unique solution; for even m
//     the system is singular (det = 1 + (−1)^{m+1} = 0) for every parametrization:
//     Error::EvenClosedQuadratic.
// Errors propagate along the recursion with alternating sign and are not damped (seed 002): one
// rounding per ratio and product per segment, so after n segments the inner points carry about n
// rounding units times the largest ratio product. Uniform knots make every ratio exactly 1.
// Quadratic interpolants often loop (seed 001 §6.2); cubic splines are preferred in practice.
#pragma once

#include <array>
#include <cstddef>
#include <span>

#include <curvestep/core/interpolation/detail/spline_input.hpp>
#include <curvestep/core/interpolation/parametrization.hpp>
#include <curvestep/core/interpolation/tridiagonal.hpp>

namespace curvestep {

namespace detail {

/// Follows the C1 reflection from q_0 and appends the quadratic segments to `out` (emptied first).
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxSegments>
[[nodiscard]] constexpr Result<void> assemble_quadratic(std::span<const Vec<S, Dim>> points, std::span<const S> knots,
                                                        std::size_t segment_count, Vec<S, Dim> inner,
                                                        CompositeBezier<S, Dim, MaxDegree, MaxSegments>& out) noexcept {
  using Curve = CompositeBezier<S, Dim, MaxDegree, MaxSegments>;
  out = Curve(knots[0]);
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < segment_count; ++i) {
    const std::size_t next = i + 1 == n ? 0 : i + 1;
    const std::array<Vec<S, Dim>, 3> control{points[i], inner, points[next]};
    auto segment = Bezier<S, Dim, MaxDegree>::create(std::span<const Vec<S, Dim>>(control));
    Result<void> appended = segment ? out.try_append(segment.value(), knots[i + 1]) : Result<void>(segment.failure());
    if (!appended) {
      out = Curve(knots[0]);
      return fail(appended.error(), i);
    }
    if (i + 1 < segment_count) {
      CURVESTEP_TRY(const S h, knot_interval(knots, i));
      CURVESTEP_TRY(const S h_next, knot_interval(knots, i + 1));
      for (std::size_t axis = 0; axis < Dim; ++axis) {
        const Checked<S> p(points[next][axis]);
        const auto q = (p + Checked<S>(h_next) * (p - Checked<S>(inner[axis])) / Checked<S>(h)).result();
        if (!q) {
          out = Curve(knots[0]);
          return fail(q.error(), i + 1);
        }
        inner[axis] = q.value();
      }
    }
  }
  return ok();
}

/// Common input checks; Closure::Closed adds the closing knot.
template <Scalar S, std::size_t Dim, std::size_t MaxSegments>
[[nodiscard]] constexpr Result<void> check_quadratic_input(std::span<const Vec<S, Dim>> points, std::span<const S> knots,
                                                           Closure closure) noexcept {
  const std::size_t n = points.size();
  const bool closed = closure == Closure::Closed;
  if (n < (closed ? 3u : 2u)) return fail(Error::TooFewPoints, n);
  const std::size_t segments = closed ? n : n - 1;
  if (segments > MaxSegments) return fail(Error::CapacityExceeded, segments);
  CURVESTEP_CHECK(check_interpolation_points(points));
  return check_interpolation_knots(knots, closed ? n + 1 : n);
}

}  // namespace detail

/// The C1 quadratic spline through `points` at `knots` (same count) with s'(u_0) = start_tangent
/// (a derivative in u, any dimension). TooFewPoints, CapacityExceeded, InvalidArgument (knot
/// count), InvalidInterval, NotFinite, FixedOverflow (index = segment).
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxSegments>
  requires(MaxDegree >= 2)
[[nodiscard]] constexpr Result<void> interpolate_quadratic(std::span<const Vec<S, Dim>> points, std::span<const S> knots,
                                                           const Vec<S, Dim>& start_tangent,
                                                           CompositeBezier<S, Dim, MaxDegree, MaxSegments>& out) noexcept {
  using detail::Checked;
  CURVESTEP_CHECK((detail::check_quadratic_input<S, Dim, MaxSegments>(points, knots, Closure::Open)));
  CURVESTEP_TRY(const S h, detail::knot_interval(knots, 0));
  Vec<S, Dim> inner;
  for (std::size_t axis = 0; axis < Dim; ++axis) {
    const Checked<S> half_step = Checked<S>(h) * Checked<S>(start_tangent[axis]) / Checked<S>(from_int<S>(2));
    const auto q = (Checked<S>(points[0][axis]) + half_step).result();
    if (!q) return fail(q.error(), 0);
    inner[axis] = q.value();
  }
  return detail::assemble_quadratic(points, knots, points.size() - 1, inner, out);
}

/// The unique plane C1 quadratic spline through `points` at `knots` whose end derivatives are
/// parallel to `start_direction` and `end_direction` (seed 002 Thm 3.2; the directions' lengths
/// and signs are free). SingularSystem when the directions are parallel (or zero); other errors
/// as interpolate_quadratic.
template <Scalar S, std::size_t MaxDegree, std::size_t MaxSegments>
  requires(MaxDegree >= 2)
[[nodiscard]] constexpr Result<void> interpolate_quadratic(std::span<const Vec<S, 2>> points, std::span<const S> knots,
                                                           const Vec<S, 2>& start_direction, const Vec<S, 2>& end_direction,
                                                           CompositeBezier<S, 2, MaxDegree, MaxSegments>& out) noexcept {
  using detail::Checked;
  CURVESTEP_CHECK((detail::check_quadratic_input<S, 2, MaxSegments>(points, knots, Closure::Open)));
  const std::size_t n = points.size() - 1;  // segments
  // R = Σ_{j<n} (−1)^j δ_{n−1−j}
  std::array<Checked<S>, 2> alternating{};
  for (std::size_t j = 0; j < n; ++j) {
    const std::size_t i = n - 1 - j;
    CURVESTEP_TRY(const S h, detail::knot_interval(knots, i));
    for (std::size_t axis = 0; axis < 2; ++axis) {
      const Checked<S> slope = (Checked<S>(points[i + 1][axis]) - Checked<S>(points[i][axis])) / Checked<S>(h);
      alternating[axis] = j % 2 == 0 ? alternating[axis] + slope : alternating[axis] - slope;
    }
  }
  // μ·t_n + σ·λ·t_0 = R with σ = −(−1)^n; columns c0 = t_n (for μ), c1 = σ t_0 (for λ).
  const bool n_even = n % 2 == 0;
  const Checked<S> c0x(end_direction[0]);
  const Checked<S> c0y(end_direction[1]);
  const Checked<S> c1x(n_even ? -start_direction[0] : start_direction[0]);
  const Checked<S> c1y(n_even ? -start_direction[1] : start_direction[1]);
  const Checked<S> determinant = c0x * c1y - c0y * c1x;
  CURVESTEP_TRY(const S det, determinant.result());
  const Checked<S> scale = Checked<S>(abs(c0x.value) + abs(c0y.value)) * Checked<S>(abs(c1x.value) + abs(c1y.value));
  CURVESTEP_TRY(const S magnitude, scale.result());
  if (detail::negligible_pivot(det, magnitude)) return fail(Error::SingularSystem);
  const Checked<S> lambda = (c0x * alternating[1] - c0y * alternating[0]) / determinant;
  CURVESTEP_TRY(const S h, detail::knot_interval(knots, 0));
  Vec<S, 2> inner;
  for (std::size_t axis = 0; axis < 2; ++axis) {
    const auto q = (Checked<S>(points[0][axis]) + Checked<S>(h) * lambda * Checked<S>(start_direction[axis])).result();
    if (!q) return fail(q.error(), 0);
    inner[axis] = q.value();
  }
  return detail::assemble_quadratic(points, knots, n, inner, out);
}

/// The closed C1 quadratic spline through m points (do not repeat the first) with m + 1 knots.
/// EvenClosedQuadratic (index = m) when m is even: the periodic system is singular.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxSegments>
  requires(MaxDegree >= 2)
[[nodiscard]] constexpr Result<void> interpolate_closed_quadratic(std::span<const Vec<S, Dim>> points, std::span<const S> knots,
                                                                  CompositeBezier<S, Dim, MaxDegree, MaxSegments>& out) noexcept {
  using detail::Checked;
  CURVESTEP_CHECK((detail::check_quadratic_input<S, Dim, MaxSegments>(points, knots, Closure::Closed)));
  const std::size_t m = points.size();
  if (m % 2 == 0) return fail(Error::EvenClosedQuadratic, m);
  // Once round the loop from q_0 = 0 gives A; then q_0 = A/2.
  Vec<S, Dim> inner{};
  for (std::size_t i = 0; i < m; ++i) {
    const std::size_t next = i + 1 == m ? 0 : i + 1;
    CURVESTEP_TRY(const S h, detail::knot_interval(knots, i));
    CURVESTEP_TRY(const S h_next, detail::knot_interval(knots, next));
    for (std::size_t axis = 0; axis < Dim; ++axis) {
      const Checked<S> p(points[next][axis]);
      const auto q = (p + Checked<S>(h_next) * (p - Checked<S>(inner[axis])) / Checked<S>(h)).result();
      if (!q) return fail(q.error(), i);
      inner[axis] = q.value();
    }
  }
  for (std::size_t axis = 0; axis < Dim; ++axis) {
    CURVESTEP_TRY(inner[axis], (Checked<S>(inner[axis]) / Checked<S>(from_int<S>(2))).result());
  }
  return detail::assemble_quadratic(points, knots, m, inner, out);
}

/// Open quadratic spline with a start tangent and knots from a parametrization (u_0 = 0).
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxSegments>
  requires(MaxDegree >= 2)
[[nodiscard]] constexpr Result<void> interpolate_quadratic(std::span<const Vec<S, Dim>> points, Parametrization kind,
                                                           const Vec<S, Dim>& start_tangent,
                                                           CompositeBezier<S, Dim, MaxDegree, MaxSegments>& out) noexcept {
  if (points.size() > MaxSegments + 1) return fail(Error::CapacityExceeded, points.size() - 1);
  return detail::with_parametrized_knots<MaxSegments>(points, kind, Closure::Open, [&](std::span<const S> knots) {
    return interpolate_quadratic(points, knots, start_tangent, out);
  });
}

/// Plane quadratic spline with end directions and knots from a parametrization (u_0 = 0).
template <Scalar S, std::size_t MaxDegree, std::size_t MaxSegments>
  requires(MaxDegree >= 2)
[[nodiscard]] constexpr Result<void> interpolate_quadratic(std::span<const Vec<S, 2>> points, Parametrization kind,
                                                           const Vec<S, 2>& start_direction, const Vec<S, 2>& end_direction,
                                                           CompositeBezier<S, 2, MaxDegree, MaxSegments>& out) noexcept {
  if (points.size() > MaxSegments + 1) return fail(Error::CapacityExceeded, points.size() - 1);
  return detail::with_parametrized_knots<MaxSegments>(points, kind, Closure::Open, [&](std::span<const S> knots) {
    return interpolate_quadratic(points, knots, start_direction, end_direction, out);
  });
}

/// Closed quadratic spline with knots from a parametrization (closing chord included).
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxSegments>
  requires(MaxDegree >= 2)
[[nodiscard]] constexpr Result<void> interpolate_closed_quadratic(std::span<const Vec<S, Dim>> points, Parametrization kind,
                                                                  CompositeBezier<S, Dim, MaxDegree, MaxSegments>& out) noexcept {
  if (points.size() > MaxSegments) return fail(Error::CapacityExceeded, points.size());
  return detail::with_parametrized_knots<MaxSegments>(points, kind, Closure::Closed, [&](std::span<const S> knots) {
    return interpolate_closed_quadratic(points, knots, out);
  });
}

}  // namespace curvestep
