// SPDX-License-Identifier: MIT
// Knot-ratio arithmetic for the B-spline algorithms: a + (b-a)·num/den and a·b/c with one rounding.
//
// Every B-spline algorithm (de Boor, Boehm, blossoms, Cox–de Boor) combines two values with a
// ratio of knot differences α = (u − u_i)/(u_j − u_i). Rounding α first and then multiplying
// would cost |b − a|·2^-F-1 per step in fixed point (0.8 µm for points 100 mm apart in Q16.16);
// here the exact product (b − a)·num is formed in the wide integer and divided once, so each
// step costs at most half a unit whatever the distance. If that product cannot be held in 64
// bits (points and knots both huge) the rounded-α form is used instead: still deterministic,
// since both paths are pure integer arithmetic, and still inside [a, b].
// For float/double these are the plain expressions.
#pragma once

#include <cstddef>
#include <cstdint>

#include <curvestep/core/contract.hpp>
#include <curvestep/core/geometry/vec.hpp>
#include <curvestep/core/result.hpp>
#include <curvestep/core/scalar.hpp>

namespace curvestep::detail {

/// a + (b − a)·numerator/denominator. Contract: 0 <= numerator <= denominator, denominator > 0.
/// The result lies between a and b (inclusive) and cannot overflow.
template <Scalar S>
[[nodiscard]] constexpr S ratio_lerp(S a, S b, S numerator, S denominator) {
  CURVESTEP_EXPECTS(S{} < denominator && !(numerator < S{}) && !(denominator < numerator));
  if constexpr (FixedPoint<S>) {
    using W = typename S::wide;
    const W difference = W{b.raw()} - W{a.raw()};
    W product = 0;
    if (!__builtin_mul_overflow(difference, W{numerator.raw()}, &product)) {
      return S::from_raw(static_cast<typename S::rep>(W{a.raw()} + S::round_divide(product, W{denominator.raw()})));
    }
    const W t = S::round_divide(W{numerator.raw()} * S::one_raw, W{denominator.raw()});  // <= one_raw
    return S::from_raw(static_cast<typename S::rep>(W{a.raw()} + S::round_shift(difference * t, S::fraction_bits)));
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
