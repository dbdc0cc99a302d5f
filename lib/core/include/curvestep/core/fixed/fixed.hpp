// SPDX-License-Identifier: MIT
// Fixed<Rep, FracBits>: a Q-format number whose arithmetic never wraps silently.
//
// A value v is stored as the integer raw = round(v * 2^FracBits) in Rep. Q16.16 (Rep = int32,
// 16 fraction bits) spans [-32768, 32767.99998] with a resolution of 2^-16 = 15.3 µm/mm^-1:
// as millimetres, ±32 m at 15 nm.
//
// Rounding (documented in docs/fixed_point.md):
//   * multiply:   the exact product in the wide type, rounded to nearest, ties away from zero;
//   * divide:     the exact quotient rounded to nearest, ties away from zero;
//   * from_double: rounded to nearest, ties away from zero.
// Rounding symmetric about zero means f(-x) == -f(x), which keeps mirrored curves mirrored.
//
// Overflow: the operators compute in the wide type and check the result. A result outside the
// range is a contract violation (the board stops; tests see an exception), never a wrapped value.
// Code that takes numbers from outside uses the checked forms (from_double, checked_add, ...),
// which return Result with Error::FixedOverflow, or saturating_* where clamping is wanted.
#pragma once

#include <compare>
#include <concepts>
#include <cstdint>
#include <limits>
#include <type_traits>

#include <curvestep/core/contract.hpp>
#include <curvestep/core/result.hpp>

namespace curvestep {

namespace detail {
template <class Rep>
struct WiderInteger;
template <>
struct WiderInteger<std::int8_t> {
  using type = std::int16_t;
};
template <>
struct WiderInteger<std::int16_t> {
  using type = std::int32_t;
};
template <>
struct WiderInteger<std::int32_t> {
  using type = std::int64_t;
};
/// Deliberately not constexpr: reaching it in a constant expression is a compile error.
inline void fixed_constant_out_of_range() {}
}  // namespace detail

/// The integer type twice as wide as Rep, used for exact intermediate products.
template <class Rep>
using wider_integer_t = typename detail::WiderInteger<Rep>::type;

/// A signed fixed-point number with FracBits fraction bits stored in Rep.
/// Rep must be int8, int16 or int32 (a wider type must exist for exact products).
template <std::signed_integral Rep, int FracBits>
class Fixed {
  static_assert(FracBits > 0, "Fixed needs at least one fraction bit");
  static_assert(FracBits < std::numeric_limits<Rep>::digits,
                "Fixed needs at least one integer bit besides the sign");
  static_assert(sizeof(Rep) <= 4, "Fixed supports Rep up to 32 bits (products need a wider type)");

 public:
  using rep = Rep;
  using wide = wider_integer_t<Rep>;
  static constexpr int fraction_bits = FracBits;
  static constexpr wide one_raw = wide{1} << FracBits;

  /// Zero.
  constexpr Fixed() noexcept = default;

  /// An integer value; out of range is a contract violation (use from_integer for input data).
  constexpr explicit Fixed(int integer) : raw_(checked_raw_integer(static_cast<long long>(integer) * one_raw)) {}

  /// Wraps a raw Q-format integer. Escape hatch: the caller vouches for the scaling.
  [[nodiscard]] static constexpr Fixed from_raw(Rep raw) noexcept {
    Fixed f;
    f.raw_ = raw;
    return f;
  }

  /// The raw Q-format integer (value * 2^FracBits).
  [[nodiscard]] constexpr Rep raw() const noexcept { return raw_; }

  /// An integer from input data: FixedOverflow if it does not fit.
  [[nodiscard]] static constexpr Result<Fixed> from_integer(long long integer) noexcept {
    if (integer > max_integer || integer < min_integer) return fail(Error::FixedOverflow);
    return from_raw(static_cast<Rep>(static_cast<wide>(integer) * one_raw));
  }

