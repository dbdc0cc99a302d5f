// SPDX-License-Identifier: MIT
// NaN, infinity and out-of-range values at every boundary where outside data enters the core:
// PathSegment::make_*, MachineLimits::validate, RationalBezier weights, BSpline knots, and the
// MotionController fed with geometry far outside the position range. Each gives an error.
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>

#include <catch2/catch.hpp>

#include <curvestep/core/bspline/bspline.hpp>
#include <curvestep/core/curve/rational_bezier.hpp>
#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/core/motion/motion_controller.hpp>

#include "core/motion/motion_test_support.hpp"
#include "support/numeric.hpp"

using namespace curvestep;
using curvestep::testing::mp;
using curvestep::testing::test_machine;

namespace {
constexpr double nan_value = std::numeric_limits<double>::quiet_NaN();
constexpr double inf_value = std::numeric_limits<double>::infinity();
constexpr std::array<double, 3> non_finite{nan_value, inf_value, -inf_value};
}  // namespace

TEST_CASE("range: make_line and make_bezier refuse NaN and infinity in any coordinate", "[core][range]") {
  for (const double bad : non_finite) {
    for (std::size_t axis = 0; axis < 3; ++axis) {
      MachinePoint p = mp(1, 2, 3);
      p[axis] = bad;
      CHECK(PathSegment::make_line(mp(0, 0, 0), p).error() == Error::NotFinite);
      CHECK(PathSegment::make_line(p, mp(0, 0, 0)).error() == Error::NotFinite);
      const std::array<MachinePoint, 3> control{mp(0, 0), p, mp(5, 5)};
      const auto bezier = PathSegment::make_bezier(control);
      CHECK(bezier.error() == Error::NotFinite);
      CHECK(bezier.where() == 1);
    }
  }
}

TEST_CASE("range: make_rational_bezier refuses NaN and infinite weights and points", "[core][range]") {
  const std::array<MachinePoint, 3> control{mp(0, 0), mp(1, 1), mp(2, 0)};
  for (const double bad : non_finite) {
    const std::array<double, 3> weights{1, bad, 1};
    const auto s = PathSegment::make_rational_bezier(control, weights);
    CHECK(s.error() == Error::NotFinite);
    CHECK(s.where() == 1);
    const std::array<MachinePoint, 3> bad_control{mp(0, 0), mp(1, 1), mp(2, bad)};
    const std::array<double, 3> good{1, 2, 1};
    CHECK(PathSegment::make_rational_bezier(bad_control, good).error() == Error::NotFinite);
  }
  const std::array<double, 3> zero{1, 0, 1};
  CHECK(PathSegment::make_rational_bezier(control, zero).error() == Error::NonPositiveWeight);
  const std::array<double, 3> negative{1, 1, -1e-300};
  CHECK(PathSegment::make_rational_bezier(control, negative).error() == Error::NonPositiveWeight);
}

TEST_CASE("range: make_arc refuses NaN and infinity in the centre, the ends and the helix height", "[core][range]") {
  for (const double bad : non_finite) {
    CHECK(PathSegment::make_arc(mp(1, 0), mp(-1, 0), mp(bad, 0), ArcDirection::CounterClockwise, 0, 1e-3).error() ==
          Error::NotFinite);
    CHECK(PathSegment::make_arc(mp(1, bad), mp(-1, 0), mp(0, 0), ArcDirection::CounterClockwise, 0, 1e-3).error() ==
          Error::NotFinite);
    // z only moves along the helix, but a NaN there would reach every setpoint.
    CHECK(PathSegment::make_arc(mp(1, 0, bad), mp(-1, 0), mp(0, 0), ArcDirection::CounterClockwise, 0, 1e-3).error() ==
          Error::NotFinite);
    CHECK(PathSegment::make_arc(mp(1, 0), mp(-1, 0, bad), mp(0, 0), ArcDirection::CounterClockwise, 0, 1e-3).error() ==
          Error::NotFinite);
  }
  // Finite ends whose height difference overflows double.
  CHECK(PathSegment::make_arc(mp(1, 0, -1e308), mp(-1, 0, 1e308), mp(0, 0), ArcDirection::CounterClockwise, 0, 1e-3)
            .error() == Error::NotFinite);
  // A NaN radius tolerance would accept any pair of radii: refused like a mismatch.
  CHECK(PathSegment::make_arc(mp(1, 0), mp(-1, 0), mp(0, 0), ArcDirection::CounterClockwise, 0, nan_value).error() ==
        Error::InvalidArgument);
    // Far-away XY whose squared radius overflows double.
  CHECK(PathSegment::make_arc(mp(1e200, 0), mp(-1e200, 0), mp(0, 0), ArcDirection::CounterClockwise, 0, 1e-3).error() ==
        Error::NotFinite);
}

