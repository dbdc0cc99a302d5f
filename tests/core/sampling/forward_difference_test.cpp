// SPDX-License-Identifier: MIT
// ForwardDifference against the seed vectors (exact) and a long-double de Casteljau (bounded error).
#include <array>
#include <cmath>
#include <cstdint>
#include <random>

#include <catch2/catch.hpp>

#include <curvestep/core/bspline/bezier_extraction.hpp>
#include <curvestep/core/bspline/bspline.hpp>
#include <curvestep/core/sampling/forward_difference.hpp>
#include <support/numeric.hpp>
#include <support/seed_vectors.hpp>

#include "sampling_reference.hpp"

using namespace curvestep;
using namespace curvestep::testing;  // support/numeric.hpp, sampling_reference.hpp

namespace {

template <class S, std::size_t Dim>
using Curve = Bezier<S, Dim, 7>;

/// Runs the stepper to the end and returns the largest deviation from the long-double reference.
template <class S, std::size_t Dim>
long double max_deviation(const Curve<S, Dim>& curve, std::uint32_t steps, std::uint32_t* reseed_interval = nullptr,
                          double* bound = nullptr) {
  auto stepper = ForwardDifference<S, Dim>::create(curve, steps);
  REQUIRE(stepper.has_value());
  auto fd = stepper.value();
  if (reseed_interval != nullptr) *reseed_interval = fd.reseed_interval();
  if (bound != nullptr) *bound = fd.error_bound();
  const auto polygon = reference_polygon(curve);
  long double worst = 0;
  for (std::uint32_t k = 0;; ++k) {
    REQUIRE(fd.index() == k);
    const long double t = static_cast<long double>(k) / static_cast<long double>(steps);
    worst = std::fmax(worst, curvestep::testing::deviation(fd.point(), reference_point<Dim>(polygon, t)));
    if (fd.finished()) break;
    fd.step();
  }
  return worst;
}

template <class S, std::size_t Dim>
Curve<S, Dim> random_curve(std::mt19937& rng, std::size_t degree, double extent) {
  std::uniform_real_distribution<double> coordinate(-extent, extent);
  std::array<Vec<S, Dim>, 8> points{};
  for (std::size_t i = 0; i <= degree; ++i) {
    for (std::size_t axis = 0; axis < Dim; ++axis) {
      // Round to a multiple of 2^-16 so that every scalar type holds the same control points.
      points[i][axis] = scalar<S>(std::round(coordinate(rng) * 65536.0) / 65536.0);
    }
  }
  return Curve<S, Dim>::create(std::span<const Vec<S, Dim>>(points.data(), degree + 1)).value();
}

}  // namespace

TEMPLATE_TEST_CASE("forward_difference: TV-10 steps the TV-04 cubic at h = 1/4 exactly", "[core][sampling][seed]", double,
                   float, Q16_16) {
  using S = TestType;
  const auto curve = Curve<S, 2>::create({point<S>(0, 0), point<S>(1, 2), point<S>(3, 3), point<S>(4, 0)}).value();
  auto fd = ForwardDifference<S, 2>::create(curve, 4).value();
  const std::array<std::array<double, 2>, 5> expected{{{0, 0}, {29 / 32., 81 / 64.}, {2, 15 / 8.}, {99 / 32., 99 / 64.}, {4, 0}}};
  for (std::size_t k = 0; k < expected.size(); ++k) {
    CHECK(to_double(fd.point()[0]) == expected[k][0]);
    CHECK(to_double(fd.point()[1]) == expected[k][1]);
    if (!fd.finished()) fd.step();
  }
  CHECK(fd.finished());
}

TEMPLATE_TEST_CASE("forward_difference: TV-08 steps seed 001 Example 1.2 at h = 1/4 and 1/8 exactly",
                   "[core][sampling][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto curve = Curve<S, 2>::create({point<S>(0, 1), point<S>(0, 4), point<S>(5, 5), point<S>(7, 0)}).value();
  SECTION("h = 1/4") {
    auto fd = ForwardDifference<S, 2>::create(curve, 4).value();
    const std::array<std::array<double, 2>, 5> expected{{{0, 1}, {13 / 16., 45 / 16.}, {11 / 4., 7 / 2.}, {81 / 16., 43 / 16.}, {7, 0}}};
    for (const auto& e : expected) {
      CHECK(to_double(fd.point()[0]) == e[0]);
      CHECK(to_double(fd.point()[1]) == e[1]);
      if (!fd.finished()) fd.step();
    }
  }
  SECTION("h = 1/8 gives the nine TV-05 points") {
    auto fd = ForwardDifference<S, 2>::create_with_step(curve, scalar<S>(0.125)).value();
    REQUIRE(fd.steps() == 8);
    const auto& expected = curvestep::testing::example_1_2_eighths;  // TV-03, TV-05
    for (const auto& e : expected) {
      CHECK(to_double(fd.point()[0]) == e[0]);
      CHECK(to_double(fd.point()[1]) == e[1]);
      if (!fd.finished()) fd.step();
    }
  }
}

