// SPDX-License-Identifier: MIT
// NURBS against the seed digests (000 TV-15/TV-16, 004 TV-04/TV-15/TV-17), the exact circle and
// ellipse, rational extraction, derivatives and knot insertion, in double, float and Q16.16.
// Where Q16.16 must round an input (a weight), its result is compared with a double evaluation
// of the rounded inputs by the rational Cox–de Boor sum Σ w N P / Σ w N (an independent algorithm).
#include <array>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/bspline/basis.hpp>
#include <curvestep/core/bspline/bezier_extraction.hpp>
#include <curvestep/core/bspline/conics.hpp>
#include <curvestep/core/curve/arc_length.hpp>
#include <curvestep/core/curve/curvature.hpp>
#include <curvestep/core/curve/curve_concept.hpp>
#include <support/numeric.hpp>

#include "random_curves.hpp"

using namespace curvestep;
using namespace curvestep::testing;  // support/numeric.hpp and the folder's helpers

namespace {
template <class S>
using Rational = Nurbs<S, 2, 15, 24>;

static_assert(ParametricCurve<Rational<double>>);
static_assert(ParametricCurve<Rational<Q16_16>>);
static_assert(ParametricCurve<BSpline<float, 3, 3, 8>>);

template <class S>
Rational<S> make_nurbs(const std::vector<Vec2<S>>& control, const std::vector<S>& weights, const std::vector<S>& knots,
                       std::size_t degree) {
  const auto made = Rational<S>::create(std::span<const Vec2<S>>(control), std::span<const S>(weights),
                                        std::span<const S>(knots), degree);
  INFO("create failed with error " << static_cast<int>(made.error()) << " at " << made.where());
  REQUIRE(made.has_value());
  return made.value();
}

/// r^(order)(u) for order 0, 1 or 2 from the rational Cox–de Boor sums in double, using the
/// curve's own (possibly rounded) inputs: r = A/w, r' = (A' − w' r)/w, r'' = (A'' − 2w' r' − w'' r)/w.
template <class Curve>
std::array<double, 2> reference(const Curve& curve, double u, std::size_t order) {
  std::vector<double> knots;
  for (const auto& k : curve.knots()) knots.push_back(to_double(k));
  const std::size_t count = curve.size();
  std::array<std::vector<double>, 3> n;
  for (std::size_t k = 0; k <= order; ++k) {
    n[k].resize(count);
    REQUIRE(basis_values(std::span<const double>(knots), curve.degree(), u, std::span<double>(n[k]), k).has_value());
  }
  std::array<std::array<double, 3>, 3> a{};  // a[k] = (A_x^(k), A_y^(k), w^(k))
  for (std::size_t k = 0; k <= order; ++k) {
    for (std::size_t i = 0; i < count; ++i) {
      const double w = to_double(curve.weight(i));
      a[k][0] += n[k][i] * w * to_double(curve.control_points()[i][0]);
      a[k][1] += n[k][i] * w * to_double(curve.control_points()[i][1]);
      a[k][2] += n[k][i] * w;
    }
  }
  std::array<std::array<double, 2>, 3> r{};
  for (std::size_t axis = 0; axis < 2; ++axis) {
    r[0][axis] = a[0][axis] / a[0][2];
    r[1][axis] = (a[1][axis] - a[1][2] * r[0][axis]) / a[0][2];
    r[2][axis] = (a[2][axis] - 2 * a[1][2] * r[1][axis] - a[2][2] * r[0][axis]) / a[0][2];
  }
  return r[order];
}
}  // namespace

TEMPLATE_TEST_CASE("nurbs: 000 TV-15 rational quartic with weights 1 1 3 5 1", "[core][nurbs][seed]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto curve = make_nurbs<S>(points<S>({{0, 0}, {1, 2}, {2, 3}, {3, 2}, {4, 0}}), scalars<S>({1, 1, 3, 5, 1}),
                                   scalars<S>({0, 0, 0, 0, 0, 1, 1, 1, 1, 1}), 4);
  const std::array<double, 3> at{0.25, 0.5, 0.75};
  const std::array<std::array<double, 2>, 3> expected{
      {{154 / 103., 411 / 206.}, {26 / 11., 51 / 22.}, {570 / 199., 795 / 398.}}};
  for (std::size_t k = 0; k < 3; ++k) {
    CHECK(max_error(curve.evaluate(scalar<S>(at[k])).value(), expected[k]) <= tolerance<S>(4, 8));
  }
  CHECK(max_error(curve.evaluate(scalar<S>(1)).value(), {4, 0}) == 0.0);
}