TEST_CASE("range: MachineLimits::validate refuses NaN and infinity in every field", "[core][range]") {
  using Setter = void (*)(MachineLimits&, double);
  const std::array<std::pair<Setter, LimitField>, 8> fields{{
      {[](MachineLimits& m, double v) { m.v_max_mm_per_s = v; }, LimitField::VMax},
      {[](MachineLimits& m, double v) { m.a_max_mm_per_s2 = v; }, LimitField::AMax},
      {[](MachineLimits& m, double v) { m.j_max_mm_per_s3 = v; }, LimitField::JMax},
      {[](MachineLimits& m, double v) { m.feed_mm_per_s = v; }, LimitField::Feed},
      {[](MachineLimits& m, double v) { m.tolerance_mm = v; }, LimitField::Tolerance},
      {[](MachineLimits& m, double v) { m.junction_deviation_mm = v; }, LimitField::JunctionDeviation},
      {[](MachineLimits& m, double v) { m.max_step_rate_hz = v; }, LimitField::MaxStepRate},
      {[](MachineLimits& m, double v) { m.axes[1].a_max_mm_per_s2 = v; }, LimitField::AxisAMax},
  }};
  for (const double bad : non_finite) {
    for (std::size_t i = 0; i < fields.size(); ++i) {
      MachineLimits m = test_machine();
      fields[i].first(m, bad);
      const auto r = m.validate();
      REQUIRE_FALSE(r);
      CHECK(r.error() == Error::InvalidLimit);
      const auto expected = static_cast<std::size_t>(fields[i].second) + (fields[i].second == LimitField::AxisAMax ? 1 : 0);
      CHECK(r.where() == expected);
    }
    MachineLimits m = test_machine();
    m.rate_hz = bad;
    CHECK(m.validate().error() == Error::InvalidRate);
    m = test_machine();
    m.axes[2].steps_per_mm = bad;
    CHECK(m.validate().error() == Error::InvalidLimit);
  }
}

TEST_CASE("range: MachineLimits::validate refuses a NaN, infinite or negative rapid speed", "[core][range]") {
  for (const double bad : {nan_value, inf_value, -inf_value, -1.0}) {
    MachineLimits m = test_machine();
    m.rapid_mm_per_s = bad;
    const auto r = m.validate();
    REQUIRE_FALSE(r);
    CHECK(r.error() == Error::InvalidLimit);
    CHECK(r.where() == static_cast<std::size_t>(LimitField::Rapid));
  }
  MachineLimits m = test_machine();
  m.rapid_mm_per_s = 0;  // 0 means "use v_max"
  CHECK(m.validate().has_value());
}

TEST_CASE("range: RationalBezier and BSpline refuse NaN weights and knots in every scalar", "[core][range]") {
  using Point = Vec<double, 2>;
  const std::array<Point, 3> control{Point{{0, 0}}, Point{{1, 1}}, Point{{2, 0}}};
  for (const double bad : non_finite) {
    const std::array<double, 3> weights{1, 1, bad};
    const auto r = RationalBezier<double, 2, 3>::create(control, weights);
    CHECK(r.error() == Error::NotFinite);
    CHECK(r.where() == 2);
    const std::array<float, 3> float_weights{1, static_cast<float>(bad), 1};
    const std::array<Vec<float, 2>, 3> float_control{Vec<float, 2>{{0, 0}}, Vec<float, 2>{{1, 1}}, Vec<float, 2>{{2, 0}}};
    CHECK(RationalBezier<float, 2, 3>::create(float_control, float_weights).error() == Error::NotFinite);
    // Knots: clamped quadratic with one interior knot; each knot in turn is bad.
    for (std::size_t k = 0; k < 7; ++k) {
      std::array<double, 7> knots{0, 0, 0, 0.5, 1, 1, 1};
      knots[k] = bad;
      const std::array<Point, 4> points{Point{{0, 0}}, Point{{1, 1}}, Point{{2, 0}}, Point{{3, 1}}};
      const auto spline = BSpline<double, 2, 3, 8>::create(points, knots, 2);
      REQUIRE_FALSE(spline);
      CHECK(spline.error() == Error::NotFinite);
      CHECK(spline.where() == k);
    }
  }
}

