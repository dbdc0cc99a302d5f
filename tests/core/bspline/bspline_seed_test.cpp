// SPDX-License-Identifier: MIT
// B-spline basis, de Boor, derivatives and Boehm insertion against the seed digests
// (shared/docs/seeds: 000/002/003 TV-17..TV-20, 004 §8 TV-13/14/15/16/17 and Appendix A TV-A5),
// in double, float and Q16.16. Dyadic results are compared exactly in every type.
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/bspline/basis.hpp>
#include <curvestep/core/bspline/bspline.hpp>
#include <curvestep/core/curve/curvature.hpp>
#include <support/numeric.hpp>

#include "random_curves.hpp"

using namespace curvestep;
using namespace curvestep::testing;  // support/numeric.hpp and the folder's helpers

namespace {
template <class S>
using Cubic = BSpline<S, 2, 5, 24>;

template <class S>
std::vector<S> tv17_knots() {  // digest 000 §2.6: v = (0,0,0,0,1,2,2,2,2)
  return scalars<S>({0, 0, 0, 0, 1, 2, 2, 2, 2});
}
template <class S>
Cubic<S> tv19_curve() {
  return make_spline<Cubic<S>>(points<S>({{0, 0}, {1, 2}, {2, -1}, {3, 2}, {4, 0}}), tv17_knots<S>(), 3);
}
template <class S>
std::vector<Vec2<S>> tv13_points() {  // digest 004 TV-13
  return points<S>({{-3, 7}, {-1, 6}, {0, 4}, {0, 0}, {4, 0}, {6, 1}, {7, 3}, {9, 4}});
}
template <class S>
Cubic<S> tv13_curve() {
  return make_spline<Cubic<S>>(tv13_points<S>(), scalars<S>({0, 0, 0, 0, 1, 2, 3, 4, 5, 5, 5, 5}), 3);
}
template <class S>
double cross_2d(const std::array<double, 2>& a, const std::array<double, 2>& b) {
  return a[0] * b[1] - a[1] * b[0];
}
}  // namespace

TEMPLATE_TEST_CASE("bspline: TV-17 cubic basis table is exact and sums to one", "[core][bspline][seed]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto knots = tv17_knots<S>();
  const std::array<std::array<double, 5>, 9> table{{{1, 0, 0, 0, 0},
                                                    {27 / 64., 127 / 256., 5 / 64., 1 / 256., 0},
                                                    {1 / 8., 19 / 32., 1 / 4., 1 / 32., 0},
                                                    {1 / 64., 117 / 256., 27 / 64., 27 / 256., 0},
                                                    {0, 1 / 4., 1 / 2., 1 / 4., 0},
                                                    {0, 27 / 256., 27 / 64., 117 / 256., 1 / 64.},
                                                    {0, 1 / 32., 1 / 4., 19 / 32., 1 / 8.},
                                                    {0, 1 / 256., 5 / 64., 127 / 256., 27 / 64.},
                                                    {0, 0, 0, 0, 1}}};  // last row: the right-end rule
  for (std::size_t k = 0; k < table.size(); ++k) {
    std::array<S, 5> values{};
    REQUIRE(basis_values(std::span<const S>(knots), 3, scalar<S>(static_cast<double>(k) / 4.0), std::span<S>(values)).has_value());
    double sum = 0;
    for (std::size_t i = 0; i < 5; ++i) {
      CHECK(to_double(values[i]) == table[k][i]);
      sum += to_double(values[i]);
    }
    CHECK(sum == 1.0);
  }
}

TEMPLATE_TEST_CASE("bspline: TV-17 basis derivatives at 0 and the C2 joint at 1", "[core][bspline][seed]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto knots = tv17_knots<S>();
  const std::span<const S> k(knots);
  CHECK(to_double(basis_derivative(k, 3, 0, scalar<S>(0), 1).value()) == -3.0);
  CHECK(to_double(basis_derivative(k, 3, 1, scalar<S>(0), 1).value()) == 3.0);
  CHECK(to_double(basis_derivative(k, 3, 2, scalar<S>(0), 1).value()) == 0.0);
  CHECK(to_double(basis_derivative(k, 3, 1, scalar<S>(1), 1).value()) == -0.75);
  CHECK(to_double(basis_derivative(k, 3, 1, scalar<S>(1), 2).value()) == 1.5);
  CHECK(to_double(basis_derivative(k, 3, 2, scalar<S>(1), 1).value()) == 0.0);
  CHECK(to_double(basis_derivative(k, 3, 2, scalar<S>(1), 2).value()) == -3.0);
  // Just left of the joint the closed forms N1 = 7/4 t³ − 9/2 t² + 3t, N2 = t²/2 (3 − 2t) give
  // values converging to the same numbers: at t = 1 − 1/64 (exact in every type).
  const double t = 1 - 1 / 64.0;
  CHECK(to_double(basis_derivative(k, 3, 1, scalar<S>(t), 1).value()) ==
        Approx(21 / 4. * t * t - 9 * t + 3).margin(tolerance<S>(4, 8)));
  CHECK(to_double(basis_derivative(k, 3, 2, scalar<S>(t), 2).value()) ==
        Approx(3 - 6 * t).margin(tolerance<S>(4, 16)));
  CHECK(to_double(basis_derivative(k, 3, 0, scalar<S>(1), 4).value()) == 0.0);  // order above the degree
}

