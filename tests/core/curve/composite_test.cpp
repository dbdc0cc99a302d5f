// SPDX-License-Identifier: MIT
// Composite Bézier curves and joins: seed digest 000/002/003 TV-13/TV-14 (G2 and C2 joins of
// cubics) and seed 001 TV-06 on [0,2], TV-09 (C^r continuation), TV-10 (control polygon bound),
// continuity classification and segment lookup, in double, float and Q16.16.
#include <array>
#include <cmath>
#include <vector>

#include "curve_test_support.hpp"

using namespace curvestep;
using namespace curvestep::testing;

namespace {

template <class S>
using Cubic = Bezier<S, 2, 7>;
template <class S, std::size_t Segments = 8>
using Composite = CompositeBezier<S, 2, 7, Segments>;

template <class S>
Cubic<S> tv04() {  // (0,0),(1,2),(3,3),(4,0)
  return must(Cubic<S>::create({point<S>(0, 0), point<S>(1, 2), point<S>(3, 3), point<S>(4, 0)}));
}
template <class S>
Cubic<S> example_1_2() {  // seed 001 Example 1.2: (0,1),(0,4),(5,5),(7,0)
  return must(Cubic<S>::create({point<S>(0, 1), point<S>(0, 4), point<S>(5, 5), point<S>(7, 0)}));
}
template <class S>
Cubic<S> example_1_1() {  // seed 001 Example 1.1: (0,1),(1,1),(2,0)
  return must(Cubic<S>::create({point<S>(0, 1), point<S>(1, 1), point<S>(2, 0)}));
}

/// Continuity tolerance for derivatives of size ~`scale` built from inputs rounded to the format.
template <class S>
double join_tolerance(double scale) {
  return FixedPoint<S> ? 256 * unit<S>() * std::fmax(1.0, scale / 32) : 1e3 * unit<S>() * std::fmax(1.0, scale);
}

}  // namespace

TEMPLATE_TEST_CASE("composite: seed 001 TV-06 derivatives on [0,2] are scaled by 1 over (b-a)^r", "[core][composite][seed]", double,
                   float, Q16_16) {
  using S = TestType;
  Composite<S> curve(from_int<S>(0));
  REQUIRE(curve.try_append(example_1_2<S>(), from_int<S>(2)).has_value());
  CHECK(max_error(must(curve.derivative_at(from_int<S>(0), 1)), {0, 9 / 2.}) == 0.0);
  CHECK(max_error(must(curve.derivative_at(from_int<S>(2), 1)), {3, -15 / 2.}) == 0.0);
  CHECK(max_error(must(curve.derivative_at(from_int<S>(0), 2)), {15 / 2., -3}) == 0.0);
  // The shape is unchanged: s(u) = p(u/2), e.g. s(1) = p(1/2) = (2.75, 3.5), s(1/2) = p(1/4).
  CHECK(max_error(must(curve.evaluate(from_int<S>(1))), {2.75, 3.5}) == 0.0);
  CHECK(max_error(must(curve.evaluate(scalar<S>(0.5))), {13 / 16., 45 / 16.}) == 0.0);
  // On [0,1] the same control points give the unscaled TV-06 values.
  Composite<S> unit_curve(from_int<S>(0));
  REQUIRE(unit_curve.try_append(example_1_2<S>(), from_int<S>(1)).has_value());
  CHECK(max_error(must(unit_curve.derivative_at(scalar<S>(0.25), 1)), {6, 21 / 4.}) == 0.0);
  CHECK(max_error(must(unit_curve.derivative_at(scalar<S>(0.75), 2)), {-6, -30}) == 0.0);
}

