// SPDX-License-Identifier: MIT
// PathSegment: every kind starts and ends exactly where it was built, arcs follow the circle,
// derivatives match finite differences, and the deterministic trigonometry matches libm.
#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include <curvestep/core/motion/path_segment.hpp>
#include <support/numeric.hpp>

using namespace curvestep;

namespace {
MachinePoint mp(double x, double y, double z = 0) { return MachinePoint{{x, y, z}}; }

double difference(const MachinePoint& a, const MachinePoint& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

void check_derivatives_match_finite_differences(const PathSegment& s) {
  for (double u : {0.1, 0.37, 0.5, 0.81}) {
    const double h = 1e-5;
    for (std::size_t axis = 0; axis < 3; ++axis) {
      const double fd1 = (s.point(u + h)[axis] - s.point(u - h)[axis]) / (2 * h);
      const double fd2 = (s.derivative(u + h, 1)[axis] - s.derivative(u - h, 1)[axis]) / (2 * h);
      const double fd3 = (s.derivative(u + h, 2)[axis] - s.derivative(u - h, 2)[axis]) / (2 * h);
      CHECK(s.derivative(u, 1)[axis] == Approx(fd1).margin(1e-5).epsilon(1e-6));
      CHECK(s.derivative(u, 2)[axis] == Approx(fd2).margin(1e-4).epsilon(1e-6));
      CHECK(s.derivative(u, 3)[axis] == Approx(fd3).margin(1e-3).epsilon(1e-5));
    }
  }
}
}  // namespace

TEST_CASE("deterministic_math: sin, cos and atan2 agree with libm to a few ulp", "[core][motion]") {
  std::mt19937 rng(testing::test_seed());
  std::uniform_real_distribution<double> angle(-100, 100);
  for (int i = 0; i < 20000; ++i) {
    const double x = angle(rng);
    const auto sc = detail::sin_cos(x);
    CHECK(std::fabs(sc.sin - std::sin(x)) < 4e-15);
    CHECK(std::fabs(sc.cos - std::cos(x)) < 4e-15);
    const double y = angle(rng);
    CHECK(std::fabs(detail::atan2(y, x) - std::atan2(y, x)) < 4e-15);
  }
  CHECK(detail::atan2(0, -1) == Approx(detail::pi));
  CHECK(detail::atan2(0, 0) == 0);
}

TEST_CASE("path_segment: a counter-clockwise quarter arc follows the circle exactly", "[core][motion]") {
  const auto arc = PathSegment::make_arc(mp(10, 0), mp(0, 10), mp(0, 0), ArcDirection::CounterClockwise, 0, 1e-9).value();
  CHECK(arc.arc_sweep_rad() == Approx(detail::pi / 2));
  for (int k = 0; k <= 16; ++k) {
    const double u = k / 16.0;
    const auto p = arc.point(u);
    CHECK(p[0] == Approx(10 * std::cos(u * detail::pi / 2)).margin(1e-12));
    CHECK(p[1] == Approx(10 * std::sin(u * detail::pi / 2)).margin(1e-12));
  }
  CHECK(arc.point(1) == mp(0, 10));
  check_derivatives_match_finite_differences(arc);
}

TEST_CASE("path_segment: clockwise, helical and full-circle arcs", "[core][motion]") {
  const auto cw = PathSegment::make_arc(mp(10, 0), mp(0, 10), mp(0, 0), ArcDirection::Clockwise, 0, 1e-9).value();
  CHECK(cw.arc_sweep_rad() == Approx(-1.5 * detail::pi));
  CHECK(cw.point(1.0 / 3)[1] == Approx(-10).margin(1e-12));  // a clockwise arc passes (0,-10) first
  check_derivatives_match_finite_differences(cw);
  const auto helix = PathSegment::make_arc(mp(5, 0, 0), mp(5, 0, 3), mp(0, 0), ArcDirection::CounterClockwise, 1, 1e-9).value();
  CHECK(helix.arc_sweep_rad() == Approx(4 * detail::pi));  // full circle (start == end) plus one turn
  CHECK(helix.point(0.5)[2] == Approx(1.5));
  CHECK(helix.point(0.125)[1] == Approx(5).margin(1e-12));
  check_derivatives_match_finite_differences(helix);
  CHECK(PathSegment::make_arc(mp(10, 0), mp(0, 11), mp(0, 0), ArcDirection::Clockwise, 0, 0.01).error() == Error::InvalidArgument);
  CHECK(PathSegment::make_arc(mp(0, 0), mp(0, 0), mp(0, 0), ArcDirection::Clockwise, 0, 0.01).error() == Error::DegenerateCurve);
}

TEST_CASE("path_segment: lines and Béziers start and end exactly where they were built", "[core][motion]") {
  const auto line = PathSegment::make_line(mp(1, 2, 3), mp(4, 6, 3)).value();
  CHECK(line.point(0.5) == mp(2.5, 4, 3));
  CHECK(line.start() == mp(1, 2, 3));
  CHECK(line.end() == mp(4, 6, 3));
  CHECK(PathSegment::make_line(mp(1, 2), mp(1, 2)).error() == Error::DegenerateCurve);
  const std::array<MachinePoint, 4> cubic{mp(0, 0), mp(1, 2), mp(3, 3), mp(4, 0)};
  const auto bez = PathSegment::make_bezier(cubic).value();
  CHECK(difference(bez.point(0.25), mp(29 / 32., 81 / 64.)) == 0.0);
  check_derivatives_match_finite_differences(bez);
  const std::array<double, 4> weights{1, 2, 0.5, 1};
  const auto rat = PathSegment::make_rational_bezier(cubic, weights).value();
  CHECK(rat.end() == mp(4, 0));
  check_derivatives_match_finite_differences(rat);
  const std::array<double, 4> bad_weights{1, 0, 1, 1};
  const auto bad = PathSegment::make_rational_bezier(cubic, bad_weights);
  CHECK(bad.error() == Error::NonPositiveWeight);
  CHECK(bad.where() == 1);
  const std::array<MachinePoint, 1> single{mp(0, 0)};
  CHECK(PathSegment::make_bezier(single).error() == Error::TooFewPoints);
  const std::array<MachinePoint, 3> same{mp(1, 1), mp(1, 1), mp(1, 1)};
  CHECK(PathSegment::make_bezier(same).error() == Error::DegenerateCurve);
}

TEST_CASE("path_segment: an arc whose end radius differs slightly spirals onto its end point", "[core][motion]") {
  const auto arc = PathSegment::make_arc(mp(10, 0), mp(0, 10.002), mp(0, 0), ArcDirection::CounterClockwise, 0, 0.01).value();
  const auto near_end = arc.point(1 - 1e-9);
  CHECK(difference(near_end, mp(0, 10.002)) < 1e-7);  // no jump at u = 1
  CHECK(norm(arc.point(0.5) - mp(0, 0)) == Approx(10.001).margin(1e-12));  // radius halfway between
  check_derivatives_match_finite_differences(arc);
}
