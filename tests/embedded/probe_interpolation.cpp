// SPDX-License-Identifier: MIT
// Probe: Hermite segments, interpolating splines, solvers and subdivision in Q16.16 and float.
#include <array>
#include <span>

#include <curvestep/core/interpolation/catmull_rom.hpp>
#include <curvestep/core/interpolation/cubic_spline.hpp>
#include <curvestep/core/interpolation/hermite.hpp>
#include <curvestep/core/interpolation/parametrization.hpp>
#include <curvestep/core/interpolation/quadratic_spline.hpp>
#include <curvestep/core/interpolation/tridiagonal.hpp>
#include <curvestep/core/subdivision/limit.hpp>
#include <curvestep/core/subdivision/refinable_polygon.hpp>
#include <curvestep/core/subdivision/refine.hpp>
#include <curvestep/core/subdivision/subdivision_mask.hpp>

#include "probe.hpp"

namespace curvestep::probe {
namespace {

template <Scalar S>
void keep(S value) {
  sink = sink + static_cast<std::int32_t>(to_double(value) * 1000);
}

template <Scalar S>
void exercise_interpolation(S quarter) {
  using P = Vec2<S>;
  const S one = from_int<S>(1);
  const S two = one + one;
  const std::array<P, 5> points{P{{S{}, S{}}}, P{{one, two}}, P{{two + one, two + one}}, P{{two + two, S{}}}, P{{two + two + two, one}}};
  const std::span<const P> data(points);
  const std::span<const P> odd = data.first(3);
  const P tangent{{one, one}};

  if (auto basis = hermite_basis(quarter)) keep(basis.value().start_tangent);
  if (auto b = hermite_to_bezier(points[0], points[1], tangent, tangent)) keep(b.value().point_at(quarter)[1]);
  if (auto f = ferguson_coefficients(points[0], points[1], tangent, tangent)) keep(f.value().evaluate(quarter)[0]);

  CompositeBezier<S, 2, 3, 8> curve;
  if (interpolate_natural_cubic(data, Parametrization::ChordLength, curve)) keep(curve.segment(1).point_at(quarter)[0]);
  if (interpolate_clamped_cubic(data, Parametrization::Centripetal, tangent, tangent, curve)) keep(curve.segment(0)[1][1]);
  if (interpolate_closed_cubic(data, Parametrization::Uniform, curve)) keep(curve.segment(4)[2][0]);
  std::array<S, 5> knots{};
  if (auto count = parametrize(data, Parametrization::Uniform, std::span<S>(knots))) {
    const std::span<const S> u(knots.data(), count.value());
    if (interpolate_quadratic(data, u, tangent, curve)) keep(curve.segment(2)[1][0]);
    if (interpolate_quadratic(data, u, tangent, P{{S{}, one}}, curve)) keep(curve.segment(3)[1][1]);
    if (knot_ratios_within_bound(u).value_or(false)) sink = sink + 1;
  }
  if (interpolate_closed_quadratic(odd, Parametrization::Uniform, curve)) keep(curve.segment(0)[1][0]);
  if (interpolate_catmull_rom(data, tangent, tangent, curve)) keep(curve.segment(2)[1][1]);
  if (interpolate_closed_catmull_rom(data, curve)) keep(curve.segment(3)[2][1]);

  std::array<S, 3> band{two, two + two, two};
  std::array<S, 3> values{one, two, one};
  std::array<S, 6> scratch{};
  const std::span<const S> coefficients(band);
  if (solve_cyclic_tridiagonal(coefficients, coefficients, coefficients, std::span<S>(values), std::span<S>(scratch))) {
    keep(values[1]);
  }

  auto polygon = RefinablePolygon<S, 2, 64>::create(data, Boundary::PseudoFinite);
  if (polygon && polygon.value().try_refine(chaikin_mask(), 2)) keep(polygon.value().vertices()[3][0]);
  std::array<P, 16> refined{};
  if (auto r = refine(four_point_mask(), data.first(4), Boundary::Closed, std::span<P>(refined))) keep(refined[r.value().count - 1][1]);
  if (auto r = refine(ternary_quadratic_mask(), data, Boundary::Finite, std::span<P>(refined))) keep(refined[0][0]);
  if (auto l = limit_point(SubdivisionScheme::CubicBSpline, data, 2, Boundary::Closed)) keep(l.value()[0]);
  if (auto b = limit_bezier(SubdivisionScheme::Chaikin, data, 1, Boundary::PseudoFinite)) keep(b.value()[2][1]);
}

}  // namespace

void probe_interpolation() {
  exercise_interpolation<Q16_16>(Q16_16::constant(0.25));
  exercise_interpolation<float>(static_cast<float>(sink) * 1e-9f + 0.25f);
}

}  // namespace curvestep::probe
