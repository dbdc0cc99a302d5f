// SPDX-License-Identifier: MIT
// Every documented input error of the Bézier core comes back as the documented Error with the
// index of the offending input, in double, float and Q16.16; nothing wraps or returns garbage.
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <support/contract_violation.hpp>

#include "curve_test_support.hpp"

using namespace curvestep;
using namespace curvestep::testing;

namespace {

template <class S, std::size_t Dim = 2>
using Curve = Bezier<S, Dim, 7>;
template <class S>
using Rational = RationalBezier<S, 2, 7>;

/// Checks that `result` failed with `code` at `index`.
template <class T>
void check_failure(const Result<T>& result, Error code, std::uint16_t index = no_index) {
  INFO("expected " << error_name(code) << " at " << index);
  REQUIRE_FALSE(result.has_value());
  CHECK(error_name(result.error()) == error_name(code));
  CHECK(result.where() == index);
}

template <class S>
Curve<S> tv04() {
  return must(Curve<S>::create({point<S>(0, 0), point<S>(1, 2), point<S>(3, 3), point<S>(4, 0)}));
}

}  // namespace

TEMPLATE_TEST_CASE("bad input: empty polygons and too many control points", "[core][bezier][error]", double, float, Q16_16) {
  using S = TestType;
  check_failure(Curve<S>::create(std::span<const Vec<S, 2>>{}), Error::EmptyControlPolygon);
  check_failure(Rational<S>::create(std::span<const Vec<S, 2>>{}, std::span<const S>{}), Error::EmptyControlPolygon);
  // Nine points in a MaxDegree = 7 curve: control point 8 (degree 8) does not fit.
  std::vector<Vec<S, 2>> nine;
  for (int i = 0; i < 9; ++i) nine.push_back(point<S>(i, i % 2));
  check_failure(Curve<S>::create(std::span<const Vec<S, 2>>(nine)), Error::DegreeAboveCapacity, 8);
  const std::vector<S> nine_weights(9, from_int<S>(1));
  check_failure(Rational<S>::create(std::span<const Vec<S, 2>>(nine), std::span<const S>(nine_weights)), Error::DegreeAboveCapacity,
                8);
  // Eight points fit; elevating degree 7 asks for degree 8.
  const auto seven = must(Curve<S>::create(std::span<const Vec<S, 2>>(nine.data(), 8)));
  CHECK(seven.degree() == 7);
  check_failure(seven.elevated(), Error::DegreeAboveCapacity, 8);
  // A power basis of degree 8 cannot become a MaxDegree 7 curve... it cannot even be stored:
  // PowerBasis<.., 7> holds 8 coefficients, so the degree field is the only way to ask for 8.
  PowerBasis<S, 2, 7> power;
  power.degree = 8;
  check_failure(from_power_basis(power), Error::DegreeAboveCapacity, 8);
}

TEMPLATE_TEST_CASE("bad input: NaN and infinite coordinates name the control point", "[core][bezier][error]", double, float) {
  using S = TestType;
  const S nan = std::numeric_limits<S>::quiet_NaN();
  const S inf = std::numeric_limits<S>::infinity();
  check_failure(Curve<S>::create({point<S>(0, 0), point<S>(1, 1), Vec<S, 2>{{nan, S{0}}}}), Error::NotFinite, 2);
  check_failure(Curve<S>::create({Vec<S, 2>{{S{0}, -inf}}, point<S>(1, 1)}), Error::NotFinite, 0);
  check_failure(Curve<S, 3>::create({point<S>(0, 0, 0), Vec<S, 3>{{S{1}, S{1}, inf}}}), Error::NotFinite, 1);
  check_failure(Rational<S>::create({point<S>(0, 0), Vec<S, 2>{{nan, nan}}, point<S>(2, 0)}, {S{1}, S{1}, S{1}}), Error::NotFinite, 1);
  check_failure(Rational<S>::create({point<S>(0, 0), point<S>(1, 1), point<S>(2, 0)}, {S{1}, nan, S{1}}), Error::NotFinite, 1);
  check_failure(Rational<S>::create({point<S>(0, 0), point<S>(1, 1), point<S>(2, 0)}, {S{1}, S{1}, inf}), Error::NotFinite, 2);
  // Conversion of input data: NaN/inf are NotFinite, the index names the coordinate.
  check_failure(vec_from_doubles<S, 2>({1.0, std::nan("")}), Error::NotFinite, 1);
}

