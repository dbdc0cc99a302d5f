// SPDX-License-Identifier: MIT
// C2 cubic interpolating splines against seed digests 000/002/003 TV-23..TV-28 (open, natural and
// clamped, uniform / non-uniform / chord-length) and seed 001 TV-12, TV-13 (closed), property P-6.
#include <array>
#include <cmath>
#include <random>
#include <span>
#include <type_traits>

#include <catch2/catch.hpp>

#include <curvestep/core.hpp>
#include <support/numeric.hpp>

#include "interpolation_support.hpp"

using namespace curvestep;
using namespace curvestep::testing;  // interpolation_support.hpp, support/numeric.hpp

namespace {
template <class S>
using Spline = CompositeBezier<S, 2, 3, 16>;

/// s'(u_j) read from the Bézier segments: 3 (q1 − p_j)/h_j, or at the last knot 3 (p_n − q2)/h.
template <class S>
Vec2<S> tangent_at_knot(const Spline<S>& curve, std::size_t j) {
  if (j < curve.size()) return curve.segment_derivative(j, S{}, 1).value();
  return curve.segment_derivative(j - 1, from_int<S>(1), 1).value();
}
}  // namespace

TEMPLATE_TEST_CASE("interpolation: TV-23 natural Ferguson spline through 4 points", "[core][interpolation][seed]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto p = points2<S, 4>({{{0, 0}, {1, 1}, {2, 0}, {3, 1}}});
  const auto u = scalars<S, 4>({0, 1, 2, 3});
  Spline<S> curve;
  REQUIRE(interpolate_natural_cubic(view(p), view(u), curve).has_value());
  check_passes_through(curve, p, false);
  const double tol = solve_tolerance<S>();
  const std::array<std::array<double, 2>, 4> d{{{1, 5 / 3.}, {1, -1 / 3.}, {1, -1 / 3.}, {1, 5 / 3.}}};
  for (std::size_t j = 0; j < 4; ++j) CHECK(max_error(tangent_at_knot(curve, j), d[j]) <= tol);
  const std::array<std::array<double, 2>, 3> middle{{{0.5, 0.75}, {1.5, 0.5}, {2.5, 0.25}}};
  for (std::size_t j = 0; j < 3; ++j) CHECK(max_error(curve.segment(j).point_at(scalar<S>(0.5)), middle[j]) <= tol);
  // r'' at the knots: 0, (0,-4), (0,4), 0, the same from both sides.
  CHECK(max_error(curve.segment_derivative(0, S{}, 2).value(), {0, 0}) <= 8 * tol);
  CHECK(max_error(curve.segment_derivative(0, from_int<S>(1), 2).value(), {0, -4}) <= 8 * tol);
  CHECK(max_error(curve.segment_derivative(1, S{}, 2).value(), {0, -4}) <= 8 * tol);
  CHECK(max_error(curve.segment_derivative(1, from_int<S>(1), 2).value(), {0, 4}) <= 8 * tol);
  CHECK(max_error(curve.segment_derivative(2, S{}, 2).value(), {0, 4}) <= 8 * tol);
  CHECK(max_error(curve.segment_derivative(2, from_int<S>(1), 2).value(), {0, 0}) <= 8 * tol);
  CHECK(joint_jump(curve, 1, false) <= tol);
  CHECK(joint_jump(curve, 2, false) <= 8 * tol);
  for (std::size_t j = 1; j < 3; ++j) CHECK(continuity(curve, j, 8 * tol).value().parametric == 2);
}

