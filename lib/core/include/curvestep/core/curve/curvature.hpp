// SPDX-License-Identifier: MIT
// Curvature κ = |r' × r''| / |r'|^3 of any parametric curve, and the 2D osculating circle.
//
// In 2D the result is signed: positive where the curve turns left (counter-clockwise).
// A zero first derivative (a cusp or a degenerate curve) has no curvature: DegenerateCurve.
// With Fixed scalars every intermediate product is checked (FixedOverflow, never a wrapped value).
#pragma once

#include <curvestep/core/curve/curve_concept.hpp>
#include <curvestep/core/detail/checked.hpp>
#include <curvestep/core/geometry/vec.hpp>

namespace curvestep {

/// Curvature at t: signed in 2D, non-negative in 3D. DegenerateCurve where r'(t) = 0.
template <ParametricCurve C>
[[nodiscard]] constexpr Result<typename C::scalar_type> curvature(const C& curve, typename C::scalar_type t) {
  using S = typename C::scalar_type;
  using detail::Checked;
  CURVESTEP_TRY(const auto d1, curve.derivative_at(t, 1));
  CURVESTEP_TRY(const auto d2, curve.derivative_at(t, 2));
  constexpr std::size_t dim = C::Point::dimension;
  static_assert(dim == 2 || dim == 3, "curvature is defined here for 2D and 3D curves");
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