TEST_CASE("bad input: NaN and infinity cannot enter Q16.16 and out-of-range values do not wrap", "[core][fixed][error]") {
  check_failure(from_double<Q16_16>(std::nan("")), Error::NotFinite);
  check_failure(from_double<Q16_16>(std::numeric_limits<double>::infinity()), Error::NotFinite);
  check_failure(vec_from_doubles<Q16_16, 2>({std::numeric_limits<double>::infinity(), 0.0}), Error::NotFinite, 0);
  check_failure(vec_from_doubles<Q16_16, 3>({0.0, 0.0, 40000.0}), Error::FixedOverflow, 2);
  check_failure(from_double<Q16_16>(-32769.0), Error::FixedOverflow);
}

TEMPLATE_TEST_CASE("bad input: parameters outside the domain", "[core][bezier][error]", double, float, Q16_16) {
  using S = TestType;
  const auto curve = tv04<S>();
  const S below = scalar<S>(-0.1);
  const S above = scalar<S>(1.1);
  check_failure(curve.evaluate(below), Error::ParameterOutOfRange);
  check_failure(curve.evaluate(above), Error::ParameterOutOfRange);
  check_failure(curve.split(from_int<S>(2)), Error::ParameterOutOfRange);
  check_failure(curve.split(below), Error::ParameterOutOfRange);
  check_failure(curve.triangle(above), Error::ParameterOutOfRange);
  check_failure(curve.derivative_at(above, 1), Error::ParameterOutOfRange);
  check_failure(curve.derivative_at(below, 2), Error::ParameterOutOfRange);
  check_failure(curve.segment(scalar<S>(0.5), scalar<S>(0.25)), Error::ParameterOutOfRange);
  check_failure(curve.segment(below, scalar<S>(0.5)), Error::ParameterOutOfRange);
  check_failure(curve.segment(scalar<S>(0.5), above), Error::ParameterOutOfRange);
  // The smallest step outside is already out.
  check_failure(curve.evaluate(from_int<S>(0) - resolution<S>()), Error::ParameterOutOfRange);
  const auto rational = must(Rational<S>::create({point<S>(1, 0), point<S>(1, 1), point<S>(0, 1)},
                                                 {from_int<S>(1), scalar<S>(0.5), from_int<S>(1)}));
  check_failure(rational.evaluate(above), Error::ParameterOutOfRange);
  check_failure(rational.derivative_at(below, 1), Error::ParameterOutOfRange);
  check_failure(rational.split(above), Error::ParameterOutOfRange);
  check_failure(rational.derivative_at(scalar<S>(0.5), 12), Error::InvalidArgument);
  // Composite: outside [u_0, u_m] and on an empty curve.
  CompositeBezier<S, 2, 7, 4> composite(from_int<S>(1));
  check_failure(composite.locate(from_int<S>(1)), Error::ParameterOutOfRange);
  check_failure(composite.evaluate(from_int<S>(1)), Error::ParameterOutOfRange);
  REQUIRE(composite.try_append(curve, from_int<S>(3)).has_value());
  check_failure(composite.evaluate(scalar<S>(0.9)), Error::ParameterOutOfRange);
  check_failure(composite.evaluate(scalar<S>(3.1)), Error::ParameterOutOfRange);
  check_failure(composite.derivative_at(scalar<S>(3.1), 1), Error::ParameterOutOfRange);
}