TEMPLATE_TEST_CASE("interpolation: TV-24 natural spline through 5 points", "[core][interpolation][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto p = points2<S, 5>({{{0, 0}, {1, 2}, {3, 3}, {4, 0}, {6, 1}}});
  const auto u = scalars<S, 5>({0, 1, 2, 3, 4});
  Spline<S> curve;
  REQUIRE(interpolate_natural_cubic(view(p), view(u), curve).has_value());
  check_passes_through(curve, p, false);
  const double tol = solve_tolerance<S>(4);
  const std::array<std::array<double, 2>, 5> d{
      {{9 / 14., 107 / 56.}, {12 / 7., 61 / 28.}, {1.5, -13 / 8.}, {9 / 7., -47 / 28.}, {33 / 14., 131 / 56.}}};
  for (std::size_t j = 0; j < 5; ++j) CHECK(max_error(tangent_at_knot(curve, j), d[j]) <= tol);
  const std::array<std::array<double, 2>, 4> middle{
      {{41 / 112., 433 / 448.}, {227 / 112., 1333 / 448.}, {395 / 112., 675 / 448.}, {545 / 112., -1 / 448.}}};
  for (std::size_t j = 0; j < 4; ++j) CHECK(max_error(curve.segment(j).point_at(scalar<S>(0.5)), middle[j]) <= tol);
  const std::array<std::array<double, 2>, 3> second{{{15 / 7., 15 / 28.}, {-18 / 7., -57 / 7.}, {15 / 7., 225 / 28.}}};
  for (std::size_t j = 1; j < 4; ++j) {
    CHECK(max_error(curve.segment_derivative(j, S{}, 2).value(), second[j - 1]) <= 8 * tol);
    CHECK(max_error(curve.segment_derivative(j - 1, from_int<S>(1), 2).value(), second[j - 1]) <= 8 * tol);
  }
  CHECK(max_error(curve.segment_derivative(0, S{}, 2).value(), {0, 0}) <= 8 * tol);
  CHECK(max_error(curve.segment_derivative(3, from_int<S>(1), 2).value(), {0, 0}) <= 8 * tol);
}

TEMPLATE_TEST_CASE("interpolation: TV-25 clamped uniform spline", "[core][interpolation][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto p = points2<S, 5>({{{0, 0}, {1, 2}, {3, 3}, {4, 0}, {6, 1}}});
  Spline<S> curve;
  REQUIRE(interpolate_clamped_cubic(view(p), Parametrization::Uniform, point<S>(1, 1), point<S>(1, -1), curve).has_value());
  check_passes_through(curve, p, false);
  const double tol = solve_tolerance<S>(4);
  const std::array<std::array<double, 2>, 5> v{{{1, 1}, {23 / 14., 139 / 56.}, {10 / 7., -27 / 14.}, {23 / 14., -43 / 56.}, {1, -1}}};
  for (std::size_t j = 0; j < 5; ++j) CHECK(max_error(tangent_at_knot(curve, j), v[j]) <= tol);
  const std::array<std::array<double, 3>, 4> values{
      {{0.5, 47 / 112., 365 / 448.}, {1.5, 227 / 112., 1367 / 448.}, {2.5, 389 / 112., 607 / 448.}, {3.5, 569 / 112., 237 / 448.}}};
  for (const auto& e : values) CHECK(max_error(curve.evaluate(scalar<S>(e[0])).value(), {e[1], e[2]}) <= tol);
  CHECK(max_error(curve.segment(0)[0], {0, 0}) == 0);
  CHECK(max_error(curve.segment(0)[1], {1 / 3., 1 / 3.}) <= tol);
  CHECK(max_error(curve.segment(0)[2], {19 / 42., 197 / 168.}) <= tol);
  CHECK(max_error(curve.segment(0)[3], {1, 2}) == 0);
  CHECK(joint_jump(curve, 2, false) <= 8 * tol);
}

