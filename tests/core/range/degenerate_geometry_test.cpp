// SPDX-License-Identifier: MIT
// Degenerate geometry: each case is either followed correctly or refused with a clear error, and
// each test says which (the table in docs/robustness.md lists the same cases).
// Expected points come from the closed forms of the curves (Bernstein sums written out by hand).
#include <array>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/bspline/bezier_extraction.hpp>
#include <curvestep/core/bspline/bspline.hpp>
#include <curvestep/core/curve/circular_arc.hpp>
#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/core/motion/motion_controller.hpp>

#include "core/motion/motion_test_support.hpp"
#include "support/numeric.hpp"

using namespace curvestep;
using curvestep::testing::mp;
using curvestep::testing::run_job;
using curvestep::testing::test_machine;

namespace {

double distance(const MachinePoint& a, const MachinePoint& b) { return norm(a - b); }

template <class S>
MachinePoint position_of(const Setpoint<S>& sp) {
  return MachinePoint{{to_double(sp.position[0]), to_double(sp.position[1]), to_double(sp.position[2])}};
}

/// Smallest distance from p to the polyline through `samples` points of the curve.
double distance_to_curve(const PathSegment& s, const MachinePoint& p) {
  double best = 1e300;
  constexpr int samples = 4000;
  for (int k = 0; k <= samples; ++k) best = std::fmin(best, distance(s.point(static_cast<double>(k) / samples), p));
  return best;
}

/// Runs `segment` alone and checks: the job finishes, every setpoint lies on the curve (within the
/// machine tolerance plus one Q16.16 step), and the last setpoint is the end point.
template <class S>
void check_followed(const PathSegment& segment) {
  const auto setpoints = run_job<S>({segment}, test_machine());
  REQUIRE(!setpoints.empty());
  for (std::size_t i = 0; i < setpoints.size(); i += 7) {
    REQUIRE(distance_to_curve(segment, position_of(setpoints[i])) < test_machine().tolerance_mm + 2.0 / 65536);
  }
  const auto end = vec_from_doubles<S, 3>(to_doubles(segment.end())).value();
  for (std::size_t a = 0; a < 3; ++a) CHECK(setpoints.back().position[a] == end[a]);
}

}  // namespace

TEST_CASE("degenerate: a zero-length line is refused with DegenerateCurve", "[core][range]") {
  CHECK(PathSegment::make_line(mp(3, 4, 5), mp(3, 4, 5)).error() == Error::DegenerateCurve);
}

TEST_CASE("degenerate: a Bezier whose control points all coincide is refused with DegenerateCurve", "[core][range]") {
  const std::array<MachinePoint, 4> same{mp(1, 1), mp(1, 1), mp(1, 1), mp(1, 1)};
  CHECK(PathSegment::make_bezier(same).error() == Error::DegenerateCurve);
  const std::array<double, 4> weights{1, 2, 3, 1};
  CHECK(PathSegment::make_rational_bezier(same, weights).error() == Error::DegenerateCurve);
}

TEMPLATE_TEST_CASE("degenerate: coincident end control points (zero start and end velocity) are followed", "[core][range]",
                   double, Q16_16) {
  // b0 = b1 and b2 = b3: p'(0) = p'(1) = 0, the curve is the straight segment from (0,0) to (10,0)
  // traversed with a smoothstep parameter: p(t) = (10 (3t^2 - 2t^3), 0).
  const std::array<MachinePoint, 4> control{mp(0, 0), mp(0, 0), mp(10, 0), mp(10, 0)};
  const auto segment = PathSegment::make_bezier(control);
  REQUIRE(segment.has_value());
  CHECK(segment.value().point(0.5)[0] == Approx(5.0));
  check_followed<TestType>(segment.value());
}

TEMPLATE_TEST_CASE("degenerate: a cubic with a cusp (zero derivative inside) is followed through the cusp",
                   "[core][range]", double, Q16_16) {
  // b = (0,0), (1,1), (0,1), (1,0): p'(1/2) = 3 [ (1,1)/4 + 2 (-1,0)/4 + (1,-1)/4 ] = 0, a cusp at
  // p(1/2) = (0 + 3/8 + 0 + 1/8, 0 + 3/8 + 3/8 + 0) = (1/2, 3/4).
  const std::array<MachinePoint, 4> control{mp(0, 0), mp(1, 1), mp(0, 1), mp(1, 0)};
  const auto segment = PathSegment::make_bezier(control);
  REQUIRE(segment.has_value());
  const auto d = segment.value().derivative(0.5, 1);
  CHECK(norm(d) == Approx(0.0).margin(1e-12));
  check_followed<TestType>(segment.value());
  // The path reaches the cusp point itself (it is not cut short).
  const auto setpoints = run_job<TestType>({segment.value()}, test_machine());
  double closest = 1e300;
  for (const auto& sp : setpoints) closest = std::fmin(closest, distance(position_of(sp), mp(0.5, 0.75)));
  CHECK(closest < 1e-3);
}