TEST_CASE("range: a Q16.16 controller faults with FixedOverflow on a path that leaves the position range", "[core][range]") {
  // The line is fine in double, but its far end is outside Q16.16: the setpoint that would wrap
  // is an error instead, and the controller stops in Fault.
  MotionController<Q16_16, 8, 4> controller;
  MachineLimits m = test_machine();
  m.v_max_mm_per_s = 20000;
  m.feed_mm_per_s = 20000;
  m.a_max_mm_per_s2 = 1e6;
  m.j_max_mm_per_s3 = 1e9;
  REQUIRE(controller.configure(m).has_value());
  REQUIRE(controller.try_push(PathSegment::make_line(mp(32000, 0), mp(33000, 0)).value(), 0).has_value());
  controller.end_of_job();
  REQUIRE(controller.start().has_value());
  Result<Setpoint<Q16_16>> last = fail(Error::InvalidState);
  double furthest = 0;
  for (int tick = 0; tick < 100000; ++tick) {
    last = controller.next_setpoint();
    if (!last) break;
    furthest = to_double(last.value().position[0]);
  }
  REQUIRE_FALSE(last);
  CHECK(last.error() == Error::FixedOverflow);
  CHECK(controller.state() == ControllerState::Fault);
  CHECK(controller.fault().code == Error::FixedOverflow);
  CHECK(furthest > 32700);  // it moved up to the edge, monotonically, without wrapping to -32768
}

TEST_CASE("range: segments whose derivatives overflow double are refused with NotFinite", "[core][range]") {
  // Finite end points 2e308 apart: b - a is infinite, so the planner could not evaluate the
  // tangent (PathSegment::derivative would trap). Refused when the segment is made.
  CHECK(PathSegment::make_line(mp(-1e308, 0), mp(1e308, 0)).error() == Error::NotFinite);
  // A cubic whose second hodograph 6 (b2 - 2 b1 + b0) overflows although 3 (b1 - b0) does not.
  const std::array<MachinePoint, 4> control{mp(0, 0), mp(1e307, 0), mp(-1e307, 0), mp(1e307, 1)};
  CHECK(PathSegment::make_bezier(control).error() == Error::NotFinite);
  // Large but harmless: 1e150 mm segments are accepted (a Q16.16 controller then faults on output).
  CHECK(PathSegment::make_line(mp(-1e150, 0), mp(1e150, 0)).has_value());
}

TEST_CASE("range: rational segments whose weight ratio makes derivatives overflow are refused with NotFinite",
          "[core][range]") {
  // Found by the planner fuzz harness: a degree-7 rational Bézier with w_0 = 2e-321 (a denormal)
  // and w_1 = 4e-20. r''(0) grows like (w_1 / w_0)^2 ~ 1e603: PathSegment::derivative trapped
  // inside the planner. Now make_rational_bezier refuses it.
  const std::array<MachinePoint, 8> control{mp(-29.7, -20.7), mp(-30.0, -34.8, 1.1), mp(-40.8, 29.0), mp(-44.8, -43.0),
                                            mp(7.2, -3.4),    mp(0.0, -41.3, -49.8), mp(0.0, -41.3, -49.8), mp(-22.1, 10.6, -17.3)};
  const std::array<double, 8> weights{2.005906522115461e-321, 3.9175360785733789e-20, 15.4, 19.9, 1.9, 12.9, 1.1, 17.2};
  CHECK(PathSegment::make_rational_bezier(control, weights).error() == Error::NotFinite);
  // A weight ratio of 1e6 on a 1e4 mm curve is an ordinary (if extreme) conic: accepted, and every
  // derivative the planner evaluates is finite.
  const std::array<MachinePoint, 3> conic{mp(0, 0), mp(5000, 10000), mp(10000, 0)};
  const std::array<double, 3> conic_weights{1, 1e6, 1};
  const auto accepted = PathSegment::make_rational_bezier(conic, conic_weights);
  REQUIRE(accepted.has_value());
  for (int k = 0; k <= 64; ++k) {
    for (std::size_t order = 1; order <= 3; ++order) {
      const auto d = accepted.value().derivative(k / 64.0, order);
      for (std::size_t axis = 0; axis < 3; ++axis) REQUIRE(std::isfinite(d[axis]));
    }
  }
}

