// SPDX-License-Identifier: MIT
// Junction speeds: grbl's junction deviation with the right angle (hand-computed values), gentle
// corners never slower than sharp ones, and the limits held at corners, trapezoid and S-curve, also
// when j_max > 2 a_max rate (the velocity jump of a corner must respect a_max too).
#include <cmath>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/motion/segment_plan.hpp>

#include "motion_test_support.hpp"

using namespace curvestep;
using namespace curvestep::testing;

namespace {

constexpr double pi = 3.14159265358979323846;

/// A plan of a straight segment along `direction` (unit) with a high speed cap: only the corner counts.
SegmentPlan straight_plan(double angle_deg) {
  SegmentPlan plan;
  plan.length_mm = 100;
  plan.limits = ProfileLimits{1e9, 2000, 50000, true};
  const double a = angle_deg * pi / 180;
  plan.start_tangent = mp(std::cos(a), std::sin(a));
  plan.end_tangent = plan.start_tangent;
  return plan;
}

/// A machine whose corner speed is set by the junction deviation alone (the per-tick velocity-jump
/// rule is made irrelevant by a very low rate: the jump may then be k·a_max·1 s).
MachineLimits deviation_only_machine() {
  MachineLimits m = test_machine();
  m.a_max_mm_per_s2 = 2000;
  m.junction_deviation_mm = 0.02;
  m.rate_hz = 1;
  return m;
}

}  // namespace

TEST_CASE("junction speed: grbl's junction deviation at 5, 45, 90 and 135 degrees of deflection, computed by hand", "[core][motion][junction]") {
  // grbl (its documentation): v² = a δ sin(φ/2) / (1 − sin(φ/2)), φ the angle between the reversed
  // incoming direction and the outgoing one, φ = 180° − deflection. a = 2000 mm/s², δ = 0.02 mm:
  //   deflection   5°: φ = 175°, sin 87.5° = 0.99904822 -> r = 0.02·0.99904822/0.00095178 = 20.9933 mm, v = 204.906 mm/s
  //   deflection  45°: φ = 135°, sin 67.5° = 0.92387953 -> r = 0.242741 mm, v = 22.0337 mm/s
  //   deflection  90°: φ =  90°, sin 45°   = 0.70710678 -> r = 0.0482843 mm, v = 9.82693 mm/s
  //   deflection 135°: φ =  45°, sin 22.5° = 0.38268343 -> r = 0.0123983 mm, v = 4.97962 mm/s
  const struct {
    double deflection_deg;
    double expected_mm_per_s;
  } cases[] = {{5, 204.906}, {45, 22.0337}, {90, 9.82693}, {135, 4.97962}};
  const MachineLimits m = deviation_only_machine();
  for (const auto& c : cases) {
    INFO("deflection " << c.deflection_deg << " degrees");
    const double cos_deflection = std::cos(c.deflection_deg * pi / 180);
    CHECK(junction_deviation_speed(cos_deflection, 2000, 0.02) == Approx(c.expected_mm_per_s).epsilon(1e-5));
    // Through junction_speed, from an incoming direction of 10° to 10° + deflection.
    const double v = junction_speed(straight_plan(10), straight_plan(10 + c.deflection_deg), m);
    CHECK(v == Approx(c.expected_mm_per_s).epsilon(1e-5));
  }
}

TEST_CASE("junction speed: straight on is not limited by the corner rules, a reversal stops", "[core][motion][junction]") {
  const MachineLimits m = test_machine();
  CHECK(std::isinf(junction_deviation_speed(1.0, 2000, 0.02)));
  CHECK(junction_deviation_speed(-1.0, 2000, 0.02) == 0);
  CHECK(junction_speed(straight_plan(30), straight_plan(30), m) == 1e9);
  CHECK(junction_speed(straight_plan(30), straight_plan(210), m) == 0);
}

TEST_CASE("junction speed: a gentler corner is never slower than a sharper one (random angle pairs)", "[core][motion][junction]") {
  std::mt19937_64 random(20261125);
  std::uniform_real_distribution<double> angle(0.0, 179.9);
  for (const bool jerk_limited : {true, false}) {
    for (const double rate : {1000.0, 40000.0}) {
      MachineLimits m = test_machine();
      m.jerk_limited = jerk_limited;
      m.rate_hz = rate;
      for (int i = 0; i < 2000; ++i) {
        double gentle = angle(random);
        double sharp = angle(random);
        if (gentle > sharp) std::swap(gentle, sharp);
        const double v_gentle = junction_speed(straight_plan(0), straight_plan(gentle), m);
        const double v_sharp = junction_speed(straight_plan(0), straight_plan(sharp), m);
        INFO("gentle " << gentle << " sharp " << sharp << " rate " << rate << " jerk-limited " << jerk_limited);
        REQUIRE(v_gentle >= v_sharp);
      }
    }
  }
}

TEST_CASE("junction speed: the trapezoid passes a corner at the velocity-jump speed, not at a stop", "[core][motion][junction]") {
  MachineLimits m = test_machine();
  m.jerk_limited = false;
  // Deflection 10°: the jump 2 v sin 5° may use k = √(s² + ε) − s of a_max Δt, s = sin 5°,
  // ε = 2·0.0075 + 0.0075² (the corner's 0.75 % allowance). Hand: s = 0.0871557, ε = 0.01505625,
  // k = √(0.00759612 + 0.01505625) − 0.0871557 = 0.0633513, v = k · 2000 · 0.001 / (2 s) = 0.726875 mm/s.
  const double v = junction_speed(straight_plan(0), straight_plan(10), m);
  CHECK(v == Approx(0.726875).epsilon(1e-5));
  CHECK(v > 0);
}

TEST_CASE("junction speed: corners keep the measured acceleration and jerk within the limits, also with j_max > 2 a_max rate", "[core][motion][junction]") {
  // Polylines with corners of 1..135 degrees, run through the controller, measured by differences.
  std::vector<PathSegment> zigzag;
  MachinePoint p = mp(0, 0);
  double heading = 0;
  const double turns[] = {1, -5, 30, -90, 135, -45, 2, 60, -120, 10};
  for (const double turn : turns) {
    const MachinePoint q = p + mp(6 * std::cos(heading), 6 * std::sin(heading));
    zigzag.push_back(line(p, q));
    p = q;
    heading += turn * pi / 180;
  }
  for (const double jerk : {50000.0, 1e9}) {  // 1e9 > 2 · 2000 · 1000: the acceleration overshoot
    for (const bool jerk_limited : {true, false}) {
      MachineLimits m = test_machine();
      m.j_max_mm_per_s3 = jerk;
      m.jerk_limited = jerk_limited;
      INFO("j_max " << jerk << " jerk-limited " << jerk_limited);
      const auto sp = run_job<double>(zigzag, m);
      const auto peaks = measure(sp, m.rate_hz);
      CHECK(peaks.acceleration <= m.a_max_mm_per_s2 * 1.0075 + 1e-9);
      if (jerk_limited) CHECK(peaks.jerk <= m.j_max_mm_per_s3 * 1.0075);
    }
  }
}