TEMPLATE_TEST_CASE("continuation: seed 001 TV-09 cubic C2 joins for mu 2 3 and 3/2", "[core][composite][seed]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto p = example_1_2<S>();
  SECTION("mu = 2 (uniform): d = (7,0), (9,-5), (8,-16), also the blossoms P(1,1,2), P(1,2,2)") {
    const auto d = must(continuation_points(p, from_int<S>(2), 2));
    CHECK(max_error(d[0], {7, 0}) == 0.0);
    CHECK(max_error(d[1], {9, -5}) == 0.0);
    CHECK(max_error(d[2], {8, -16}) == 0.0);
    const std::array<S, 3> u112{from_int<S>(1), from_int<S>(1), from_int<S>(2)};
    const std::array<S, 3> u122{from_int<S>(1), from_int<S>(2), from_int<S>(2)};
    CHECK(max_error(must(p.blossom(u112)), {9, -5}) == 0.0);
    CHECK(max_error(must(p.blossom(u122)), {8, -16}) == 0.0);
    // As a composite on [0,1] + [1,2]: p' = q' = (6,-15), p'' = q'' = (-18,-36) at u = 1.
    Composite<S> curve(from_int<S>(0));
    REQUIRE(curve.try_append(p, from_int<S>(1)).has_value());
    REQUIRE(curve.try_append(must(Cubic<S>::create({d[0], d[1], d[2], point<S>(10, -20)})), from_int<S>(2)).has_value());
    CHECK(max_error(must(curve.segment_derivative(0, from_int<S>(1), 1)), {6, -15}) == 0.0);
    CHECK(max_error(must(curve.segment_derivative(1, from_int<S>(0), 1)), {6, -15}) == 0.0);
    CHECK(max_error(must(curve.segment_derivative(0, from_int<S>(1), 2)), {-18, -36}) == 0.0);
    CHECK(max_error(must(curve.segment_derivative(1, from_int<S>(0), 2)), {-18, -36}) == 0.0);
    const auto c = must(continuity(curve, 1, join_tolerance<S>(36)));
    CHECK(c.parametric == 2);
    CHECK(c.geometric == 2);
  }
  SECTION("mu = 3: d = (7,0), (11,-10), (3,-44)") {
    const auto d = must(continuation_points(p, from_int<S>(3), 2));
    CHECK(max_error(d[0], {7, 0}) == 0.0);
    CHECK(max_error(d[1], {11, -10}) == 0.0);
    CHECK(max_error(d[2], {3, -44}) == 0.0);
    // Composite on [0,1] + [1,3]: the derivatives with respect to u agree (C2).
    Composite<S> curve(from_int<S>(0));
    REQUIRE(curve.try_append(p, from_int<S>(1)).has_value());
    REQUIRE(curve.try_append(must(Cubic<S>::create({d[0], d[1], d[2], point<S>(0, -60)})), from_int<S>(3)).has_value());
    CHECK(must(continuity(curve, 1, join_tolerance<S>(36))).parametric == 2);
  }
  SECTION("[a,b] = [0,2], c = 3 (mu = 3/2): d = (7,0), (8,-5/2), (33/4,-13/2) and q' q'' at u = 2") {
    const auto d = must(continuation_points(p, scalar<S>(1.5), 2));
    CHECK(max_error(d[0], {7, 0}) == 0.0);
    CHECK(max_error(d[1], {8, -2.5}) == 0.0);
    CHECK(max_error(d[2], {33 / 4., -6.5}) == 0.0);
    Composite<S> curve(from_int<S>(0));
    REQUIRE(curve.try_append(p, from_int<S>(2)).has_value());
    REQUIRE(curve.try_append(must(Cubic<S>::create({d[0], d[1], d[2], point<S>(9, -9)})), from_int<S>(3)).has_value());
    CHECK(max_error(must(curve.segment_derivative(0, from_int<S>(1), 1)), {3, -7.5}) == 0.0);
    CHECK(max_error(must(curve.segment_derivative(1, from_int<S>(0), 1)), {3, -7.5}) == 0.0);
    CHECK(max_error(must(curve.segment_derivative(0, from_int<S>(1), 2)), {-4.5, -9}) == 0.0);
    CHECK(max_error(must(curve.segment_derivative(1, from_int<S>(0), 2)), {-4.5, -9}) == 0.0);
    // derivative_at(u = 2) lies on the breakpoint and reads the later segment.
    CHECK(max_error(must(curve.derivative_at(from_int<S>(2), 1)), {3, -7.5}) == 0.0);
    CHECK(must(continuity(curve, 1, join_tolerance<S>(10))).parametric == 2);
  }
  SECTION("C^3 continuation with k = n extends the cubic itself") {
    const auto d = must(continuation_points(p, from_int<S>(2), 3));
    // d_3 = p(2) = (-4,-37) (seed 001 TV-07 extrapolation on [0,2]).
    CHECK(max_error(d[3], {-4, -37}) == 0.0);
  }
}