TEMPLATE_TEST_CASE("forward_difference: TV-A4 of seed 004 is exact in every scalar type", "[core][sampling][seed]", double,
                   float, Q16_16) {
  using S = TestType;
  const auto curve = Curve<S, 2>::create({point<S>(0, 0), point<S>(1, 2), point<S>(3, 2), point<S>(4, 0)}).value();
  auto fd = ForwardDifference<S, 2>::create(curve, 4).value();
  const std::array<std::array<double, 2>, 5> expected{{{0, 0}, {29 / 32., 9 / 8.}, {2, 1.5}, {99 / 32., 9 / 8.}, {4, 0}}};
  for (const auto& e : expected) {
    CHECK(to_double(fd.point()[0]) == e[0]);
    CHECK(to_double(fd.point()[1]) == e[1]);
    if (!fd.finished()) fd.step();
  }
}

TEST_CASE("forward_difference: a 1000 mm cubic over 100000 steps stays within 1 um in Q16.16 and 10 um in float",
          "[core][sampling][acceptance]") {
  // About 1160 mm long (arc length by the arc-length tests' reference); 3 axes.
  const auto make = [](auto tag) {
    using S = decltype(tag);
    return Curve<S, 3>::create({point<S>(0, 0, 0), point<S>(250, 400, 30), point<S>(750, -400, 60), point<S>(1000, 0, 100)})
        .value();
  };
  std::uint32_t interval = 0;
  double bound = 0;
  const long double fixed_error = max_deviation(make(Q16_16{}), 100000, &interval, &bound);
  INFO("Q16.16: max deviation " << static_cast<double>(fixed_error) * 1000 << " um, re-seed every " << interval
                                << " steps, bound " << bound * 1000 << " um");
  CHECK(fixed_error <= 0.001L);
  CHECK(fixed_error <= static_cast<long double>(bound));
  CHECK(interval >= 256);
  const long double float_error = max_deviation(make(float{}), 100000, &interval, &bound);
  INFO("float: max deviation " << static_cast<double>(float_error) * 1000 << " um, re-seed every " << interval
                               << " steps, bound " << bound * 1000 << " um");
  CHECK(float_error <= 0.010L);
  CHECK(float_error <= static_cast<long double>(bound));
  const long double double_error = max_deviation(make(double{}), 100000, &interval, &bound);
  CHECK(double_error <= 1e-9L);
  CHECK(double_error <= static_cast<long double>(bound));
}

TEMPLATE_TEST_CASE("forward_difference: random segments of degree 1 to 5 stay within the documented bound at every step",
                   "[core][sampling][property]", double, float, Q16_16) {
  using S = TestType;
  std::mt19937 rng(curvestep::testing::test_seed());
  std::uniform_int_distribution<std::uint32_t> step_count(1, 3000);
  const int count = curvestep::testing::test_count(12);
  for (int c = 0; c < count; ++c) {
    for (std::size_t degree = 1; degree <= 5; ++degree) {
      const std::uint32_t steps = c == 0 ? 1u : step_count(rng);
      double bound = 0;
      const auto curve3 = random_curve<S, 3>(rng, degree, 2000.0);
      const long double e3 = max_deviation(curve3, steps, nullptr, &bound);
      INFO("degree " << degree << " steps " << steps << " error " << static_cast<double>(e3) << " bound " << bound);
      CHECK(e3 <= static_cast<long double>(bound));
      const auto curve1 = random_curve<S, 1>(rng, degree, 10.0);
      const long double e1 = max_deviation(curve1, steps, nullptr, &bound);
      CHECK(e1 <= static_cast<long double>(bound));
    }
  }
}

