// SPDX-License-Identifier: MIT
// Bézier core against the seed digests' test vectors (shared/docs/seeds), in double, float, Q16.16.
// Dyadic inputs give dyadic results: those are compared exactly in every scalar type.
#include <array>
#include <cmath>

#include <catch2/catch.hpp>

#include <curvestep/core.hpp>
#include <support/numeric.hpp>
#include <support/seed_vectors.hpp>

using namespace curvestep;
using curvestep::testing::max_error;
using curvestep::testing::point;
using curvestep::testing::scalar;
using curvestep::testing::tolerance;

namespace {
template <class S>
using Cubic2 = Bezier<S, 2, 7>;

template <class S>
Cubic2<S> tv04_cubic() {  // digest 000/002/003 TV-04: (0,0),(1,2),(3,3),(4,0)
  return Cubic2<S>::create({point<S>(0, 0), point<S>(1, 2), point<S>(3, 3), point<S>(4, 0)}).value();
}
template <class S>
Cubic2<S> example_1_2() {  // digest 001 Example 1.2: (0,1),(0,4),(5,5),(7,0)
  return Cubic2<S>::create({point<S>(0, 1), point<S>(0, 4), point<S>(5, 5), point<S>(7, 0)}).value();
}
}  // namespace

TEMPLATE_TEST_CASE("bernstein: TV-01/TV-02 values and partition of unity", "[core][bezier][seed]", double, float, Q16_16) {
  using S = TestType;
  const std::array<std::array<double, 4>, 5> expected{{{1, 0, 0, 0},
                                                       {27 / 64., 27 / 64., 9 / 64., 1 / 64.},
                                                       {1 / 8., 3 / 8., 3 / 8., 1 / 8.},
                                                       {1 / 64., 9 / 64., 27 / 64., 27 / 64.},
                                                       {0, 0, 0, 1}}};
  for (int k = 0; k <= 4; ++k) {
    const auto b = bernstein_all<7>(3, scalar<S>(k / 4.0));
    for (std::size_t i = 0; i < 4; ++i) CHECK(to_double(b[i]) == expected[static_cast<std::size_t>(k)][i]);
  }
  const auto quartic = bernstein_all<7>(4, scalar<S>(0.5));
  const std::array<double, 5> q{1 / 16., 1 / 4., 3 / 8., 1 / 4., 1 / 16.};
  for (std::size_t i = 0; i < 5; ++i) CHECK(to_double(quartic[i]) == q[i]);
  CHECK(to_double(bernstein(2, 1, scalar<S>(0.5))) == 0.5);
  CHECK(to_double(bernstein(3, 4, scalar<S>(0.5))) == 0.0);
}

TEST_CASE("bernstein: TV-03 maxima and seed 001 TV-01 at thirds", "[core][bezier][seed]") {
  CHECK(bernstein(3, 1, 1.0 / 3) == Approx(4.0 / 9));
  CHECK(bernstein(3, 2, 2.0 / 3) == Approx(4.0 / 9));
  CHECK(bernstein(4, 2, 0.5) == Approx(3.0 / 8));
  const auto b = bernstein_all<7>(3, 1.0 / 3);
  CHECK(b[0] == Approx(8.0 / 27));
  CHECK(b[1] == Approx(4.0 / 9));
  CHECK(b[2] == Approx(2.0 / 9));
  CHECK(b[3] == Approx(1.0 / 27));
}