TEMPLATE_TEST_CASE("continuation: seed 001 TV-09 quadratic C1 joins for mu 4 2 and 4/3", "[core][composite][seed]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto p = example_1_1<S>();
  struct Case {
    double c, x, y;
  };
  for (const Case& k : {Case{4, 5, -3}, Case{2, 3, -1}, Case{4 / 3., 7 / 3., -1 / 3.}}) {
    INFO("c = " << k.c);
    // µ = (c - a)/(b - a) = c for [a,b] = [0,1]; 4/3 is not representable: one rounding of µ,
    // magnified by |b2 - b1| = √2 in d1.
    const S mu = scalar<S>(k.c);
    const double tol = FixedPoint<S> ? 2 * unit<S>() : 8 * unit<S>() * 4;
    const auto d = must(continuation_points(p, mu, 1));
    CHECK(max_error(d[0], {2, 0}) == 0.0);
    CHECK(max_error(d[1], {k.x, k.y}) <= tol);
    // q'(1) = p'(1) = (2,-2) with respect to u on [1, c].
    Composite<S> curve(from_int<S>(0));
    REQUIRE(curve.try_append(p, from_int<S>(1)).has_value());
    REQUIRE(curve.try_append(must(Cubic<S>::create({d[0], d[1], point<S>(3, 1)})), mu).has_value());
    const double derivative_tol = FixedPoint<S> ? 8 * unit<S>() : 64 * unit<S>() * 4;
    CHECK(max_error(must(curve.segment_derivative(0, from_int<S>(1), 1)), {2, -2}) == 0.0);
    CHECK(max_error(must(curve.segment_derivative(1, from_int<S>(0), 1)), {2, -2}) <= derivative_tol);
    CHECK(must(continuity(curve, 1, join_tolerance<S>(4))).parametric >= 1);
    // Example 2.2: b2 divides b1 d1 in the ratio |[a,b]| : |[b,c]| = 1 : (c - 1).
    const double ratio = std::hypot(to_double(d[1][0]) - 2, to_double(d[1][1])) / std::hypot(1.0, 1.0);
    CHECK(std::fabs(ratio - (k.c - 1)) <= 16 * tolerance<S>(4, 4));
  }
}