TEMPLATE_TEST_CASE("bad input: a NaN parameter is outside the domain", "[core][bezier][error]", double, float) {
  using S = TestType;
  const S nan = std::numeric_limits<S>::quiet_NaN();
  const auto curve = tv04<S>();
  check_failure(curve.evaluate(nan), Error::ParameterOutOfRange);
  check_failure(curve.split(nan), Error::ParameterOutOfRange);
  check_failure(curve.triangle(nan), Error::ParameterOutOfRange);
  check_failure(curve.derivative_at(nan, 1), Error::ParameterOutOfRange);
  check_failure(curve.segment(nan, S{1}), Error::ParameterOutOfRange);
  check_failure(curve.segment(S{0}, nan), Error::ParameterOutOfRange);
  const auto rational = must(Rational<S>::create({point<S>(1, 0), point<S>(1, 1), point<S>(0, 1)}, {S{1}, S{0.5}, S{1}}));
  check_failure(rational.evaluate(nan), Error::ParameterOutOfRange);
  check_failure(rational.derivative_at(nan, 1), Error::ParameterOutOfRange);
  check_failure(rational.split(nan), Error::ParameterOutOfRange);
  CompositeBezier<S, 2, 7, 4> composite(S{0});
  REQUIRE(composite.try_append(curve, S{1}).has_value());
  check_failure(composite.locate(nan), Error::ParameterOutOfRange);
  check_failure(composite.evaluate(nan), Error::ParameterOutOfRange);
  // A contract-checked hot path must not accept it either.
  CHECK_THROWS_AS(curve.point_at(nan), ContractViolation);
}

TEMPLATE_TEST_CASE("bad input: zero negative and mismatched weights", "[core][rational][error]", double, float, Q16_16) {
  using S = TestType;
  const std::array<Vec<S, 2>, 3> points{point<S>(0, 0), point<S>(1, 1), point<S>(2, 0)};
  const auto create = [&](std::initializer_list<double> w) {
    std::vector<S> weights;
    for (double x : w) weights.push_back(scalar<S>(x));
    return Rational<S>::create(points, std::span<const S>(weights));
  };
  check_failure(create({1, 0, 1}), Error::NonPositiveWeight, 1);
  check_failure(create({1, 1, -0.5}), Error::NonPositiveWeight, 2);
  check_failure(create({-1, 1, 1}), Error::NonPositiveWeight, 0);
  // Counts differ: InvalidArgument, the index is the weight count.
  check_failure(create({1, 1}), Error::InvalidArgument, 2);
  check_failure(create({1, 1, 1, 1}), Error::InvalidArgument, 4);
  CHECK(create({1, 1, 1}).has_value());
}

TEST_CASE("bad input: Q16.16 derivatives and power bases report FixedOverflow instead of wrapping", "[core][bezier][error]") {
  using S = Q16_16;
  // Control points near ±30000: the hodograph 3 (b1 - b0) = 180000 does not fit (max 32767).
  const auto curve = must(Curve<S>::create({point<S>(-30000, 0), point<S>(30000, 0), point<S>(-30000, 1), point<S>(30000, 1)}));
  check_failure(curve.derivative(), Error::FixedOverflow, 0);
  check_failure(curve.derivative_at(scalar<S>(0.5), 1), Error::FixedOverflow, 0);
  check_failure(curve.derivative(2), Error::FixedOverflow, 0);
  // A later difference: only b3 - b2 is large.
  const auto late = must(Curve<S>::create({point<S>(0, 0), point<S>(1, 0), point<S>(2, 0), point<S>(20000, 0)}));
  check_failure(late.derivative(), Error::FixedOverflow, 2);
  // Power basis: a1 = 3 (b1 - b0) overflows (index = coefficient 1).
  check_failure(to_power_basis(curve), Error::FixedOverflow, 1);
  const auto alternating = must(Curve<S>::create({point<S>(-5000, 0), point<S>(0, 0), point<S>(0, 0), point<S>(5000, 0)}));
  const auto power = to_power_basis(alternating);
  REQUIRE(power.has_value());  // a1 = 15000, a2 = -15000, a3 = 10000: all fit
  const auto wild = must(Curve<S>::create({point<S>(-10000, 0), point<S>(10000, 0), point<S>(-10000, 0), point<S>(10000, 0)}));
  check_failure(to_power_basis(wild), Error::FixedOverflow, 1);
  // The contract-checked operators also refuse to wrap.
  CHECK_THROWS_AS(scalar<S>(30000) + scalar<S>(30000), ContractViolation);
  check_failure(checked_add(scalar<S>(30000), scalar<S>(30000)), Error::FixedOverflow);
  check_failure(checked_mul(scalar<S>(300), scalar<S>(300)), Error::FixedOverflow);
  check_failure(checked_div(scalar<S>(1), S{}), Error::DivisionByZero);
  // w b must fit as well.
  check_failure(Rational<S>::create({point<S>(0, 0), point<S>(20000, 0)}, {scalar<S>(1), scalar<S>(2)}), Error::FixedOverflow, 1);
}

