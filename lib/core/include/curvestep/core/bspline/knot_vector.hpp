// SPDX-License-Identifier: MIT
// Knot vectors: validation, span lookup and the uniform clamped / periodic constructions.
//
// A B-spline of degree p with n+1 control points has m+1 = n+p+2 knots u_0 <= ... <= u_m.
// Its domain is [u_p, u_{n+1}]: there the p+1 basis functions that are non-zero on each knot
// span sum to one. Three layouts are common:
//   * clamped (open): u_0 = ... = u_p and u_{n+1} = ... = u_m; the curve starts at P_0 and
//     ends at P_n, tangent to the first and last legs of the control polygon;
//   * unclamped: any other non-decreasing vector; the curve generally touches no control point;
//   * periodic (closed): equal spacing pattern repeated, u_{j+1} − u_j = λ_{j mod N}, with the
//     first p control points repeated at the end (N distinct points, N + p stored), so the
//     curve closes on itself with C^{p−1} continuity at the seam (seed 004 Def 3.2).
//
// Span lookup is a binary search for the s in [p, n] with u_s <= u < u_{s+1}. Half-open spans
// leave the right end of the domain in no span; the explicit rule used everywhere in this
// library is that u = u_{n+1} belongs to the last non-empty span, so the curve's value there is
// its limit from the left (for a clamped curve, P_n: the last basis function is 1 there).
//
// Validation (validate_knots) accepts a knot value repeated at most p+1 times, and at most p
// times strictly inside the domain (where p+1 would break the curve); it also requires a
// non-empty domain and, for fixed point, that the whole knot range fits the format so every
// knot difference can be formed without overflow.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/core/bspline/detail/ratio.hpp>
#include <curvestep/core/contract.hpp>
#include <curvestep/core/result.hpp>
#include <curvestep/core/scalar.hpp>