TEMPLATE_TEST_CASE("join: TV-13 G2 join of cubics with alpha 0.8 and beta 2", "[core][composite][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto p = tv04<S>();
  const auto q = must(g2_join_cubic(p, scalar<S>(0.8), scalar<S>(2)));
  // α = 0.8 is rounded in Q16.16 and float (half a unit); |∂q2/∂α| = |2α p1 - (4α+2) p2 + (2α+2) p3| < 40.
  const double input = FixedPoint<S> ? 20 * unit<S>() + 8 * unit<S>() : 64 * unit<S>() * 40;
  CHECK(max_error(q[0], {24 / 5., -12 / 5.}) <= input);
  CHECK(max_error(q[1], {149 / 25., -259 / 25.}) <= input);
  // The second arc with a free q3 (chosen as (8,-12)).
  const auto second = must(Cubic<S>::create({p[3], q[0], q[1], point<S>(8, -12)}));
  // Derivative checks of the digest: r1'(1), r2'(0) = 0.8 r1'(1), r1''(1), r2''(0) = 0.64 r1''(1) + 2 r1'(1).
  CHECK(max_error(must(p.derivative_at(from_int<S>(1), 1)), {3, -9}) == 0.0);
  CHECK(max_error(must(p.derivative_at(from_int<S>(1), 2)), {-6, -24}) == 0.0);
  CHECK(max_error(must(second.derivative_at(from_int<S>(0), 1)), {12 / 5., -36 / 5.}) <= 3 * input);
  CHECK(max_error(must(second.derivative_at(from_int<S>(0), 2)), {54 / 25., -834 / 25.}) <= 18 * input);
  // Signed curvature on both sides -0.147572957475 (curvature divides by |r'|^3: tolerance relative).
  const double kappa = -0.147572957475;
  const double kappa_tol = FixedPoint<S> ? 1e-3 : 1e-4;
  CHECK(std::fabs(to_double(must(curvature(p, from_int<S>(1)))) - kappa) <= kappa_tol);
  CHECK(std::fabs(to_double(must(curvature(second, from_int<S>(0)))) - kappa) <= kappa_tol);
  // As a composite on unit intervals: not C1 (speed ratio 0.8) but G2.
  Composite<S> curve(from_int<S>(0));
  REQUIRE(curve.try_append(p, from_int<S>(1)).has_value());
  REQUIRE(curve.try_append(second, from_int<S>(2)).has_value());
  const auto c = must(continuity(curve, 1, join_tolerance<S>(36)));
  CHECK(c.parametric == 0);
  CHECK(c.geometric == 2);
  // Reparametrised on [1, 1.8] the same polygon is C1 (the interval absorbs α = 0.8) but still
  // not C2 (β ≠ 0).
  Composite<S> rescaled(from_int<S>(0));
  REQUIRE(rescaled.try_append(p, from_int<S>(1)).has_value());
  REQUIRE(rescaled.try_append(second, scalar<S>(1.8)).has_value());
  const auto r = must(continuity(rescaled, 1, join_tolerance<S>(60)));
  CHECK(r.parametric == 1);
  CHECK(r.geometric == 2);
}

TEMPLATE_TEST_CASE("join: TV-14 parametric C2 join of cubics", "[core][composite][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto p = tv04<S>();
  const auto q = must(g2_join_cubic(p, from_int<S>(1), from_int<S>(0)));
  CHECK(max_error(q[0], {5, -3}) == 0.0);
  CHECK(max_error(q[1], {5, -10}) == 0.0);
  // The seed's [D] formulas q1 = 2p3 - p2, q2 = p1 - 4p2 + 4p3 and the C2 continuation with µ = 2 agree.
  const auto d = must(continuation_points(p, from_int<S>(2), 2));
  CHECK(d[1] == q[0]);
  CHECK(d[2] == q[1]);
  Composite<S> curve(from_int<S>(0));
  REQUIRE(curve.try_append(p, from_int<S>(1)).has_value());
  REQUIRE(curve.try_append(must(Cubic<S>::create({p[3], q[0], q[1], point<S>(7, -12)})), from_int<S>(2)).has_value());
  const auto c = must(continuity(curve, 1, join_tolerance<S>(30)));
  CHECK(c.parametric == 2);
  CHECK(c.geometric == 2);
}