TEST_CASE("range: machine limits at the ends of the double range give finite setpoints or an error", "[core][range]") {
  // Every limit 1e300 (squares overflow double): the controller either refuses the limits, or runs
  // the job to its end point with finite setpoints, or stops with a Result error. Never NaN output.
  for (const double huge : {1e150, 1e300, std::numeric_limits<double>::max()}) {
    MachineLimits m = test_machine();
    m.v_max_mm_per_s = huge;
    m.feed_mm_per_s = huge;
    m.a_max_mm_per_s2 = huge;
    m.j_max_mm_per_s3 = huge;
    m.rapid_mm_per_s = huge;
    CHECK_FALSE(m.validate());  // beyond limit_range: refused before anything is planned
    MotionController<double, 8, 4> controller;
    if (!controller.configure(m)) continue;
    const auto pushed = controller.try_push(PathSegment::make_line(mp(0, 0), mp(10, 5)).value(), 0);
    if (!pushed) continue;
    controller.end_of_job();
    REQUIRE(controller.start().has_value());
    Setpoint<double> last{};
    bool errored = false;
    for (int tick = 0; tick < 10000 && !controller.finished(); ++tick) {
      const auto sp = controller.next_setpoint();
      if (!sp) {
        errored = true;
        CHECK(controller.state() == ControllerState::Fault);
        break;
      }
      last = sp.value();
      for (std::size_t a = 0; a < 3; ++a) REQUIRE(std::isfinite(last.position[a]));
      REQUIRE(std::isfinite(last.speed_mm_per_s));
    }
    if (!errored) {
      REQUIRE(controller.finished());
      CHECK(last.position[0] == 10.0);
      CHECK(last.position[1] == 5.0);
    }
  }
  // Tiny limits are refused (issue 19.8 / 21 / 24.4: v_max 5e-324 streamed setpoints at the start
  // for ever): InvalidLimit naming the field, for each field alone.
  for (const double tiny : {1e-300, 5e-324}) {
    MachineLimits slow = test_machine();
    slow.v_max_mm_per_s = tiny;
    MotionController<double, 8, 4> controller;
    const auto refused = controller.configure(slow);
    REQUIRE_FALSE(refused);
    CHECK(refused.error() == Error::InvalidLimit);
    CHECK(refused.where() == static_cast<std::size_t>(LimitField::VMax));
    MachineLimits fine_tolerance = test_machine();
    fine_tolerance.tolerance_mm = tiny;
    CHECK(fine_tolerance.validate().where() == static_cast<std::size_t>(LimitField::Tolerance));
  }
}

TEST_CASE("range: each machine limit just outside its documented range is refused naming its field", "[core][range]") {
  // The ranges of limit_range() (docs/errors.md): one field at a time, just below and just above.
  struct Case {
    double MachineLimits::*field;
    LimitField name;
    double below, above;
  };
  const Case cases[] = {
      {&MachineLimits::v_max_mm_per_s, LimitField::VMax, 0.9e-3, 1.1e6},
      {&MachineLimits::a_max_mm_per_s2, LimitField::AMax, 0.9e-3, 1.1e9},
      {&MachineLimits::j_max_mm_per_s3, LimitField::JMax, 0.9e-3, 1.1e12},
      {&MachineLimits::feed_mm_per_s, LimitField::Feed, 0.9e-3, 1.1e6},
      {&MachineLimits::tolerance_mm, LimitField::Tolerance, 0.9e-6, 101},
      {&MachineLimits::junction_deviation_mm, LimitField::JunctionDeviation, -1e-9, 101},
      {&MachineLimits::rapid_mm_per_s, LimitField::Rapid, 0.9e-3, 1.1e6},
      {&MachineLimits::max_step_rate_hz, LimitField::MaxStepRate, 0.9, 1.1e8},
  };
  for (const auto& c : cases) {
    INFO("field " << static_cast<int>(c.name));
    for (const double v : {c.below, c.above}) {
      MachineLimits m = test_machine();
      m.*c.field = v;
      const auto r = m.validate();
      REQUIRE_FALSE(r);
      CHECK(r.error() == Error::InvalidLimit);
      CHECK(r.where() == static_cast<std::size_t>(c.name));
    }
    MachineLimits edge = test_machine();
    edge.*c.field = limit_range(c.name).high;
    CHECK(edge.validate().has_value());
  }
  MachineLimits axis = test_machine();
  axis.axes[2].a_max_mm_per_s2 = 2e9;
  CHECK(axis.validate().where() == static_cast<std::size_t>(LimitField::AxisAMax) + 2);
}
