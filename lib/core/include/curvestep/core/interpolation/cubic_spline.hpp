// SPDX-License-Identifier: MIT
// C2 cubic interpolating splines (natural, clamped, closed) as composite Bézier curves, no heap.
//
// The spline through p_0..p_n at knots u_0 < … < u_n is a chain of Hermite segments (see
// hermite.hpp) whose tangents v_i = s'(u_i) are chosen so that s'' is continuous (seeds 000
// §3.3, 002 Thm 3.3, 003). With h_i = u_{i+1} − u_i and slopes δ_i = (p_{i+1} − p_i)/h_i, equal
// second derivatives at an interior knot j give (seed 000 §3.3.2, divided by h_{j−1} + h_j so that
// every coefficient lies in [0, 2], which keeps Q16.16 precision independent of the knot scale)
//   λ_j v_{j−1} + 2 v_j + μ_j v_{j+1} = 3 (μ_j δ_j + λ_j δ_{j−1}),
//   λ_j = h_j / (h_{j−1} + h_j),  μ_j = 1 − λ_j.
// Uniform knots give λ = μ = ½, i.e. v_{j−1} + 4v_j + v_{j+1} = 3(p_{j+1} − p_{j−1}) (seed 003).
// End rows: natural (s'' = 0):  2v_0 + v_1 = 3δ_0,  v_{n−1} + 2v_n = 3δ_{n−1};
//           clamped:            v_0 and v_n given (rows of the identity);
//           closed (periodic):  the interior row at every knot, indices mod m, so the matrix is
//                               cyclic tridiagonal (seed 001 §6.1, in tangent form).
// Every system is strictly diagonally dominant (2 > λ + μ = 1) for any increasing knots, so it is
// uniquely solvable (the ratio bound of 002 Thm 3.3 is sufficient, not necessary) and the Thomas /
// Sherman–Morrison solvers need no pivoting; the solution error is a small multiple of the
// rounding unit times |v| (see tridiagonal.hpp). Each coordinate is solved with the same pivots.
//
// Output: the n Bézier segments p_i, p_i + h_i v_i/3, p_{i+1} − h_i v_{i+1}/3, p_{i+1} in a
// caller-provided CompositeBezier whose breakpoints are the knots, so derivatives taken through
// CompositeBezier are with respect to u. Storage: the functions keep (Dim + 5)·(MaxSegments + 1)
// scalars of solver work space on the stack; MaxSegments is the caller's capacity.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/core/interpolation/detail/spline_input.hpp>
#include <curvestep/core/interpolation/parametrization.hpp>
#include <curvestep/core/interpolation/tridiagonal.hpp>