TEST_CASE("bad input: float derivatives and power bases report NotFinite instead of infinity", "[core][bezier][error]") {
  using S = float;
  const auto curve = must(Curve<S>::create({point<S>(-3e38, 0), point<S>(3e38, 0), point<S>(0, 0)}));
  check_failure(curve.derivative(), Error::NotFinite, 0);
  check_failure(to_power_basis(curve), Error::NotFinite, 1);
}

TEMPLATE_TEST_CASE("bad input: extrapolated blossoms and continuations that leave the range", "[core][bezier][error]", Q16_16, float) {
  using S = TestType;
  const Error expected = FixedPoint<S> ? Error::FixedOverflow : Error::NotFinite;
  const double far = FixedPoint<S> ? 30000.0 : 3e38;
  const auto curve = tv04<S>();
  // Level 1 with u = far: (b1 - b0)·far leaves the range: the index names argument 0.
  const std::array<S, 3> first{scalar<S>(far), scalar<S>(0.5), scalar<S>(0.5)};
  check_failure(curve.blossom(first), expected, 0);
  // Level 1 fine, level 2 extrapolates.
  const std::array<S, 3> second{scalar<S>(0.5), scalar<S>(far), scalar<S>(0.5)};
  check_failure(curve.blossom(second), expected, 1);
  // Extrapolation that stays in range works: P(0,0,2) (seed 001 TV-07 on [0,2] for TV-04-like data).
  const std::array<S, 3> fine{scalar<S>(2), scalar<S>(2), scalar<S>(2)};
  CHECK(curve.blossom(fine).has_value());
  // A C2 continuation with a huge µ (its index is not documented: only the code is checked).
  const auto continued = continuation_points(curve, scalar<S>(far), 2);
  REQUIRE_FALSE(continued.has_value());
  CHECK(continued.error() == expected);
}

TEMPLATE_TEST_CASE("bad input: arcs with mismatched radii zero radius or too much sweep", "[core][rational][arc][error]", double,
                   float, Q16_16) {
  using S = TestType;
  const auto center = point<S>(10, 10);
  const S tolerance_value = scalar<S>(0.001);
  const auto ccw = ArcDirection::CounterClockwise;
  const auto cw = ArcDirection::Clockwise;
  // End radius 5.1 vs start radius 5.
  check_failure(circular_arc<S, 7>(center, point<S>(15, 10), point<S>(10, 15.1), ccw, tolerance_value), Error::InvalidArgument, 1);
  // Zero radius: start at the centre.
  check_failure(circular_arc<S, 7>(center, center, point<S>(10, 15), ccw, tolerance_value), Error::DegenerateCurve);
  // Start and end coincide: a 0° or 360° arc.
  check_failure(circular_arc<S, 7>(center, point<S>(15, 10), point<S>(15, 10), ccw, tolerance_value), Error::DegenerateCurve);
  // 270°: counter-clockwise from +x to -y, and clockwise from +x to +y.
  check_failure(circular_arc<S, 7>(center, point<S>(15, 10), point<S>(10, 5), ccw, tolerance_value), Error::SweepTooLarge);
  check_failure(circular_arc<S, 7>(center, point<S>(15, 10), point<S>(10, 15), cw, tolerance_value), Error::SweepTooLarge);
  // The same end points the other way round are fine (90°).
  CHECK(circular_arc<S, 7>(center, point<S>(15, 10), point<S>(10, 5), cw, tolerance_value).has_value());
  // By angle.
  const S radius = scalar<S>(5);
  check_failure(circular_arc_by_angle<S, 7>(center, radius, 0.0, 3.2), Error::SweepTooLarge);
  check_failure(circular_arc_by_angle<S, 7>(center, radius, 0.0, -3.2), Error::SweepTooLarge);
  check_failure(circular_arc_by_angle<S, 7>(center, radius, 0.0, 0.0), Error::DegenerateCurve);
  check_failure(circular_arc_by_angle<S, 7>(center, radius, std::nan(""), 1.0), Error::NotFinite);
  check_failure(circular_arc_by_angle<S, 7>(center, radius, 0.0, std::numeric_limits<double>::infinity()), Error::NotFinite);
  // Full circles need a positive radius.
  check_failure(full_circle<S, 7>(center, S{}), Error::DegenerateCurve);
  check_failure(full_circle<S, 7>(center, scalar<S>(-1)), Error::DegenerateCurve);
}