TEMPLATE_TEST_CASE("nurbs: 000 TV-16 and 004 TV-04 rational quadratics", "[core][nurbs][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto control = points<S>({{1, 0}, {1, 1}, {0, 1}});
  const auto knots = scalars<S>({0, 0, 0, 1, 1, 1});
  // √2/2 is rounded in Q16.16: the arc then deviates from the circle by at most 1.9e-7 (conics.hpp).
  const double weight_error = FixedPoint<S> ? 2e-7 : 0;
  const auto quarter = make_nurbs<S>(control, {scalar<S>(1), constant<S>(0.70710678118654752), scalar<S>(1)}, knots, 2);
  CHECK(max_error(quarter.evaluate(scalar<S>(0.5)).value(), {0.707106781186548, 0.707106781186548}) <=
        tolerance<S>(1, 4) + weight_error + 1e-15);
  CHECK(max_error(quarter.evaluate(scalar<S>(0.25)).value(), {0.929788301062430, 0.368094709561873}) <=
        tolerance<S>(1, 4) + weight_error + 1e-15);
  CHECK(to_double(curvature(quarter, scalar<S>(0.3)).value()) == Approx(1).margin(FixedPoint<S> ? 2e-4 : 1e-5));
  // 004 TV-04: w1 = 1.5 moves r(0.5) to (0.8, 0.8).
  const auto moved = make_nurbs<S>(control, scalars<S>({1, 1.5, 1}), knots, 2);
  CHECK(max_error(moved.evaluate(scalar<S>(0.5)).value(), {0.8, 0.8}) <= tolerance<S>(1, 4) + 1e-15);
}

TEMPLATE_TEST_CASE("nurbs: 004 TV-15 weight-modified curves pass through (3.2, 3.0)", "[core][nurbs][seed]", double,
                   float, Q16_16) {
  using S = TestType;
  const auto control = points<S>({{0, 0}, {1, 3}, {3, 4}, {5, 3}, {6, 0}, {8, -1}, {9, 2}});
  const auto knots = scalars<S>({0, 0, 0, 0, 1, 2, 3, 4, 4, 4, 4});
  const std::array<std::array<double, 3>, 2> modified{{{0.1333333333, 0.0265700483, 1}, {0.1022576361, 0.0389552900, 0.7669322707}}};
  for (const auto& w : modified) {
    const auto curve = make_nurbs<S>(control, scalars<S>({1, 1, w[0], w[1], w[2], 1, 1}), knots, 3);
    const auto p = curve.evaluate(scalar<S>(1.5)).value();
    if constexpr (FixedPoint<S>) {
      CHECK(max_error(p, reference(curve, 1.5, 0)) <= tolerance<S>(9, 6));  // weights rounded to 2^-16
    } else {
      CHECK(max_error(p, {3.2, 3.0}) <= tolerance<S>(9, 16) + 5e-10);  // the weights carry 10 digits
    }
  }
}

TEMPLATE_TEST_CASE("nurbs: 004 TV-17 closed rational B-spline of order 16", "[core][nurbs][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto polygon = points<S>({{0, 0}, {4, 0}, {4, 2}, {0, 6}});
  const auto weights = scalars<S>({4, 1, 1, 1});
  const auto curve = Rational<S>::closed(std::span<const Vec2<S>>(polygon), std::span<const S>(weights), 15, scalar<S>(15));
  REQUIRE(curve.has_value());
  CHECK(curve.value().layout() == KnotLayout::Periodic);
  CHECK(curve.value().weight(4) == scalar<S>(4));  // the weights wrap with the points
  CHECK(max_error(curve.value().evaluate(scalar<S>(15.3)).value(), {0.798786, 1.286798}) <= tolerance<S>(6, 32) + 5e-7);
  CHECK(max_error(curve.value().evaluate(scalar<S>(15)).value(), to_doubles(curve.value().evaluate(scalar<S>(19)).value())) <=
        tolerance<S>(6, 32));
}