TEMPLATE_TEST_CASE("continuity: corners C0 joins G1 joins and gaps are told apart", "[core][composite]", double, float, Q16_16) {
  using S = TestType;
  const auto line = [](double x0, double y0, double x1, double y1) {
    return must(Cubic<S>::create({point<S>(x0, y0), point<S>(x1, y1)}));
  };
  SECTION("a corner is G0 only") {
    Composite<S> curve(from_int<S>(0));
    REQUIRE(curve.try_append(line(0, 0, 1, 0), from_int<S>(1)).has_value());
    REQUIRE(curve.try_append(line(1, 0, 1, 1), from_int<S>(2)).has_value());
    const auto c = must(continuity(curve, 1, join_tolerance<S>(1)));
    CHECK(c.parametric == 0);
    CHECK(c.geometric == 0);
  }
  SECTION("a gap is not even C0") {
    Composite<S> curve(from_int<S>(0));
    REQUIRE(curve.try_append(line(0, 0, 1, 0), from_int<S>(1)).has_value());
    REQUIRE(curve.try_append(line(1, 0.5, 2, 0.5), from_int<S>(2)).has_value());
    const auto c = must(continuity(curve, 1, join_tolerance<S>(1)));
    CHECK(c.parametric == -1);
    CHECK(c.geometric == -1);
  }
  SECTION("collinear lines at different speeds: G2 (zero curvature) but only C0") {
    Composite<S> curve(from_int<S>(0));
    REQUIRE(curve.try_append(line(0, 0, 1, 0), from_int<S>(1)).has_value());
    REQUIRE(curve.try_append(line(1, 0, 3, 0), from_int<S>(2)).has_value());
    const auto c = must(continuity(curve, 1, join_tolerance<S>(2)));
    CHECK(c.parametric == 0);
    CHECK(c.geometric == 2);
  }
  SECTION("a C1 join with a curvature jump is G1") {
    // TV-04 followed by q1 = 2p3 - p2 = (5,-3) but a different q2: r2'' differs, κ jumps.
    Composite<S> curve(from_int<S>(0));
    REQUIRE(curve.try_append(tv04<S>(), from_int<S>(1)).has_value());
    REQUIRE(curve.try_append(must(Cubic<S>::create({point<S>(4, 0), point<S>(5, -3), point<S>(7, -4), point<S>(9, -4)})),
                             from_int<S>(2))
                .has_value());
    const auto c = must(continuity(curve, 1, join_tolerance<S>(30)));
    CHECK(c.parametric == 1);
    CHECK(c.geometric == 1);
  }
  SECTION("joint index outside 1..size-1") {
    Composite<S> curve(from_int<S>(0));
    REQUIRE(curve.try_append(line(0, 0, 1, 0), from_int<S>(1)).has_value());
    REQUIRE(curve.try_append(line(1, 0, 2, 0), from_int<S>(2)).has_value());
    const auto zero = continuity(curve, 0, 1e-3);
    REQUIRE_FALSE(zero.has_value());
    CHECK(zero.error() == Error::InvalidArgument);
    CHECK(zero.where() == 0);
    const auto two = continuity(curve, 2, 1e-3);
    REQUIRE_FALSE(two.has_value());
    CHECK(two.error() == Error::InvalidArgument);
    CHECK(two.where() == 2);
  }
}

TEMPLATE_TEST_CASE("composite: locate finds the segment at and between breakpoints", "[core][composite]", double, float, Q16_16) {
  using S = TestType;
  // Seven segments on dyadic breakpoints (exact in every format).
  const std::array<double, 8> breaks{-2, -1.5, 0, 0.25, 1, 3, 3.5, 8};
  Composite<S, 7> curve(scalar<S>(breaks[0]));
  for (std::size_t j = 0; j + 1 < breaks.size(); ++j) {
    const double x = static_cast<double>(j);
    REQUIRE(curve.try_append(must(Cubic<S>::create({point<S>(x, 0), point<S>(x + 1, 0)})), scalar<S>(breaks[j + 1])).has_value());
  }
  REQUIRE(curve.size() == 7);
  CHECK(curve.full());
  CHECK(curve.available() == 0);
  CHECK(to_double(curve.domain_start()) == -2);
  CHECK(to_double(curve.domain_end()) == 8);
  for (std::size_t j = 0; j < 7; ++j) {
    INFO("segment " << j);
    // On the breakpoint u_j: segment j, local 0 (a breakpoint belongs to the later segment).
    const auto at = must(curve.locate(scalar<S>(breaks[j])));
    CHECK(at.segment == j);
    CHECK(at.local == S{});
    // Halfway between breakpoints: local 1/2, and the point is the segment's midpoint.
    const double middle = (breaks[j] + breaks[j + 1]) / 2;
    const auto between = must(curve.locate(scalar<S>(middle)));
    CHECK(between.segment == j);
    CHECK(to_double(between.local) == 0.5);
    CHECK(max_error(must(curve.evaluate(scalar<S>(middle))), {static_cast<double>(j) + 0.5, 0}) == 0.0);
  }
  // The domain end belongs to the last segment at local 1.
  const auto end = must(curve.locate(scalar<S>(8)));
  CHECK(end.segment == 6);
  CHECK(end.local == from_int<S>(1));
  // Random parameters against a linear search.
  Random random(31);
  for (int k = 0; k < test_count(500); ++k) {
    const S u = random.coordinate<S>(-2, 8);
    std::size_t expected = 0;
    while (expected + 1 < 7 && !(u < scalar<S>(breaks[expected + 1]))) ++expected;
    const auto where = must(curve.locate(u));
    INFO("u = " << to_double(u));
    CHECK(where.segment == expected);
    const double local = (to_double(u) - breaks[expected]) / (breaks[expected + 1] - breaks[expected]);
    CHECK(std::fabs(to_double(where.local) - local) <= tolerance<S>(1, 4));
  }
}