  /// A double from input data, rounded to nearest (ties away from zero).
  /// NotFinite for NaN/inf, FixedOverflow outside the range.
  [[nodiscard]] static constexpr Result<Fixed> from_double(double value) noexcept {
    if (value != value || value == std::numeric_limits<double>::infinity() ||
        value == -std::numeric_limits<double>::infinity()) {
      return fail(Error::NotFinite);
    }
    const double scaled = value * static_cast<double>(one_raw);
    const double limit_high = static_cast<double>(std::numeric_limits<Rep>::max()) + 0.5;
    const double limit_low = static_cast<double>(std::numeric_limits<Rep>::min()) - 0.5;
    // Both limits are exclusive: min - 0.5 would round (ties away from zero) to min - 1.
    if (!(scaled < limit_high) || !(scaled > limit_low)) return fail(Error::FixedOverflow);
    return from_raw(static_cast<Rep>(round_half_away(scaled)));
  }

  /// A compile-time constant; a value out of range does not compile.
  [[nodiscard]] static consteval Fixed constant(double value) {
    const auto result = from_double(value);
    if (!result) detail::fixed_constant_out_of_range();  // not constexpr: stops compilation
    return result.value();
  }

  /// The value as a double (exact: every Q value up to 32 bits is a double).
  [[nodiscard]] constexpr double to_double() const noexcept {
    return static_cast<double>(raw_) / static_cast<double>(one_raw);
  }
  /// The value as a float (rounded to float precision).
  [[nodiscard]] constexpr float to_float() const noexcept { return static_cast<float>(to_double()); }

  /// Largest, smallest (most negative) and smallest positive values.
  [[nodiscard]] static constexpr Fixed max() noexcept { return from_raw(std::numeric_limits<Rep>::max()); }
  [[nodiscard]] static constexpr Fixed lowest() noexcept { return from_raw(std::numeric_limits<Rep>::min()); }
  [[nodiscard]] static constexpr Fixed resolution() noexcept { return from_raw(1); }

  // --- arithmetic: exact in the wide type, checked on the way back ---
  [[nodiscard]] constexpr Fixed operator-() const { return from_raw(checked_raw(-wide{raw_})); }
  [[nodiscard]] constexpr Fixed operator+() const noexcept { return *this; }

  [[nodiscard]] friend constexpr Fixed operator+(Fixed a, Fixed b) {
    return from_raw(checked_raw(wide{a.raw_} + wide{b.raw_}));
  }
  [[nodiscard]] friend constexpr Fixed operator-(Fixed a, Fixed b) {
    return from_raw(checked_raw(wide{a.raw_} - wide{b.raw_}));
  }
  [[nodiscard]] friend constexpr Fixed operator*(Fixed a, Fixed b) {
    return from_raw(checked_raw(multiply_raw(a.raw_, b.raw_)));
  }
  [[nodiscard]] friend constexpr Fixed operator/(Fixed a, Fixed b) {
    CURVESTEP_EXPECTS(b.raw_ != 0);
    return from_raw(checked_raw(divide_raw(a.raw_, b.raw_)));
  }
  /// Multiplication and division by an integer (exact for multiplication).
  [[nodiscard]] friend constexpr Fixed operator*(Fixed a, int k) {
    return from_raw(checked_raw_integer(static_cast<long long>(a.raw_) * k));
  }
  [[nodiscard]] friend constexpr Fixed operator*(int k, Fixed a) { return a * k; }
  [[nodiscard]] friend constexpr Fixed operator/(Fixed a, int k) {
    CURVESTEP_EXPECTS(k != 0);
    return from_raw(checked_raw_integer(round_divide_integer(static_cast<long long>(a.raw_), static_cast<long long>(k))));
  }

  constexpr Fixed& operator+=(Fixed b) { return *this = *this + b; }
  constexpr Fixed& operator-=(Fixed b) { return *this = *this - b; }
  constexpr Fixed& operator*=(Fixed b) { return *this = *this * b; }
  constexpr Fixed& operator/=(Fixed b) { return *this = *this / b; }