TEMPLATE_TEST_CASE("interpolation: TV-27 clamped non-uniform spline matches second derivatives from both sides",
                   "[core][interpolation][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto p = points2<S, 4>({{{0, 0}, {1, 1}, {2, 0}, {3, 1}}});
  const auto u = scalars<S, 4>({0, 1, 3, 4});
  Spline<S> curve;
  REQUIRE(interpolate_clamped_cubic(view(p), view(u), point<S>(1, 0), point<S>(1, 0), curve).has_value());
  check_passes_through(curve, p, false);
  const double tol = solve_tolerance<S>(4);
  const std::array<std::array<double, 2>, 4> v{{{1, 0}, {11 / 14., 9 / 14.}, {11 / 14., 9 / 14.}, {1, 0}}};
  for (std::size_t j = 0; j < 4; ++j) CHECK(max_error(tangent_at_knot(curve, j), v[j]) <= tol);
  CHECK(max_error(curve.segment_derivative(0, from_int<S>(1), 2).value(), {-6 / 7., -24 / 7.}) <= 8 * tol);
  CHECK(max_error(curve.segment_derivative(1, S{}, 2).value(), {-6 / 7., -24 / 7.}) <= 8 * tol);
  CHECK(max_error(curve.segment_derivative(1, from_int<S>(1), 2).value(), {6 / 7., 24 / 7.}) <= 8 * tol);
  CHECK(max_error(curve.segment_derivative(2, S{}, 2).value(), {6 / 7., 24 / 7.}) <= 8 * tol);
  CHECK(max_error(curve.evaluate(scalar<S>(0.5)).value(), {59 / 112., 47 / 112.}) <= tol);
  CHECK(max_error(curve.evaluate(scalar<S>(2)).value(), {1.5, 0.5}) <= tol);
  CHECK(max_error(curve.evaluate(scalar<S>(3.5)).value(), {277 / 112., 65 / 112.}) <= tol);
  for (std::size_t j = 1; j < 3; ++j) CHECK(continuity(curve, j, 8 * tol).value().parametric == 2);
}

TEMPLATE_TEST_CASE("interpolation: TV-28 chord-length knots and natural and clamped splines", "[core][interpolation][seed]",
                   double, float, Q16_16) {
  using S = TestType;
  const auto p = points2<S, 4>({{{0, 0}, {3, 4}, {3, 10}, {11, 16}}});
  std::array<S, 4> u{};
  REQUIRE(parametrize(view(p), Parametrization::ChordLength, std::span<S>(u)).value() == 4);
  CHECK(to_double(u[0]) == 0);
  CHECK(to_double(u[1]) == 5);
  CHECK(to_double(u[2]) == 11);
  CHECK(to_double(u[3]) == 21);
  const double tol = solve_tolerance<S>(16);
  SECTION("natural ends") {
    Spline<S> curve;
    REQUIRE(interpolate_natural_cubic(view(p), Parametrization::ChordLength, curve).has_value());
    check_passes_through(curve, p, false);
    CHECK(to_double(curve.breakpoint(3)) == 21);
    const std::array<std::array<double, 2>, 4> v{
        {{651 / 835., 613 / 835.}, {201 / 835., 778 / 835.}, {138 / 835., 751 / 835.}, {933 / 835., 376 / 835.}}};
    for (std::size_t j = 0; j < 4; ++j) CHECK(max_error(tangent_at_knot(curve, j), v[j]) <= tol);
    CHECK(max_error(curve.evaluate(scalar<S>(2.5)).value(), {1227 / 668., 2507 / 1336.}) <= tol);
    CHECK(max_error(curve.evaluate(scalar<S>(8)).value(), {10209 / 3340., 23461 / 3340.}) <= tol);
    CHECK(max_error(curve.evaluate(scalar<S>(16)).value(), {3881 / 668., 9059 / 668.}) <= tol);
    CHECK(joint_jump(curve, 2, false) <= tol);
  }
  SECTION("clamped with near-unit tangents") {
    Spline<S> curve;
    REQUIRE(interpolate_clamped_cubic(view(p), view(u), point<S>(0.6, 0.8), point<S>(0.8, 0.6), curve).has_value());
    const std::array<std::array<double, 2>, 4> v{{{0.6, 0.8}, {152 / 545., 501 / 545.}, {116 / 545., 477 / 545.}, {0.8, 0.6}}};
    for (std::size_t j = 0; j < 4; ++j) CHECK(max_error(tangent_at_knot(curve, j), v[j]) <= tol);
    CHECK(max_error(curve.evaluate(scalar<S>(2.5)).value(), {1483 / 872., 1679 / 872.}) <= tol);
    CHECK(max_error(curve.evaluate(scalar<S>(8)).value(), {1662 / 545., 3833 / 545.}) <= tol);
    CHECK(max_error(curve.evaluate(scalar<S>(16)).value(), {683 / 109., 2909 / 218.}) <= tol);
    // Interior speeds ~0.961 and ~0.901: the parameter follows arc length closely.
    CHECK(std::hypot(v[1][0], v[1][1]) == Approx(0.961).margin(0.001));
    CHECK(std::hypot(v[2][0], v[2][1]) == Approx(0.901).margin(0.001));
    CHECK(joint_jump(curve, 2, false) <= tol);
  }
}