TEMPLATE_TEST_CASE("bspline: TV-18 Cox-de Boor intermediate degrees at one half", "[core][bspline][seed]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto knots = tv17_knots<S>();
  const std::array<std::vector<double>, 4> expected{{{0, 0, 0, 1, 0, 0, 0, 0},
                                                     {0, 0, 0.5, 0.5, 0, 0, 0},
                                                     {0, 0.25, 5 / 8., 1 / 8., 0, 0},
                                                     {1 / 8., 19 / 32., 1 / 4., 1 / 32., 0}}};
  for (std::size_t j = 0; j <= 3; ++j) {
    for (std::size_t i = 0; i < expected[j].size(); ++i) {
      CHECK(to_double(basis_function(std::span<const S>(knots), j, i, scalar<S>(0.5)).value()) == expected[j][i]);
    }
  }
}

TEMPLATE_TEST_CASE("bspline: TV-20 uniform cubic basis on knots 0..7", "[core][bspline][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto knots = scalars<S>({0, 1, 2, 3, 4, 5, 6, 7});
  const std::array<std::array<double, 4>, 2> expected{{{1 / 6., 2 / 3., 1 / 6., 0}, {1 / 48., 23 / 48., 23 / 48., 1 / 48.}}};
  const std::array<double, 2> at{3, 3.5};
  for (std::size_t k = 0; k < 2; ++k) {
    for (std::size_t i = 0; i < 4; ++i) {
      CHECK(to_double(basis_function(std::span<const S>(knots), 3, i, scalar<S>(at[k])).value()) ==
            Approx(expected[k][i]).margin(tolerance<S>(1, 4)));
    }
  }
  // The same as a curve: the domain is [3, 4].
  const auto curve = make_spline<Cubic<S>>(points<S>({{0, 0}, {6, 0}, {6, 6}, {0, 6}}), knots, 3);
  CHECK(to_double(curve.domain_start()) == 3.0);
  CHECK(to_double(curve.domain_end()) == 4.0);
  CHECK(curve.layout() == KnotLayout::Unclamped);
  CHECK(max_error(curve.evaluate(scalar<S>(3)).value(), {5, 1}) <= tolerance<S>(6, 4));  // (P0 + 4P1 + P2)/6
  CHECK(curve.evaluate(scalar<S>(2.5)).error() == Error::ParameterOutOfRange);
}

TEMPLATE_TEST_CASE("bspline: TV-19 de Boor values at quarters are exact", "[core][bspline][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto curve = tv19_curve<S>();
  CHECK(curve.layout() == KnotLayout::Clamped);
  const std::array<std::array<double, 2>, 9> expected{{{0, 0},
                                                       {85 / 128., 59 / 64.},
                                                       {19 / 16., 1},
                                                       {207 / 128., 45 / 64.},
                                                       {2, 0.5},
                                                       {305 / 128., 45 / 64.},
                                                       {45 / 16., 1},
                                                       {427 / 128., 59 / 64.},
                                                       {4, 0}}};
  for (std::size_t k = 0; k < expected.size(); ++k) {
    CHECK(max_error(curve.evaluate(scalar<S>(static_cast<double>(k) / 4.0)).value(), expected[k]) == 0.0);
  }
  CHECK(max_error(curve.derivative_at(scalar<S>(0), 1).value(), {3, 6}) == 0.0);
  CHECK(max_error(curve.derivative_at(scalar<S>(2), 1).value(), {3, -6}) == 0.0);
  CHECK(max_error(curve.derivative_at(scalar<S>(1), 4).value(), {0, 0}) == 0.0);
}

