// SPDX-License-Identifier: MIT
// Hermite / Ferguson segments against seed digest 000/002/003 TV-21, TV-22 and the TV-23 power form.
#include <array>

#include <catch2/catch.hpp>

#include <curvestep/core.hpp>
#include <support/numeric.hpp>

#include "interpolation_support.hpp"

using namespace curvestep;
using curvestep::testing::max_error;
using curvestep::testing::point;
using curvestep::testing::scalar;

TEMPLATE_TEST_CASE("interpolation: TV-21 Hermite basis values are exact at dyadic parameters", "[core][interpolation][seed]",
                   double, float, Q16_16) {
  using S = TestType;
  const auto half = hermite_basis(scalar<S>(0.5)).value();
  CHECK(to_double(half.start_point) == 0.5);
  CHECK(to_double(half.end_point) == 0.5);
  CHECK(to_double(half.start_tangent) == 0.125);
  CHECK(to_double(half.end_tangent) == -0.125);
  const auto quarter = hermite_basis(scalar<S>(0.25)).value();
  CHECK(to_double(quarter.start_point) == 27.0 / 32);
  CHECK(to_double(quarter.end_point) == 5.0 / 32);
  CHECK(to_double(quarter.start_tangent) == 9.0 / 64);
  CHECK(to_double(quarter.end_tangent) == -3.0 / 64);
  const auto zero = hermite_basis(S{}).value();
  CHECK((to_double(zero.start_point) == 1 && to_double(zero.end_point) == 0 && to_double(zero.start_tangent) == 0 &&
         to_double(zero.end_tangent) == 0));
  const auto one = hermite_basis(from_int<S>(1)).value();
  CHECK((to_double(one.start_point) == 0 && to_double(one.end_point) == 1 && to_double(one.start_tangent) == 0 &&
         to_double(one.end_tangent) == 0));
}

TEMPLATE_TEST_CASE("interpolation: TV-21 Hermite second derivatives at the ends", "[core][interpolation][seed]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto at_zero = hermite_basis_second_derivative(S{}).value();
  CHECK(to_double(at_zero.start_point) == -6);
  CHECK(to_double(at_zero.end_point) == 6);
  CHECK(to_double(at_zero.start_tangent) == -4);
  CHECK(to_double(at_zero.end_tangent) == -2);
  const auto at_one = hermite_basis_second_derivative(from_int<S>(1)).value();
  CHECK(to_double(at_one.start_point) == 6);
  CHECK(to_double(at_one.end_point) == -6);
  CHECK(to_double(at_one.start_tangent) == 2);
  CHECK(to_double(at_one.end_tangent) == 4);
}

TEMPLATE_TEST_CASE("interpolation: Hermite basis rejects parameters outside the unit interval", "[core][interpolation]", double,
                   float, Q16_16) {
  using S = TestType;
  CHECK(hermite_basis(scalar<S>(-0.25)).error() == Error::ParameterOutOfRange);
  CHECK(hermite_basis_second_derivative(scalar<S>(1.5)).error() == Error::ParameterOutOfRange);
}

TEMPLATE_TEST_CASE("interpolation: TV-22 Hermite segment equals its Bezier form", "[core][interpolation][seed]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto p0 = point<S>(0, 0);
  const auto p1 = point<S>(4, 0);
  const auto v0 = point<S>(3, 6);
  const auto v1 = point<S>(3, -9);
  const auto bezier = hermite_to_bezier(p0, p1, v0, v1).value();
  REQUIRE(bezier.degree() == 3);
  CHECK(max_error(bezier[0], {0, 0}) == 0);
  CHECK(max_error(bezier[1], {1, 2}) == 0);
  CHECK(max_error(bezier[2], {3, 3}) == 0);
  CHECK(max_error(bezier[3], {4, 0}) == 0);
  // TV-04 values, reached by two independent paths: the basis and de Casteljau.
  const std::array<std::array<double, 3>, 3> expected{{{0.25, 29 / 32., 81 / 64.}, {0.5, 2, 15 / 8.}, {0.75, 99 / 32., 99 / 64.}}};
  for (const auto& e : expected) {
    const S t = scalar<S>(e[0]);
    CHECK(max_error(hermite_point(p0, p1, v0, v1, t).value(), {e[1], e[2]}) == 0);
    CHECK(max_error(bezier.point_at(t), {e[1], e[2]}) == 0);
  }
}

