// SPDX-License-Identifier: MIT
// C1 quadratic splines (digest 000/002/003 TV-29, P-7; seed 001 TV-11) and Catmull–Rom / Hermite
// splines (TV-26), in double, float and Q16.16.
#include <array>
#include <span>

#include <catch2/catch.hpp>

#include <curvestep/core.hpp>
#include <curvestep/core/interpolation/catmull_rom.hpp>
#include <curvestep/core/interpolation/quadratic_spline.hpp>
#include <support/numeric.hpp>

#include "interpolation_support.hpp"

using namespace curvestep;
using namespace curvestep::testing;  // interpolation_support.hpp, support/numeric.hpp

namespace {
template <class S>
using Quadratic = CompositeBezier<S, 2, 3, 8>;
}  // namespace

TEMPLATE_TEST_CASE("interpolation: TV-29 C1 quadratic with end tangent directions, uniform knots", "[core][interpolation][seed]",
                   double, float, Q16_16) {
  using S = TestType;
  const auto p = points2<S, 4>({{{0, 0}, {1, 1}, {2, 0}, {3, 1}}});
  const auto u = scalars<S, 4>({0, 1, 2, 3});
  Quadratic<S> curve;
  REQUIRE(interpolate_quadratic(view(p), view(u), point<S>(1, 0), point<S>(0, 1), curve).has_value());
  check_passes_through(curve, p, false);
  const std::array<std::array<double, 2>, 3> inner{{{1, 0}, {1, 2}, {3, -2}}};
  const std::array<std::array<double, 2>, 3> middle{{{0.75, 0.25}, {1.25, 1.25}, {2.75, -0.75}}};
  for (std::size_t j = 0; j < 3; ++j) {
    REQUIRE(curve.segment(j).degree() == 2);
    CHECK(max_error(curve.segment(j)[1], inner[j]) == 0);
    CHECK(max_error(curve.segment(j).point_at(scalar<S>(0.5)), middle[j]) == 0);
  }
  // End check: (p3 − q2)/h = (0,3) = µ·t3, so s'(u_3) = (0,6) and λ = 1 gives s'(u_0) = 2·(1,0).
  CHECK(max_error(curve.derivative_at(scalar<S>(3)).value(), {0, 6}) == 0);
  CHECK(max_error(curve.derivative_at(S{}).value(), {2, 0}) == 0);
  CHECK(joint_jump(curve, 1, false) == 0);
  // The same spline from a parametrization, and from its start tangent s'(u_0) = (2, 0).
  Quadratic<S> same;
  REQUIRE(interpolate_quadratic(view(p), Parametrization::Uniform, point<S>(1, 0), point<S>(0, 1), same).has_value());
  for (std::size_t j = 0; j < 3; ++j) CHECK(same.segment(j) == curve.segment(j));
  REQUIRE(interpolate_quadratic(view(p), Parametrization::Uniform, point<S>(2, 0), same).has_value());
  for (std::size_t j = 0; j < 3; ++j) CHECK(same.segment(j) == curve.segment(j));
}

TEMPLATE_TEST_CASE("interpolation: TV-29 C1 quadratic with end tangent directions, knots 0 1 3 4", "[core][interpolation][seed]",
                   double, float, Q16_16) {
  using S = TestType;
  const auto p = points2<S, 4>({{{0, 0}, {1, 1}, {2, 0}, {3, 1}}});
  const auto u = scalars<S, 4>({0, 1, 3, 4});
  Quadratic<S> curve;
  REQUIRE(interpolate_quadratic(view(p), view(u), point<S>(1, 0), point<S>(0, 1), curve).has_value());
  check_passes_through(curve, p, false);
  const double tol = solve_tolerance<S>(4);
  const std::array<std::array<double, 2>, 3> inner{{{1.5, 0}, {0, 3}, {3, -1.5}}};
  const std::array<std::array<double, 2>, 3> middle{{{1, 0.25}, {0.75, 1.75}, {2.75, -0.5}}};
  for (std::size_t j = 0; j < 3; ++j) {
    CHECK(max_error(curve.segment(j)[1], inner[j]) <= tol);
    CHECK(max_error(curve.segment(j).point_at(scalar<S>(0.5)), middle[j]) <= tol);
  }
  // λ = 3/2 and µ = 5/2: s'(u_0) = 2λ t0 and s'(u_3) = 2µ t3.
  CHECK(max_error(curve.derivative_at(S{}).value(), {3, 0}) <= tol);
  CHECK(max_error(curve.derivative_at(scalar<S>(4)).value(), {0, 5}) <= tol);
  CHECK(joint_jump(curve, 1, false) <= tol);
}