TEMPLATE_TEST_CASE("interpolation: TV-12 closed C2 cubic through a square and a triangle", "[core][interpolation][seed]", double,
                   float, Q16_16) {
  using S = TestType;
  const double tol = solve_tolerance<S>(4);
  {
    const auto p = points2<S, 4>({{{0, 0}, {4, 0}, {4, 4}, {0, 4}}});
    Spline<S> curve;
    REQUIRE(interpolate_closed_cubic(view(p), Parametrization::Uniform, curve).has_value());
    check_passes_through(curve, p, true);
    const std::array<std::array<std::array<double, 2>, 2>, 4> inner{
        {{{{1, -1}, {3, -1}}}, {{{5, 1}, {5, 3}}}, {{{3, 5}, {1, 5}}}, {{{-1, 3}, {-1, 1}}}}};
    for (std::size_t j = 0; j < 4; ++j) {
      CHECK(max_error(curve.segment(j)[1], inner[j][0]) <= tol);
      CHECK(max_error(curve.segment(j)[2], inner[j][1]) <= tol);
    }
    CHECK(max_error(curve.segment(0).point_at(scalar<S>(0.5)), {2, -0.75}) <= tol);
    CHECK(joint_jump(curve, 1, true) <= tol);
    CHECK(joint_jump(curve, 2, true) <= 8 * tol);
  }
  {
    const auto p = points2<S, 3>({{{0, 0}, {1, 0}, {0, 1}}});
    const auto u = scalars<S, 4>({0, 1, 2, 3});
    Spline<S> curve;
    REQUIRE(interpolate_closed_cubic(view(p), view(u), curve).has_value());
    check_passes_through(curve, p, true);
    const std::array<std::array<std::array<double, 2>, 2>, 3> inner{
        {{{{1 / 3., -1 / 3.}, {1, -1 / 3.}}}, {{{1, 1 / 3.}, {1 / 3., 1}}}, {{{-1 / 3., 1}, {-1 / 3., 1 / 3.}}}}};
    for (std::size_t j = 0; j < 3; ++j) {
      CHECK(max_error(curve.segment(j)[1], inner[j][0]) <= tol);
      CHECK(max_error(curve.segment(j)[2], inner[j][1]) <= tol);
    }
  }
}

