// SPDX-License-Identifier: MIT
// sin, cos and atan2 built from +, -, *, / only, so they give the same bits on every target.
//
// libm's transcendental functions differ between glibc (host) and newlib (firmware) in the last
// bit, which would break the bit-identical setpoint guarantee. These versions reduce the argument
// with a two-part π/2 (Cody–Waite) and evaluate Taylor polynomials on |x| <= π/4, where the terms
// used bound the truncation error below 1e-16 relative; atan uses two halvings of the argument
// (atan x = 2 atan(x / (1 + sqrt(1 + x²)))) and a Taylor series on |x| <= tan(π/16).
// Accuracy is a few units in the last place: far below any machine's resolution.
#pragma once

#include <cmath>

namespace curvestep::detail {

inline constexpr double pi = 3.14159265358979323846;
inline constexpr double half_pi_high = 1.5707963267341256e+00;   // π/2 rounded to 33 bits
inline constexpr double half_pi_low = 6.0771005065061922e-11;    // π/2 - half_pi_high

/// sin and cos of x (radians), |x| < 1e9.
struct SinCos {
  double sin = 0;
  double cos = 1;
};

[[nodiscard]] constexpr double sin_kernel(double x) noexcept {  // |x| <= π/4
  const double x2 = x * x;
  double term = x;
  double sum = x;
  for (int k = 1; k <= 11; ++k) {
    term = -term * x2 / static_cast<double>((2 * k) * (2 * k + 1));
    sum += term;
  }
  return sum;
}

[[nodiscard]] constexpr double cos_kernel(double x) noexcept {  // |x| <= π/4
  const double x2 = x * x;
  double term = 1;
  double sum = 1;
  for (int k = 1; k <= 11; ++k) {
    term = -term * x2 / static_cast<double>((2 * k - 1) * (2 * k));
    sum += term;
  }
  return sum;
}

[[nodiscard]] constexpr SinCos sin_cos(double x) noexcept {
  // Nearest multiple of π/2 (round half away from zero, done by hand for constexpr).
  const double q = x / (half_pi_high + half_pi_low);
  const auto quadrant = static_cast<long long>(q >= 0 ? q + 0.5 : q - 0.5);
  const double r = (x - static_cast<double>(quadrant) * half_pi_high) - static_cast<double>(quadrant) * half_pi_low;
  const double s = sin_kernel(r);
  const double c = cos_kernel(r);
  switch (((quadrant % 4) + 4) % 4) {
    case 0: return {s, c};
    case 1: return {c, -s};
    case 2: return {-s, -c};
    default: return {-c, s};
  }
}

[[nodiscard]] inline double atan_series(double x) noexcept {  // |x| <= tan(π/16) ≈ 0.199
  const double x2 = x * x;
  double power = x;
  double sum = x;
  for (int k = 1; k <= 22; ++k) {
    power = -power * x2;
    sum += power / static_cast<double>(2 * k + 1);
  }
  return sum;
}

/// atan(x) for any finite x.
[[nodiscard]] inline double atan(double x) noexcept {
  const bool negative = x < 0;
  double a = negative ? -x : x;
  const bool inverted = a > 1;
  if (inverted) a = 1 / a;  // atan a = π/2 - atan(1/a)
  // two halvings: |a| <= 1 -> <= tan(π/8) -> <= tan(π/16)
  a = a / (1 + std::sqrt(1 + a * a));
  a = a / (1 + std::sqrt(1 + a * a));
  double result = 4 * atan_series(a);
  if (inverted) result = pi / 2 - result;
  return negative ? -result : result;
}

/// atan2(y, x) in (-π, π]; 0 for (0, 0).
[[nodiscard]] inline double atan2(double y, double x) noexcept {
  if (x == 0) {
    if (y > 0) return pi / 2;
    if (y < 0) return -pi / 2;
    return 0;
  }
  const double base = atan(y / x);
  if (x > 0) return base;
  return y >= 0 ? base + pi : base - pi;
}

}  // namespace curvestep::detail
