// SPDX-License-Identifier: MIT
// Seeding a forward-difference table from Bézier control points: exact sub-curves, Stirling weights.
//
// A seed covers one chunk [k0/N, (k0+K)/N] of a segment stepped at h = 1/N, with K a power of
// two. Its sub-curve control points c_i come from two de Casteljau splits (at k1/N, then at
// k0/k1), each lerp a + round((b-a) k / d) with exact integer k/d, so every level is a convex
// combination rounded once. In the sub-curve's own parameter the step is 1/K = 2^-r, and
//     Δ^j(0) = Σ_{i>=j} a_i j! S(i,j) / K^i,     a_i = C(n,i) Δ^i c_0  (power coefficients)
// where S(i,j) are Stirling numbers of the second kind (Δ_h^j t^i at 0 is h^i j! S(i,j)). The
// division by K^i is a shift, so the only roundings are the lerps and one per term here.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>


namespace curvestep::detail {

/// j! S(i, j): the j-th forward difference of t^i at 0 with step h is h^i times this (i, j <= 5).
inline constexpr std::array<std::array<std::int64_t, 6>, 6> stirling_difference_weights{{
    {1, 0, 0, 0, 0, 0},
    {0, 1, 0, 0, 0, 0},
    {0, 1, 2, 0, 0, 0},
    {0, 1, 6, 6, 0, 0},
    {0, 1, 14, 36, 24, 0},
    {0, 1, 30, 150, 240, 120},
}};

/// C(n, k) for n, k <= 5 (seeding runs every re-seed: no loops or divisions).
inline constexpr std::array<std::array<std::int64_t, 6>, 6> small_binomial{{
    {1, 0, 0, 0, 0, 0},
    {1, 1, 0, 0, 0, 0},
    {1, 2, 1, 0, 0, 0},
    {1, 3, 3, 1, 0, 0},
    {1, 4, 6, 4, 1, 0},
    {1, 5, 10, 10, 5, 1},
}};

/// Number of significant bits of v (0 for 0).
[[nodiscard]] constexpr int bit_width(std::uint64_t v) noexcept {
  int width = 0;
  while (v != 0) {
    ++width;
    v >>= 1;
  }
  return width;
}

/// The largest power of two <= v (v >= 1), as its exponent.
[[nodiscard]] constexpr int floor_log2(std::uint64_t v) noexcept { return bit_width(v) - 1; }

/// round(x * k / d), ties away from zero, exact for |x| < 2^56 and 0 <= k, 0 < d < 2^32.
[[nodiscard]] constexpr std::int64_t multiply_divide_round(std::int64_t x, std::uint64_t k, std::uint64_t d) noexcept {
  const bool negative = x < 0;
  const auto magnitude = static_cast<std::uint64_t>(negative ? -x : x);
  const std::uint64_t high = magnitude >> 24;
  const std::uint64_t low = magnitude & ((std::uint64_t{1} << 24) - 1);
  const std::uint64_t p1 = high * k;  // < 2^64
  const std::uint64_t q1 = p1 / d;
  const std::uint64_t r1 = p1 % d;
  const std::uint64_t p2 = (r1 << 24) + low * k;  // < 2^57
  std::uint64_t q = (q1 << 24) + p2 / d;
  const std::uint64_t r2 = p2 % d;
  if (2 * r2 >= d) ++q;
  const auto signed_q = static_cast<std::int64_t>(q);
  return negative ? -signed_q : signed_q;
}

/// v / 2^bits rounded to nearest, ties away from zero (|v| < 2^62 when bits >= 63).
[[nodiscard]] constexpr std::int64_t round_shift_right(std::int64_t v, int bits) noexcept {
  if (bits <= 0) return v;
  if (bits >= 63) return 0;  // |v| < 2^62 rounds to 0
  const std::int64_t half = std::int64_t{1} << (bits - 1);
  return (v + (v >= 0 ? half : half - 1)) >> bits;
}

/// v * 2^bits modulo 2^64 (the wrap is intended: see the essay in forward_difference.hpp).
[[nodiscard]] constexpr std::uint64_t shift_left_modular(std::int64_t v, int bits) noexcept {
  if (bits >= 64) return 0;
  return static_cast<std::uint64_t>(v) << bits;
}

/// Control points of the sub-curve on [k0/N, k1/N] (0 <= k0 < k1 <= N), one coordinate, in the
/// same integer units as `control`. Each of the 2n lerp levels rounds by at most half a unit.
template <std::size_t Capacity>
[[nodiscard]] constexpr std::array<std::int64_t, Capacity> integer_sub_curve(const std::array<std::int64_t, Capacity>& control,
                                                                             std::size_t degree, std::uint64_t k0,
                                                                             std::uint64_t k1, std::uint64_t steps) noexcept {
  std::array<std::int64_t, Capacity> work = control;
  std::array<std::int64_t, Capacity> left{};
  left[0] = work[0];
  for (std::size_t r = 1; r <= degree; ++r) {
    for (std::size_t i = 0; i + r <= degree; ++i) work[i] += multiply_divide_round(work[i + 1] - work[i], k1, steps);
    left[r] = work[0];
  }
  std::array<std::int64_t, Capacity> sub{};
  work = left;
  sub[degree] = work[degree];
  for (std::size_t r = 1; r <= degree; ++r) {
    for (std::size_t i = 0; i + r <= degree; ++i) work[i] += multiply_divide_round(work[i + 1] - work[i], k0, k1);
    sub[degree - r] = work[degree - r];
  }
  return sub;
}

/// Control points of the sub-curve on [k0/N, k1/N] in floating point (T = double usually).
template <class T, std::size_t Capacity>
[[nodiscard]] constexpr std::array<T, Capacity> floating_sub_curve(const std::array<T, Capacity>& control, std::size_t degree,
                                                                   std::uint64_t k0, std::uint64_t k1,
                                                                   std::uint64_t steps) noexcept {
  std::array<T, Capacity> work = control;
  std::array<T, Capacity> left{};
  const T t1 = static_cast<T>(k1) / static_cast<T>(steps);
  const T s = static_cast<T>(k0) / static_cast<T>(k1);
  left[0] = work[0];
  for (std::size_t r = 1; r <= degree; ++r) {
#pragma GCC unroll 6
    for (std::size_t i = 0; i + r <= degree; ++i) work[i] = work[i] + (work[i + 1] - work[i]) * t1;
    left[r] = work[0];
  }
  std::array<T, Capacity> sub{};
  work = left;
  sub[degree] = work[degree];
  for (std::size_t r = 1; r <= degree; ++r) {
#pragma GCC unroll 6
    for (std::size_t i = 0; i + r <= degree; ++i) work[i] = work[i] + (work[i + 1] - work[i]) * s;
    sub[degree - r] = work[degree - r];
  }
  return sub;
}

/// Power coefficients a_i = C(n,i) Δ^i c_0 of a Bézier coordinate, degree <= 5 (exact for integers).
template <class T, std::size_t Capacity>
[[nodiscard]] constexpr std::array<T, Capacity> power_coefficients(const std::array<T, Capacity>& control,
                                                                   std::size_t degree) noexcept {
  std::array<T, Capacity> differences = control;  // differences[i] becomes Δ^i c_0
  std::array<T, Capacity> power{};
  power[0] = control[0];
  for (std::size_t i = 1; i <= degree; ++i) {
    for (std::size_t k = 0; k + i <= degree; ++k) differences[k] = differences[k + 1] - differences[k];
    power[i] = static_cast<T>(small_binomial[degree][i]) * differences[0];
  }
  return power;
}

}  // namespace curvestep::detail