TEMPLATE_TEST_CASE("interpolation: TV-13 closed C2 cubic through a pentagon, uniform and non-uniform",
                   "[core][interpolation][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto p = points2<S, 5>({{{0, 0}, {2, 0}, {3, 2}, {1, 3}, {-1, 1}}});
  const double tol = solve_tolerance<S>(4);
  SECTION("uniform") {
    const auto u = scalars<S, 6>({0, 1, 2, 3, 4, 5});
    Spline<S> curve;
    REQUIRE(interpolate_closed_cubic(view(p), view(u), curve).has_value());
    check_passes_through(curve, p, true);
    const std::array<std::array<double, 4>, 5> inner{{{7, -2, 15, -4}, {29, 4, 35, 14}, {31, 30, 21, 36}, {1, 30, -9, 18}, {-13, 4, -7, 2}}};
    for (std::size_t j = 0; j < 5; ++j) {
      CHECK(max_error(curve.segment(j)[1], {inner[j][0] / 11, inner[j][1] / 11}) <= tol);
      CHECK(max_error(curve.segment(j)[2], {inner[j][2] / 11, inner[j][3] / 11}) <= tol);
    }
    CHECK(joint_jump(curve, 2, true) <= 8 * tol);
  }
  SECTION("non-uniform") {
    const auto u = scalars<S, 6>({0, 2, 4, 5, 7, 9});
    Spline<S> curve;
    REQUIRE(interpolate_closed_cubic(view(p), view(u), curve).has_value());
    check_passes_through(curve, p, true);
    const std::array<std::array<double, 4>, 5> inner{{{5 / 9., -5 / 36., 53 / 45., -14 / 45.},
                                                      {127 / 45., 14 / 45., 173 / 45., 199 / 180.},
                                                      {116 / 45., 881 / 360., 76 / 45., 1051 / 360.},
                                                      {-17 / 45., 569 / 180., -43 / 45., 79 / 45.},
                                                      {-47 / 45., 11 / 45., -5 / 9., 5 / 36.}}};
    for (std::size_t j = 0; j < 5; ++j) {
      CHECK(max_error(curve.segment(j)[1], {inner[j][0], inner[j][1]}) <= tol);
      CHECK(max_error(curve.segment(j)[2], {inner[j][2], inner[j][3]}) <= tol);
    }
    CHECK(joint_jump(curve, 1, true) <= tol);
    CHECK(joint_jump(curve, 2, true) <= 8 * tol);
    for (std::size_t j = 1; j < 5; ++j) CHECK(continuity(curve, j, 8 * tol).value().parametric == 2);
  }
}

namespace {
/// ∫|s''|² du over a composite cubic, exactly (in double): s'' is linear on each segment.
template <class S>
double bending_energy(const CompositeBezier<S, 2, 3, 16>& curve) {
  double energy = 0;
  for (std::size_t j = 0; j < curve.size(); ++j) {
    const auto a = to_doubles(curve.segment_derivative(j, S{}, 2).value());
    const auto b = to_doubles(curve.segment_derivative(j, from_int<S>(1), 2).value());
    const double h = to_double(curve.breakpoint(j + 1)) - to_double(curve.breakpoint(j));
    energy += h * (a[0] * a[0] + a[1] * a[1] + a[0] * b[0] + a[1] * b[1] + b[0] * b[0] + b[1] * b[1]) / 3;
  }
  return energy;
}
}  // namespace

TEMPLATE_TEST_CASE("interpolation: P-6 the clamped C2 spline has the least bending energy", "[core][interpolation][seed]", double,
                   float, Q16_16) {
  using S = TestType;
  const auto p = points2<S, 5>({{{0, 0}, {1, 2}, {3, 3}, {4, 0}, {6, 1}}});
  const auto u = scalars<S, 5>({0, 1, 2, 3, 4});
  Spline<S> spline;
  REQUIRE(interpolate_clamped_cubic(view(p), view(u), point<S>(1, 1), point<S>(1, -1), spline).has_value());
  const double minimum = bending_energy(spline);
  std::array<Vec2<S>, 5> v{};
  for (std::size_t j = 0; j < 5; ++j) v[j] = tangent_at_knot(spline, j);
  // The energy grows quadratically in the perturbation: small steps only where rounding allows.
  const std::array<double, 4> steps = FixedPoint<S> || std::is_same_v<S, float> ? std::array<double, 4>{-0.5, -0.125, 0.125, 0.5}
                                                                                 : std::array<double, 4>{-0.5, -0.01, 0.01, 0.5};
  for (std::size_t j = 1; j < 4; ++j) {
    for (const double delta : steps) {
      for (std::size_t axis = 0; axis < 2; ++axis) {
        auto w = v;
        w[j][axis] = w[j][axis] + scalar<S>(delta);
        Spline<S> other(u[0]);
        for (std::size_t i = 0; i < 4; ++i) {
          REQUIRE(other.try_append(hermite_to_bezier(p[i], p[i + 1], w[i], w[i + 1], u[i], u[i + 1]).value(), u[i + 1]).has_value());
        }
        CHECK(bending_energy(other) > minimum);
      }
    }
  }
}

