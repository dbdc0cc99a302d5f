// SPDX-License-Identifier: MIT
// AdaptiveForwardDifference: in-place halving/doubling against a long-double de Casteljau.
#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include <curvestep/core/sampling/adaptive_forward_difference.hpp>
#include <support/numeric.hpp>

#include "sampling_reference.hpp"

using namespace curvestep;
using curvestep::testing::point;
using curvestep::testing::reference_point;
using curvestep::testing::reference_polygon;
using curvestep::testing::scalar;

TEMPLATE_TEST_CASE("adaptive_forward_difference: halving and doubling the TV-04 cubic stays exact on dyadic points",
                   "[core][sampling][adaptive][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto curve = Bezier<S, 2, 3>::create({point<S>(0, 0), point<S>(1, 2), point<S>(3, 3), point<S>(4, 0)}).value();
  auto fd = AdaptiveForwardDifference<S, 2, 3>::create(curve, 2).value();
  CHECK(fd.level() == 4);  // raised to h <= 1/(4n)
  const auto polygon = reference_polygon(curve);
  // A fixed pattern of halvings (up to level 5: t = k/32, exact in Q16.16 for a cubic with
  // integer control points) and doublings, to the end.
  int pattern = 0;
  while (!fd.finished()) {
    const auto exact = reference_point<2>(polygon, static_cast<long double>(fd.parameter()));
    CHECK(static_cast<long double>(to_double(fd.point()[0])) == exact[0]);
    CHECK(static_cast<long double>(to_double(fd.point()[1])) == exact[1]);
    switch (pattern++ % 7) {
      case 2: if (fd.level() < 5) fd.halve(); break;
      case 4: fd.double_step(); break;
      case 5: if (fd.level() < 5) fd.halve(); break;
      default: break;
    }
    fd.step();
  }
  CHECK(fd.point() == point<S>(4, 0));
}

TEMPLATE_TEST_CASE("adaptive_forward_difference: random halvings and doublings stay within the carried bound",
                   "[core][sampling][adaptive][property]", double, float, Q16_16) {
  using S = TestType;
  std::mt19937 rng(curvestep::testing::test_seed() + 5);
  std::uniform_real_distribution<double> coordinate(-500, 500);
  std::uniform_int_distribution<int> action(0, 19);
  for (int c = 0; c < curvestep::testing::test_count(4); ++c) {
    for (std::size_t degree = 1; degree <= 5; ++degree) {
      std::array<Vec<S, 3>, 6> points{};
      for (std::size_t i = 0; i <= degree; ++i) {
        points[i] = point<S>(std::round(coordinate(rng) * 1024) / 1024, std::round(coordinate(rng) * 1024) / 1024,
                             std::round(coordinate(rng) * 1024) / 1024);
      }
      const auto curve = Bezier<S, 3, 5>::create(std::span<const Vec<S, 3>>(points.data(), degree + 1)).value();
      const auto polygon = reference_polygon(curve);
      auto fd = AdaptiveForwardDifference<S, 3>::create(curve, 9).value();
      long double worst_ratio = 0;
      int steps = 0;
      while (!fd.finished() && steps < 2500) {
        const auto exact = reference_point<3>(polygon, static_cast<long double>(fd.parameter()));
        const long double error = curvestep::testing::deviation(fd.point(), exact);
        INFO("degree " << degree << " level " << fd.level() << " t " << fd.parameter() << " error " << static_cast<double>(error)
                       << " bound " << fd.error_bound());
        CHECK(error <= static_cast<long double>(fd.error_bound()));
        worst_ratio = std::fmax(worst_ratio, error / static_cast<long double>(fd.error_bound()));
        const int a = action(rng);
        if (a == 0 && fd.level() < 14) fd.halve();
        if (a == 1) fd.double_step();
        fd.step();
        ++steps;
      }
    }
  }
}

TEMPLATE_TEST_CASE("adaptive_forward_difference: step_within holds consecutive points in a chord band",
                   "[core][sampling][adaptive]", double, float, Q16_16) {
  using S = TestType;
  // Speed varies about 20x along this cubic (control points bunched at the start).
  const auto curve = Bezier<S, 2, 3>::create({point<S>(0, 0), point<S>(1, 1), point<S>(2, 0), point<S>(300, 200)}).value();
  auto fd = AdaptiveForwardDifference<S, 2, 3>::create(curve, 6).value();
  const double min_chord = 1.0, max_chord = 2.5;
  int chords = 0, too_short = 0, too_long = 0;
  auto previous = fd.point();
  while (!fd.finished()) {
    fd.step_within(min_chord, max_chord);
    const double dx = to_double(fd.point()[0]) - to_double(previous[0]);
    const double dy = to_double(fd.point()[1]) - to_double(previous[1]);
    const double chord = std::hypot(dx, dy);
    ++chords;
    if (chord > max_chord + 1e-4) ++too_long;
    if (chord < min_chord - 1e-4 && !fd.finished()) ++too_short;
    previous = fd.point();
  }
  INFO("chords " << chords << " too short " << too_short << " too long " << too_long);
  CHECK(too_long == 0);
  CHECK(too_short * 20 <= chords);  // short chords only while the grid forbids a doubling
  // The chord count is near length / average band: 362 mm of curve.
  CHECK(chords >= 362 / 2.5);
  CHECK(chords <= 362 / 1.0 + 2);
}

TEMPLATE_TEST_CASE("adaptive_forward_difference: invalid inputs are reported", "[core][sampling][adaptive][errors]", double,
                   float, Q16_16) {
  using S = TestType;
  const auto constant = Bezier<S, 2, 3>::create({point<S>(1, 1)}).value();
  CHECK(AdaptiveForwardDifference<S, 2, 3>::create(constant, 4).error() == Error::DegreeTooLow);
  const auto line = Bezier<S, 2, 3>::create({point<S>(0, 0), point<S>(3, 3)}).value();
  CHECK(AdaptiveForwardDifference<S, 2, 3>::create(line, 31).error() == Error::InvalidStep);
  auto fd = AdaptiveForwardDifference<S, 2, 3>::create(line, 2).value();
  fd.step();
  CHECK_FALSE(fd.double_step());  // odd index
  fd.step();
  CHECK_FALSE(fd.double_step());  // already at the minimum level (h <= 1/4 for a line)
  while (!fd.finished()) fd.step();
  CHECK(fd.point() == point<S>(3, 3));
}