TEMPLATE_TEST_CASE("bezier: seed 001 TV-10 control polygon bound values", "[core][bezier][seed]", double, float, Q16_16) {
  using S = TestType;
  // Theorem 4.1: max_i ||p(i/n) - b_i||_inf <= floor(n/2) ceil(n/2) / (2n) · max ||Δ² b_i||_inf,
  // computed here from the formula (the library has no flatness function).
  const auto bound = [](const std::vector<std::array<double, 2>>& b) {
    const std::size_t n = b.size() - 1;
    double m = 0;
    for (std::size_t i = 0; i + 2 <= n; ++i) {
      for (std::size_t a = 0; a < 2; ++a) m = std::fmax(m, std::fabs(b[i + 2][a] - 2 * b[i + 1][a] + b[i][a]));
    }
    return static_cast<double>((n / 2) * ((n + 1) / 2)) / (2.0 * static_cast<double>(n)) * m;
  };
  const std::vector<std::array<double, 2>> cubic{{0, 1}, {0, 4}, {5, 5}, {7, 0}};
  CHECK(bound(cubic) == 2.0);  // Δ² = (5,-2), (-3,-6): M = 6/3
  const auto p = example_1_2<S>();
  // p(1/3) - b1 = (37/27, -22/27), p(2/3) - b2 = (-19/27, -50/27): 1/3 is rounded (float, Q16.16),
  // which moves p by at most |p'| · half a unit (|p'| <= 15).
  const double tol = FixedPoint<S> ? 16 * unit<S>() : 64 * unit<S>() * 8;
  const auto third = must(p.evaluate(scalar<S>(1 / 3.)));
  const auto two_thirds = must(p.evaluate(scalar<S>(2 / 3.)));
  CHECK(max_error(third, {37 / 27., 4 - 22 / 27.}) <= tol);
  CHECK(max_error(two_thirds, {5 - 19 / 27., 5 - 50 / 27.}) <= tol);
  CHECK(std::fmax(std::fabs(to_double(third[0]) - 0), std::fabs(to_double(third[1]) - 4)) <= 2.0);
  CHECK(std::fmax(std::fabs(to_double(two_thirds[0]) - 5), std::fabs(to_double(two_thirds[1]) - 5)) <= 2.0);
  // Example 1.1: Δ²b0 = (0,-1), p(1/2) - b1 = (0,-1/4): equality with the constant 1/4.
  const std::vector<std::array<double, 2>> quadratic{{0, 1}, {1, 1}, {2, 0}};
  CHECK(bound(quadratic) == 0.25);
  const auto middle = must(example_1_1<S>().evaluate(scalar<S>(0.5)));
  CHECK(max_error(middle, {1, 0.75}) == 0.0);
  CHECK(std::fabs(to_double(middle[1]) - 1) == bound(quadratic));
}