TEMPLATE_TEST_CASE("de_casteljau: TV-04 cubic at quarters is exact", "[core][bezier][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto c = tv04_cubic<S>();
  const std::array<std::array<double, 2>, 5> expected{{{0, 0}, {29 / 32., 81 / 64.}, {2, 15 / 8.}, {99 / 32., 99 / 64.}, {4, 0}}};
  for (int k = 0; k <= 4; ++k) {
    CHECK(max_error(c.evaluate(scalar<S>(k / 4.0)).value(), expected[static_cast<std::size_t>(k)]) == 0.0);
  }
  const auto tri = c.triangle(scalar<S>(0.5)).value();
  CHECK(max_error(tri.levels[1][0], {0.5, 1}) == 0.0);
  CHECK(max_error(tri.levels[1][1], {2, 2.5}) == 0.0);
  CHECK(max_error(tri.levels[1][2], {3.5, 1.5}) == 0.0);
  CHECK(max_error(tri.levels[2][0], {1.25, 1.75}) == 0.0);
  CHECK(max_error(tri.levels[2][1], {2.75, 2}) == 0.0);
  CHECK(max_error(tri.levels[3][0], {2, 1.875}) == 0.0);
}

TEMPLATE_TEST_CASE("split: TV-04 halves and seed 001 TV-04 splits", "[core][bezier][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto halves = tv04_cubic<S>().split(scalar<S>(0.5)).value();
  const std::array<std::array<double, 2>, 4> left{{{0, 0}, {0.5, 1}, {1.25, 1.75}, {2, 1.875}}};
  const std::array<std::array<double, 2>, 4> right{{{2, 1.875}, {2.75, 2}, {3.5, 1.5}, {4, 0}}};
  for (std::size_t i = 0; i < 4; ++i) {
    CHECK(max_error(halves.left[i], left[i]) == 0.0);
    CHECK(max_error(halves.right[i], right[i]) == 0.0);
  }
  const auto quarter = example_1_2<S>().split(scalar<S>(0.25)).value();
  const std::array<std::array<double, 2>, 4> ql{{{0, 1}, {0, 7 / 4.}, {5 / 16., 19 / 8.}, {13 / 16., 45 / 16.}}};
  const std::array<std::array<double, 2>, 4> qr{{{13 / 16., 45 / 16.}, {37 / 16., 33 / 8.}, {11 / 2., 15 / 4.}, {7, 0}}};
  for (std::size_t i = 0; i < 4; ++i) {
    CHECK(max_error(quarter.left[i], ql[i]) == 0.0);
    CHECK(max_error(quarter.right[i], qr[i]) == 0.0);
  }
}

TEST_CASE("split: seed 001 TV-04 split at t=1/3 (non-dyadic)", "[core][bezier][seed]") {
  const auto third = example_1_2<double>().split(1.0 / 3).value();
  const std::array<std::array<double, 2>, 4> l{{{0, 1}, {0, 2}, {5 / 9., 25 / 9.}, {37 / 27., 86 / 27.}}};
  const std::array<std::array<double, 2>, 4> r{{{37 / 27., 86 / 27.}, {3, 4}, {17 / 3., 10 / 3.}, {7, 0}}};
  for (std::size_t i = 0; i < 4; ++i) {
    CHECK(max_error(third.left[i], l[i]) < 1e-14);
    CHECK(max_error(third.right[i], r[i]) < 1e-14);
  }
  const auto fixed = example_1_2<Q16_16>().split(scalar<Q16_16>(1.0 / 3)).value();
  for (std::size_t i = 0; i < 4; ++i) CHECK(max_error(fixed.left[i], l[i]) < tolerance<Q16_16>(1, 16));
}

TEMPLATE_TEST_CASE("de_casteljau: seed 001 Example 1.2 values at eighths (TV-03, TV-05)", "[core][bezier][seed]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto c = example_1_2<S>();
  const auto& expected = curvestep::testing::example_1_2_eighths;  // TV-03, TV-05
  for (int k = 0; k <= 8; ++k) {
    CHECK(max_error(c.point_at(scalar<S>(k / 8.0)), expected[static_cast<std::size_t>(k)]) == 0.0);
  }
  CHECK(max_error(c.point_at(scalar<S>(1.0 / 3)), {37 / 27., 86 / 27.}) <= tolerance<S>(8, 16));
}

