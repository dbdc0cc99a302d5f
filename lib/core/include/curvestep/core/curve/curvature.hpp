// SPDX-License-Identifier: MIT
// Curvature κ = |r' × r''| / |r'|^3 of any parametric curve, and the 2D osculating circle.
//
// In 2D the result is signed: positive where the curve turns left (counter-clockwise).
// A zero first derivative (a cusp or a degenerate curve) has no curvature: DegenerateCurve.
// With Fixed scalars |r'|³ and r' × r'' leave the range for any curve of machine size (a 100 mm
// cubic has |r'| ~ 300), so they are never formed in the format: the cross product is exact in
// the wide integer type (2F fraction bits), |r'| is the rounded integer square root of the exact
// sum of squares, and κ = ((r' × r'') / |r'|) / |r'| / |r'| is divided down one |r'| at a time,
// each step rounded to nearest (error about half a unit, plus 3·2^-(F+1)/|r'| relative from the
// rounding of |r'|). Only a κ (or centre) outside the range is FixedOverflow.
#pragma once

#include <array>
#include <cstdint>
#include <limits>

#include <curvestep/core/curve/curve_concept.hpp>
#include <curvestep/core/detail/checked.hpp>
#include <curvestep/core/geometry/vec.hpp>

namespace curvestep {

namespace detail {
/// |v| in raw units of S for raw components |v_i| < 2^32 and Dim <= 3 (exact sum of squares),
/// larger components are shifted down first.
template <std::size_t Dim>
[[nodiscard]] constexpr std::int64_t raw_length(const std::array<std::int64_t, Dim>& v) noexcept {
  static_assert(Dim <= 3, "raw_length sums at most three squares");
  std::uint64_t largest = 0;
  for (const std::int64_t c : v) {
    const auto m = static_cast<std::uint64_t>(c < 0 ? -c : c);
    if (m > largest) largest = m;
  }
  int shift = 0;
  while ((largest >> shift) >= (std::uint64_t{1} << 31)) ++shift;
  std::uint64_t sum = 0;
  for (const std::int64_t c : v) {
    const std::uint64_t m = static_cast<std::uint64_t>(c < 0 ? -c : c) >> shift;
    sum += m * m;
  }
  return static_cast<std::int64_t>(rounded_sqrt(sum) << shift);
}

/// n / d rounded to nearest (ties away from zero), d != 0.
[[nodiscard]] constexpr std::int64_t divide_nearest(std::int64_t n, std::int64_t d) noexcept {
  const bool negative = (n < 0) != (d < 0);
  const auto mn = static_cast<std::uint64_t>(n < 0 ? -n : n);
  const auto md = static_cast<std::uint64_t>(d < 0 ? -d : d);
  const auto q = static_cast<std::int64_t>((mn + md / 2) / md);
  return negative ? -q : q;
}

/// (x << bits) / d rounded; FixedOverflow if x << bits does not fit 63 bits.
[[nodiscard]] constexpr Result<std::int64_t> shift_divide(std::int64_t x, int bits, std::int64_t d) noexcept {
  std::int64_t shifted = 0;
  if (__builtin_mul_overflow(x, std::int64_t{1} << bits, &shifted)) return fail(Error::FixedOverflow);
  return divide_nearest(shifted, d);
}

/// What curvature and the osculating centre need, in raw units of a Fixed S with F fraction
/// bits: speed |r'| (F bits) and (r' × r'') / |r'| (F bits; signed in 2D, its length in 3D).
struct RawCurvatureParts {
  std::int64_t speed = 0;
  std::int64_t cross_over_speed = 0;
};

template <Scalar S, std::size_t Dim>
  requires FixedPoint<S>
[[nodiscard]] constexpr Result<RawCurvatureParts> raw_curvature_parts(const Vec<S, Dim>& d1, const Vec<S, Dim>& d2) noexcept {
  static_assert(sizeof(typename S::rep) <= 4, "raw products must fit 64 bits");
  std::array<std::int64_t, Dim> first{};
  for (std::size_t i = 0; i < Dim; ++i) first[i] = d1[i].raw();
  RawCurvatureParts parts;
  parts.speed = raw_length<Dim>(first);
  if (parts.speed == 0) return fail(Error::DegenerateCurve);
  const auto product = [&](std::size_t i, std::size_t j) {
    return std::int64_t{d1[i].raw()} * std::int64_t{d2[j].raw()} - std::int64_t{d1[j].raw()} * std::int64_t{d2[i].raw()};
  };
  if constexpr (Dim == 2) {
    parts.cross_over_speed = divide_nearest(product(0, 1), parts.speed);
  } else {
    const std::array<std::int64_t, 3> cross{divide_nearest(product(1, 2), parts.speed), divide_nearest(product(2, 0), parts.speed),
                                            divide_nearest(product(0, 1), parts.speed)};
    parts.cross_over_speed = raw_length<3>(cross);
  }
  return parts;
}
}  // namespace detail

/// Curvature at t: signed in 2D, non-negative in 3D. DegenerateCurve where r'(t) = 0.
template <ParametricCurve C>
[[nodiscard]] constexpr Result<typename C::scalar_type> curvature(const C& curve, typename C::scalar_type t) {
  using S = typename C::scalar_type;
  using detail::Checked;
  CURVESTEP_TRY(const auto d1, curve.derivative_at(t, 1));
  CURVESTEP_TRY(const auto d2, curve.derivative_at(t, 2));
  constexpr std::size_t dim = C::Point::dimension;
  static_assert(dim == 2 || dim == 3, "curvature is defined here for 2D and 3D curves");
  if constexpr (FixedPoint<S>) {
    CURVESTEP_TRY(const auto parts, (detail::raw_curvature_parts<S, dim>(d1, d2)));
    CURVESTEP_TRY(const auto over_speed_squared, detail::shift_divide(parts.cross_over_speed, S::fraction_bits, parts.speed));
    CURVESTEP_TRY(const auto kappa, detail::shift_divide(over_speed_squared, S::fraction_bits, parts.speed));
    if (kappa > std::int64_t{std::numeric_limits<typename S::wide>::max()} ||
        kappa < std::int64_t{std::numeric_limits<typename S::wide>::min()}) {
      return fail(Error::FixedOverflow);
    }
    return S::from_wide(static_cast<typename S::wide>(kappa));
  }
  Checked<S> speed_squared{};
  for (std::size_t i = 0; i < dim; ++i) speed_squared = speed_squared + Checked<S>(d1[i]) * Checked<S>(d1[i]);
  if (speed_squared.ok && speed_squared.value == S{}) return fail(Error::DegenerateCurve);
  const Checked<S> speed = detail::checked_sqrt(speed_squared);
  const Checked<S> speed_cubed = speed * speed * speed;
  if (speed_cubed.ok && speed_cubed.value == S{}) return fail(Error::DegenerateCurve);
  if constexpr (dim == 2) {
    const Checked<S> z = Checked<S>(d1[0]) * Checked<S>(d2[1]) - Checked<S>(d1[1]) * Checked<S>(d2[0]);
    return (z / speed_cubed).result();
  } else {
    const Checked<S> cx = Checked<S>(d1[1]) * Checked<S>(d2[2]) - Checked<S>(d1[2]) * Checked<S>(d2[1]);
    const Checked<S> cy = Checked<S>(d1[2]) * Checked<S>(d2[0]) - Checked<S>(d1[0]) * Checked<S>(d2[2]);
    const Checked<S> cz = Checked<S>(d1[0]) * Checked<S>(d2[1]) - Checked<S>(d1[1]) * Checked<S>(d2[0]);
    return (detail::checked_sqrt(cx * cx + cy * cy + cz * cz) / speed_cubed).result();
  }
}

/// Centre of the osculating circle of a 2D curve at t: r + (|r'|^2 / (r' × r'')) (-y', x').
/// DegenerateCurve where the curvature is zero (the circle is a line) or r' = 0.
template <ParametricCurve C>
  requires(C::Point::dimension == 2)
[[nodiscard]] constexpr Result<typename C::Point> osculating_center(const C& curve, typename C::scalar_type t) {
  using S = typename C::scalar_type;
  using detail::Checked;
  CURVESTEP_TRY(const auto p, curve.evaluate(t));
  CURVESTEP_TRY(const auto d1, curve.derivative_at(t, 1));
  CURVESTEP_TRY(const auto d2, curve.derivative_at(t, 2));
  if constexpr (FixedPoint<S>) {
    // centre = r + (|r'|² / (r' × r'')) (-y', x') with |r'|² / (r' × r'') = |r'| / ((r' × r'') / |r'|).
    CURVESTEP_TRY(const auto parts, (detail::raw_curvature_parts<S, 2>(d1, d2)));
    if (parts.cross_over_speed == 0) return fail(Error::DegenerateCurve);
    typename C::Point centre;
    const std::array<std::int64_t, 2> normal{-std::int64_t{d1[1].raw()}, std::int64_t{d1[0].raw()}};
    for (std::size_t i = 0; i < 2; ++i) {
      // |r'| n_i / ((r' × r'') / |r'|): 2F / F fraction bits, one rounding.
      std::int64_t numerator = 0;
      if (__builtin_mul_overflow(parts.speed, normal[i], &numerator)) return fail(Error::FixedOverflow);
      std::int64_t sum = 0;
      if (__builtin_add_overflow(std::int64_t{p[i].raw()}, detail::divide_nearest(numerator, parts.cross_over_speed), &sum)) {
        return fail(Error::FixedOverflow);
      }
      if (sum > std::int64_t{std::numeric_limits<typename S::wide>::max()} ||
          sum < std::int64_t{std::numeric_limits<typename S::wide>::min()}) {
        return fail(Error::FixedOverflow);
      }
      CURVESTEP_TRY(centre[i], S::from_wide(static_cast<typename S::wide>(sum)));
    }
    return centre;
  }
  const Checked<S> z = Checked<S>(d1[0]) * Checked<S>(d2[1]) - Checked<S>(d1[1]) * Checked<S>(d2[0]);
  if (z.ok && z.value == S{}) return fail(Error::DegenerateCurve);
  const Checked<S> k = (Checked<S>(d1[0]) * Checked<S>(d1[0]) + Checked<S>(d1[1]) * Checked<S>(d1[1])) / z;
  const Checked<S> cx = Checked<S>(p[0]) - k * Checked<S>(d1[1]);
  const Checked<S> cy = Checked<S>(p[1]) + k * Checked<S>(d1[0]);
  CURVESTEP_TRY(const S x, cx.result());
  CURVESTEP_TRY(const S y, cy.result());
  return typename C::Point{{x, y}};
}

}  // namespace curvestep
