// SPDX-License-Identifier: MIT
// Range safety of Q16.16 curve maths with far-away control points: hodographs, derivatives at a
// parameter, curvature and arc length either give the right value or FixedOverflow, never a
// wrapped value. Expected values are computed in double from the control points (exact for the
// hodograph: n (b_{i+1} - b_i) of Q16.16 values is exact in double) or from the closed form.
#include <array>
#include <cmath>
#include <cstddef>
#include <random>

#include <catch2/catch.hpp>

#include <curvestep/core/curve/arc_length.hpp>
#include <curvestep/core/curve/bezier.hpp>
#include <curvestep/core/curve/curvature.hpp>
#include <curvestep/core/curve/rational_bezier.hpp>
#include <curvestep/core/fixed/fixed.hpp>

#include "support/numeric.hpp"

using namespace curvestep;
using curvestep::testing::test_count;
using curvestep::testing::test_seed;

namespace {
using Q = Q16_16;
using P2 = Vec<Q, 2>;
using Cubic = Bezier<Q, 2, 7>;
constexpr double q_max = 32767.0 + 65535.0 / 65536;
constexpr double q_min = -32768.0;

P2 q2(double x, double y) { return P2{{Q::from_double(x).value(), Q::from_double(y).value()}}; }
bool representable(double v) { return v >= q_min && v <= q_max; }
}  // namespace

TEST_CASE("range: the hodograph of a Q16.16 Bezier spanning the range overflows with an error", "[core][range]") {
  // A cubic from one corner of the range to the other: 3 (b1 - b0) = 3 * 65535.99 is far outside.
  const auto curve = Cubic::create({q2(q_min, q_min), q2(q_max, q_min), q2(q_min, q_max), q2(q_max, q_max)}).value();
  const auto hodograph = curve.derivative();
  REQUIRE_FALSE(hodograph);
  CHECK(hodograph.error() == Error::FixedOverflow);
  CHECK(curve.derivative_at(Q::from_double(0.5).value(), 1).error() == Error::FixedOverflow);
  CHECK(curve.derivative_at(Q::from_double(0.0).value(), 2).error() == Error::FixedOverflow);
  CHECK(curvature(curve, Q::from_double(0.5).value()).error() == Error::FixedOverflow);
  // Positions stay inside the convex hull and are always representable.
  const auto mid = curve.point_at(Q::from_double(0.5).value());
  CHECK(to_double(mid[0]) == Approx(0.0).margin(1e-3));
  // The length (about 2.2 x 65536) is beyond Q16.16: an error, not a wrapped length.
  const auto length = arc_length(curve, Q{}, Q::from_double(1.0).value(), Q::from_double(0.01).value());
  REQUIRE_FALSE(length);
  CHECK(length.error() == Error::FixedOverflow);
}

TEST_CASE("range: a long Q16.16 line has the right length up to the edge of the range", "[core][range]") {
  // 30000 mm along x: the length fits and is exact to the tolerance.
  const auto line = Cubic::create({q2(-15000, 0), q2(15000, 0)}).value();
  const auto length = arc_length(line, Q{}, Q::from_double(1.0).value(), Q::from_double(0.01).value());
  REQUIRE(length.has_value());
  CHECK(to_double(length.value()) == Approx(30000.0).margin(0.02));
  // 60000 mm cannot be represented: an error.
  const auto longer = Cubic::create({q2(-30000, 0), q2(30000, 0)}).value();
  CHECK(arc_length(longer, Q{}, Q::from_double(1.0).value(), Q::from_double(0.01).value()).error() == Error::FixedOverflow);
}

TEST_CASE("range: Q16.16 hodographs over the whole range are exact or FixedOverflow, property", "[core][range]") {
  std::mt19937_64 rng(test_seed() + 3);
  std::uniform_real_distribution<double> log_span(-3.0, 15.0);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const int n = test_count(3000);
  int overflows = 0;
  int exact = 0;
  for (int i = 0; i < n; ++i) {
    const std::size_t degree = 1 + rng() % 7;
    const double span = std::pow(2.0, log_span(rng));  // control points spread up to 2^15 mm
    const double centre = unit(rng) * (32768 - span > 0 ? 32768 - span : 0);
    std::array<P2, 8> points{};
    for (std::size_t k = 0; k <= degree; ++k) points[k] = q2(centre + span * unit(rng), centre + span * unit(rng));
    const auto curve = Cubic::create(std::span<const P2>(points.data(), degree + 1)).value();
    const auto hodograph = curve.derivative();
    bool fits = true;
    for (std::size_t k = 0; k < degree; ++k) {
      for (std::size_t a = 0; a < 2; ++a) {
        // Exact in double: Q16.16 values have 32 significant bits, times an integer <= 7.
        const double expected = static_cast<double>(degree) * (to_double(points[k + 1][a]) - to_double(points[k][a]));
        if (!representable(expected)) fits = false;
      }
    }
    if (!fits) {
      ++overflows;
      REQUIRE(hodograph.error() == Error::FixedOverflow);
      continue;
    }
    ++exact;
    REQUIRE(hodograph.has_value());
    for (std::size_t k = 0; k < degree; ++k) {
      for (std::size_t a = 0; a < 2; ++a) {
        const double expected = static_cast<double>(degree) * (to_double(points[k + 1][a]) - to_double(points[k][a]));
        REQUIRE(to_double(hodograph.value().control_points()[k][a]) == expected);
      }
    }
  }
  CHECK(overflows > 0);
  CHECK(exact > 0);
}

TEST_CASE("range: Q16.16 curvature of far-away circles is right or FixedOverflow", "[core][range]") {
  // A quarter circle as a rational quadratic (weights 1, √2/2, 1) of radius r about a centre far
  // from the origin: curvature 1/r wherever it is computed; an error only if r' itself overflows.
  for (const double r : {0.5, 10.0, 1000.0, 8000.0, 16000.0}) {
    for (const double centre : {0.0, 15000.0, -16000.0}) {
      using Rational = RationalBezier<Q, 2, 3>;
      const std::array<P2, 3> control{q2(centre + r, centre), q2(centre + r, centre + r), q2(centre, centre + r)};
      const std::array<Q, 3> weights{Q::from_double(1).value(), Q::from_double(std::sqrt(0.5)).value(), Q::from_double(1).value()};
      if (!representable(centre + r)) continue;
      const auto arc = Rational::create(control, weights);
      REQUIRE(arc.has_value());
      const auto k = curvature(arc.value(), Q::from_double(0.5).value());
      if (!k) {
        CHECK(k.error() == Error::FixedOverflow);
        continue;
      }
      // Q16.16 curvature of a large circle is a few resolution steps: allow 4 steps plus 0.1 %.
      CHECK(to_double(k.value()) == Approx(1.0 / r).margin(4.0 / 65536 + 1e-3 / r));
    }
  }
}