TEMPLATE_TEST_CASE("interpolation: P-7 collinear data with tangents along the line give the line", "[core][interpolation][seed]",
                   double, float, Q16_16) {
  using S = TestType;
  const auto p = points2<S, 4>({{{0, 0}, {1, 1}, {3, 3}, {4, 4}}});
  Quadratic<S> curve;
  std::array<S, 4> u{};
  REQUIRE(parametrize(view(p), Parametrization::Uniform, std::span<S>(u)).has_value());
  REQUIRE(interpolate_quadratic(view(p), view(u), point<S>(1, 1), curve).has_value());
  for (std::size_t j = 0; j < 3; ++j) {
    const auto q = curve.segment(j)[1];
    CHECK(to_double(q[0]) == to_double(q[1]));
  }
  // With only the directions given, parallel end directions leave λ, µ undetermined.
  const auto r = interpolate_quadratic(view(p), view(u), point<S>(1, 1), point<S>(2, 2), curve);
  CHECK(r.error() == Error::SingularSystem);
}

TEMPLATE_TEST_CASE("interpolation: TV-11 closed C1 quadratic through a triangle and a pentagon", "[core][interpolation][seed]",
                   double, float, Q16_16) {
  using S = TestType;
  const double tol = solve_tolerance<S>(4);
  const auto triangle = points2<S, 3>({{{0, 0}, {1, 0}, {0, 1}}});
  SECTION("triangle, uniform knots") {
    Quadratic<S> curve;
    REQUIRE(interpolate_closed_quadratic(view(triangle), Parametrization::Uniform, curve).has_value());
    check_passes_through(curve, triangle, true);
    const std::array<std::array<double, 2>, 3> inner{{{1, -1}, {1, 1}, {-1, 1}}};
    for (std::size_t j = 0; j < 3; ++j) CHECK(max_error(curve.segment(j)[1], inner[j]) == 0);
    CHECK(joint_jump(curve, 1, true) == 0);
  }
  SECTION("triangle, knots 0 1 3 4") {
    const auto u = scalars<S, 4>({0, 1, 3, 4});
    Quadratic<S> curve;
    REQUIRE(interpolate_closed_quadratic(view(triangle), view(u), curve).has_value());
    check_passes_through(curve, triangle, true);
    const std::array<std::array<double, 2>, 3> inner{{{0.75, -0.75}, {1.5, 1.5}, {-0.75, 0.75}}};
    for (std::size_t j = 0; j < 3; ++j) CHECK(max_error(curve.segment(j)[1], inner[j]) <= tol);
    CHECK(joint_jump(curve, 1, true) <= tol);
  }
  SECTION("pentagon, uniform knots, against the alternating-sum closed form") {
    const auto pentagon = points2<S, 5>({{{0, 0}, {2, 0}, {3, 2}, {1, 3}, {-1, 1}}});
    Quadratic<S> curve;
    REQUIRE(interpolate_closed_quadratic(view(pentagon), Parametrization::Uniform, curve).has_value());
    check_passes_through(curve, pentagon, true);
    const std::array<std::array<double, 2>, 5> inner{{{1, 0}, {3, 0}, {3, 4}, {-1, 2}, {-1, 0}}};
    for (std::size_t j = 0; j < 5; ++j) {
      CHECK(max_error(curve.segment(j)[1], inner[j]) == 0);
      // b^j_1 = Σ_k (−1)^k x_{j−1−k} (indices mod m, seed 001 §6.2 note), segment j+1 in 1-based terms.
      std::array<double, 2> sum{0, 0};
      for (std::size_t k = 0; k < 5; ++k) {
        const auto& x = pentagon[(j + 5 - k) % 5];
        const double sign = k % 2 == 0 ? 1 : -1;
        sum[0] += sign * to_double(x[0]);
        sum[1] += sign * to_double(x[1]);
      }
      CHECK(max_error(curve.segment(j)[1], sum) == 0);
    }
    CHECK(joint_jump(curve, 1, true) == 0);
  }
  SECTION("an even number of points is reported") {
    const auto square = points2<S, 4>({{{4, 0}, {4, 4}, {0, 4}, {0, 0}}});
    Quadratic<S> curve;
    const auto r = interpolate_closed_quadratic(view(square), Parametrization::Uniform, curve);
    CHECK(r.error() == Error::EvenClosedQuadratic);
    CHECK(r.where() == 4);
  }
}

