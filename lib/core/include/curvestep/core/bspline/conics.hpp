// SPDX-License-Identifier: MIT
// Exact full circles and ellipses as quadratic NURBS (the 9-point construction).
//
// A quarter of the unit circle is the rational quadratic Bézier curve (1,0), (1,1), (0,1) with
// weights 1, √2/2, 1 (an isosceles control triangle of half-angle θ = 45° has w_1 = cos θ). Four
// such arcs joined at double knots give the closed curve
//     control points  c+a, c+a+b, c+b, c−a+b, c−a, c−a−b, c−b, c+a−b, c+a
//     weights         1, √2/2, 1, √2/2, 1, √2/2, 1, √2/2, 1
//     knots           0, 0, 0, ¼, ¼, ½, ½, ¾, ¾, 1, 1, 1
// which is exactly the circle of radius r for a = (r,0), b = (0,r), and for any two linearly
// independent semi-axis vectors a, b the ellipse {c + a cos φ + b sin φ} (an affine image of the
// circle; a and b are conjugate semi-diameters, in the plane they span when Dim = 3).
// The parametrization is not by arc length: the speed varies by a factor of about 1.4 per quarter.
// It is C¹ as a parametric curve (and G^∞ as a point set); the double knots are where the arcs meet.
//
// Fixed point: √2/2 is rounded to the format (Q16.16: 46341·2^-16, 7.6e-7 too large), which
// turns each quarter into a slightly different conic; the radial error this causes is at most
// 0.243·r·(weight error) ≈ 1.9e-7·r for Q16.16 (0.02 µm at r = 100 mm), plus a few units of
// rounding from evaluation. Floats round √2/2 to their own precision.
#pragma once

#include <array>
#include <cstddef>

#include <curvestep/core/bspline/nurbs.hpp>

namespace curvestep {

/// The ellipse c + a·cos φ + b·sin φ as a 9-point quadratic NURBS on [0,1] (for a ⊥ b, |a| = |b|: a
/// circle). DegenerateCurve if a and b are linearly dependent; FixedOverflow / NotFinite if a
/// control point c ± a ± b is out of range (index = control point).
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxControlPoints>
  requires(MaxDegree >= 2 && MaxControlPoints >= 9)
[[nodiscard]] constexpr Result<Nurbs<S, Dim, MaxDegree, MaxControlPoints>> nurbs_ellipse(const Vec<S, Dim>& center,
                                                                                        const Vec<S, Dim>& a,
                                                                                        const Vec<S, Dim>& b) noexcept {
  // Linear independence: Gram determinant |a|²|b|² − (a·b)² > 0, decided in double (exact enough
  // for a yes/no on data that came from doubles).
  double aa = 0;
  double bb = 0;
  double ab = 0;
  for (std::size_t axis = 0; axis < Dim; ++axis) {
    if (!is_finite(center[axis]) || !is_finite(a[axis]) || !is_finite(b[axis])) return fail(Error::NotFinite);
    aa += to_double(a[axis]) * to_double(a[axis]);
    bb += to_double(b[axis]) * to_double(b[axis]);
    ab += to_double(a[axis]) * to_double(b[axis]);
  }
  if (!(aa * bb - ab * ab > 1e-12 * aa * bb) || aa == 0 || bb == 0) return fail(Error::DegenerateCurve);
  // Multiples of a and b around the square: (1,0), (1,1), (0,1), (−1,1), (−1,0), (−1,−1), (0,−1), (1,−1), (1,0).
  constexpr std::array<int, 9> along_a{1, 1, 0, -1, -1, -1, 0, 1, 1};
  constexpr std::array<int, 9> along_b{0, 1, 1, 1, 0, -1, -1, -1, 0};
  std::array<Vec<S, Dim>, 9> control{};
  for (std::size_t i = 0; i < 9; ++i) {
    for (std::size_t axis = 0; axis < Dim; ++axis) {
      const detail::Checked<S> value = detail::Checked<S>(center[axis]) + detail::Checked<S>(a[axis]) * detail::Checked<S>(from_int<S>(along_a[i])) +
                                       detail::Checked<S>(b[axis]) * detail::Checked<S>(from_int<S>(along_b[i]));
      const auto coordinate = value.result();
      if (!coordinate) return fail(coordinate.error(), i);
      control[i][axis] = coordinate.value();
    }
  }
  const S one = from_int<S>(1);
  const S corner = constant<S>(0.70710678118654752440);  // √2/2 = cos 45°
  const std::array<S, 9> weights{one, corner, one, corner, one, corner, one, corner, one};
  const S quarter = constant<S>(0.25);
  const S half = constant<S>(0.5);
  const S three_quarters = constant<S>(0.75);
  const std::array<S, 12> knots{S{}, S{}, S{}, quarter, quarter, half, half, three_quarters, three_quarters, one, one, one};
  return Nurbs<S, Dim, MaxDegree, MaxControlPoints>::create(std::span<const Vec<S, Dim>>(control),
                                                             std::span<const S>(weights), std::span<const S>(knots), 2);
}

/// The circle of `radius` around `center` in the plane, starting at center + (radius, 0) and
/// running counter-clockwise, as a 9-point quadratic NURBS on [0,1]. DegenerateCurve if
/// radius <= 0; NotFinite; FixedOverflow if the bounding square leaves the range.
template <Scalar S, std::size_t MaxDegree, std::size_t MaxControlPoints>
  requires(MaxDegree >= 2 && MaxControlPoints >= 9)
[[nodiscard]] constexpr Result<Nurbs<S, 2, MaxDegree, MaxControlPoints>> nurbs_circle(const Vec<S, 2>& center,
                                                                                     S radius) noexcept {
  if (!is_finite(radius)) return fail(Error::NotFinite);
  if (!(S{} < radius)) return fail(Error::DegenerateCurve);
  return nurbs_ellipse<S, 2, MaxDegree, MaxControlPoints>(center, Vec<S, 2>{{radius, S{}}}, Vec<S, 2>{{S{}, radius}});
}

}  // namespace curvestep