TEMPLATE_TEST_CASE("derivative: TV-05 hodograph, second and third derivatives", "[core][bezier][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto c = tv04_cubic<S>();
  const auto h = c.derivative().value();
  REQUIRE(h.degree() == 2);
  CHECK(max_error(h[0], {3, 6}) == 0.0);
  CHECK(max_error(h[1], {6, 3}) == 0.0);
  CHECK(max_error(h[2], {3, -9}) == 0.0);
  const auto h2 = c.derivative(2).value();
  CHECK(max_error(h2[0], {6, -6}) == 0.0);
  CHECK(max_error(h2[1], {-6, -24}) == 0.0);
  const auto h3 = c.derivative(3).value();
  REQUIRE(h3.degree() == 0);
  CHECK(max_error(h3[0], {-12, -18}) == 0.0);
  CHECK(c.derivative(4).value().degree() == 0);
  CHECK(max_error(c.derivative(4).value()[0], {0, 0}) == 0.0);
  const std::array<std::array<double, 2>, 5> d1{{{3, 6}, {33 / 8., 63 / 16.}, {4.5, 0.75}, {33 / 8., -57 / 16.}, {3, -9}}};
  const std::array<std::array<double, 2>, 5> d2{{{6, -6}, {3, -10.5}, {0, -15}, {-3, -19.5}, {-6, -24}}};
  for (int k = 0; k <= 4; ++k) {
    const S t = scalar<S>(k / 4.0);
    CHECK(max_error(c.derivative_at(t, 1).value(), d1[static_cast<std::size_t>(k)]) == 0.0);
    CHECK(max_error(c.derivative_at(t, 2).value(), d2[static_cast<std::size_t>(k)]) == 0.0);
  }
}

TEMPLATE_TEST_CASE("derivative: seed 001 TV-06 derivative values", "[core][bezier][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto c = example_1_2<S>();
  const std::array<std::array<double, 2>, 5> d1{{{0, 9}, {6, 21 / 4.}, {9, 0}, {9, -27 / 4.}, {6, -15}}};
  const std::array<std::array<double, 2>, 5> d2{{{30, -12}, {18, -18}, {6, -24}, {-6, -30}, {-18, -36}}};
  for (int k = 0; k <= 4; ++k) {
    const S t = scalar<S>(k / 4.0);
    CHECK(max_error(c.derivative_at(t, 1).value(), d1[static_cast<std::size_t>(k)]) == 0.0);
    CHECK(max_error(c.derivative_at(t, 2).value(), d2[static_cast<std::size_t>(k)]) == 0.0);
  }
  CHECK(max_error(c.derivative(3).value()[0], {-48, -24}) == 0.0);
}

TEMPLATE_TEST_CASE("curvature: TV-06 planar cubic and its osculating circle", "[core][bezier][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto c = tv04_cubic<S>();
  const std::array<double, 5> kappa{0.178885438200, 0.297257066199, 0.710914539699, 0.562792967154, 0.147572957475};
  const double tol = FixedPoint<S> ? 2e-4 : (std::is_same_v<S, float> ? 1e-5 : 1e-11);
  for (int k = 0; k <= 4; ++k) {
    const auto value = curvature(c, scalar<S>(k / 4.0)).value();
    CHECK(to_double(value) < 0);  // clockwise
    CHECK(std::fabs(-to_double(value) - kappa[static_cast<std::size_t>(k)]) < tol);
  }
  const auto centre = osculating_center(c, scalar<S>(0.5)).value();
  CHECK(max_error(centre, {357 / 160., 39 / 80.}) < (FixedPoint<S> ? 1e-3 : 1e-5));
}