TEMPLATE_TEST_CASE("nurbs: circle points lie on the circle within the format's resolution", "[core][nurbs][property]",
                   double, float, Q16_16) {
  using S = TestType;
  std::mt19937 random(curvestep::testing::test_seed());
  std::uniform_real_distribution<double> centre(-1000, 1000);
  std::uniform_real_distribution<double> radius_pick(0.5, 500);
  const int cases = curvestep::testing::test_count(200);
  double worst = 0;
  for (int c = 0; c < cases; ++c) {
    const auto middle = point<S>(centre(random), centre(random));
    const S radius = scalar<S>(radius_pick(random));
    const auto circle = nurbs_circle<S, 2, 9>(middle, radius);
    REQUIRE(circle.has_value());
    const double r = to_double(radius);
    const auto m = to_doubles(middle);
    // Q16.16: 1.9e-7·r from the rounded weight √2/2, plus the evaluation's roundings; floats: relative.
    const double bound = FixedPoint<S> ? 1.9e-7 * r + 4 * to_double(resolution<S>())
                                       : 16 * to_double(std::numeric_limits<S>::epsilon()) * (r + std::fabs(m[0]) + std::fabs(m[1]));
    for (int k = 0; k <= 64; ++k) {
      const auto p = to_doubles(circle.value().evaluate(scalar<S>(k / 64.0)).value());
      const double error = std::fabs(std::hypot(p[0] - m[0], p[1] - m[1]) - r);
      worst = std::fmax(worst, error / bound);
      CHECK(error <= bound);
    }
  }
  INFO("worst error / bound = " << worst);
  CHECK(worst <= 1.0);
}

TEMPLATE_TEST_CASE("nurbs: a small circle far from the origin keeps full resolution", "[core][nurbs]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto circle = nurbs_circle<S, 2, 9>(point<S>(20000, -15000), scalar<S>(2));
  REQUIRE(circle.has_value());
  for (int k = 0; k <= 64; ++k) {
    const auto p = to_doubles(circle.value().evaluate(scalar<S>(k / 64.0)).value());
    const double bound = FixedPoint<S> ? 4 * to_double(resolution<S>()) + 4e-7 : tolerance<S>(25000, 16);
    CHECK(std::fabs(std::hypot(p[0] - 20000, p[1] + 15000) - 2) <= bound);
  }
}

TEMPLATE_TEST_CASE("nurbs: circle geometry, derivatives, curvature and arc length", "[core][nurbs]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto circle = nurbs_circle<S, 2, 9>(point<S>(3, -2), scalar<S>(5)).value();
  const auto unit = nurbs_circle<S, 2, 9>(point<S>(0, 0), scalar<S>(1)).value();
  CHECK(circle.layout() == KnotLayout::Clamped);
  CHECK(circle.size() == 9);
  CHECK(circle.evaluate(scalar<S>(0)).value() == point<S>(8, -2));
  CHECK(circle.evaluate(scalar<S>(1)).value() == point<S>(8, -2));
  CHECK(max_error(circle.evaluate(scalar<S>(0.25)).value(), {3, 3}) == 0.0);
  CHECK(max_error(circle.evaluate(scalar<S>(0.5)).value(), {-2, -2}) == 0.0);
  const double tolerance_k = FixedPoint<S> ? 1e-4 : 1e-5;
  for (int k = 0; k <= 16; ++k) {
    const S u = scalar<S>(k / 16.0);
    const auto p = to_doubles(circle.evaluate(u).value());
    const auto d = to_doubles(circle.derivative_at(u, 1).value());
    // The tangent is perpendicular to the radius and turns counter-clockwise.
    const double speed = std::hypot(d[0], d[1]);
    CHECK(std::fabs((p[0] - 3) * d[0] + (p[1] + 2) * d[1]) / speed <= 5 * tolerance_k);
    CHECK((p[0] - 3) * d[1] - (p[1] + 2) * d[0] > 0);
    // Q16.16 cannot hold |r'|³ of this curve everywhere (|r'| reaches 28): curvature on the unit circle.
    CHECK(to_double(curvature(unit, u).value()) == Approx(1).margin(tolerance_k));
    const auto d2 = to_doubles(circle.derivative_at(u, 2).value());
    const auto r2 = reference(circle, k / 16.0, 2);
    CHECK(d2[0] == Approx(r2[0]).margin(tolerance_k * 1000));
    CHECK(d2[1] == Approx(r2[1]).margin(tolerance_k * 1000));
  }
  if constexpr (std::is_same_v<S, double>) {
    CHECK(arc_length(circle, 0.0, 1.0, 1e-9).value() == Approx(2 * M_PI * 5).epsilon(1e-9));
  }
}

