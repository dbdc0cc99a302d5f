// SPDX-License-Identifier: MIT
// Σ (numerator_k / denominator) * p_k with a single rounding: exact sums in the wide integer for
// Fixed, plain arithmetic with a finiteness check for float/double. Used wherever a curve
// algorithm has integer or rational coefficients (hodographs, degree elevation, basis changes).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/core/geometry/vec.hpp>
#include <curvestep/core/result.hpp>

namespace curvestep::detail {

/// Σ numerators[k] * points[k] / denominator. FixedOverflow/NotFinite if the result is out of range.
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr Result<Vec<S, Dim>> exact_combination(std::span<const Vec<S, Dim>> points,
                                                              std::span<const std::int64_t> numerators,
                                                              std::int64_t denominator) noexcept {
  Vec<S, Dim> r;
  for (std::size_t axis = 0; axis < Dim; ++axis) {
    if constexpr (FixedPoint<S>) {
      using W = typename S::wide;
      W sum = 0;
      for (std::size_t k = 0; k < points.size(); ++k) {
        W term = 0;
        if (__builtin_mul_overflow(W{points[k][axis].raw()}, static_cast<W>(numerators[k]), &term) ||
            __builtin_add_overflow(sum, term, &sum)) {
          return fail(Error::FixedOverflow, k);
        }
      }
      const auto narrowed = S::from_wide(S::round_divide(sum, static_cast<W>(denominator)));
      if (!narrowed) return narrowed.failure();
      r[axis] = narrowed.value();
    } else {
      S sum{};
      for (std::size_t k = 0; k < points.size(); ++k) {
        sum += static_cast<S>(numerators[k]) * points[k][axis];
      }
      sum /= static_cast<S>(denominator);
      if (!is_finite(sum)) return fail(Error::NotFinite);
      r[axis] = sum;
    }
  }
  return r;
}

}  // namespace curvestep::detail