TEST_CASE("degenerate: an arc of zero radius is refused with DegenerateCurve", "[core][range]") {
  CHECK(PathSegment::make_arc(mp(2, 2), mp(2, 2), mp(2, 2), ArcDirection::Clockwise, 0, 1e-3).error() ==
        Error::DegenerateCurve);
  using P = Vec2<double>;
  CHECK(circular_arc<double>(P{{0, 0}}, P{{0, 0}}, P{{0, 0}}, ArcDirection::Clockwise, 1e-3).error() ==
        Error::DegenerateCurve);
  CHECK(circular_arc<Q16_16>(Vec2<Q16_16>{}, Vec2<Q16_16>{}, Vec2<Q16_16>{}, ArcDirection::Clockwise,
                             Q16_16::from_double(1e-3).value())
            .error() == Error::DegenerateCurve);
}

TEMPLATE_TEST_CASE("degenerate: an arc with start equal to end is a full circle and is followed", "[core][range]", double,
                   Q16_16) {
  const auto circle = PathSegment::make_arc(mp(5, 0), mp(5, 0), mp(0, 0), ArcDirection::CounterClockwise, 0, 1e-3);
  REQUIRE(circle.has_value());
  CHECK(circle.value().arc_sweep_rad() == Approx(2 * 3.14159265358979).epsilon(1e-12));
  check_followed<TestType>(circle.value());
}

TEST_CASE("degenerate: a B-spline with a full-multiplicity interior knot is followed as two pieces", "[core][range]") {
  // Cubic, knots 0,0,0,0, 1/2,1/2,1/2, 1,1,1,1: interior multiplicity 3 = degree, so the curve is
  // C0 at u = 1/2 and passes through control point 3 there; the pieces are the Bézier curves on
  // control points 0..3 and 3..6.
  using Spline = BSpline<double, 3, 3, 8>;
  const std::array<MachinePoint, 7> points{mp(0, 0), mp(1, 2), mp(2, 2), mp(3, 0), mp(4, -2), mp(5, -2), mp(6, 0)};
  const std::array<double, 11> knots{0, 0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1, 1};
  const auto spline = Spline::create(points, knots, 3);
  REQUIRE(spline.has_value());
  std::vector<PathSegment> job;
  REQUIRE(for_each_bezier(spline.value(), [&](const BezierSpan<double, 3, 3>& piece) {
            const auto control = piece.curve.control_points();
            const auto s = PathSegment::make_bezier(std::span<const MachinePoint>(control.data(), control.size()));
            REQUIRE(s.has_value());
            job.push_back(s.value());
          }).has_value());
  REQUIRE(job.size() == 2);
  for (std::size_t k = 0; k < 4; ++k) {
    CHECK(distance(job[0].polynomial().control_points()[k], points[k]) < 1e-12);
    CHECK(distance(job[1].polynomial().control_points()[k], points[k + 3]) < 1e-12);
  }
  const auto setpoints = run_job<Q16_16>(job, test_machine());
  CHECK(to_double(setpoints.back().position[0]) == 6.0);
  CHECK(to_double(setpoints.back().position[1]) == 0.0);
  // The corner at (3,0) is reached (the junction speed there is limited, not skipped).
  double closest = 1e300;
  for (const auto& sp : setpoints) closest = std::fmin(closest, distance(position_of(sp), mp(3, 0)));
  CHECK(closest < 0.06);  // within the junction deviation allowance (0.05 mm) plus a step
}

TEST_CASE("degenerate: a knot repeated more than the degree inside is refused with KnotMultiplicityTooHigh",
          "[core][range]") {
  using Spline = BSpline<double, 3, 3, 8>;
  const std::array<MachinePoint, 8> points{mp(0, 0), mp(1, 2), mp(2, 2), mp(3, 0), mp(4, -2), mp(5, -2), mp(6, 0), mp(7, 1)};
  const std::array<double, 12> knots{0, 0, 0, 0, 0.5, 0.5, 0.5, 0.5, 1, 1, 1, 1};
  const auto spline = Spline::create(points, knots, 3);
  REQUIRE_FALSE(spline);
  CHECK(spline.error() == Error::KnotMultiplicityTooHigh);
}