TEMPLATE_TEST_CASE("nurbs: a tilted 3D ellipse satisfies its parametric equation", "[core][nurbs]", double, float, Q16_16) {
  using S = TestType;
  using P3 = Vec<S, 3>;
  const P3 c = point<S>(1, 2, 3);
  const P3 a = point<S>(4, 0, 3);    // |a| = 5
  const P3 b = point<S>(0, 2, 0.5);  // not orthogonal to a: conjugate semi-diameters
  const auto ellipse = nurbs_ellipse<S, 3, 2, 9>(c, a, b);
  REQUIRE(ellipse.has_value());
  const auto ad = to_doubles(a);
  const auto bd = to_doubles(b);
  const double aa = ad[0] * ad[0] + ad[1] * ad[1] + ad[2] * ad[2];
  const double bb = bd[0] * bd[0] + bd[1] * bd[1] + bd[2] * bd[2];
  const double ab = ad[0] * bd[0] + ad[1] * bd[1] + ad[2] * bd[2];
  for (int k = 0; k <= 32; ++k) {
    const auto p = to_doubles(ellipse.value().evaluate(scalar<S>(k / 32.0)).value());
    const std::array<double, 3> q{p[0] - 1, p[1] - 2, p[2] - 3};
    const double qa = q[0] * ad[0] + q[1] * ad[1] + q[2] * ad[2];
    const double qb = q[0] * bd[0] + q[1] * bd[1] + q[2] * bd[2];
    const double det = aa * bb - ab * ab;
    const double alpha = (qa * bb - qb * ab) / det;
    const double beta = (qb * aa - qa * ab) / det;
    const std::array<double, 3> residual{q[0] - alpha * ad[0] - beta * bd[0], q[1] - alpha * ad[1] - beta * bd[1],
                                         q[2] - alpha * ad[2] - beta * bd[2]};
    CHECK(std::fabs(residual[0]) + std::fabs(residual[1]) + std::fabs(residual[2]) <= tolerance<S>(5, 16));
    CHECK(alpha * alpha + beta * beta == Approx(1).margin(FixedPoint<S> ? 2e-5 : 1e-5));
  }
  CHECK(nurbs_ellipse<S, 3, 2, 9>(c, a, point<S>(8, 0, 6)).error() == Error::DegenerateCurve);
  CHECK(nurbs_circle<S, 2, 9>(point<S>(0, 0), scalar<S>(0)).error() == Error::DegenerateCurve);
  CHECK(nurbs_circle<S, 2, 9>(point<S>(0, 0), scalar<S>(-1)).error() == Error::DegenerateCurve);
  if constexpr (FixedPoint<S>) {
    CHECK(nurbs_circle<S, 2, 9>(point<S>(31000, 0), scalar<S>(2000)).error() == Error::FixedOverflow);
  } else {
    CHECK(nurbs_circle<S, 2, 9>(point<S>(0, 0), std::numeric_limits<S>::infinity()).error() == Error::NotFinite);
  }
}

TEMPLATE_TEST_CASE("nurbs: circle extraction gives four quarter arcs that match the curve", "[core][nurbs]", double,
                   float, Q16_16) {
  using S = TestType;
  const auto circle = nurbs_circle<S, 2, 9>(point<S>(0, 0), scalar<S>(1)).value();
  std::array<RationalBezierSpan<S, 2, 2>, 4> pieces{};
  const auto count = extract_bezier(circle, std::span<RationalBezierSpan<S, 2, 2>>(pieces));
  REQUIRE(count.has_value());
  REQUIRE(count.value() == 4);
  // The first piece is TV-16's quarter circle: (1,0), (1,1), (0,1) with weights 1, √2/2, 1.
  CHECK(max_error(pieces[0].curve.control_points()[1], {1, 1}) == 0.0);
  CHECK(to_double(pieces[0].curve.weight(1)) == Approx(0.70710678118654752).margin(tolerance<S>(1, 1)));
  for (std::size_t j = 0; j < 4; ++j) {
    CHECK(to_double(pieces[j].start) == 0.25 * static_cast<double>(j));
    if (j > 0) CHECK(pieces[j - 1].curve.back() == pieces[j].curve.front());
    for (int k = 0; k <= 8; ++k) {
      const S t = scalar<S>(k / 8.0);
      const S u = scalar<S>(0.25 * static_cast<double>(j) + k / 32.0);
      CHECK(max_error(pieces[j].curve.point_at(t), to_doubles(circle.evaluate(u).value())) <= tolerance<S>(1, 8));
    }
  }
}