  friend constexpr bool operator==(Fixed a, Fixed b) noexcept = default;
  friend constexpr auto operator<=>(Fixed a, Fixed b) noexcept = default;

  // --- checked forms for data from outside: errors instead of contract violations ---
  [[nodiscard]] friend constexpr Result<Fixed> checked_add(Fixed a, Fixed b) noexcept {
    return from_wide(wide{a.raw_} + wide{b.raw_});
  }
  [[nodiscard]] friend constexpr Result<Fixed> checked_sub(Fixed a, Fixed b) noexcept {
    return from_wide(wide{a.raw_} - wide{b.raw_});
  }
  [[nodiscard]] friend constexpr Result<Fixed> checked_mul(Fixed a, Fixed b) noexcept {
    return from_wide(multiply_raw(a.raw_, b.raw_));
  }
  [[nodiscard]] friend constexpr Result<Fixed> checked_div(Fixed a, Fixed b) noexcept {
    if (b.raw_ == 0) return fail(Error::DivisionByZero);
    return from_wide(divide_raw(a.raw_, b.raw_));
  }
  /// Clamps to [lowest, max] instead of failing.
  [[nodiscard]] friend constexpr Fixed saturating_add(Fixed a, Fixed b) noexcept {
    return from_raw(saturate(wide{a.raw_} + wide{b.raw_}));
  }
  [[nodiscard]] friend constexpr Fixed saturating_mul(Fixed a, Fixed b) noexcept {
    return from_raw(saturate(multiply_raw(a.raw_, b.raw_)));
  }

  /// Exact product a*b as a wide raw value with 2*FracBits fraction bits (for accumulators).
  [[nodiscard]] static constexpr wide multiply_exact(Fixed a, Fixed b) noexcept {
    return wide{a.raw_} * wide{b.raw_};
  }
  /// Divides a wide value by d, rounding to nearest with ties away from zero.
  [[nodiscard]] static constexpr wide round_divide(wide n, wide d) noexcept {
    const bool negative = (n < 0) != (d < 0);
    const auto magnitude_n = static_cast<std::make_unsigned_t<wide>>(n < 0 ? -n : n);
    const auto magnitude_d = static_cast<std::make_unsigned_t<wide>>(d < 0 ? -d : d);
    const auto q = static_cast<wide>((magnitude_n + magnitude_d / 2) / magnitude_d);
    return negative ? -q : q;
  }
  /// Shifts a wide value right by `bits`, rounding to nearest with ties away from zero.
  [[nodiscard]] static constexpr wide round_shift(wide v, int bits) noexcept {
    if (bits <= 0) return v;
    const wide half = wide{1} << (bits - 1);
    return static_cast<wide>((v + (v >= 0 ? half : half - 1)) >> bits);
  }
  /// Narrows a wide raw value; FixedOverflow if it does not fit.
  [[nodiscard]] static constexpr Result<Fixed> from_wide(wide raw) noexcept {
    if (raw > wide{std::numeric_limits<Rep>::max()} || raw < wide{std::numeric_limits<Rep>::min()}) {
      return fail(Error::FixedOverflow);
    }
    return from_raw(static_cast<Rep>(raw));
  }

 private:
  static constexpr long long max_integer = std::numeric_limits<Rep>::max() >> FracBits;
  static constexpr long long min_integer = std::numeric_limits<Rep>::min() >> FracBits;

