// SPDX-License-Identifier: MIT
// The Scalar concept and the few operations every algorithm needs, for float, double and Fixed.
//
// Algorithms are written once against these functions. For Fixed they are exact where they can be
// (lerp uses one rounding of the exact wide product), for floating point they are the obvious
// expressions. The checked_* forms return Result: FixedOverflow for Fixed, NotFinite for floats.
#pragma once

#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>

#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/core/result.hpp>

namespace curvestep {

/// float, double or a curvestep Fixed.
template <class T>
concept Scalar = std::floating_point<T> || FixedPoint<T>;

/// The scalar value of an integer (contract-checked for Fixed).
template <Scalar S>
[[nodiscard]] constexpr S from_int(int value) {
  if constexpr (FixedPoint<S>) {
    return S{value};
  } else {
    return static_cast<S>(value);
  }
}

/// Converts input data to S: NotFinite for NaN/inf, FixedOverflow if out of the Q range.
template <Scalar S>
[[nodiscard]] constexpr Result<S> from_double(double value) noexcept {
  if constexpr (FixedPoint<S>) {
    return S::from_double(value);
  } else {
    if (!std::isfinite(value)) return fail(Error::NotFinite);
    const auto narrowed = static_cast<S>(value);
    if (!std::isfinite(narrowed)) return fail(Error::NotFinite);
    return narrowed;
  }
}

/// A compile-time constant in S (Fixed: consteval, so no runtime double maths).
template <Scalar S>
[[nodiscard]] consteval S constant(double value) {
  if constexpr (FixedPoint<S>) {
    return S::constant(value);
  } else {
    return static_cast<S>(value);
  }
}

/// The value as a double.
template <Scalar S>
[[nodiscard]] constexpr double to_double(S value) noexcept {
  if constexpr (FixedPoint<S>) {
    return value.to_double();
  } else {
    return static_cast<double>(value);
  }
}

/// True unless NaN or infinity (always true for Fixed).
template <Scalar S>
[[nodiscard]] constexpr bool is_finite(S value) noexcept {
  if constexpr (FixedPoint<S>) {
    return true;
  } else {
    return std::isfinite(value);
  }
}

/// The smallest step of S near 1 (Fixed: one raw unit; float: machine epsilon).
template <Scalar S>
[[nodiscard]] constexpr S resolution() noexcept {
  return std::numeric_limits<S>::epsilon();
}

/// (1-t)*a + t*b, checked: FixedOverflow/NotFinite if the result leaves the range. Any t.
/// Fixed: computed as a + (b-a)*t with one rounding of the exact wide product.
template <Scalar S>
[[nodiscard]] constexpr Result<S> checked_lerp(S a, S b, S t) noexcept {
  if constexpr (FixedPoint<S>) {
    using W = typename S::wide;
    const W difference = W{b.raw()} - W{a.raw()};
    W product = 0;
    // An int64 overflow here means |result| >= 2^46 raw units: out of range anyway.
    if (__builtin_mul_overflow(difference, W{t.raw()}, &product)) return fail(Error::FixedOverflow);
    return S::from_wide(W{a.raw()} + S::round_shift(product, S::fraction_bits));
  } else {
    const S r = (S{1} - t) * a + t * b;
    if (!std::isfinite(r)) return fail(Error::NotFinite);
    return r;
  }
}

/// (1-t)*a + t*b. Exact at t = 0 and t = 1; for t in [0,1] it lies between a and b and cannot
/// overflow. Outside [0,1] an out-of-range result is a contract violation (use checked_lerp).
template <Scalar S>
[[nodiscard]] constexpr S lerp(S a, S b, S t) {
  if constexpr (FixedPoint<S>) {
    const auto result = checked_lerp(a, b, t);
    CURVESTEP_EXPECTS(result.has_value());
    return result.value();
  } else {
    return (S{1} - t) * a + t * b;
  }
}

/// |value|.
template <Scalar S>
[[nodiscard]] constexpr S abs(S value) {
  return value < S{} ? -value : value;
}

namespace detail {
/// floor(sqrt(n)) for 64-bit unsigned n, by the bitwise method (no division, deterministic).
[[nodiscard]] constexpr std::uint64_t integer_sqrt(std::uint64_t n) noexcept {
  std::uint64_t root = 0;
  std::uint64_t bit = std::uint64_t{1} << 62;
  while (bit > n) bit >>= 2;
  while (bit != 0) {
    if (n >= root + bit) {
      n -= root + bit;
      root = (root >> 1) + bit;
    } else {
      root >>= 1;
    }
    bit >>= 2;
  }
  return root;
}
}  // namespace detail

/// Square root; contract: value >= 0. Fixed: rounded to nearest, deterministic on every target.
template <Scalar S>
[[nodiscard]] constexpr S sqrt(S value) {
  CURVESTEP_EXPECTS(!(value < S{}));
  if constexpr (FixedPoint<S>) {
    // sqrt(raw / 2^F) * 2^F = sqrt(raw * 2^F); keep one extra bit to round to nearest.
    const auto scaled = static_cast<std::uint64_t>(value.raw()) << (S::fraction_bits + 2);
    const std::uint64_t root2 = detail::integer_sqrt(scaled);  // sqrt * 2
    const std::uint64_t rounded = (root2 + 1) >> 1;
    return S::from_raw(static_cast<typename S::rep>(rounded));
  } else {
    return std::sqrt(value);
  }
}

/// a + b, checked: FixedOverflow (Fixed) or NotFinite (float).
template <Scalar S>
[[nodiscard]] constexpr Result<S> checked_add(S a, S b) noexcept {
  if constexpr (FixedPoint<S>) {
    return checked_add(a, b);
  } else {
    const S r = a + b;
    if (!std::isfinite(r)) return fail(Error::NotFinite);
    return r;
  }
}

/// a - b, checked.
template <Scalar S>
[[nodiscard]] constexpr Result<S> checked_sub(S a, S b) noexcept {
  if constexpr (FixedPoint<S>) {
    return checked_sub(a, b);
  } else {
    const S r = a - b;
    if (!std::isfinite(r)) return fail(Error::NotFinite);
    return r;
  }
}

/// a * b, checked.
template <Scalar S>
[[nodiscard]] constexpr Result<S> checked_mul(S a, S b) noexcept {
  if constexpr (FixedPoint<S>) {
    return checked_mul(a, b);
  } else {
    const S r = a * b;
    if (!std::isfinite(r)) return fail(Error::NotFinite);
    return r;
  }
}

/// a / b, checked: DivisionByZero, FixedOverflow or NotFinite.
template <Scalar S>
[[nodiscard]] constexpr Result<S> checked_div(S a, S b) noexcept {
  if (b == S{}) return fail(Error::DivisionByZero);
  if constexpr (FixedPoint<S>) {
    return checked_div(a, b);
  } else {
    const S r = a / b;
    if (!std::isfinite(r)) return fail(Error::NotFinite);
    return r;
  }
}

}  // namespace curvestep
