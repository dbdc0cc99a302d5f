// SPDX-License-Identifier: MIT
// Conversion between the Bézier form Σ b_i B^n_i(t) and the power form Σ a_i t^i.
//
//   a_i = C(n,i) Σ_{k<=i} (-1)^{i-k} C(i,k) b_k        (Bézier -> power; integer weights)
//   b_i = Σ_{k<=i} [C(i,k) / C(n,k)] a_k                (power -> Bézier; rational weights)
// Both are computed as exact integer combinations with one final rounding for Fixed.
// Power coefficients grow with the degree (up to 2^n |b|), so the Bézier -> power direction
// reports FixedOverflow instead of wrapping.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/core/curve/bezier.hpp>

namespace curvestep {

/// Power-form coefficients a_0..a_n of a polynomial curve (first degree+1 entries used).
template <Scalar S, std::size_t Dim, std::size_t MaxDegree>
struct PowerBasis {
  std::array<Vec<S, Dim>, MaxDegree + 1> coefficients{};  ///< a_i, the coefficient of t^i
  std::size_t degree = 0;                                 ///< n

  /// p(t) by Horner's rule. Fixed: the partial sums a_n t^k + ... may leave the range even where
  /// p(t) does not, so they are kept in the wide type (one rounding per step); a result or partial
  /// sum beyond that is a contract violation. Use for t in [0,1] with Fixed.
  [[nodiscard]] constexpr Vec<S, Dim> evaluate(S t) const {
    if constexpr (FixedPoint<S>) {
      using W = typename S::wide;
      Vec<S, Dim> r;
      for (std::size_t axis = 0; axis < Dim; ++axis) {
        W sum = coefficients[degree][axis].raw();
        for (std::size_t i = degree; i-- > 0;) {
          W product = 0;
          CURVESTEP_EXPECTS(!__builtin_mul_overflow(sum, W{t.raw()}, &product));
          sum = S::round_shift(product, S::fraction_bits) + W{coefficients[i][axis].raw()};
        }
        const auto narrowed = S::from_wide(sum);
        CURVESTEP_EXPECTS(narrowed.has_value());
        r[axis] = narrowed.value();
      }
      return r;
    } else {
      Vec<S, Dim> r = coefficients[degree];
      for (std::size_t i = degree; i-- > 0;) r = r * t + coefficients[i];
      return r;
    }
  }
};

/// Bézier -> power form. FixedOverflow/NotFinite (index = coefficient) if a coefficient is out of range.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree>
[[nodiscard]] constexpr Result<PowerBasis<S, Dim, MaxDegree>> to_power_basis(const Bezier<S, Dim, MaxDegree>& curve) noexcept {
  PowerBasis<S, Dim, MaxDegree> power;
  const std::size_t n = curve.degree();
  power.degree = n;
  std::array<std::int64_t, MaxDegree + 1> weights{};
  for (std::size_t i = 0; i <= n; ++i) {
    for (std::size_t k = 0; k <= i; ++k) {
      const std::int64_t sign = ((i - k) % 2 == 0) ? 1 : -1;
      weights[k] = sign * detail::binomial(n, i) * detail::binomial(i, k);
    }
    auto a = detail::exact_combination<S, Dim>(curve.control_points().first(i + 1),
                                               std::span<const std::int64_t>(weights.data(), i + 1), 1);
    if (!a) return fail(a.error(), i);
    power.coefficients[i] = a.value();
  }
  return power;
}

/// Power form -> Bézier control points of the same degree.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree>
[[nodiscard]] constexpr Result<Bezier<S, Dim, MaxDegree>> from_power_basis(const PowerBasis<S, Dim, MaxDegree>& power) noexcept {
  const std::size_t n = power.degree;
  if (n > MaxDegree) return fail(Error::DegreeAboveCapacity, n);
  std::array<Vec<S, Dim>, MaxDegree + 1> points{};
  std::array<std::int64_t, MaxDegree + 1> weights{};
  for (std::size_t i = 0; i <= n; ++i) {
    // Common denominator of C(i,k)/C(n,k) for k <= i, so the sum is exact before one rounding.
    std::int64_t denominator = 1;
    for (std::size_t k = 0; k <= i; ++k) denominator = detail::lcm(denominator, detail::binomial(n, k));
    for (std::size_t k = 0; k <= i; ++k) {
      weights[k] = detail::binomial(i, k) * (denominator / detail::binomial(n, k));
    }
    auto b = detail::exact_combination<S, Dim>(std::span<const Vec<S, Dim>>(power.coefficients.data(), i + 1),
                                               std::span<const std::int64_t>(weights.data(), i + 1), denominator);
    if (!b) return fail(b.error(), i);
    points[i] = b.value();
  }
  return Bezier<S, Dim, MaxDegree>::create(std::span<const Vec<S, Dim>>(points.data(), n + 1));
}

}  // namespace curvestep