  static constexpr wide multiply_raw(Rep a, Rep b) noexcept {
    return round_shift(wide{a} * wide{b}, FracBits);
  }
  static constexpr wide divide_raw(Rep a, Rep b) noexcept {
    return round_divide(wide{a} * one_raw, wide{b});
  }
  /// Narrows a product or quotient computed in long long (int arguments need not fit `wide`).
  static constexpr Rep checked_raw_integer(long long raw) {
    CURVESTEP_EXPECTS(raw <= static_cast<long long>(std::numeric_limits<Rep>::max()) &&
                      raw >= static_cast<long long>(std::numeric_limits<Rep>::min()));
    return static_cast<Rep>(raw);
  }
  /// n / d rounded to nearest, ties away from zero, for |n|, |d| < 2^62.
  static constexpr long long round_divide_integer(long long n, long long d) noexcept {
    const bool negative = (n < 0) != (d < 0);
    const long long magnitude_n = n < 0 ? -n : n;
    const long long magnitude_d = d < 0 ? -d : d;
    const long long q = (magnitude_n + magnitude_d / 2) / magnitude_d;
    return negative ? -q : q;
  }
  static constexpr Rep checked_raw(wide raw) {
    CURVESTEP_EXPECTS(raw <= wide{std::numeric_limits<Rep>::max()} &&
                      raw >= wide{std::numeric_limits<Rep>::min()});
    return static_cast<Rep>(raw);
  }
  static constexpr Rep saturate(wide raw) noexcept {
    if (raw > wide{std::numeric_limits<Rep>::max()}) return std::numeric_limits<Rep>::max();
    if (raw < wide{std::numeric_limits<Rep>::min()}) return std::numeric_limits<Rep>::min();
    return static_cast<Rep>(raw);
  }
  static constexpr long long round_half_away(double scaled) noexcept {
    const double magnitude = scaled < 0 ? -scaled : scaled;
    auto whole = static_cast<long long>(magnitude);  // truncates; magnitude < 2^31 here
    if (magnitude - static_cast<double>(whole) >= 0.5) ++whole;
    return scaled < 0 ? -whole : whole;
  }

  Rep raw_ = 0;
};

/// Q16.16: the default position type (millimetres: ±32 m range, 15 nm resolution).
using Q16_16 = Fixed<std::int32_t, 16>;
/// Q8.24: ±128 range, 6e-8 resolution; curve parameters and ratios.
using Q8_24 = Fixed<std::int32_t, 24>;
/// Q2.30: [-2, 2) at 9.3e-10; unit-interval parameters with headroom.
using Q2_30 = Fixed<std::int32_t, 30>;

/// True for every Fixed<Rep, FracBits>.
template <class T>
inline constexpr bool is_fixed_v = false;
template <std::signed_integral Rep, int FracBits>
inline constexpr bool is_fixed_v<Fixed<Rep, FracBits>> = true;

/// A curvestep fixed-point type.
template <class T>
concept FixedPoint = is_fixed_v<T>;

namespace literals {
/// `1.25_q16` is a Q16_16 constant computed at compile time (no runtime double maths).
consteval Q16_16 operator""_q16(long double value) { return Q16_16::constant(static_cast<double>(value)); }
consteval Q16_16 operator""_q16(unsigned long long value) {
  return Q16_16::constant(static_cast<double>(value));
}
}  // namespace literals

}  // namespace curvestep

/// numeric_limits for Fixed, so generic code can ask for max/lowest/epsilon.
template <std::signed_integral Rep, int FracBits>
class std::numeric_limits<curvestep::Fixed<Rep, FracBits>> {
  using F = curvestep::Fixed<Rep, FracBits>;

 public:
  static constexpr bool is_specialized = true;
  static constexpr bool is_signed = true;
  static constexpr bool is_integer = false;
  static constexpr bool is_exact = true;
  static constexpr bool has_infinity = false;
  static constexpr bool has_quiet_NaN = false;
  static constexpr int digits = std::numeric_limits<Rep>::digits;
  static constexpr int radix = 2;
  static constexpr F min() noexcept { return F::resolution(); }
  static constexpr F max() noexcept { return F::max(); }
  static constexpr F lowest() noexcept { return F::lowest(); }
  static constexpr F epsilon() noexcept { return F::resolution(); }
  static constexpr F round_error() noexcept { return F::from_raw(Rep{1} << (FracBits - 1)); }
};
