// SPDX-License-Identifier: MIT
// Knot-ratio arithmetic for the B-spline algorithms: a + (b-a)·num/den and a·b/c with one rounding.
//
// Every B-spline algorithm (de Boor, Boehm, blossoms, Cox–de Boor) combines two values with a
// ratio of knot differences α = (u − u_i)/(u_j − u_i). Rounding α first and then multiplying
// would cost |b − a|·2^-F-1 per step in fixed point (0.8 µm for points 100 mm apart in Q16.16);
// here (b − a)·num/den is computed exactly and rounded once (a 64-bit long division, no 128-bit
// type needed), so each step costs at most half a unit whatever the distance and the knot
// values. Pure integer arithmetic: bit-identical on every target. For float/double these are
// the plain expressions.
#pragma once

#include <cstddef>
#include <cstdint>

#include <curvestep/core/contract.hpp>
#include <curvestep/core/geometry/vec.hpp>
#include <curvestep/core/result.hpp>
#include <curvestep/core/scalar.hpp>

namespace curvestep::detail {

/// round(value·n/d) for |value| < 2^33 and 0 <= n <= d < 2^31, exact (one rounding, ties away
/// from zero) with 64-bit operations only: value is split into 16-bit halves (long division).
[[nodiscard]] constexpr std::int64_t scale_exactly(std::int64_t value, std::int64_t n, std::int64_t d) noexcept {
  const std::int64_t magnitude = value < 0 ? -value : value;
  const std::int64_t high = magnitude >> 16;     // < 2^17
  const std::int64_t low = magnitude & 0xFFFF;   // < 2^16
  const std::int64_t first = high * n;           // < 2^48
  const std::int64_t second = ((first % d) << 16) + low * n;  // < 2^48
  std::int64_t quotient = ((first / d) << 16) + second / d;
  if (2 * (second % d) >= d) ++quotient;
  return value < 0 ? -quotient : quotient;
}

/// a + (b − a)·numerator/denominator. Contract: 0 <= numerator <= denominator, denominator > 0.
/// The result lies between a and b (inclusive) and cannot overflow.
template <Scalar S>
[[nodiscard]] constexpr S ratio_lerp(S a, S b, S numerator, S denominator) {
  CURVESTEP_EXPECTS(S{} < denominator && !(numerator < S{}) && !(denominator < numerator));
  if constexpr (FixedPoint<S>) {
    const std::int64_t difference = std::int64_t{b.raw()} - std::int64_t{a.raw()};
    return S::from_raw(static_cast<typename S::rep>(std::int64_t{a.raw()} +
                                                    scale_exactly(difference, numerator.raw(), denominator.raw())));
  } else {
    const S t = numerator / denominator;
    return (S{1} - t) * a + t * b;
  }
}

/// Component-wise ratio_lerp.
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr Vec<S, Dim> ratio_lerp(const Vec<S, Dim>& a, const Vec<S, Dim>& b, S numerator, S denominator) {
  Vec<S, Dim> r;
  for (std::size_t i = 0; i < Dim; ++i) r[i] = ratio_lerp(a[i], b[i], numerator, denominator);
  return r;
}

/// a·b/c with one rounding. Contract: c != 0. FixedOverflow/NotFinite if the result is out of range.
template <Scalar S>
[[nodiscard]] constexpr Result<S> multiply_divide(S a, S b, S c) noexcept {
  CURVESTEP_EXPECTS(!(c == S{}));
  if constexpr (FixedPoint<S>) {
    using W = typename S::wide;
    return S::from_wide(S::round_divide(W{a.raw()} * W{b.raw()}, W{c.raw()}));
  } else {
    const S r = a * b / c;
    if (!is_finite(r)) return fail(Error::NotFinite);
    return r;
  }
}

/// factor·(b − a)/width with one rounding (a derivative control point coordinate).
/// Contract: width > 0, 0 < factor <= 64. FixedOverflow/NotFinite if the result is out of range.
template <Scalar S>
[[nodiscard]] constexpr Result<S> scaled_difference(S a, S b, int factor, S width) noexcept {
  CURVESTEP_EXPECTS(S{} < width && factor > 0 && factor <= 64);
  if constexpr (FixedPoint<S>) {
    using W = typename S::wide;
    W numerator = 0;
    if (__builtin_mul_overflow((W{b.raw()} - W{a.raw()}) * W{factor}, S::one_raw, &numerator)) {
      return fail(Error::FixedOverflow);
    }
    return S::from_wide(S::round_divide(numerator, W{width.raw()}));
  } else {
    const S r = static_cast<S>(factor) * (b - a) / width;
    if (!is_finite(r)) return fail(Error::NotFinite);
    return r;
  }
}

/// value·numerator/denominator with one rounding. Contract: denominator > 0.
/// FixedOverflow/NotFinite if the result is out of range.
template <Scalar S>
[[nodiscard]] constexpr Result<S> scale_ratio(S value, std::int64_t numerator, std::int64_t denominator) noexcept {
  CURVESTEP_EXPECTS(denominator > 0);
  if constexpr (FixedPoint<S>) {
    using W = typename S::wide;
    W product = 0;
    if (__builtin_mul_overflow(W{value.raw()}, static_cast<W>(numerator), &product)) return fail(Error::FixedOverflow);
    return S::from_wide(S::round_divide(product, static_cast<W>(denominator)));
  } else {
    const S r = value * static_cast<S>(numerator) / static_cast<S>(denominator);
    if (!is_finite(r)) return fail(Error::NotFinite);
    return r;
  }
}

}  // namespace curvestep::detail