TEMPLATE_TEST_CASE("bad input: composite breakpoints must increase and capacity is fixed", "[core][composite][error]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto curve = tv04<S>();
  CompositeBezier<S, 2, 7, 3> composite(from_int<S>(0));
  // Not after the start: equal and smaller ends are InvalidInterval for segment 0.
  check_failure(composite.try_append(curve, from_int<S>(0)), Error::InvalidInterval, 0);
  check_failure(composite.try_append(curve, from_int<S>(-1)), Error::InvalidInterval, 0);
  REQUIRE(composite.try_append(curve, from_int<S>(1)).has_value());
  check_failure(composite.try_append(curve, from_int<S>(1)), Error::InvalidInterval, 1);
  REQUIRE(composite.try_append(curve, from_int<S>(2)).has_value());
  REQUIRE(composite.try_append(curve, from_int<S>(3)).has_value());
  CHECK(composite.full());
  check_failure(composite.try_append(curve, from_int<S>(4)), Error::CapacityExceeded, 3);
  // Failed appends change nothing.
  CHECK(composite.size() == 3);
  CHECK(composite.domain_end() == from_int<S>(3));
}

TEMPLATE_TEST_CASE("bad input: curvature at a cusp and other degenerate analysis", "[core][bezier][error]", double, float, Q16_16) {
  using S = TestType;
  // r'(t) = 3[(1-t)² (2,2) + 2(1-t)t (-2,0) + t² (2,-2)] vanishes at t = 1/2: a cusp.
  const auto cusp = must(Curve<S>::create({point<S>(0, 0), point<S>(2, 2), point<S>(0, 2), point<S>(2, 0)}));
  CHECK(max_error(must(cusp.derivative_at(scalar<S>(0.5), 1)), {0, 0}) == 0.0);
  check_failure(curvature(cusp, scalar<S>(0.5)), Error::DegenerateCurve);
  check_failure(osculating_center(cusp, scalar<S>(0.5)), Error::DegenerateCurve);
  // A straight line has zero curvature: its osculating circle does not exist.
  const auto line = must(Curve<S>::create({point<S>(0, 0), point<S>(1, 1), point<S>(3, 3)}));
  check_failure(osculating_center(line, scalar<S>(0.5)), Error::DegenerateCurve);
  CHECK(to_double(must(curvature(line, scalar<S>(0.5)))) == 0.0);
  // A degree-0 curve has no tangent anywhere.
  const auto dot = must(Curve<S>::create({point<S>(1, 1)}));
  check_failure(curvature(dot, scalar<S>(0.5)), Error::DegenerateCurve);
  // G2 join construction: α must be positive and the curve a cubic.
  check_failure(g2_join_cubic(tv04<S>(), S{}, S{}), Error::InvalidArgument);
  check_failure(g2_join_cubic(tv04<S>(), scalar<S>(-1), S{}), Error::InvalidArgument);
  check_failure(g2_join_cubic(line, from_int<S>(1), S{}), Error::DegreeMismatch);
  // Arc length: tolerance must be positive and the interval ordered.
  check_failure(arc_length(tv04<S>(), S{}, from_int<S>(1), S{}), Error::InvalidTolerance);
  check_failure(arc_length(tv04<S>(), from_int<S>(1), S{}, scalar<S>(0.01)), Error::InvalidInterval);
}

