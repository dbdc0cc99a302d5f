// SPDX-License-Identifier: MIT
// RationalForwardDifference against a long-double homogeneous de Casteljau.
#include <cmath>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/curve/circular_arc.hpp>
#include <curvestep/core/sampling/rational_forward_difference.hpp>
#include <support/numeric.hpp>

#include "sampling_reference.hpp"

using namespace curvestep;
using curvestep::testing::point;
using curvestep::testing::scalar;

namespace {
template <class S, std::size_t Dim, std::size_t MaxDegree>
long double rational_deviation(const RationalBezier<S, Dim, MaxDegree>& curve, std::uint32_t steps, double* bound) {
  auto fd = RationalForwardDifference<S, Dim>::create(curve, steps).value();
  *bound = fd.error_bound();
  const auto polygon = curvestep::testing::reference_polygon(curve);
  std::vector<long double> weights;
  for (std::size_t i = 0; i <= curve.degree(); ++i) weights.push_back(static_cast<long double>(to_double(curve.weight(i))));
  long double worst = 0;
  while (true) {
    const long double t = static_cast<long double>(fd.index()) / steps;
    worst = std::fmax(worst, curvestep::testing::deviation(fd.point(), curvestep::testing::reference_rational_point<Dim>(polygon, weights, t)));
    if (fd.finished()) break;
    fd.step();
  }
  return worst;
}
}  // namespace

TEMPLATE_TEST_CASE("rational_forward_difference: arcs of 500 mm radius over 30000 steps stay within the bound",
                   "[core][sampling][rational]", double, float, Q16_16) {
  using S = TestType;
  for (const bool half : {false, true}) {
    const auto arc = circular_arc<S>(point<S>(0, 0), point<S>(500, 0), half ? point<S>(-500, 0) : point<S>(0, 500),
                                     ArcDirection::CounterClockwise, scalar<S>(0.01))
                         .value();
    double bound = 0;
    const long double error = rational_deviation(arc, 30000, &bound);
    INFO((half ? "half" : "quarter") << " circle: max deviation " << static_cast<double>(error) << " bound " << bound);
    CHECK(error <= static_cast<long double>(bound));
    if constexpr (FixedPoint<S>) {
      CHECK(error <= 1e-3L);  // 1 um
      CHECK(bound < 2 * to_double(resolution<S>()));
    }
  }
}

TEMPLATE_TEST_CASE("rational_forward_difference: random rational curves of degree 1 to 5 stay within the bound",
                   "[core][sampling][rational][property]", double, float, Q16_16) {
  using S = TestType;
  std::mt19937 rng(curvestep::testing::test_seed() + 11);
  std::uniform_real_distribution<double> coordinate(-300, 300);
  std::uniform_real_distribution<double> weight(0.25, 4.0);
  std::uniform_int_distribution<std::uint32_t> steps(1, 2000);
  for (int c = 0; c < curvestep::testing::test_count(6); ++c) {
    for (std::size_t degree = 1; degree <= 5; ++degree) {
      std::array<Vec<S, 3>, 6> points{};
      std::array<S, 6> weights{};
      for (std::size_t i = 0; i <= degree; ++i) {
        points[i] = point<S>(std::round(coordinate(rng) * 64) / 64, std::round(coordinate(rng) * 64) / 64,
                             std::round(coordinate(rng) * 64) / 64);
        weights[i] = scalar<S>(std::round(weight(rng) * 256) / 256);
      }
      const auto curve = RationalBezier<S, 3, 5>::create(std::span<const Vec<S, 3>>(points.data(), degree + 1),
                                                         std::span<const S>(weights.data(), degree + 1))
                             .value();
      double bound = 0;
      const long double error = rational_deviation(curve, steps(rng), &bound);
      INFO("degree " << degree << " error " << static_cast<double>(error) << " bound " << bound);
      CHECK(error <= static_cast<long double>(bound));
    }
  }
}
