// SPDX-License-Identifier: MIT
// Rational (weighted) combination of control points for NURBS de Boor, blossoms and Boehm insertion.
//
// The homogeneous form (w·P, w) makes a rational algorithm polynomial, but in fixed point it
// rounds w to the format's resolution (2^-16 in Q16.16) and the projection A/w then errs by
// |P|·2^-16/w: 1.5 µm for a point 100 mm from the origin, however small the curve. Here the
// points stay Cartesian and only the weights are combined:
//     w = ((den − num)·w_a + num·w_b) / den,     P = P_a + (P_b − P_a)·β,
//     β = num·w_b / ((den − num)·w_a + num·w_b),
// which is the same (1−α, α) step, α = num/den, applied to (w·P, w) and projected. In fixed
// point the weights are carried as 64-bit integers scaled up to about 2^30 (weight_shift), the
// products are exact, β is applied with one rounding, so each step costs half a unit plus
// |P_b − P_a|·2^-30 — independent of where the curve lies and of the weights' resolution.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>

#include <curvestep/core/bspline/detail/ratio.hpp>
#include <curvestep/core/contract.hpp>
#include <curvestep/core/geometry/vec.hpp>
#include <curvestep/core/scalar.hpp>

namespace curvestep::detail {

/// How weights are carried inside rational algorithms: raw 64-bit integers for Fixed, S otherwise.
template <Scalar S>
using WeightRep = std::conditional_t<FixedPoint<S>, std::int64_t, S>;

/// A control point with its weight.
template <Scalar S, std::size_t Dim>
struct WeightedPoint {
  Vec<S, Dim> point{};      ///< Cartesian point
  WeightRep<S> weight{};    ///< positive weight (scaled by 2^shift for Fixed)
};

/// The left shift that brings the largest of `weights` (all positive) to about 2^30 raw (Fixed); 0 for floats.
template <Scalar S>
[[nodiscard]] constexpr int weight_shift(std::span<const S> weights) noexcept {
  if constexpr (FixedPoint<S>) {
    std::uint32_t largest = 1;
    for (const S& w : weights) {
      const auto raw = static_cast<std::uint32_t>(w.raw());
      if (raw > largest) largest = raw;
    }
    const auto width = static_cast<int>(std::bit_width(largest));
    return width < 30 ? 30 - width : 0;
  } else {
    static_cast<void>(weights);
    return 0;
  }
}

/// A weight in the internal representation.
template <Scalar S>
[[nodiscard]] constexpr WeightRep<S> scale_weight(S weight, int shift) noexcept {
  if constexpr (FixedPoint<S>) {
    return static_cast<std::int64_t>(weight.raw()) << shift;
  } else {
    static_cast<void>(shift);
    return weight;
  }
}

/// Back from the internal representation (rounded to nearest; stays positive).
template <Scalar S>
[[nodiscard]] constexpr S unscale_weight(WeightRep<S> weight, int shift) noexcept {
  if constexpr (FixedPoint<S>) {
    const std::int64_t raw = shift > 0 ? (weight + (std::int64_t{1} << (shift - 1))) >> shift : weight;
    return S::from_raw(static_cast<typename S::rep>(raw < 1 ? 1 : raw));
  } else {
    static_cast<void>(shift);
    return weight;
  }
}

/// The rational step between a and b at the knot ratio numerator/denominator.
/// Contract: 0 <= numerator <= denominator, denominator > 0, positive weights.
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr WeightedPoint<S, Dim> rational_lerp(const WeightedPoint<S, Dim>& a, const WeightedPoint<S, Dim>& b,
                                                           S numerator, S denominator) {
  CURVESTEP_EXPECTS(S{} < denominator && !(numerator < S{}) && !(denominator < numerator));
  WeightedPoint<S, Dim> r;
  if constexpr (FixedPoint<S>) {
    using U = std::uint64_t;
    using W = std::int64_t;
    const auto num = static_cast<U>(numerator.raw());
    const auto den = static_cast<U>(denominator.raw());
    // Each product < 2^31·2^31 = 2^62 (weights stay below 2^31), so the sum fits in 63 bits.
    const U right = num * static_cast<U>(b.weight);
    const U total = (den - num) * static_cast<U>(a.weight) + right;
    const auto width = static_cast<int>(std::bit_width(total));
    const int drop = width > 31 ? width - 31 : 0;
    const auto beta_numerator = static_cast<W>(right >> drop);
    const auto beta_denominator = static_cast<W>(total >> drop);  // >= 2^30 once anything is dropped
    for (std::size_t axis = 0; axis < Dim; ++axis) {
      const W difference = W{b.point[axis].raw()} - W{a.point[axis].raw()};  // |.| < 2^33
      r.point[axis] = S::from_raw(static_cast<typename S::rep>(
          W{a.point[axis].raw()} + scale_exactly(difference, beta_numerator, beta_denominator)));
    }
    r.weight = static_cast<W>((total + den / 2) / den);
  } else {
    const S left = (denominator - numerator) * a.weight;
    const S right = numerator * b.weight;
    const S total = left + right;
    const S beta = right / total;
    for (std::size_t axis = 0; axis < Dim; ++axis) r.point[axis] = (S{1} - beta) * a.point[axis] + beta * b.point[axis];
    r.weight = total / denominator;
  }
  return r;
}

}  // namespace curvestep::detail
