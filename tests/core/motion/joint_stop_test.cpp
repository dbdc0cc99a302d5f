// SPDX-License-Identifier: MIT
// JointStop: an exact stop at a joint makes each side a rest-to-rest move, and a rest of R ticks
// adds exactly R setpoints at the joint (speed 0, labelled with the next segment) and shifts the
// rest of the stream by R ticks bit for bit.
#include <cstdint>
#include <vector>

#include <catch2/catch.hpp>

#include "motion_test_support.hpp"

using namespace curvestep;
using namespace curvestep::testing;

namespace {

/// Checks that `rested` is `plain` with `rest` setpoints at `joint` inserted before plain[at]:
/// identical positions, speeds and segments before, the rest, then plain's tail `rest` ticks later.
template <class S>
void check_rest_inserted(const std::vector<Setpoint<S>>& plain, const std::vector<Setpoint<S>>& rested, std::size_t at,
                         std::uint32_t rest, const MachinePoint& joint, std::uint32_t next_segment) {
  REQUIRE(rested.size() == plain.size() + rest);
  for (std::size_t i = 0; i < at; ++i) REQUIRE(rested[i] == plain[i]);
  for (std::size_t i = at; i < at + rest; ++i) {
    for (std::size_t axis = 0; axis < motion_axes; ++axis) REQUIRE(to_double(rested[i].position[axis]) == joint[axis]);
    REQUIRE(rested[i].speed_mm_per_s == 0);
    REQUIRE(rested[i].segment == next_segment);
    REQUIRE(rested[i].tick == i);
  }
  for (std::size_t i = at; i < plain.size(); ++i) {
    Setpoint<S> shifted = plain[i];
    shifted.tick += rest;
    REQUIRE(rested[i + rest] == shifted);
  }
}

/// Index of the first setpoint of `segment`.
template <class S>
std::size_t first_of(const std::vector<Setpoint<S>>& sp, std::uint32_t segment) {
  for (std::size_t i = 0; i < sp.size(); ++i) {
    if (sp[i].segment == segment) return i;
  }
  FAIL("segment " << segment << " has no setpoint");
  return 0;
}

}  // namespace

TEMPLATE_TEST_CASE("joint stop: a rest at a reversal adds exactly its ticks, the rest unchanged", "[core][motion][joint_stop]",
                   double, Q16_16) {
  // A reversal stops anyway (junction speed 0), so the only difference a rest makes is the rest.
  const MachineLimits m = test_machine();
  const std::vector<PathSegment> job{line(mp(0, 0), mp(10, 0)), line(mp(10, 0), mp(0, 0))};
  const auto plain = run_job<TestType>(job, m);
  const auto rested = run_job<TestType>(job, m, 2000000, {JointStop{}, JointStop{true, 500}});
  check_rest_inserted(plain, rested, first_of(plain, 1), 500, mp(10, 0), 1);
}

TEMPLATE_TEST_CASE("joint stop: a collinear joint with a stop is two rest-to-rest moves", "[core][motion][joint_stop]", double,
                   Q16_16) {
  const MachineLimits m = test_machine();
  const std::vector<PathSegment> job{line(mp(0, 0), mp(10, 0)), line(mp(10, 0), mp(20, 0))};
  const auto passed = run_job<TestType>(job, m);
  const auto stopped = run_job<TestType>(job, m, 2000000, {JointStop{}, JointStop{true, 0}});
  const auto single = run_job<TestType>({line(mp(0, 0), mp(10, 0))}, m);
  // Each half takes the single move's time T: the job's last setpoint is at the first tick >= 2T,
  // the single move's at the first tick >= T (so 2 n1 - 1 <= n2 <= 2 n1).
  const std::uint64_t n1 = single.back().tick;
  const std::uint64_t n2 = stopped.back().tick;
  CHECK(n2 <= 2 * n1);
  CHECK(n2 + 1 >= 2 * n1);
  CHECK(passed.back().tick < n2);  // passed at speed, the job is shorter
  // Near the joint the speed falls to (almost) zero: below what a single tick of jerk gives.
  double slowest_near_joint = 1e9;
  for (const auto& sp : stopped) {
    if (sp.tick + 2 >= n1 && sp.tick <= n1 + 2) slowest_near_joint = std::fmin(slowest_near_joint, sp.speed_mm_per_s);
  }
  CHECK(slowest_near_joint < m.j_max_mm_per_s3 / (m.rate_hz * m.rate_hz));
  // A 0.5 s rest at 1 kHz there: exactly 500 setpoints more, at the joint.
  const auto rested = run_job<TestType>(job, m, 2000000, {JointStop{}, JointStop{true, 500}});
  check_rest_inserted(stopped, rested, first_of(stopped, 1), 500, mp(10, 0), 1);
}

