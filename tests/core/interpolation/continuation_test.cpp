// SPDX-License-Identifier: MIT
// Seed 001 TV-09: C^r continuation of a segment (continuity.hpp's continuation_points), with the
// joins checked by derivatives from both sides; digest 000/002/003 TV-30 knot-ratio bound.
#include <array>
#include <span>

#include <catch2/catch.hpp>

#include <curvestep/core.hpp>
#include <curvestep/core/interpolation/cubic_spline.hpp>
#include <support/numeric.hpp>

#include "interpolation_support.hpp"

using namespace curvestep;
using namespace curvestep::testing;  // support/numeric.hpp and the folder's helpers

namespace {
template <class S>
Bezier<S, 2, 3> example_1_2() {
  return Bezier<S, 2, 3>::create({point<S>(0, 1), point<S>(0, 4), point<S>(5, 5), point<S>(7, 0)}).value();
}
}  // namespace

TEMPLATE_TEST_CASE("interpolation: TV-09 C2 continuation of a cubic for several interval ratios", "[core][interpolation][seed]",
                   double, float, Q16_16) {
  using S = TestType;
  const auto p = example_1_2<S>();
  struct Case {
    double a, b, c;
    std::array<std::array<double, 2>, 3> d;
    std::array<double, 2> first, second;  // q', q'' at the joint (in u)
  };
  const std::array<Case, 3> cases{{
      {0, 1, 2, {{{7, 0}, {9, -5}, {8, -16}}}, {6, -15}, {-18, -36}},
      {0, 1, 3, {{{7, 0}, {11, -10}, {3, -44}}}, {6, -15}, {-18, -36}},
      {0, 2, 3, {{{7, 0}, {8, -2.5}, {33 / 4., -6.5}}}, {3, -7.5}, {-4.5, -9}},
  }};
  for (const auto& e : cases) {
    const S mu = scalar<S>((e.c - e.a) / (e.b - e.a));
    const auto d = continuation_points(p, mu, 2).value();
    for (std::size_t k = 0; k < 3; ++k) CHECK(max_error(d[k], e.d[k]) == 0);
    // Both sides of the joint: the new segment with a free last point (20, 20).
    CompositeBezier<S, 2, 3, 2> curve(scalar<S>(e.a));
    REQUIRE(curve.try_append(p, scalar<S>(e.b)).has_value());
    REQUIRE(curve.try_append(Bezier<S, 2, 3>::create({d[0], d[1], d[2], point<S>(20, 20)}).value(), scalar<S>(e.c)).has_value());
    CHECK(max_error(curve.segment_derivative(0, from_int<S>(1), 1).value(), e.first) == 0);
    CHECK(max_error(curve.segment_derivative(1, S{}, 1).value(), e.first) == 0);
    CHECK(max_error(curve.segment_derivative(0, from_int<S>(1), 2).value(), e.second) == 0);
    CHECK(max_error(curve.segment_derivative(1, S{}, 2).value(), e.second) == 0);
    CHECK(continuity(curve, 1, 0.0).value().parametric == 2);
  }
}

TEMPLATE_TEST_CASE("interpolation: TV-09 C1 continuation of a quadratic for µ = 4, 2 and 4/3", "[core][interpolation][seed]", double,
                   float, Q16_16) {
  using S = TestType;
  const auto p = Bezier<S, 2, 3>::create({point<S>(0, 1), point<S>(1, 1), point<S>(2, 0)}).value();
  const std::array<std::array<double, 3>, 3> cases{{{4, 5, -3}, {2, 3, -1}, {4 / 3., 7 / 3., -1 / 3.}}};
  for (const auto& e : cases) {
    const double tol = e[0] == 4 / 3. ? solve_tolerance<S>(4) : 0.0;  // 4/3 is not dyadic
    const auto d = continuation_points(p, scalar<S>(e[0]), 1).value();
    CHECK(max_error(d[0], {2, 0}) == 0);
    CHECK(max_error(d[1], {e[1], e[2]}) <= tol);
    // p on [0,1], q on [1, µ]: q'(1) = 2 (d1 − d0)/(µ − 1) = p'(1) = (2, −2).
    CompositeBezier<S, 2, 3, 2> curve(S{});
    REQUIRE(curve.try_append(p, from_int<S>(1)).has_value());
    REQUIRE(curve.try_append(Bezier<S, 2, 3>::create({d[0], d[1], point<S>(9, 9)}).value(), scalar<S>(e[0])).has_value());
    CHECK(max_error(curve.segment_derivative(1, S{}, 1).value(), {2, -2}) <= 4 * tol);
    CHECK(max_error(curve.segment_derivative(0, from_int<S>(1), 1).value(), {2, -2}) == 0);
  }
}

TEMPLATE_TEST_CASE("interpolation: TV-30 knot ratio bound of Theorem 3.3 is sufficient, not necessary", "[core][interpolation][seed]",
                   double, float, Q16_16) {
  using S = TestType;
  const double low = 0.381966011250105;
  const double high = 2.618033988749895;
  CHECK(to_double(knot_ratio_lower_bound<S>()) == Approx(low).margin(to_double(resolution<S>())));
  CHECK(to_double(knot_ratio_upper_bound<S>()) == Approx(high).margin(4 * to_double(resolution<S>())));
  const auto inside = scalars<S, 4>({0, 1, 3, 4});  // ratios 2 and 1/2
  CHECK(knot_ratios_within_bound(std::span<const S>(inside)).value());
  const auto outside = scalars<S, 4>({0, 1, 4, 5});  // ratio 3
  CHECK(!knot_ratios_within_bound(std::span<const S>(outside)).value());
  // The spline exists anyway: the system is diagonally dominant for any increasing knots.
  const auto p = curvestep::testing::points2<S, 4>({{{0, 0}, {1, 1}, {2, 0}, {3, 1}}});
  CompositeBezier<S, 2, 3, 4> curve;
  REQUIRE(interpolate_clamped_cubic(std::span<const Vec2<S>>(p), std::span<const S>(outside), point<S>(1, 0), point<S>(1, 0), curve)
              .has_value());
  CHECK(curvestep::testing::joint_jump(curve, 2, false) <= 8 * solve_tolerance<S>(4));
  const auto bad = scalars<S, 3>({0, 1, 1});
  CHECK(knot_ratios_within_bound(std::span<const S>(bad)).error() == Error::InvalidInterval);
}