TEMPLATE_TEST_CASE("interpolation: TV-24 tangents straight from the solver", "[core][interpolation][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto p = points2<S, 5>({{{0, 0}, {1, 2}, {3, 3}, {4, 0}, {6, 1}}});
  const auto u = scalars<S, 5>({0, 1, 2, 3, 4});
  std::array<Vec2<S>, 5> tangents{};
  REQUIRE((cubic_spline_tangents<8>(view(p), view(u), CubicEnd::Natural, Vec2<S>{}, Vec2<S>{}, std::span<Vec2<S>>(tangents))
               .has_value()));
  const std::array<std::array<double, 2>, 5> d{
      {{9 / 14., 107 / 56.}, {12 / 7., 61 / 28.}, {1.5, -13 / 8.}, {9 / 7., -47 / 28.}, {33 / 14., 131 / 56.}}};
  for (std::size_t j = 0; j < 5; ++j) CHECK(max_error(tangents[j], d[j]) <= solve_tolerance<S>(4));
  std::array<Vec2<S>, 4> short_buffer{};
  CHECK((cubic_spline_tangents<8>(view(p), view(u), CubicEnd::Natural, Vec2<S>{}, Vec2<S>{}, std::span<Vec2<S>>(short_buffer))
             .error() == Error::BufferTooSmall));
  CHECK((cubic_spline_tangents<4>(view(p), view(u), CubicEnd::Natural, Vec2<S>{}, Vec2<S>{}, std::span<Vec2<S>>(tangents))
             .error() == Error::CapacityExceeded));
}

TEMPLATE_TEST_CASE("interpolation: parametrize reports short buffers and too few points", "[core][interpolation]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto p = points2<S, 3>({{{0, 0}, {3, 4}, {3, 10}}});
  std::array<S, 3> u{};
  CHECK(parametrize(view(p), Parametrization::ChordLength, std::span<S>(u)).value() == 3);
  const auto r = parametrize(view(p), Parametrization::ChordLength, std::span<S>(u), Closure::Closed);
  CHECK(r.error() == Error::BufferTooSmall);
  CHECK(r.where() == 4);
  CHECK(parametrize(view(p).first(1), Parametrization::Uniform, std::span<S>(u)).error() == Error::TooFewPoints);
  CHECK(to_double(checked_distance(p[1], p[2]).value()) == 6);
}

TEST_CASE("interpolation: Q16.16 distances do not overflow for far-apart points", "[core][interpolation]") {
  // 60000 mm apart: the squared distance would overflow Q16.16 many times over.
  const auto a = point<Q16_16>(-30000, -100);
  const auto b = point<Q16_16>(30000, 100);
  const auto d = checked_distance(a, b);
  REQUIRE(d.has_value() == false);  // 60000.3 is beyond the Q16.16 range itself
  CHECK(d.error() == Error::FixedOverflow);
  const auto c = checked_distance(point<Q16_16>(-15000, 0), point<Q16_16>(15000, 400));
  CHECK(to_double(c.value()) == Approx(std::hypot(30000.0, 400.0)).margin(1e-4));
}

TEMPLATE_TEST_CASE("interpolation: centripetal knots are square roots of the chords", "[core][interpolation]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto p = points2<S, 4>({{{0, 0}, {3, 4}, {3, 13}, {3, 14}}});
  std::array<S, 5> u{};
  REQUIRE(parametrize(view(p), Parametrization::Centripetal, std::span<S>(u), Closure::Closed).value() == 5);
  const std::array<double, 5> expected{0, std::sqrt(5.0), std::sqrt(5.0) + 3, std::sqrt(5.0) + 4, std::sqrt(5.0) + 4 + std::sqrt(std::sqrt(205.0))};
  for (std::size_t i = 0; i < 5; ++i) CHECK(std::fabs(to_double(u[i]) - expected[i]) <= solve_tolerance<S>(16));
  Spline<S> closed;
  REQUIRE(interpolate_closed_cubic(view(p), Parametrization::Centripetal, closed).has_value());
  check_passes_through(closed, p, true);
  CHECK(joint_jump(closed, 1, true) <= solve_tolerance<S>(16));
}