TEMPLATE_TEST_CASE("joint stop: a rest before the first segment holds the start", "[core][motion][joint_stop]", double, Q16_16) {
  const MachineLimits m = test_machine();
  const std::vector<PathSegment> job{line(mp(1, 2), mp(11, 2))};
  const auto plain = run_job<TestType>(job, m);
  const auto rested = run_job<TestType>(job, m, 2000000, {JointStop{true, 7}});
  check_rest_inserted(plain, rested, 0, 7, mp(1, 2), 0);
}

TEMPLATE_TEST_CASE("joint stop: a rest after the last move adds its ticks at the end point, labelled after the last segment",
                   "[core][motion][joint_stop]", double, Q16_16) {
  // A G4 dwell after the job's last move: the motion is unchanged, then 250 setpoints stand at the
  // end point (10, 5) with speed 0, labelled 2 (last segment 1, + 1), and only then the job finishes.
  const MachineLimits m = test_machine();
  const std::vector<PathSegment> job{line(mp(0, 0), mp(10, 0)), line(mp(10, 0), mp(10, 5))};
  const auto plain = run_job<TestType>(job, m);
  const auto rested = run_job<TestType>(job, m, 2000000, {JointStop{}, JointStop{}, JointStop{true, 250}});
  check_rest_inserted(plain, rested, plain.size(), 250, mp(10, 5), 2);
}

TEST_CASE("joint stop: a feed hold during the rest after the last move holds, resume serves the rest, then finishes",
          "[core][motion][joint_stop]") {
  const MachineLimits m = test_machine();
  MotionController<double> controller;
  REQUIRE(controller.configure(m).has_value());
  REQUIRE(controller.try_push(line(mp(0, 0), mp(10, 0)), 0).has_value());
  controller.end_of_job(100);
  REQUIRE(controller.start().has_value());
  std::size_t rest_seen = 0;
  while (rest_seen < 30) {
    REQUIRE(controller.next_setpoint().has_value());
    if (controller.resting()) ++rest_seen;
  }
  controller.hold();
  REQUIRE(controller.state() == ControllerState::Held);
  for (int i = 0; i < 20; ++i) {
    const auto sp = controller.next_setpoint();
    REQUIRE(sp.has_value());
    CHECK(sp.value().position[0] == 10.0);
  }
  REQUIRE(controller.resume().has_value());
  for (int i = 0; i < 70; ++i) {
    REQUIRE_FALSE(controller.finished());
    const auto sp = controller.next_setpoint();
    REQUIRE(sp.has_value());
    REQUIRE(controller.resting());
    CHECK(sp.value().position[0] == 10.0);
    CHECK(sp.value().segment == 1u);
  }
  CHECK(controller.finished());
}

TEST_CASE("joint stop: a rest through a cusp split stays before the first piece", "[core][motion][joint_stop]") {
  const MachineLimits m = test_machine();
  // A cubic with a cusp (queued as two pieces) after a line into it at a corner.
  const std::vector<PathSegment> job{line(mp(-10, 0), mp(0, 0)), cubic(mp(0, 0), mp(30, 30), mp(0, 30), mp(30, 0))};
  const auto stopped = run_job<double>(job, m, 2000000, {JointStop{}, JointStop{true, 0}});
  const auto rested = run_job<double>(job, m, 2000000, {JointStop{}, JointStop{true, 40}});
  check_rest_inserted(stopped, rested, first_of(stopped, 1), 40, mp(0, 0), 1);
}

TEST_CASE("joint stop: a feed hold during a rest holds at the joint, resume finishes the rest, then moves",
          "[core][motion][joint_stop]") {
  const MachineLimits m = test_machine();
  MotionController<double> controller;
  REQUIRE(controller.configure(m).has_value());
  REQUIRE(controller.try_push(line(mp(0, 0), mp(10, 0)), 0).has_value());
  REQUIRE(controller.try_push(line(mp(10, 0), mp(10, 10)), 1, JointStop{true, 100}).has_value());
  controller.end_of_job();
  REQUIRE(controller.start().has_value());
  std::size_t rest_seen = 0;
  while (rest_seen < 30) {
    const auto sp = controller.next_setpoint();
    REQUIRE(sp.has_value());
    if (controller.resting()) ++rest_seen;
  }
  controller.hold();
  REQUIRE(controller.state() == ControllerState::Held);
  for (int i = 0; i < 50; ++i) {
    const auto sp = controller.next_setpoint();
    REQUIRE(sp.has_value());
    CHECK(sp.value().position[0] == 10.0);
    CHECK(sp.value().position[1] == 0.0);
  }
  REQUIRE(controller.resume().has_value());
  for (int i = 0; i < 70; ++i) {
    const auto sp = controller.next_setpoint();
    REQUIRE(sp.has_value());
    REQUIRE(controller.resting());
    CHECK(sp.value().position[1] == 0.0);
  }
  const auto moving = controller.next_setpoint();
  REQUIRE(moving.has_value());
  CHECK_FALSE(controller.resting());
  CHECK(controller.rested_ticks() == 100);
}