TEMPLATE_TEST_CASE("bspline: 004 TV-13 clamped cubic values", "[core][bspline][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto curve = tv13_curve<S>();
  const std::array<double, 8> at{0, 0.5, 1, 2, 2.5, 3, 4, 5};
  const std::array<std::array<double, 2>, 8> expected{{{-3, 7},
                                                       {-31 / 32., 263 / 48.},
                                                       {-0.25, 23 / 6.},
                                                       {2 / 3., 2 / 3.},
                                                       {49 / 24., 5 / 48.},
                                                       {11 / 3., 1 / 6.},
                                                       {71 / 12., 4 / 3.},
                                                       {9, 4}}};
  for (std::size_t k = 0; k < at.size(); ++k) {
    CHECK(max_error(curve.evaluate(scalar<S>(at[k])).value(), expected[k]) <= tolerance<S>(9, 4));
  }
}

TEMPLATE_TEST_CASE("bspline: TV-A5 Boehm insertion of 5/2 into 004 TV-13", "[core][bspline][seed]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto original = tv13_curve<S>();
  const auto inserted = original.insert_knot(scalar<S>(2.5));
  REQUIRE(inserted.has_value());
  const auto& curve = inserted.value();
  const std::array<double, 13> knots{0, 0, 0, 0, 1, 2, 2.5, 3, 4, 5, 5, 5, 5};
  REQUIRE(curve.knots().size() == knots.size());
  for (std::size_t i = 0; i < knots.size(); ++i) CHECK(to_double(curve.knots()[i]) == knots[i]);
  const std::array<std::array<double, 2>, 9> expected{
      {{-3, 7}, {-1, 6}, {0, 4}, {0, 2 / 3.}, {2, 0}, {13 / 3., 1 / 6.}, {6, 1}, {7, 3}, {9, 4}}};
  REQUIRE(curve.size() == expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    CHECK(max_error(curve.control_points()[i], expected[i]) <= tolerance<S>(9, 1));
  }
  for (int k = 0; k <= 40; ++k) {
    const S u = scalar<S>(k / 8.0);
    CHECK(max_error(curve.evaluate(u).value(), to_doubles(original.evaluate(u).value())) <= tolerance<S>(9, 6));
  }
}

TEMPLATE_TEST_CASE("bspline: 004 Thm 3.5 envelope check on the TV-13 curve", "[core][bspline][seed]", double, float,
                   Q16_16) {
  using S = TestType;
  // h: order 3 on knots [0,0,0,0,1,3,4,5,5,5,5] with u_5 deleted. Its first and last basis
  // functions vanish identically (support of zero width), so h is the same curve with d0, d7 and
  // one end knot on each side dropped: d1..d6 on [0,0,0,1,3,4,5,5,5].
  const auto d = tv13_points<S>();
  const auto h = make_spline<Cubic<S>>(std::vector<Vec2<S>>(d.begin() + 1, d.begin() + 7),
                                       scalars<S>({0, 0, 0, 1, 3, 4, 5, 5, 5}), 2);
  const std::array<double, 3> moved{1.4, 2.0, 2.6};
  const std::array<std::array<double, 2>, 3> expected{{{0.1066666667, 1.7066666667},
                                                       {0.6666666667, 0.6666666667},
                                                       {1.7066666667, 0.1066666667}}};
  for (std::size_t k = 0; k < 3; ++k) {
    const auto g = make_spline<Cubic<S>>(d, scalars<S>({0, 0, 0, 0, 1, moved[k], 3, 4, 5, 5, 5, 5}), 3);
    const S u = scalar<S>(moved[k]);
    const double margin = tolerance<S>(9, 8) + 1e-10;
    CHECK(max_error(g.evaluate(u).value(), expected[k]) <= margin);
    CHECK(max_error(h.evaluate(u).value(), expected[k]) <= margin);
    const auto dg = to_doubles(g.derivative_at(u, 1).value());
    const auto dh = to_doubles(h.derivative_at(u, 1).value());
    for (std::size_t axis = 0; axis < 2; ++axis) CHECK(dh[axis] == Approx(2 / 3. * dg[axis]).margin(tolerance<S>(9, 64)));
  }
  // Cor 3.4: curvature ratio 0.75 at u_5 = 2.2.
  const auto g = make_spline<Cubic<S>>(d, scalars<S>({0, 0, 0, 0, 1, 2.2, 3, 4, 5, 5, 5, 5}), 3);
  const S u = scalar<S>(2.2);
  CHECK(to_double(curvature(h, u).value()) ==
        Approx(0.75 * to_double(curvature(g, u).value())).epsilon(FixedPoint<S> ? 2e-3 : 1e-4));
}