TEMPLATE_TEST_CASE("interpolation: quadratic spline input errors", "[core][interpolation]", double, float, Q16_16) {
  using S = TestType;
  const auto p = points2<S, 3>({{{0, 0}, {1, 1}, {2, 0}}});
  const auto u = scalars<S, 3>({0, 2, 1});
  Quadratic<S> curve;
  CHECK(interpolate_quadratic(view(p), view(u), point<S>(1, 0), curve).error() == Error::InvalidInterval);
  const auto one = points2<S, 1>({{{0, 0}}});
  const auto u1 = scalars<S, 1>({0});
  CHECK(interpolate_quadratic(view(one), view(u1), point<S>(1, 0), curve).error() == Error::TooFewPoints);
  CompositeBezier<S, 2, 2, 1> small;
  const auto good = scalars<S, 3>({0, 1, 2});
  CHECK(interpolate_quadratic(view(p), view(good), point<S>(1, 0), small).error() == Error::CapacityExceeded);
  CHECK(interpolate_quadratic(view(p), view(good), point<S>(0, 0), point<S>(0, 1), curve).error() == Error::SingularSystem);
}

TEMPLATE_TEST_CASE("interpolation: TV-26 Catmull-Rom spline with central-difference tangents", "[core][interpolation][seed]",
                   double, float, Q16_16) {
  using S = TestType;
  const auto p = points2<S, 5>({{{0, 0}, {1, 2}, {3, 3}, {4, 0}, {6, 1}}});
  CompositeBezier<S, 2, 3, 8> curve;
  REQUIRE(interpolate_catmull_rom(view(p), point<S>(1, 1), point<S>(1, -1), curve).has_value());
  check_passes_through(curve, p, false);
  // Thirds of the tangents are not dyadic: Q16.16 rounds the inner Bézier points.
  const double tol = solve_tolerance<S>(4);
  const std::array<std::array<double, 2>, 3> v{{{1.5, 1.5}, {1.5, -1}, {1.5, -1}}};
  for (std::size_t j = 1; j < 4; ++j) CHECK(max_error(curve.segment_derivative(j, S{}, 1).value(), v[j - 1]) <= tol);
  CHECK(max_error(curve.evaluate(scalar<S>(1.5)).value(), {2, 45 / 16.}) <= tol);
  CHECK(max_error(curve.evaluate(scalar<S>(2.5)).value(), {3.5, 1.5}) <= tol);
  CHECK(max_error(curve.derivative_at(S{}).value(), {1, 1}) <= tol);
  CHECK(max_error(curve.derivative_at(scalar<S>(4)).value(), {1, -1}) <= tol);
  CHECK(joint_jump(curve, 1, false) <= tol);
  for (std::size_t j = 1; j < 4; ++j) CHECK(continuity(curve, j, tol).value().parametric >= 1);
}

TEMPLATE_TEST_CASE("interpolation: closed Catmull-Rom uses cyclic neighbours and is C1 at the wrap", "[core][interpolation]",
                   double, float, Q16_16) {
  using S = TestType;
  const auto square = points2<S, 4>({{{0, 0}, {4, 0}, {4, 4}, {0, 4}}});
  CompositeBezier<S, 2, 3, 8> curve;
  REQUIRE(interpolate_closed_catmull_rom(view(square), curve).has_value());
  check_passes_through(curve, square, true);
  // v_0 = ½(p_1 − p_3) = (2,−2): Bézier point p_0 + v_0/3.
  CHECK(max_error(curve.segment(0)[1], {2 / 3., -2 / 3.}) <= solve_tolerance<S>(4));
  CHECK(joint_jump(curve, 1, true) <= solve_tolerance<S>(4));
  const auto two = points2<S, 2>({{{0, 0}, {1, 0}}});
  CHECK(interpolate_closed_catmull_rom(view(two), curve).error() == Error::TooFewPoints);
}

TEMPLATE_TEST_CASE("interpolation: Hermite spline with given tangents checks its inputs", "[core][interpolation]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto p = points2<S, 3>({{{0, 0}, {1, 1}, {2, 0}}});
  const auto v = points2<S, 2>({{{1, 0}, {1, 0}}});
  const auto u = scalars<S, 3>({0, 1, 2});
  CompositeBezier<S, 2, 3, 8> curve;
  CHECK(interpolate_hermite(view(p), view(v), view(u), curve).error() == Error::InvalidArgument);
  const auto v3 = points2<S, 3>({{{1, 0}, {1, 0}, {1, 0}}});
  REQUIRE(interpolate_hermite(view(p), view(v3), view(u), curve).has_value());
  CHECK(max_error(curve.derivative_at(scalar<S>(1)).value(), {1, 0}) <= solve_tolerance<S>());
}
