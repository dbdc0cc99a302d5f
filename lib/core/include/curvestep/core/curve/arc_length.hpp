// SPDX-License-Identifier: MIT
// Arc length L = ∫ |r'(t)| dt by adaptive Gauss–Legendre quadrature.
//
// Each interval is integrated with the 5-point rule (exact for polynomials of degree 9, so a
// cubic's speed, a square root of a quartic, converges fast). An interval is accepted when the
// rule on it and the sum of the rule on its two halves differ by at most its share of the
// tolerance; otherwise both halves are pushed on a fixed-size stack (no recursion, no heap).
// The tolerance is absolute (curve units). Cusps (|r'| not smooth) converge slowly but surely
// until the stack depth limit, which reports IterationLimit instead of looping.
#pragma once

#include <array>
#include <cstddef>

#include <curvestep/core/curve/curve_concept.hpp>
#include <curvestep/core/geometry/vec.hpp>

namespace curvestep {

namespace detail {
// Gauss–Legendre 5-point nodes on [-1,1] and weights (Abramowitz & Stegun 25.4.30).
inline constexpr std::array<double, 5> gauss_legendre_5_nodes{
    -0.906179845938663992797627, -0.538469310105683091036314, 0.0, 0.538469310105683091036314,
    0.906179845938663992797627};
inline constexpr std::array<double, 5> gauss_legendre_5_weights{
    0.236926885056189087514264, 0.478628670499366468041982, 0.568888888888888888888889,
    0.478628670499366468041982, 0.236926885056189087514264};
/// The same nodes and weights in S, converted at compile time (no runtime double maths on an MCU).
template <Scalar S>
inline constexpr std::array<S, 5> gauss_legendre_5_nodes_as{
    constant<S>(gauss_legendre_5_nodes[0]), constant<S>(gauss_legendre_5_nodes[1]), constant<S>(gauss_legendre_5_nodes[2]),
    constant<S>(gauss_legendre_5_nodes[3]), constant<S>(gauss_legendre_5_nodes[4])};
template <Scalar S>
inline constexpr std::array<S, 5> gauss_legendre_5_weights_as{
    constant<S>(gauss_legendre_5_weights[0]), constant<S>(gauss_legendre_5_weights[1]),
    constant<S>(gauss_legendre_5_weights[2]), constant<S>(gauss_legendre_5_weights[3]),
    constant<S>(gauss_legendre_5_weights[4])};

/// ∫_a^b |r'| by the 5-point rule.
template <ParametricCurve C>
[[nodiscard]] constexpr Result<typename C::scalar_type> gauss_legendre_speed(const C& curve, typename C::scalar_type a,
                                                                              typename C::scalar_type b) {
  using S = typename C::scalar_type;
  const S half_width = (b - a) / from_int<S>(2);
  const S middle = a + half_width;
  S sum{};
  for (std::size_t k = 0; k < 5; ++k) {
    const S node = gauss_legendre_5_nodes_as<S>[k];
    const S weight = gauss_legendre_5_weights_as<S>[k];
    S t = middle + half_width * node;
    if (t < a) t = a;
    if (b < t) t = b;
    CURVESTEP_TRY(const auto d, curve.derivative_at(t, 1));
    // Each term scaled by the half width first: Σ w_k = 2, so Σ w_k |r'| alone could leave the
    // Fixed range for speeds above half of it although the integral over [a,b] ⊆ [0,1] does not.
    sum = sum + weight * (norm(d) * half_width);
  }
  return sum;
}
}  // namespace detail

/// Arc length of the curve between parameters t0 <= t1 to within `tolerance` (absolute).
/// InvalidTolerance if tolerance <= 0; IterationLimit if the stack of 48 intervals overflows.
template <ParametricCurve C>
[[nodiscard]] constexpr Result<typename C::scalar_type> arc_length(const C& curve, typename C::scalar_type t0,
                                                                    typename C::scalar_type t1,
                                                                    typename C::scalar_type tolerance) {
  using S = typename C::scalar_type;
  if (!(S{} < tolerance)) return fail(Error::InvalidTolerance);
  if (t1 < t0) return fail(Error::InvalidInterval);
  if (t0 == t1) return S{};
  struct Interval {
    S a, b, whole, tolerance;
  };
  constexpr std::size_t stack_capacity = 48;
  std::array<Interval, stack_capacity> stack{};
  std::size_t size = 0;
  // Start from four equal pieces, not one: on a single interval the 5-point rule and the sum over
  // its halves can agree by coincidence while both are off by far more than the tolerance (a
  // 93 mm cubic whose speed varies from 40 to 400 came out 0.18 long with tolerance 0.01).
  constexpr int pieces = 4;
  const S quarter = (t1 - t0) / from_int<S>(pieces);
  S piece_tolerance = tolerance / from_int<S>(pieces);
  if (!(S{} < piece_tolerance)) piece_tolerance = tolerance;
  for (int k = pieces; k-- > 0;) {
    const S a = k == 0 ? t0 : t0 + quarter * from_int<S>(k);
    const S b = k == pieces - 1 ? t1 : t0 + quarter * from_int<S>(k + 1);
    if (!(a < b)) continue;  // below the parameter resolution
    CURVESTEP_TRY(const S whole, detail::gauss_legendre_speed(curve, a, b));
    stack[size++] = Interval{a, b, whole, piece_tolerance};
  }
  S total{};
  std::size_t evaluations = 0;
  constexpr std::size_t evaluation_limit = 4096;
  while (size > 0) {
    const Interval iv = stack[--size];
    const S middle = iv.a + (iv.b - iv.a) / from_int<S>(2);
    CURVESTEP_TRY(const S left, detail::gauss_legendre_speed(curve, iv.a, middle));
    CURVESTEP_TRY(const S right, detail::gauss_legendre_speed(curve, middle, iv.b));
    evaluations += 2;
    const S refined = left + right;
    const bool resolution_reached = !(iv.a < middle) || !(middle < iv.b);
    // Accept with a safety factor of 4: the difference estimates the error of the coarse rule
    // only asymptotically (a 175 mm cubic came out 0.0101 short with tolerance 0.01 without it).
    if (abs(refined - iv.whole) * from_int<S>(4) <= iv.tolerance || resolution_reached) {
      total = total + refined;
      continue;
    }
    if (size + 2 > stack_capacity || evaluations > evaluation_limit) return fail(Error::IterationLimit);
    S half_tolerance = iv.tolerance / from_int<S>(2);
    if (!(S{} < half_tolerance)) half_tolerance = iv.tolerance;
    stack[size++] = Interval{middle, iv.b, right, half_tolerance};
    stack[size++] = Interval{iv.a, middle, left, half_tolerance};
  }
  return total;
}

}  // namespace curvestep