TEMPLATE_TEST_CASE("nurbs: random curves agree with the rational Cox-de Boor sums and survive knot insertion",
                   "[core][nurbs][property]", double, float, Q16_16) {
  using S = TestType;
  std::mt19937 random(curvestep::testing::test_seed() + 7);
  std::uniform_int_distribution<int> weight_pick(16, 256);  // weights in [0.25, 4] on a 1/64 grid
  const int cases = curvestep::testing::test_count(200);
  for (int c = 0; c < cases; ++c) {
    const auto data = curvestep::testing::random_spline<S, 2>(random, 5, 8, c % 3 != 0, 50);
    std::vector<S> weights;
    for (std::size_t i = 0; i < data.control.size(); ++i) weights.push_back(scalar<S>(weight_pick(random) / 64.0));
    const auto curve = make_nurbs<S>(data.control, weights, data.knots, data.degree);
    const double start = to_double(curve.domain_start());
    const double end = to_double(curve.domain_end());
    const double scale = 50 * 16;  // |P| times the largest weight ratio
    for (int k = 0; k <= 16; ++k) {
      const double u = start + (end - start) * k / 16.0;  // on a 1/128 grid: exact
      CHECK(max_error(curve.evaluate(scalar<S>(u)).value(), reference(curve, u, 0)) <= tolerance<S>(50, 8 * static_cast<int>(data.degree)));
      if (FixedPoint<S>) continue;  // derivatives of random rational curves need more range than Q16.16 has
      const auto d1 = curve.derivative_at(scalar<S>(u), 1).value();
      CHECK(max_error(d1, reference(curve, u, 1)) <= tolerance<S>(scale, 64) * 64);
    }
    const S inserted_at = scalar<S>(start + (end - start) * 0.375);
    const auto refined = curve.insert_knot(inserted_at, 1);
    if (!refined) {
      CHECK(refined.error() == Error::KnotMultiplicityTooHigh);
      continue;
    }
    CHECK(refined.value().size() == curve.size() + 1);
    for (int k = 0; k <= 16; ++k) {
      const S u = scalar<S>(start + (end - start) * k / 16.0);
      // Q16.16 rounds the new weights: the curve may move by |ΔP|·2^-16/w_min.
      CHECK(max_error(refined.value().evaluate(u).value(), to_doubles(curve.evaluate(u).value())) <=
            (FixedPoint<S> ? 100 * 4 * 2e-5 : tolerance<S>(50, 64)));
    }
  }
}

TEMPLATE_TEST_CASE("nurbs: validation errors name the weight at fault", "[core][nurbs][validation]", double, Q16_16) {
  using S = TestType;
  const auto control = points<S>({{0, 0}, {1, 1}, {2, 0}});
  const auto knots = scalars<S>({0, 0, 0, 1, 1, 1});
  const auto make = [&](const std::vector<S>& weights) {
    return Rational<S>::create(std::span<const Vec2<S>>(control), std::span<const S>(weights), std::span<const S>(knots), 2);
  };
  CHECK(make(scalars<S>({1, 0, 1})).error() == Error::NonPositiveWeight);
  CHECK(make(scalars<S>({1, 0, 1})).where() == 1);
  CHECK(make(scalars<S>({1, 1, -2})).error() == Error::NonPositiveWeight);
  CHECK(make(scalars<S>({1, 1, -2})).where() == 2);
  CHECK(make(scalars<S>({1, 1})).error() == Error::InvalidArgument);
  if constexpr (!FixedPoint<S>) {
    CHECK(make({1, std::nan(""), 1}).error() == Error::NotFinite);
    CHECK(make({1, std::nan(""), 1}).where() == 1);
  }
  CHECK(make(scalars<S>({1, 1, 1})).value().evaluate(scalar<S>(2)).error() == Error::ParameterOutOfRange);
  CHECK(Rational<S>{}.evaluate(scalar<S>(0)).error() == Error::EmptyControlPolygon);
  CHECK(make(scalars<S>({1, 2, 1})).value().derivative_at(scalar<S>(0.5), 20).error() == Error::InvalidArgument);
}
