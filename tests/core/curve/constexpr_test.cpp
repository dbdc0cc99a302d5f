// SPDX-License-Identifier: MIT
// The Bézier core is constexpr: TV-04 and friends evaluated at compile time in Q16.16 (R16).
#include <array>

#include <catch2/catch.hpp>

#include <curvestep/core.hpp>

using namespace curvestep;
using namespace curvestep::literals;

namespace {

consteval Vec2<Q16_16> p(double x, double y) { return Vec2<Q16_16>{{Q16_16::constant(x), Q16_16::constant(y)}}; }

constexpr auto tv04 = Bezier<Q16_16, 2, 7>::create({p(0, 0), p(1, 2), p(3, 3), p(4, 0)}).value();

// TV-04 at 1/4 and 1/2, exact.
static_assert(tv04.point_at(0.25_q16) == p(29 / 32., 81 / 64.));
static_assert(tv04.point_at(0.5_q16) == p(2, 15 / 8.));
// TV-04 split halves.
static_assert(tv04.split(0.5_q16).value().left[2] == p(1.25, 1.75));
static_assert(tv04.split(0.5_q16).value().right[1] == p(2.75, 2));
// TV-05 hodograph and second derivative at 1/2.
static_assert(tv04.derivative_at(0.5_q16, 1).value() == p(4.5, 0.75));
static_assert(tv04.derivative_at(0.5_q16, 2).value() == p(0, -15));
// Degree elevation keeps the end points; reversal swaps them.
static_assert(tv04.elevated().value().degree() == 4);
static_assert(tv04.reversed().front() == p(4, 0));
// Blossom corners are the control points, the diagonal is the point.
static_assert(tv04.blossom(std::array<Q16_16, 3>{0.0_q16, 1.0_q16, 1.0_q16}).value() == p(3, 3));
static_assert(tv04.blossom(std::array<Q16_16, 3>{0.5_q16, 0.5_q16, 0.5_q16}).value() == p(2, 15 / 8.));
// Power basis TV-08: a1 = (3,6), a3 = (-2,-3).
static_assert(to_power_basis(tv04).value().coefficients[1] == p(3, 6));
static_assert(to_power_basis(tv04).value().coefficients[3] == p(-2, -3));
// Bad input at compile time: errors, not traps.
static_assert(tv04.evaluate(1.5_q16).error() == Error::ParameterOutOfRange);
static_assert(Bezier<Q16_16, 2, 7>::create(std::span<const Vec2<Q16_16>>{}).error() == Error::EmptyControlPolygon);
// TV-14 C2 join.
static_assert(g2_join_cubic(tv04, 1.0_q16, 0.0_q16).value()[1] == p(5, -10));
// TV-09 continuation with µ = 2 on seed 001 Example 1.2.
constexpr auto example_1_2 = Bezier<Q16_16, 2, 7>::create({p(0, 1), p(0, 4), p(5, 5), p(7, 0)}).value();
static_assert(continuation_points(example_1_2, 2.0_q16, 2).value()[2] == p(8, -16));
// Curvature of the TV-07-like quarter circle needs no runtime: the TV-16 curvature is 1 within units.
constexpr auto quarter = RationalBezier<Q16_16, 2, 7>::create({p(1, 0), p(1, 1), p(0, 1)},
                                                              {1.0_q16, Q16_16::constant(0.70710678118654752), 1.0_q16})
                             .value();
constexpr Q16_16 quarter_kappa = curvature(quarter, 0.5_q16).value();
static_assert(quarter_kappa > Q16_16::constant(1 - 1e-4) && quarter_kappa < Q16_16::constant(1 + 1e-4));

}  // namespace

TEST_CASE("bezier: the core evaluates at compile time", "[core][bezier][constexpr]") {
  // Everything above is checked by static_assert; this keeps one runtime assertion per file.
  CHECK(tv04.point_at(0.5_q16) == p(2, 15 / 8.));
}