TEMPLATE_TEST_CASE("interpolation: cubic spline input errors are reported with the input at fault", "[core][interpolation]",
                   double, float, Q16_16) {
  using S = TestType;
  const auto p = points2<S, 4>({{{0, 0}, {1, 1}, {1, 1}, {3, 1}}});
  Spline<S> curve;
  SECTION("coincident points under chord-length knots") {
    const auto r = interpolate_natural_cubic(view(p), Parametrization::ChordLength, curve);
    CHECK(r.error() == Error::DegenerateCurve);
    CHECK(r.where() == 2);
  }
  SECTION("knots not increasing") {
    const auto u = scalars<S, 4>({0, 1, 1, 2});
    const auto r = interpolate_natural_cubic(view(p), view(u), curve);
    CHECK(r.error() == Error::InvalidInterval);
    CHECK(r.where() == 2);
  }
  SECTION("wrong knot count") {
    const auto u = scalars<S, 3>({0, 1, 2});
    CHECK(interpolate_natural_cubic(view(p), view(u), curve).error() == Error::InvalidArgument);
  }
  SECTION("too few points") {
    const auto one = points2<S, 1>({{{0, 0}}});
    CHECK(interpolate_natural_cubic(view(one), Parametrization::Uniform, curve).error() == Error::TooFewPoints);
    const auto two = points2<S, 2>({{{0, 0}, {1, 0}}});
    CHECK(interpolate_closed_cubic(view(two), Parametrization::Uniform, curve).error() == Error::TooFewPoints);
  }
  SECTION("more segments than the output holds") {
    CompositeBezier<S, 2, 3, 2> small;
    const auto r = interpolate_natural_cubic(view(p), Parametrization::Uniform, small);
    CHECK(r.error() == Error::CapacityExceeded);
    const auto u = scalars<S, 4>({0, 1, 2, 3});
    CHECK(interpolate_clamped_cubic(view(p), view(u), point<S>(1, 0), point<S>(1, 0), small).error() == Error::CapacityExceeded);
  }
  SECTION("a two-point spline is the chord") {
    const auto two = points2<S, 2>({{{0, 0}, {3, 6}}});
    REQUIRE(interpolate_natural_cubic(view(two), Parametrization::Uniform, curve).has_value());
    CHECK(max_error(curve.segment(0)[1], {1, 2}) == 0);
    CHECK(max_error(curve.segment(0)[2], {2, 4}) == 0);
  }
}

TEST_CASE("interpolation: NaN points are rejected", "[core][interpolation]") {
  const std::array<Vec2<double>, 3> p{{{{0, 0}}, {{std::nan(""), 1}}, {{2, 0}}}};
  CompositeBezier<double, 2, 3, 4> curve;
  const auto r = interpolate_natural_cubic(std::span<const Vec2<double>>(p), Parametrization::Uniform, curve);
  CHECK(r.error() == Error::NotFinite);
  CHECK(r.where() == 1);
}

TEST_CASE("interpolation: spline coordinates beyond the Q16.16 range report FixedOverflow", "[core][interpolation]") {
  using S = Q16_16;
  const std::array<Vec2<S>, 3> p{point<S>(-30000, 0), point<S>(30000, 0), point<S>(-30000, 0)};
  CompositeBezier<S, 2, 3, 4> curve;
  const auto r = interpolate_natural_cubic(std::span<const Vec2<S>>(p), Parametrization::Uniform, curve);
  REQUIRE(!r.has_value());
  CHECK(r.error() == Error::FixedOverflow);
}

