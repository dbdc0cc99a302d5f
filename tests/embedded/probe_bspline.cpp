// SPDX-License-Identifier: MIT
// Probe: B-splines, NURBS, knot insertion, Bézier extraction and the basis in Q16.16 and float.
#include <array>

#include <curvestep/core/bspline/basis.hpp>
#include <curvestep/core/bspline/bezier_extraction.hpp>
#include <curvestep/core/bspline/conics.hpp>
#include <curvestep/core/curve/arc_length.hpp>
#include <curvestep/core/curve/curvature.hpp>

#include "probe.hpp"

namespace curvestep::probe {
namespace {

template <class T>
void keep(const Result<T>& r) {
  if (r) sink = sink + 1;
}
template <Scalar S, std::size_t Dim>
void keep(const Vec<S, Dim>& p) {
  sink = sink + static_cast<std::int32_t>(to_double(p[0]) * 1000);
}

template <Scalar S>
void exercise_bspline(S quarter) {
  using P = Vec2<S>;
  const S one = from_int<S>(1);
  const S two = one + one;
  const std::array<P, 6> control{P{{S{}, S{}}}, P{{one, two}}, P{{two, one}}, P{{two + one, two}}, P{{two + two, S{}}},
                                 P{{two + two + one, one}}};
  const auto spline = BSpline<S, 2, 3, 16>::clamped(std::span<const P>(control), 3);
  if (!spline) return;
  const auto& curve = spline.value();
  keep(curve.point_at(quarter));
  keep(curve.derivative_at(quarter, 2));
  keep(curvature(curve, quarter));
  keep(arc_length(curve, S{}, one, constant<S>(0.01)));
  const auto refined = curve.insert_knot(quarter, 2);
  keep(refined);
  std::array<BezierSpan<S, 2, 3>, 8> pieces{};
  keep(extract_bezier(curve, std::span<BezierSpan<S, 2, 3>>(pieces)));
  keep(for_each_bezier(curve, [](const BezierSpan<S, 2, 3>& piece) { keep(piece.curve.point_at(piece.end - piece.start)); }));
  keep(basis_function(curve.knots(), 3, 2, quarter));
  keep(BSpline<S, 2, 3, 16>::closed(std::span<const P>(control), 3));

  const auto circle = nurbs_circle<S, 2, 9>(P{{one, one}}, two);
  if (!circle) return;
  keep(circle.value().evaluate(quarter));
  keep(circle.value().derivative_at(quarter, 1));
  keep(circle.value().insert_knot(quarter / two));
  std::array<RationalBezierSpan<S, 2, 2>, 4> arcs{};
  keep(extract_bezier(circle.value(), std::span<RationalBezierSpan<S, 2, 2>>(arcs)));
}

}  // namespace

void probe_bspline() {
  exercise_bspline<Q16_16>(Q16_16::constant(0.25));
  exercise_bspline<float>(static_cast<float>(sink) * 1e-9f + 0.25f);
}

}  // namespace curvestep::probe