TEST_CASE("forward_difference: Q16.16 with a power-of-two step count rounds every point to nearest or next",
          "[core][sampling]") {
  // Bound < 0.6 raw: the output is the exact value rounded to nearest, or one raw unit away only
  // when the exact value lies within 0.1 raw of a rounding boundary.
  std::mt19937 rng(curvestep::testing::test_seed() + 1);
  const auto curve = random_curve<Q16_16, 2>(rng, 3, 30000.0);
  auto fd = ForwardDifference<Q16_16, 2>::create(curve, 1u << 14).value();
  CHECK(fd.error_bound() < 0.6 * to_double(resolution<Q16_16>()));
  const auto polygon = reference_polygon(curve);
  long double worst_raw = 0;
  while (true) {
    const long double t = static_cast<long double>(fd.index()) / (1u << 14);
    const auto exact = reference_point<2>(polygon, t);
    for (std::size_t axis = 0; axis < 2; ++axis) {
      const long double raw_error = std::fabs(static_cast<long double>(fd.point()[axis].raw()) - exact[axis] * 65536);
      worst_raw = std::fmax(worst_raw, raw_error);
    }
    if (fd.finished()) break;
    fd.step();
  }
  CHECK(worst_raw < 0.6L);
}

TEMPLATE_TEST_CASE("forward_difference: invalid inputs are reported", "[core][sampling][errors]", double, float, Q16_16) {
  using S = TestType;
  const auto constant = Curve<S, 2>::create({point<S>(1, 1)}).value();
  CHECK(ForwardDifference<S, 2>::create(constant, 4).error() == Error::DegreeTooLow);
  const auto line = Curve<S, 2>::create({point<S>(0, 0), point<S>(1, 1)}).value();
  CHECK(ForwardDifference<S, 2>::create(line, 0).error() == Error::InvalidStep);
  CHECK(ForwardDifference<S, 2, 3>::create(line.elevated().value().elevated().value().elevated().value(), 4).error() ==
        Error::DegreeAboveCapacity);
  CHECK(ForwardDifference<S, 2>::create_with_step(line, scalar<S>(0.3)).error() == Error::InvalidStep);
  CHECK(ForwardDifference<S, 2>::create_with_step(line, scalar<S>(0)).error() == Error::InvalidStep);
  auto fd = ForwardDifference<S, 2>::create(line, 2).value();
  fd.step();
  fd.step();
  CHECK(fd.finished());
  CHECK(fd.point() == point<S>(1, 1));
}

TEST_CASE("forward_difference: B-spline spans are stepped through Bezier extraction and match de Boor",
          "[core][sampling][bspline]") {
  // TV-13-like cubic B-spline; each knot span becomes one Bézier piece, stepped in 256 steps.
  using Spline = BSpline<double, 2, 3, 16>;
  const std::array<Vec<double, 2>, 6> control{point<double>(0, 0), point<double>(10, 30), point<double>(30, 30),
                                              point<double>(40, 0), point<double>(60, 10), point<double>(70, 40)};
  const std::array<double, 10> knots{0, 0, 0, 0, 1, 2, 3, 3, 3, 3};
  const auto spline = Spline::create(control, knots, 3).value();
  std::size_t pieces = 0;
  const auto walked = for_each_bezier(spline, [&](const BezierSpan<double, 2, 3>& piece) {
    auto fd = ForwardDifference<double, 2>::create(piece.curve, 256).value();
    ++pieces;
    while (true) {
      const double u = to_double(piece.start) + (to_double(piece.end) - to_double(piece.start)) * fd.index() / 256.0;
      const auto expected = spline.evaluate(u).value();
      CHECK(std::fabs(fd.point()[0] - expected[0]) <= 1e-9);
      CHECK(std::fabs(fd.point()[1] - expected[1]) <= 1e-9);
      if (fd.finished()) break;
      fd.step();
    }
  });
  CHECK(walked.has_value());
  CHECK(pieces == 3);
}

TEST_CASE("forward_difference: Q16.16 quintics spanning almost the whole range keep the bound", "[core][sampling][property]") {
  std::mt19937 rng(curvestep::testing::test_seed() + 2);
  std::uniform_int_distribution<std::uint32_t> step_count(1, 400);
  for (int c = 0; c < curvestep::testing::test_count(10); ++c) {
    for (std::size_t degree = 1; degree <= 5; ++degree) {
      const auto curve = random_curve<Q16_16, 2>(rng, degree, 32700.0);
      double bound = 0;
      const long double error = max_deviation(curve, c == 0 ? 1u : step_count(rng), nullptr, &bound);
      CHECK(bound < 0.6 * to_double(resolution<Q16_16>()));
      CHECK(error <= static_cast<long double>(bound));
    }
  }
}