TEST_CASE("power basis: Horner on an in-range Q16.16 curve does not stop on large partial sums", "[core][bezier][error]") {
  using S = Q16_16;
  // b = (0, -10000, -10000, 30000): a = (0, -30000, 30000, 30000) all fit, but the Horner partial
  // sum a3 t + a2 reaches 60000 at t = 1 although p(1) = 30000.
  const auto curve = must(Curve<S, 1>::create({Vec<S, 1>{{scalar<S>(0)}}, Vec<S, 1>{{scalar<S>(-10000)}},
                                               Vec<S, 1>{{scalar<S>(-10000)}}, Vec<S, 1>{{scalar<S>(30000)}}}));
  const auto power = must(to_power_basis(curve));
  CHECK(to_double(power.coefficients[1][0]) == -30000);
  CHECK(to_double(power.coefficients[2][0]) == 30000);
  CHECK(to_double(power.coefficients[3][0]) == 30000);
  for (const double t : {0.0, 0.25, 0.5, 0.75, 0.9, 1.0}) {
    INFO("t = " << t);
    // Exact dyadic values: p(t) = -30000 t + 30000 t² + 30000 t³.
    const double expected = -30000 * t + 30000 * t * t + 30000 * t * t * t;
    Vec<S, 1> value{};
    REQUIRE_NOTHROW(value = power.evaluate(scalar<S>(t)));
    // Three roundings of half a unit, each magnified by at most t <= 1, plus t = 0.9 rounded
    // (|p'| <= 90000 times half a unit of t).
    CHECK(std::fabs(to_double(value[0]) - (t == 0.9 ? -30000 * to_double(scalar<S>(t)) +
                                                          30000 * std::pow(to_double(scalar<S>(t)), 2) +
                                                          30000 * std::pow(to_double(scalar<S>(t)), 3)
                                                    : expected)) <= 4 * unit<S>());
  }
}

TEST_CASE("bad input: a Q16.16 composite interval wider than the range is refused, not trapped later", "[core][composite][error]") {
  using S = Q16_16;
  const auto curve = tv04<S>();
  CompositeBezier<S, 2, 7, 4> composite(scalar<S>(-30000));
  // u_1 - u_0 = 60000 does not fit: the width could never be formed by locate() or derivatives.
  check_failure(composite.try_append(curve, scalar<S>(30000)), Error::FixedOverflow, 0);
  CHECK(composite.size() == 0);
  // A representable width works everywhere in the domain.
  REQUIRE(composite.try_append(curve, scalar<S>(2000)).has_value());
  CHECK(max_error(must(composite.evaluate(scalar<S>(-14000))), {2, 15 / 8.}) == 0.0);
  CHECK(must(composite.derivative_at(scalar<S>(2000), 1))[1] < S{});
}

TEMPLATE_TEST_CASE("bad input: NaN arc data is NotFinite", "[core][rational][arc][error]", double, float) {
  using S = TestType;
  const S nan = std::numeric_limits<S>::quiet_NaN();
  const auto ccw = ArcDirection::CounterClockwise;
  const S tol = S{0.001f};
  for (const auto& [center, start, end] : {std::array<Vec2<S>, 3>{Vec2<S>{{nan, S{0}}}, point<S>(1, 0), point<S>(0, 1)},
                                           std::array<Vec2<S>, 3>{point<S>(0, 0), Vec2<S>{{S{1}, nan}}, point<S>(0, 1)},
                                           std::array<Vec2<S>, 3>{point<S>(0, 0), point<S>(1, 0), Vec2<S>{{nan, S{1}}}}}) {
    const auto arc = circular_arc<S, 7>(center, start, end, ccw, tol);
    REQUIRE_FALSE(arc.has_value());
    CHECK(arc.error() == Error::NotFinite);
  }
  const auto circle = full_circle<S, 7>(Vec2<S>{{nan, S{0}}}, S{1});
  REQUIRE_FALSE(circle.has_value());
  CHECK(circle.error() == Error::NotFinite);
  CHECK_FALSE(full_circle<S, 7>(point<S>(0, 0), nan).has_value());
}
