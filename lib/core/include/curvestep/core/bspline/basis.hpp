// SPDX-License-Identifier: MIT
// B-spline basis functions N_{i,p}(u) and their derivatives by the Cox–de Boor recursion.
//
//     N_{r,0}(u) = 1 if u_r <= u < u_{r+1}, else 0
//     N_{r,j}(u) = (u − u_r)/(u_{r+j} − u_r) · N_{r,j−1}(u) + (u_{r+j+1} − u)/(u_{r+j+1} − u_{r+1}) · N_{r+1,j−1}(u)
//
// with every quotient whose denominator is zero taken as 0 (the "0/0 := 0" rule, needed at
// repeated knots). Right-end rule: at u = u_{n+1}, the end of the domain, the half-open spans
// would make every N_{r,0} zero; instead N_{s,0} = 1 for the last non-empty span s <= n, so every
// basis function takes its limit from the left there (for a clamped vector N_{n,p}(u_{n+1}) = 1).
//
// Derivatives (seed 004 §3.3, fact 3): N^(k)_{i,p} = p (N^(k−1)_{i,p−1}/(u_{i+p} − u_i)
//                                                     − N^(k−1)_{i+1,p−1}/(u_{i+p+1} − u_{i+1})),
// again with x/0 := 0; orders above p are zero.
//
// These functions are the reference definition: each call validates the knots (O(m)) and runs
// the full triangle for one function (O(p²)). They exist for analysis, for shape editing and as
// an independent check of BSpline, whose de Boor evaluation is the fast path. Values lie in
// [0, 1] (one rounding per term in fixed point); derivatives are checked for overflow.
// The domain is [u_p, u_{n+1}] with n = knots.size() − p − 2; degree 0 is allowed here.
#pragma once

#include <array>
#include <cstddef>
#include <span>

#include <curvestep/core/bspline/detail/ratio.hpp>
#include <curvestep/core/bspline/knot_vector.hpp>
#include <curvestep/core/result.hpp>
#include <curvestep/core/scalar.hpp>

namespace curvestep {

namespace detail {
/// Checks what the basis functions need: enough knots, finite, non-decreasing, non-empty domain.
template <Scalar S>
[[nodiscard]] constexpr Result<void> check_basis_knots(std::span<const S> knots, std::size_t degree, S u) noexcept {
  if (knots.size() < 2 * degree + 2) return fail(Error::WrongKnotCount, knots.size());
  CURVESTEP_CHECK(check_knot_order(knots, degree));
  const std::size_t last = knots.size() - degree - 2;
  if (!is_finite(u)) return fail(Error::NotFinite);
  if (u < knots[degree] || knots[last + 1] < u) return fail(Error::ParameterOutOfRange);
  return ok();
}

/// N_{r,q}(u) for r = index..index+p−q (q = degree − lowered), by the triangle from degree 0.
template <Scalar S, std::size_t MaxDegree>
[[nodiscard]] constexpr Result<std::array<S, MaxDegree + 1>> cox_de_boor(std::span<const S> knots, std::size_t degree,
                                                                          std::size_t index, S u, std::size_t lowered) {
  const std::size_t last = knots.size() - degree - 2;  // n
  const S end = knots[last + 1];
  std::size_t end_span = last;  // the last non-empty span <= n (used only at u == end)
  while (!(knots[end_span] < knots[end_span + 1])) --end_span;
  std::array<S, MaxDegree + 1> n{};
  for (std::size_t r = index; r <= index + degree; ++r) {
    const bool inside = u == end ? r == end_span : !(u < knots[r]) && u < knots[r + 1];
    n[r - index] = inside ? from_int<S>(1) : S{};
  }
  for (std::size_t j = 1; j + lowered <= degree; ++j) {
    for (std::size_t r = index; r + j <= index + degree; ++r) {
      S value{};
      const S rising = knots[r + j] - knots[r];
      if (S{} < rising && !(n[r - index] == S{})) {
        CURVESTEP_TRY(const S term, multiply_divide(u - knots[r], n[r - index], rising));
        value = value + term;
      }
      const S falling = knots[r + j + 1] - knots[r + 1];
      if (S{} < falling && !(n[r - index + 1] == S{})) {
        CURVESTEP_TRY(const S term, multiply_divide(knots[r + j + 1] - u, n[r - index + 1], falling));
        value = value + term;
      }
      n[r - index] = value;
    }
  }
  return n;
}
}  // namespace detail

/// The `order`-th derivative of N_{index,degree}(u) (order 0: the value) on the domain
/// [u_p, u_{n+1}]. Errors: DegreeAboveCapacity (index = degree), WrongKnotCount (fewer than
/// 2·degree+2 knots), NotFinite / KnotsNotNondecreasing (index = knot), InvalidInterval (empty
/// domain), InvalidArgument (index > n), NotFinite / ParameterOutOfRange for u, FixedOverflow /
/// NotFinite if a derivative leaves the range.
template <std::size_t MaxDegree = 15, Scalar S>
[[nodiscard]] constexpr Result<S> basis_derivative(std::span<const S> knots, std::size_t degree, std::size_t index, S u,
                                                   std::size_t order) {
  if (degree > MaxDegree) return fail(Error::DegreeAboveCapacity, degree);
  CURVESTEP_CHECK(detail::check_basis_knots(knots, degree, u));
  if (index > knots.size() - degree - 2) return fail(Error::InvalidArgument, index);
  if (order > degree) return S{};
  CURVESTEP_TRY(auto d, (detail::cox_de_boor<S, MaxDegree>(knots, degree, index, u, order)));
  for (std::size_t m = 1; m <= order; ++m) {
    const std::size_t q = degree - order + m;
    for (std::size_t r = index; r + m <= index + order; ++r) {
      S left{};
      S right{};
      const S rising = knots[r + q] - knots[r];
      if (S{} < rising) {
        CURVESTEP_TRY(left, checked_div(d[r - index], rising));
      }
      const S falling = knots[r + q + 1] - knots[r + 1];
      if (S{} < falling) {
        CURVESTEP_TRY(right, checked_div(d[r - index + 1], falling));
      }
      CURVESTEP_TRY(const S difference, checked_sub(left, right));
      CURVESTEP_TRY(d[r - index], detail::scale_ratio(difference, static_cast<std::int64_t>(q), 1));
    }
  }
  return d[0];
}

/// N_{index,degree}(u) by Cox–de Boor (0/0 := 0, right-end rule); errors as basis_derivative.
template <std::size_t MaxDegree = 15, Scalar S>
[[nodiscard]] constexpr Result<S> basis_function(std::span<const S> knots, std::size_t degree, std::size_t index, S u) {
  return basis_derivative<MaxDegree>(knots, degree, index, u, 0);
}

/// All n+1 basis functions (or their `order`-th derivatives) at u, written to out[0..n].
/// BufferTooSmall (index = n+1) if `out` is shorter; otherwise errors as basis_derivative.
template <std::size_t MaxDegree = 15, Scalar S>
[[nodiscard]] constexpr Result<void> basis_values(std::span<const S> knots, std::size_t degree, S u, std::span<S> out,
                                                  std::size_t order = 0) {
  if (knots.size() < degree + 2) return fail(Error::WrongKnotCount, knots.size());
  const std::size_t functions = knots.size() - degree - 1;
  if (out.size() < functions) return fail(Error::BufferTooSmall, functions);
  for (std::size_t i = 0; i < functions; ++i) {
    CURVESTEP_TRY(out[i], basis_derivative<MaxDegree>(knots, degree, i, u, order));
  }
  return ok();
}

}  // namespace curvestep