namespace curvestep {

/// Number of knots a B-spline of `degree` with `control_count` control points needs.
[[nodiscard]] constexpr std::size_t knot_count(std::size_t control_count, std::size_t degree) noexcept {
  return control_count + degree + 1;
}

namespace detail {
/// The checks every use of a knot vector needs: finite (NotFinite, index = knot), non-decreasing
/// (KnotsNotNondecreasing, index = knot), a range the scalar can subtract (FixedOverflow /
/// NotFinite, index = last knot) and a non-empty domain [u_degree, u_{size−degree−1}]
/// (InvalidInterval). Contract: knots.size() >= 2·degree + 2.
template <Scalar S>
[[nodiscard]] constexpr Result<void> check_knot_order(std::span<const S> knots, std::size_t degree) noexcept {
  CURVESTEP_EXPECTS(knots.size() >= 2 * degree + 2);
  for (std::size_t i = 0; i < knots.size(); ++i) {
    if (!is_finite(knots[i])) return fail(Error::NotFinite, i);
  }
  for (std::size_t i = 1; i < knots.size(); ++i) {
    if (knots[i] < knots[i - 1]) return fail(Error::KnotsNotNondecreasing, i);
  }
  if (const auto range = checked_sub(knots.back(), knots.front()); !range) return fail(range.error(), knots.size() - 1);
  if (!(knots[degree] < knots[knots.size() - degree - 1])) return fail(Error::InvalidInterval, degree);
  return ok();
}
}  // namespace detail

/// Checks `knots` for a B-spline of `degree` >= 1 with `control_count` control points.
/// Errors, in the order checked: TooFewPoints (fewer than degree+1 points), WrongKnotCount
/// (index = knots.size()), NotFinite (index = knot),
/// KnotsNotNondecreasing (index = the knot smaller than its predecessor), FixedOverflow / NotFinite
/// (knot range wider than the scalar's range, index = last knot), InvalidInterval (empty domain
/// u_p == u_{n+1}), KnotMultiplicityTooHigh (index = the first knot of a run that is too long:
/// more than degree inside the domain, more than degree+1 anywhere).
template <Scalar S>
[[nodiscard]] constexpr Result<void> validate_knots(std::span<const S> knots, std::size_t degree,
                                                   std::size_t control_count) noexcept {
  if (control_count < degree + 1) return fail(Error::TooFewPoints, control_count);
  if (knots.size() != knot_count(control_count, degree)) return fail(Error::WrongKnotCount, knots.size());
  CURVESTEP_CHECK(detail::check_knot_order(knots, degree));
  const S start = knots[degree];
  const S end = knots[control_count];
  std::size_t run_start = 0;
  for (std::size_t i = 1; i <= knots.size(); ++i) {
    if (i < knots.size() && knots[i] == knots[run_start]) continue;
    const std::size_t run = i - run_start;
    const bool interior = start < knots[run_start] && knots[run_start] < end;
    if (run > degree + 1 || (interior && run > degree)) return fail(Error::KnotMultiplicityTooHigh, run_start);
    run_start = i;
  }
  return ok();
}

/// How many knots equal `value`.
template <Scalar S>
[[nodiscard]] constexpr std::size_t knot_multiplicity(std::span<const S> knots, S value) noexcept {
  std::size_t count = 0;
  for (const S& knot : knots) count += knot == value ? 1U : 0U;
  return count;
}

/// The knot span s in [degree, n] holding u: u_s <= u < u_{s+1}, and at the right end of the
/// domain the last non-empty span. Binary search, O(log n). Contract: the knots passed
/// validate_knots for this degree. NotFinite for NaN/inf, ParameterOutOfRange outside [u_p, u_{n+1}].
template <Scalar S>
[[nodiscard]] constexpr Result<std::size_t> find_span(std::span<const S> knots, std::size_t degree, S u) noexcept {
  CURVESTEP_EXPECTS(knots.size() >= 2 * degree + 2);
  if (!is_finite(u)) return fail(Error::NotFinite);
  const std::size_t last = knots.size() - degree - 2;  // n, the last control point index
  if (u < knots[degree] || knots[last + 1] < u) return fail(Error::ParameterOutOfRange);
  const bool at_end = u == knots[last + 1];
  // Largest s in [degree, last] with u_s <= u (u_s < u at the domain end): the predicate is
  // true at low and false at high (exclusive bound).
  std::size_t low = degree;
  std::size_t high = last + 1;
  while (high - low > 1) {
    const std::size_t middle = low + (high - low) / 2;
    const bool before = at_end ? knots[middle] < u : !(u < knots[middle]);
    if (before) {
      low = middle;
    } else {
      high = middle;
    }
  }
  return low;
}

/// Writes the uniform clamped knot vector for `control_count` points of `degree` on [start, end]:
/// degree+1 copies of start, the interior knots start + (end−start)·j/(n−p+1), degree+1 copies of end.
/// Returns the number of knots written. DegreeTooLow (degree 0), TooFewPoints (fewer than
/// degree+1 points), InvalidInterval (end <= start, or a range too small for distinct knots),
/// NotFinite, FixedOverflow, BufferTooSmall (index = knots needed).
template <Scalar S>
[[nodiscard]] constexpr Result<std::size_t> uniform_clamped_knots(std::size_t control_count, std::size_t degree, S start,
                                                                  S end, std::span<S> out) noexcept {
  if (degree == 0) return fail(Error::DegreeTooLow);
  if (control_count < degree + 1) return fail(Error::TooFewPoints, control_count);
  if (!is_finite(start) || !is_finite(end)) return fail(Error::NotFinite);
  if (!(start < end)) return fail(Error::InvalidInterval);
  const std::size_t count = knot_count(control_count, degree);
  if (out.size() < count) return fail(Error::BufferTooSmall, count);
  CURVESTEP_TRY(const S width, checked_sub(end, start));
  const auto spans = static_cast<std::int64_t>(control_count - degree);
  for (std::size_t i = 0; i <= degree; ++i) {
    out[i] = start;
    out[count - 1 - i] = end;
  }
  for (std::size_t j = 1; j < control_count - degree; ++j) {
    CURVESTEP_TRY(const S offset, detail::scale_ratio(width, static_cast<std::int64_t>(j), spans));
    out[degree + j] = start + offset;
    if (!(out[degree + j - 1] < out[degree + j])) return fail(Error::InvalidInterval, degree + j);
  }
  if (!(out[control_count - 1] < end)) return fail(Error::InvalidInterval, control_count - 1);
  return count;
}

/// Writes the periodic knot vector of a closed curve through `spacings.size()` = N distinct
/// control points: N + 2·degree + 1 knots with u_degree = start and u_{j+1} − u_j = spacings[j mod N]
/// (seed 004 eq. 3.2). The domain is [start, start + Σ spacings]. Returns the number written.
/// DegreeTooLow, TooFewPoints (N < 2), NotFinite / InvalidInterval (spacing <= 0; index = spacing),
/// FixedOverflow, BufferTooSmall (index = knots needed).
template <Scalar S>
[[nodiscard]] constexpr Result<std::size_t> periodic_knots(std::span<const S> spacings, std::size_t degree, S start,
                                                           std::span<S> out) noexcept {
  if (degree == 0) return fail(Error::DegreeTooLow);
  const std::size_t points = spacings.size();
  if (points < 2) return fail(Error::TooFewPoints, points);
  if (!is_finite(start)) return fail(Error::NotFinite);
  for (std::size_t i = 0; i < points; ++i) {
    if (!is_finite(spacings[i])) return fail(Error::NotFinite, i);
    if (!(S{} < spacings[i])) return fail(Error::InvalidInterval, i);
  }
  const std::size_t count = points + 2 * degree + 1;
  if (out.size() < count) return fail(Error::BufferTooSmall, count);
  out[degree] = start;
  for (std::size_t j = degree; j + 1 < count; ++j) {
    CURVESTEP_TRY(out[j + 1], checked_add(out[j], spacings[j % points]));
  }
  for (std::size_t j = degree; j > 0; --j) {
    CURVESTEP_TRY(out[j - 1], checked_sub(out[j], spacings[(j - 1) % points]));
  }
  return count;
}

/// The uniform periodic knot vector for N = `point_count` distinct control points:
/// u_j = start + (j − degree)·spacing, domain [start, start + N·spacing]. Same errors as periodic_knots.
template <Scalar S>
[[nodiscard]] constexpr Result<std::size_t> uniform_periodic_knots(std::size_t point_count, std::size_t degree, S start,
                                                                   S spacing, std::span<S> out) noexcept {
  if (degree == 0) return fail(Error::DegreeTooLow);
  if (point_count < 2) return fail(Error::TooFewPoints, point_count);
  if (!is_finite(start) || !is_finite(spacing)) return fail(Error::NotFinite);
  if (!(S{} < spacing)) return fail(Error::InvalidInterval);
  const std::size_t count = point_count + 2 * degree + 1;
  if (out.size() < count) return fail(Error::BufferTooSmall, count);
  for (std::size_t j = 0; j < count; ++j) {
    const auto steps = static_cast<std::int64_t>(j) - static_cast<std::int64_t>(degree);
    CURVESTEP_TRY(const S offset, detail::scale_ratio(spacing, steps, 1));
    CURVESTEP_TRY(out[j], checked_add(start, offset));
  }
  return count;
}

}  // namespace curvestep