TEMPLATE_TEST_CASE("bspline: 004 Thm 3.6 double-knot envelope at 2.2", "[core][bspline][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto d = points<S>({{-3, 7}, {-1, 6}, {0, 4}, {0, 0}, {4, 0}, {6, 1}, {7, 3}, {9, 4}, {10, 1}});
  const auto g = make_spline<Cubic<S>>(d, scalars<S>({0, 0, 0, 0, 0, 1, 2.2, 2.2, 4, 5, 5, 5, 5, 5}), 4);
  // The order-3 envelope with the double knot deleted, zero-width basis functions dropped.
  const auto h = make_spline<Cubic<S>>(std::vector<Vec2<S>>(d.begin() + 2, d.begin() + 7),
                                       scalars<S>({0, 0, 0, 1, 4, 5, 5, 5}), 2);
  const S u = scalar<S>(2.2);
  CHECK(max_error(g.evaluate(u).value(), {3.16, 0.12}) <= tolerance<S>(10, 8) + 1e-12);
  CHECK(max_error(h.evaluate(u).value(), {3.16, 0.12}) <= tolerance<S>(10, 8) + 1e-12);
  const auto dg = to_doubles(g.derivative_at(u, 1).value());
  const auto dh = to_doubles(h.derivative_at(u, 1).value());
  for (std::size_t axis = 0; axis < 2; ++axis) CHECK(dh[axis] == Approx(0.5 * dg[axis]).margin(tolerance<S>(10, 64)));
  CHECK(to_double(curvature(h, u).value()) ==
        Approx(2 / 3. * to_double(curvature(g, u).value())).epsilon(FixedPoint<S> ? 2e-3 : 1e-4));
}

TEMPLATE_TEST_CASE("bspline: 004 TV-14a and TV-14b knot-modified curves pass through their targets",
                   "[core][bspline][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto a = make_spline<Cubic<S>>(tv13_points<S>(), scalars<S>({0, 0, 0, 0, 1.5, 2, 2.5, 4, 5, 5, 5, 5}), 3);
  CHECK(max_error(a.evaluate(scalar<S>(2)).value(), {0.4, 0.4}) <= tolerance<S>(9, 8));
  CHECK(max_error(a.derivative_at(scalar<S>(2), 1).value(), {2.4, -2.4}) <= tolerance<S>(9, 32));
  if constexpr (!FixedPoint<S>) {  // the knots need 12 digits; Q16.16 rounds them to 1.5e-5
    const auto b = make_spline<Cubic<S>>(
        tv13_points<S>(), scalars<S>({0, 0, 0, 0, 1.39611202329010, 2, 2.32979450547728, 4, 5, 5, 5, 5}), 3);
    CHECK(max_error(b.evaluate(scalar<S>(2)).value(), {0.6, 0.2}) <= tolerance<S>(9, 8) + 1e-11);
  }
}

TEMPLATE_TEST_CASE("bspline: 004 TV-15 curve point and basis values at 1.5", "[core][bspline][seed]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto knots = scalars<S>({0, 0, 0, 0, 1, 2, 3, 4, 4, 4, 4});
  const auto curve = make_spline<Cubic<S>>(points<S>({{0, 0}, {1, 3}, {3, 4}, {5, 3}, {6, 0}, {8, -1}, {9, 2}}), knots, 3);
  CHECK(max_error(curve.evaluate(scalar<S>(1.5)).value(), {3.9583333333, 3.40625}) <= tolerance<S>(9, 8) + 1e-10);
  const std::array<double, 3> n{0.46875, 0.4791666667, 0.0208333333};
  for (std::size_t i = 0; i < 3; ++i) {
    CHECK(to_double(basis_function(std::span<const S>(knots), 3, i + 2, scalar<S>(1.5)).value()) ==
          Approx(n[i]).margin(tolerance<S>(1, 4) + 1e-10));
  }
}