TEMPLATE_TEST_CASE("interpolation: random splines in float and Q16.16 stay close to the double spline", "[core][interpolation]",
                   float, Q16_16) {
  using S = TestType;
  std::mt19937 random(curvestep::testing::test_seed());
  std::uniform_real_distribution<double> coordinate(-100, 100);
  const int cases = curvestep::testing::test_count(100);
  for (int c = 0; c < cases; ++c) {
    const std::size_t n = 3 + static_cast<std::size_t>(c % 10);
    std::array<Vec2<double>, 12> exact{};
    std::array<Vec2<S>, 12> data{};
    for (std::size_t i = 0; i < n; ++i) {
      // Quantised to 1/256 so that every scalar type sees the same data.
      data[i] = point<S>(std::round(coordinate(random) * 256) / 256, std::round(coordinate(random) * 256) / 256);
      exact[i] = Vec2<double>{{to_double(data[i][0]), to_double(data[i][1])}};
    }
    const auto kind = c % 3 == 0 ? Parametrization::Uniform : (c % 3 == 1 ? Parametrization::ChordLength : Parametrization::Centripetal);
    CompositeBezier<double, 2, 3, 16> reference;
    CompositeBezier<S, 2, 3, 16> approximate;
    const bool closed = c % 2 == 1;
    const std::span<const Vec2<double>> exact_view(exact.data(), n);
    const std::span<const Vec2<S>> data_view(data.data(), n);
    if (closed) {
      REQUIRE(interpolate_closed_cubic(exact_view, kind, reference).has_value());
      REQUIRE(interpolate_closed_cubic(data_view, kind, approximate).has_value());
    } else {
      REQUIRE(interpolate_natural_cubic(exact_view, kind, reference).has_value());
      REQUIRE(interpolate_natural_cubic(data_view, kind, approximate).has_value());
    }
    REQUIRE(approximate.size() == reference.size());
    double worst = 0;
    for (std::size_t j = 0; j < reference.size(); ++j) {
      for (std::size_t k = 0; k <= 3; ++k) worst = std::fmax(worst, max_error(approximate.segment(j)[k], to_doubles(reference.segment(j)[k])));
    }
    // Q16.16 holds the tangents (and the system's coefficients) to an absolute 2^-16, so an inner
    // Bézier point p + h·v/3 is off by about one unit per unit of its leg |h·v/3|: the scale is the
    // longest leg. float errors are relative to the knots, which reach a few thousand with chord
    // lengths, so its scale is the largest knot.
    double longest_leg = 0;
    for (std::size_t j = 0; j < reference.size(); ++j) {
      const auto& b = reference.segment(j);
      longest_leg = std::fmax(longest_leg, std::fmax(norm(b[1] - b[0]), norm(b[3] - b[2])));
    }
    const double scale = FixedPoint<S> ? std::fmax(100.0, longest_leg) : std::fmax(100.0, to_double(reference.domain_end()));
    CHECK(worst <= solve_tolerance<S>(scale));
    CHECK(joint_jump(approximate, 1, closed) <= solve_tolerance<S>(scale));
    // C2 from both sides, at the wrap too: the second derivative is 6·(leg difference)/h², so its
    // error is the leg error times 12/h² for the shortest interval h, plus the rounding of the
    // derivative evaluation itself (a few units of the format).
    double shortest = to_double(reference.breakpoint(1)) - to_double(reference.breakpoint(0));
    for (std::size_t j = 1; j < reference.size(); ++j) {
      shortest = std::fmin(shortest, to_double(reference.breakpoint(j + 1)) - to_double(reference.breakpoint(j)));
    }
    const double evaluation = 4 * to_double(resolution<S>()) * (FixedPoint<S> ? 1 : scale);
    CHECK(joint_jump(approximate, 2, closed) <= 12 * solve_tolerance<S>(scale) / (shortest * shortest) + evaluation);
  }
}