TEMPLATE_TEST_CASE("interpolation: Hermite on an interval scales the tangents by its width", "[core][interpolation][seed]", double,
                   float, Q16_16) {
  using S = TestType;
  // The TV-22 curve on [2, 6]: derivatives with respect to u are the local ones divided by 4.
  const auto p0 = point<S>(0, 0);
  const auto p1 = point<S>(4, 0);
  const auto v0 = point<S>(0.75, 1.5);
  const auto v1 = point<S>(0.75, -2.25);
  const auto bezier = hermite_to_bezier(p0, p1, v0, v1, scalar<S>(2), scalar<S>(6)).value();
  CHECK(max_error(bezier[1], {1, 2}) == 0);
  CHECK(max_error(bezier[2], {3, 3}) == 0);
  CompositeBezier<S, 2, 3, 1> on_interval(scalar<S>(2));
  REQUIRE(on_interval.try_append(bezier, scalar<S>(6)).has_value());
  CHECK(max_error(on_interval.derivative_at(scalar<S>(2)).value(), {0.75, 1.5}) == 0);
  CHECK(max_error(on_interval.derivative_at(scalar<S>(6)).value(), {0.75, -2.25}) == 0);
  CHECK(max_error(on_interval.evaluate(scalar<S>(3)).value(), {29 / 32., 81 / 64.}) == 0);
  CHECK(hermite_to_bezier(p0, p1, v0, v1, scalar<S>(2), scalar<S>(2)).error() == Error::InvalidInterval);
}

TEMPLATE_TEST_CASE("interpolation: TV-23 Ferguson power-form coefficients", "[core][interpolation][seed]", double, float, Q16_16) {
  using S = TestType;
  // Segment 2 of TV-23: R = (1,1) -> (2,0), D = (1,-1/3), (1,-1/3): A2 = (0,-2), A3 = (0,4/3).
  const auto power = ferguson_coefficients(point<S>(1, 1), point<S>(2, 0), point<S>(1, -1 / 3.), point<S>(1, -1 / 3.)).value();
  const double tol = curvestep::testing::solve_tolerance<S>();
  CHECK(max_error(power.coefficients[0], {1, 1}) == 0);
  CHECK(max_error(power.coefficients[1], {1, -1 / 3.}) <= tol);
  CHECK(max_error(power.coefficients[2], {0, -2}) <= tol);
  CHECK(max_error(power.coefficients[3], {0, 4 / 3.}) <= tol);
  CHECK(max_error(power.evaluate(scalar<S>(0.5)), {1.5, 0.5}) <= tol);
  // Independent check: the power form and the Bezier form agree.
  const auto bezier = hermite_to_bezier(point<S>(1, 1), point<S>(2, 0), point<S>(1, -1 / 3.), point<S>(1, -1 / 3.)).value();
  CHECK(max_error(bezier.point_at(scalar<S>(0.25)), to_doubles(power.evaluate(scalar<S>(0.25)))) <= tol);
}

TEST_CASE("interpolation: Hermite Bezier points that leave the Q16.16 range report FixedOverflow", "[core][interpolation]") {
  const auto huge = point<Q16_16>(30000, 0);
  const auto r = hermite_to_bezier(point<Q16_16>(30000, 0), point<Q16_16>(30001, 0), huge, huge);
  REQUIRE(!r.has_value());
  CHECK(r.error() == Error::FixedOverflow);
  CHECK(r.where() == 1);
}