TEMPLATE_TEST_CASE("bspline: 004 TV-16 symmetric two-knot paths are straight", "[core][bspline][seed]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto polygon = points<S>({{0, 0}, {1, 3}, {3, 4}, {4, 1}, {6, 0}, {8, 2}, {9, 5}, {11, 6}, {13, 4}, {14, 1},
                                  {16, 0}, {17, 3}, {19, 4}});
  const std::array<std::array<double, 2>, 5> expected{
      {{9.083333, 4.833333}, {9.1, 4.8}, {9.125, 4.75}, {9.166667, 4.666667}, {9.25, 4.5}}};
  for (int k = 0; k < 5; ++k) {
    const double lambda = -1 + 0.5 * k;
    std::vector<double> knots;
    for (int i = 0; i < 16; ++i) knots.push_back(i + (i == 6 ? lambda : 0) - (i == 9 ? lambda : 0));
    std::vector<S> scaled;
    for (const double v : knots) scaled.push_back(scalar<S>(v));
    const auto curve = make_spline<Cubic<S>>(polygon, scaled, 2);
    const auto p = to_doubles(curve.evaluate(scalar<S>(7.5)).value());
    CHECK(max_error(curve.evaluate(scalar<S>(7.5)).value(), expected[static_cast<std::size_t>(k)]) <=
          tolerance<S>(19, 8) + 1e-6);
    // On the line through d6 = (9, 5) with the direction of the λ = 0 point.
    CHECK(std::fabs(cross_2d<S>({p[0] - 9, p[1] - 5}, {0.125, -0.25})) <= tolerance<S>(19, 16));
  }
  // k = 4, knots u6 + λ and u11 − λ: the paths are lines through the midpoint of d6 d7 = (10, 5.5).
  std::array<std::array<double, 2>, 3> path{};
  for (int k = 0; k < 3; ++k) {
    std::vector<S> knots;
    for (int i = 0; i < 17; ++i) knots.push_back(scalar<S>(i + (i == 6 ? k - 1 : 0) - (i == 11 ? k - 1 : 0)));
    path[static_cast<std::size_t>(k)] = to_doubles(make_spline<Cubic<S>>(polygon, knots, 3).evaluate(scalar<S>(8.5)).value());
  }
  const std::array<double, 2> direction{path[2][0] - path[0][0], path[2][1] - path[0][1]};
  CHECK(std::fabs(cross_2d<S>({path[1][0] - path[0][0], path[1][1] - path[0][1]}, direction)) <= tolerance<S>(19, 16));
  CHECK(std::fabs(cross_2d<S>({10 - path[0][0], 5.5 - path[0][1]}, direction)) <= tolerance<S>(19, 16));
}

TEMPLATE_TEST_CASE("bspline: 004 TV-17 closed uniform B-splines of order 4 and 16", "[core][bspline][seed]", double,
                   float, Q16_16) {
  using S = TestType;
  const auto polygon = points<S>({{0, 0}, {4, 0}, {4, 2}, {0, 6}});
  // Knots 0, 1, 2, ... as in the digest: the domain starts at u = degree.
  const auto cubic = BSpline<S, 2, 15, 20>::closed(std::span<const Vec2<S>>(polygon), 3, scalar<S>(3));
  REQUIRE(cubic.has_value());
  CHECK(cubic.value().layout() == KnotLayout::Periodic);
  CHECK(cubic.value().size() == 7);
  CHECK(to_double(cubic.value().knots()[0]) == 0.0);
  const std::array<double, 4> delta{0, 0.3, 1.7, 3.5};
  const std::array<std::array<double, 2>, 4> expected{{{10 / 3., 1 / 3.}, {3.753333, 0.723333}, {1.410667, 4.237333}, {2, 1 / 6.}}};
  for (std::size_t k = 0; k < 4; ++k) {
    CHECK(max_error(cubic.value().evaluate(scalar<S>(3 + delta[k])).value(), expected[k]) <=
          tolerance<S>(6, 8) + 5e-7);
  }
  const auto order16 = BSpline<S, 2, 15, 20>::closed(std::span<const Vec2<S>>(polygon), 15, scalar<S>(15));
  REQUIRE(order16.has_value());
  CHECK(max_error(order16.value().evaluate(scalar<S>(15)).value(), {1.627306, 2.560496}) <= tolerance<S>(6, 32) + 5e-7);
}

TEMPLATE_TEST_CASE("bspline: a closed curve meets itself with matching derivatives at the seam", "[core][bspline]",
                   double, float, Q16_16) {
  using S = TestType;
  const auto polygon = points<S>({{0, 0}, {4, 0}, {4, 2}, {0, 6}, {-2, 3}});
  const std::vector<S> spacings = scalars<S>({1, 0.5, 2, 1, 1.5});
  for (std::size_t degree = 1; degree <= 4; ++degree) {
    const auto curve = Cubic<S>::closed(std::span<const Vec2<S>>(polygon), degree, std::span<const S>(spacings));
    REQUIRE(curve.has_value());
    const auto& c = curve.value();
    CHECK(to_double(c.domain_end()) == 6.0);
    for (std::size_t order = 0; order < degree; ++order) {
      const auto start = c.derivative_at(c.domain_start(), order).value();
      const auto end = c.derivative_at(c.domain_end(), order).value();
      CHECK(max_error(start, to_doubles(end)) <= tolerance<S>(6, 16 << (2 * order)));
    }
  }
}