namespace curvestep {

/// End condition of an open C2 cubic spline.
enum class CubicEnd : std::uint8_t {
  Natural,  ///< open; zero second derivative at both ends
  Clamped,  ///< open; prescribed first derivatives (with respect to u) at both ends
  Closed,   ///< closed loop (periodic C2), no ends
};

/// (3 − √5)/2 ≈ 0.381966: lower bound on h_{i+1}/h_i in seed 002 Thm 3.3.
template <Scalar S>
[[nodiscard]] constexpr S knot_ratio_lower_bound() noexcept {
  return constant<S>(0.381966011250105);
}
/// (3 + √5)/2 ≈ 2.618034: upper bound on h_{i+1}/h_i in seed 002 Thm 3.3.
template <Scalar S>
[[nodiscard]] constexpr S knot_ratio_upper_bound() noexcept {
  return constant<S>(2.618033988749895);
}

/// True if every ratio of consecutive knot intervals lies strictly inside the bounds of seed 002
/// Thm 3.3. Only a sufficient condition (the solver works for any increasing knots): use it for an
/// optional warning about uneven spacing. InvalidInterval (index = knot) if knots do not increase.
template <Scalar S>
[[nodiscard]] constexpr Result<bool> knot_ratios_within_bound(std::span<const S> knots) noexcept {
  using detail::Checked;
  for (std::size_t i = 0; i < knots.size(); ++i) {
    if (i > 0 && !(knots[i - 1] < knots[i])) return fail(Error::InvalidInterval, i);
  }
  for (std::size_t i = 0; i + 2 < knots.size(); ++i) {
    CURVESTEP_TRY(const S h, (Checked<S>(knots[i + 1]) - Checked<S>(knots[i])).result());
    CURVESTEP_TRY(const S next, (Checked<S>(knots[i + 2]) - Checked<S>(knots[i + 1])).result());
    CURVESTEP_TRY(const S low, (Checked<S>(knot_ratio_lower_bound<S>()) * Checked<S>(h)).result());
    CURVESTEP_TRY(const S high, (Checked<S>(knot_ratio_upper_bound<S>()) * Checked<S>(h)).result());
    if (!(low < next) || !(next < high)) return false;
  }
  return true;
}

/// Solves for the tangents v_i = s'(u_i) of the C2 cubic spline through `points`.
/// Open ends: knots.size() == points.size(); CubicEnd::Closed: knots.size() == points.size() + 1
/// (the last knot closes the curve back to points[0]). The tangents are used only when Clamped.
/// Capacity bounds the number of points. Errors: TooFewPoints (< 2 open, < 3 closed), CapacityExceeded, BufferTooSmall
/// (tangents shorter than points), InvalidArgument (knot count), InvalidInterval, NotFinite,
/// SingularSystem, FixedOverflow.
template <std::size_t Capacity, Scalar S, std::size_t Dim>
[[nodiscard]] constexpr Result<void> cubic_spline_tangents(std::span<const Vec<S, Dim>> points, std::span<const S> knots,
                                                           CubicEnd end, const Vec<S, Dim>& start_tangent,
                                                           const Vec<S, Dim>& end_tangent,
                                                           std::span<Vec<S, Dim>> tangents) noexcept {
  using detail::Checked;
  const std::size_t n = points.size();
  const bool closed = end == CubicEnd::Closed;
  if (n < (closed ? 3u : 2u)) return fail(Error::TooFewPoints, n);
  if (n > Capacity) return fail(Error::CapacityExceeded, n);
  if (tangents.size() < n) return fail(Error::BufferTooSmall, n);
  CURVESTEP_CHECK(detail::check_interpolation_points(points));
  CURVESTEP_CHECK(detail::check_interpolation_knots(knots, closed ? n + 1 : n));
  std::array<S, Capacity> lower{};
  std::array<S, Capacity> diagonal{};
  std::array<S, Capacity> upper{};
  std::array<S, 2 * Capacity> scratch{};
  const std::size_t segments = closed ? n : n - 1;
  const Checked<S> three(from_int<S>(3));
  // Row j couples segment j−1 (before the knot) and segment j (after it).
  for (std::size_t j = 0; j < n; ++j) {
    const bool first = j == 0;
    const bool last = j + 1 == n;
    if ((first || last) && end == CubicEnd::Clamped) {
      diagonal[j] = from_int<S>(1);
      tangents[j] = first ? start_tangent : end_tangent;
      continue;
    }
    const std::size_t before = first ? segments - 1 : j - 1;  // wraps only when closed
    const std::size_t after = j;
    const std::size_t after_next = after + 1 == n ? 0 : after + 1;
    const bool has_before = closed || !first;
    const bool has_after = closed || !last;
    S lambda{};
    S mu{};
    Checked<S> h_before{};
    Checked<S> h_after{};
    if (has_before) {
      CURVESTEP_TRY(h_before, detail::knot_interval(knots, before));
    }
    if (has_after) {
      CURVESTEP_TRY(h_after, detail::knot_interval(knots, after));
    }
    if (has_before && has_after) {
      CURVESTEP_TRY(lambda, (h_after / (h_before + h_after)).result());
      CURVESTEP_TRY(mu, (Checked<S>(from_int<S>(1)) - Checked<S>(lambda)).result());
    } else {
      // natural end: 2v_0 + v_1 = 3δ_0 (lambda = 0, mu = 1) or v_{n−2} + 2v_{n−1} = 3δ_{n−2}
      lambda = has_before ? from_int<S>(1) : S{};
      mu = has_after ? from_int<S>(1) : S{};
    }
    diagonal[j] = from_int<S>(2);
    lower[j] = lambda;
    upper[j] = mu;
    for (std::size_t axis = 0; axis < Dim; ++axis) {
      Checked<S> rhs{};
      if (has_after) {
        const Checked<S> slope = (Checked<S>(points[after_next][axis]) - Checked<S>(points[after][axis])) / h_after;
        rhs = rhs + Checked<S>(mu) * slope;
      }
      if (has_before) {
        const Checked<S> slope = (Checked<S>(points[j][axis]) - Checked<S>(points[before][axis])) / h_before;
        rhs = rhs + Checked<S>(lambda) * slope;
      }
      const auto value = (three * rhs).result();
      if (!value) return fail(value.error(), j);
      tangents[j][axis] = value.value();
    }
  }
  const auto values = tangents.first(n);
  if (closed) {
    return solve_cyclic_tridiagonal<S>(std::span<const S>(lower.data(), n), std::span<const S>(diagonal.data(), n),
                                       std::span<const S>(upper.data(), n), values, std::span<S>(scratch.data(), 2 * n));
  }
  return solve_tridiagonal<S>(std::span<const S>(lower.data(), n), std::span<const S>(diagonal.data(), n),
                              std::span<const S>(upper.data(), n), values, std::span<S>(scratch.data(), n));
}

/// The natural C2 cubic spline through `points` at `knots` (same count), into `out`.
/// Errors as cubic_spline_tangents; CapacityExceeded if out cannot hold points.size() − 1 segments.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxSegments>
  requires(MaxDegree >= 3)
[[nodiscard]] constexpr Result<void> interpolate_natural_cubic(std::span<const Vec<S, Dim>> points, std::span<const S> knots,
                                                               CompositeBezier<S, Dim, MaxDegree, MaxSegments>& out) noexcept {
  std::array<Vec<S, Dim>, MaxSegments + 1> tangents{};
  CURVESTEP_CHECK((cubic_spline_tangents<MaxSegments + 1>(points, knots, CubicEnd::Natural, Vec<S, Dim>{}, Vec<S, Dim>{},
                                                          std::span<Vec<S, Dim>>(tangents))));
  return detail::assemble_hermite(points, std::span<const Vec<S, Dim>>(tangents.data(), points.size()), knots,
                                  points.size() - 1, out);
}

/// The clamped C2 cubic spline with s'(u_0) = start_tangent and s'(u_n) = end_tangent.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxSegments>
  requires(MaxDegree >= 3)
[[nodiscard]] constexpr Result<void> interpolate_clamped_cubic(std::span<const Vec<S, Dim>> points, std::span<const S> knots,
                                                               const Vec<S, Dim>& start_tangent, const Vec<S, Dim>& end_tangent,
                                                               CompositeBezier<S, Dim, MaxDegree, MaxSegments>& out) noexcept {
  std::array<Vec<S, Dim>, MaxSegments + 1> tangents{};
  CURVESTEP_CHECK((cubic_spline_tangents<MaxSegments + 1>(points, knots, CubicEnd::Clamped, start_tangent, end_tangent,
                                                          std::span<Vec<S, Dim>>(tangents))));
  return detail::assemble_hermite(points, std::span<const Vec<S, Dim>>(tangents.data(), points.size()), knots,
                                  points.size() - 1, out);
}

/// The closed (periodic) C2 cubic spline through the m >= 3 points (do not repeat the first);
/// knots has m + 1 entries, the last one closing the curve. m segments into `out`.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxSegments>
  requires(MaxDegree >= 3)
[[nodiscard]] constexpr Result<void> interpolate_closed_cubic(std::span<const Vec<S, Dim>> points, std::span<const S> knots,
                                                              CompositeBezier<S, Dim, MaxDegree, MaxSegments>& out) noexcept {
  std::array<Vec<S, Dim>, MaxSegments> tangents{};
  CURVESTEP_CHECK((cubic_spline_tangents<MaxSegments>(points, knots, CubicEnd::Closed, Vec<S, Dim>{}, Vec<S, Dim>{},
                                                      std::span<Vec<S, Dim>>(tangents))));
  return detail::assemble_hermite(points, std::span<const Vec<S, Dim>>(tangents.data(), points.size()), knots, points.size(),
                                  out);
}

/// Natural spline with knots from a parametrization (u_0 = 0).
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxSegments>
  requires(MaxDegree >= 3)
[[nodiscard]] constexpr Result<void> interpolate_natural_cubic(std::span<const Vec<S, Dim>> points, Parametrization kind,
                                                               CompositeBezier<S, Dim, MaxDegree, MaxSegments>& out) noexcept {
  if (points.size() > MaxSegments + 1) return fail(Error::CapacityExceeded, points.size());
  return detail::with_parametrized_knots<MaxSegments>(points, kind, Closure::Open, [&](std::span<const S> knots) {
    return interpolate_natural_cubic(points, knots, out);
  });
}

/// Clamped spline with knots from a parametrization (u_0 = 0); tangents are derivatives in u.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxSegments>
  requires(MaxDegree >= 3)
[[nodiscard]] constexpr Result<void> interpolate_clamped_cubic(std::span<const Vec<S, Dim>> points, Parametrization kind,
                                                               const Vec<S, Dim>& start_tangent, const Vec<S, Dim>& end_tangent,
                                                               CompositeBezier<S, Dim, MaxDegree, MaxSegments>& out) noexcept {
  if (points.size() > MaxSegments + 1) return fail(Error::CapacityExceeded, points.size());
  return detail::with_parametrized_knots<MaxSegments>(points, kind, Closure::Open, [&](std::span<const S> knots) {
    return interpolate_clamped_cubic(points, knots, start_tangent, end_tangent, out);
  });
}

/// Closed spline with knots from a parametrization, including the closing chord.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxSegments>
  requires(MaxDegree >= 3)
[[nodiscard]] constexpr Result<void> interpolate_closed_cubic(std::span<const Vec<S, Dim>> points, Parametrization kind,
                                                              CompositeBezier<S, Dim, MaxDegree, MaxSegments>& out) noexcept {
  if (points.size() > MaxSegments) return fail(Error::CapacityExceeded, points.size());
  return detail::with_parametrized_knots<MaxSegments>(points, kind, Closure::Closed, [&](std::span<const S> knots) {
    return interpolate_closed_cubic(points, knots, out);
  });
}

}  // namespace curvestep