TEMPLATE_TEST_CASE("curvature: TV-07 space cubic", "[core][bezier][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto c = Bezier<S, 3, 7>::create({point<S>(0, 0, 0), point<S>(1, 0, 0), point<S>(1, 1, 0), point<S>(1, 1, 1)}).value();
  const double tol = FixedPoint<S> ? 2e-4 : 1e-5;
  CHECK(std::fabs(to_double(curvature(c, scalar<S>(0.5)).value()) - 8 * std::sqrt(2.0) / 9) < tol);
  CHECK(std::fabs(to_double(curvature(c, scalar<S>(0.0)).value()) - 2.0 / 3) < tol);
  CHECK(std::fabs(to_double(curvature(c, scalar<S>(1.0)).value()) - 2.0 / 3) < tol);
  CHECK(max_error(c.point_at(scalar<S>(0.5)), {7 / 8., 1 / 2., 1 / 8.}) == 0.0);
  CHECK(max_error(c.derivative_at(scalar<S>(0.5), 1).value(), {0.75, 1.5, 0.75}) == 0.0);
  CHECK(max_error(c.derivative_at(scalar<S>(0.5), 2).value(), {-3, 0, 3}) == 0.0);
}

TEMPLATE_TEST_CASE("power basis: TV-08/TV-09 conversions and Horner", "[core][bezier][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto power = to_power_basis(tv04_cubic<S>()).value();
  const std::array<std::array<double, 2>, 4> a{{{0, 0}, {3, 6}, {3, -3}, {-2, -3}}};
  for (std::size_t i = 0; i < 4; ++i) CHECK(max_error(power.coefficients[i], a[i]) == 0.0);
  CHECK(max_error(power.evaluate(scalar<S>(0.5)), {2, 15 / 8.}) == 0.0);
  const auto back = from_power_basis(power).value();
  CHECK(back == tv04_cubic<S>());
  // 1 + 2t + 3t^2 as a quadratic: (1, 2, 6) in each coordinate.
  PowerBasis<S, 2, 7> p;
  p.degree = 2;
  p.coefficients[0] = point<S>(1, 0);
  p.coefficients[1] = point<S>(2, 0);
  p.coefficients[2] = point<S>(3, 0);
  const auto q = from_power_basis(p).value();
  CHECK(to_double(q[0][0]) == 1.0);
  CHECK(to_double(q[1][0]) == 2.0);
  CHECK(to_double(q[2][0]) == 6.0);
  // t and t^2 as cubics: (0, 1/3, 2/3, 1) and (0, 0, 1/3, 1).
  PowerBasis<S, 2, 7> lin;
  lin.degree = 3;
  lin.coefficients[1] = point<S>(1, 0);
  lin.coefficients[2] = point<S>(0, 1);
  const auto l = from_power_basis(lin).value();
  const std::array<std::array<double, 2>, 4> expected{{{0, 0}, {1 / 3., 0}, {2 / 3., 1 / 3.}, {1, 1}}};
  for (std::size_t i = 0; i < 4; ++i) CHECK(max_error(l[i], expected[i]) <= tolerance<S>(1, 1));
  // seed 001 TV-05 power form of Example 1.2.
  const auto p12 = to_power_basis(example_1_2<S>()).value();
  const std::array<std::array<double, 2>, 4> a12{{{0, 1}, {0, 9}, {15, -6}, {-8, -4}}};
  for (std::size_t i = 0; i < 4; ++i) CHECK(max_error(p12.coefficients[i], a12[i]) == 0.0);
}

TEMPLATE_TEST_CASE("bezier: TV-09 linear precision and TV-11 quadratic", "[core][bezier][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto line = Bezier<S, 2, 7>::create({point<S>(0, 0), point<S>(1, 1), point<S>(2, 2), point<S>(3, 3)}).value();
  CHECK(max_error(line.point_at(scalar<S>(0.25)), {0.75, 0.75}) == 0.0);
  CHECK(max_error(line.point_at(scalar<S>(0.5)), {1.5, 1.5}) == 0.0);
  const auto quad = Bezier<S, 2, 7>::create({point<S>(0, 0), point<S>(1, 2), point<S>(2, 0)}).value();
  CHECK(max_error(quad.point_at(scalar<S>(0.25)), {0.5, 0.75}) == 0.0);
  CHECK(max_error(quad.point_at(scalar<S>(0.5)), {1, 1}) == 0.0);
  CHECK(max_error(quad.point_at(scalar<S>(0.75)), {1.5, 0.75}) == 0.0);
  const auto tri = quad.triangle(scalar<S>(0.25)).value();  // three-tangent theorem points
  CHECK(max_error(tri.levels[1][0], {0.25, 0.5}) == 0.0);
  CHECK(max_error(tri.levels[1][1], {1.25, 1.5}) == 0.0);
  // seed 001 TV-02: Example 1.1 = (2t, 1 - t^2)
  const auto ex11 = Bezier<S, 2, 7>::create({point<S>(0, 1), point<S>(1, 1), point<S>(2, 0)}).value();
  CHECK(max_error(ex11.point_at(scalar<S>(0.75)), {1.5, 7 / 16.}) == 0.0);
  const auto h = ex11.derivative().value();
  CHECK(max_error(h[0], {2, 0}) == 0.0);
  CHECK(max_error(h[1], {2, -2}) == 0.0);
}

TEMPLATE_TEST_CASE("blossom: seed 001 TV-07", "[core][bezier][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto c = example_1_2<S>();
  const std::array<S, 3> u{scalar<S>(0), scalar<S>(0.5), scalar<S>(1)};
  CHECK(max_error(c.blossom(u).value(), {2.5, 4.5}) == 0.0);
  std::array<S, 3> v{scalar<S>(0.25), scalar<S>(0.5), scalar<S>(0.75)};
  do {
    CHECK(max_error(c.blossom(v).value(), {43 / 16., 15 / 4.}) == 0.0);
  } while (std::next_permutation(v.begin(), v.end()));
  // Bézier points of the same cubic on [0,2] by extrapolation: (0,1),(0,7),(20,5),(-4,-37).
  const std::array<std::array<double, 2>, 4> on_0_2{{{0, 1}, {0, 7}, {20, 5}, {-4, -37}}};
  for (std::size_t i = 0; i < 4; ++i) {
    std::array<S, 3> w{};
    for (std::size_t k = 0; k < 3; ++k) w[k] = k < 3 - i ? scalar<S>(0) : scalar<S>(2);
    CHECK(max_error(c.blossom(w).value(), on_0_2[i]) == 0.0);
  }
  // Ex 1.1 on [1/2, 1]: (1, 3/4), (3/2, 1/2), (2, 0)
  const auto ex11 = Bezier<S, 2, 7>::create({point<S>(0, 1), point<S>(1, 1), point<S>(2, 0)}).value();
  const auto part = ex11.segment(scalar<S>(0.5), scalar<S>(1)).value();
  CHECK(max_error(part[0], {1, 0.75}) == 0.0);
  CHECK(max_error(part[1], {1.5, 0.5}) == 0.0);
  CHECK(max_error(part[2], {2, 0}) == 0.0);
}

TEMPLATE_TEST_CASE("arc length: TV-12 cubic and quadratic", "[core][bezier][seed]", double, float, Q16_16) {
  using S = TestType;
  const double tol = FixedPoint<S> ? 2e-3 : (std::is_same_v<S, float> ? 1e-4 : 1e-9);
  const S requested = scalar<S>(FixedPoint<S> ? 1e-3 : (std::is_same_v<S, float> ? 1e-5 : 1e-10));
  const auto c = tv04_cubic<S>();
  CHECK(std::fabs(to_double(arc_length(c, scalar<S>(0), scalar<S>(1), requested).value()) - 5.829927224626644) < tol);
  CHECK(std::fabs(to_double(arc_length(c, scalar<S>(0), scalar<S>(0.5), requested).value()) - 2.834662900232897) < tol);
  const auto quad = Bezier<S, 2, 7>::create({point<S>(0, 0), point<S>(1, 2), point<S>(2, 0)}).value();
  CHECK(std::fabs(to_double(arc_length(quad, scalar<S>(0), scalar<S>(1), requested).value()) - 2.957885715089195) < tol);
  CHECK(arc_length(c, scalar<S>(0), scalar<S>(1), S{}).error() == Error::InvalidTolerance);
}
