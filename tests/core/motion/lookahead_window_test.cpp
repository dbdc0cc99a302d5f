// SPDX-License-Identifier: MIT
// MotionController::set_lookahead: a controller whose run-time window is W produces exactly the
// setpoints of an independent instantiation whose template Lookahead is W (and a smaller queue),
// the reference a small board's firmware runs; the default window is the template maximum; values
// outside 1..Lookahead and changes while moving are refused.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <catch2/catch.hpp>

#include "lookahead_test_jobs.hpp"
#include "motion_test_support.hpp"

using namespace curvestep;
using namespace curvestep::testing;
using namespace curvestep::testing::lookahead;

namespace {

/// Runs a job, pushing whenever there is room (a cusp split waits for enough room), with an
/// optional run-time window (0: the default) and an optional feed hold at `hold_at` with resume
/// once held. Returns the setpoints.
template <class S, std::size_t Queue, std::size_t Lookahead>
std::vector<Setpoint<S>> run(const std::vector<PathSegment>& job, const MachineLimits& machine, std::size_t window,
                             std::size_t hold_at = 0) {
  MotionController<S, Queue, Lookahead> c;
  REQUIRE(c.configure(machine).has_value());
  if (window != 0) REQUIRE(c.set_lookahead(window).has_value());
  std::size_t next = 0;
  auto fill = [&] {
    while (next < job.size() && !c.queue_full()) {
      const auto pushed = c.try_push(job[next], static_cast<std::uint32_t>(next));
      if (!pushed && pushed.error() == Error::QueueFull) return;
      REQUIRE(pushed.has_value());
      ++next;
    }
    if (next == job.size()) c.end_of_job();
  };
  fill();
  REQUIRE(c.start().has_value());
  std::vector<Setpoint<S>> out;
  while (!c.finished() && out.size() < 2000000) {
    fill();
    if (hold_at != 0 && out.size() == hold_at) c.hold();
    if (c.state() == ControllerState::Held) REQUIRE(c.resume().has_value());
    const auto sp = c.next_setpoint();
    REQUIRE(sp.has_value());
    out.push_back(sp.value());
  }
  REQUIRE(c.finished());
  return out;
}

template <class S>
bool identical(const std::vector<Setpoint<S>>& a, const std::vector<Setpoint<S>>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].tick != b[i].tick || a[i].segment != b[i].segment || a[i].position != b[i].position) return false;
    // speed compared as bits (both are computed by the same arithmetic)
    if (!(a[i].speed_mm_per_s == b[i].speed_mm_per_s)) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("lookahead: set_lookahead(9) on a 32/16 controller gives exactly a 16/9 controller's setpoints",
          "[core][motion][lookahead]") {
  const MachineLimits m = fast_machine();
  const auto jobs = window_jobs();
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    INFO("job " << j);
    const auto windowed = run<Q16_16, 32, 16>(jobs[j], m, 9);
    const auto reference = run<Q16_16, 16, 9>(jobs[j], m, 0);
    CHECK(identical(windowed, reference));
    const auto windowed_d = run<double, 32, 16>(jobs[j], m, 9);
    const auto reference_d = run<double, 16, 9>(jobs[j], m, 0);
    CHECK(identical(windowed_d, reference_d));
  }
}

TEST_CASE("lookahead: the window matters on these jobs (9 and 16 differ, so the comparison is not vacuous)",
          "[core][motion][lookahead]") {
  const MachineLimits m = fast_machine();
  const auto jobs = window_jobs();
  const auto nine = run<Q16_16, 16, 9>(jobs[0], m, 0);
  const auto sixteen = run<Q16_16, 32, 16>(jobs[0], m, 0);
  CHECK_FALSE(identical(nine, sixteen));
  // The shorter window brakes for a stop nearer ahead: the job takes longer.
  CHECK(nine.size() > sixteen.size());
}

TEST_CASE("lookahead: window 1 and window 4 match independent instantiations", "[core][motion][lookahead]") {
  const MachineLimits m = fast_machine();
  const auto jobs = window_jobs();
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    INFO("job " << j);
    CHECK(identical(run<Q16_16, 32, 16>(jobs[j], m, 1), run<Q16_16, 8, 1>(jobs[j], m, 0)));
    CHECK(identical(run<Q16_16, 32, 16>(jobs[j], m, 4), run<Q16_16, 12, 4>(jobs[j], m, 0)));
  }
}

TEST_CASE("lookahead: a feed hold with window 9 brakes exactly as the 16/9 controller", "[core][motion][lookahead]") {
  const MachineLimits m = fast_machine();
  const auto jobs = window_jobs();
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    for (const std::size_t at : {std::size_t{37}, std::size_t{150}, std::size_t{401}}) {
      INFO("job " << j << " hold at " << at);
      CHECK(identical(run<Q16_16, 32, 16>(jobs[j], m, 9, at), run<Q16_16, 16, 9>(jobs[j], m, 0, at)));
    }
  }
}

TEST_CASE("lookahead: the default window is the template maximum and unchanged", "[core][motion][lookahead]") {
  STATIC_REQUIRE(MotionController<Q16_16>::lookahead == 16);
  STATIC_REQUIRE(MotionController<Q16_16, 16, 9>::lookahead == 9);
  CHECK(MotionController<Q16_16>{}.lookahead_window() == 16);
  CHECK(MotionController<double, 16, 9>{}.lookahead_window() == 9);
  const MachineLimits m = fast_machine();
  const auto jobs = window_jobs();
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    INFO("job " << j);
    // default (no call) vs an explicit set_lookahead(16)
    const auto by_default = run<Q16_16, 32, 16>(jobs[j], m, 0);
    CHECK(identical(by_default, run<Q16_16, 32, 16>(jobs[j], m, 16)));
    CHECK(identical(run<Q16_16, 32, 16>(jobs[j], m, 0, 150), run<Q16_16, 32, 16>(jobs[j], m, 16, 150)));
  }
}

TEST_CASE("lookahead: default, window-9 and feed-hold streams equal digests of the controller before set_lookahead",
          "[core][motion][lookahead]") {
  // FNV-1a digests (lookahead_test_jobs.hpp) of the Q16.16 streams produced by the controller of
  // commit b31c2b3 (before the run-time window existed), compiled from that commit's header: the
  // 32/16 controller, the same with a feed hold at setpoint 150, and the 16/9 controller; and the
  // stream lengths. If the planner's arithmetic changes on purpose, these must be regenerated.
  // Regenerated for jobs 1 and 3 (corners) when junction_speed took grbl's angle right and passed
  // corners at the velocity-jump speed (issue 23): job 1 4245 -> 3198 setpoints, job 3 7862 -> 7865.
  // Regenerated for jobs 2 and 3 (curves) when the jerk cap from curvature took the orthogonal parts
  // of the jerk instead of their sum (docs/motion.md, "Jerk from curvature"): job 2 1288 -> 1239,
  // job 3 7865 -> 6283 setpoints. Regenerated again for jobs 2 and 3 when a curve's profile took
  // the jerk its curvature leaves instead of half (curve_profile_jerk): job 2 1239 -> 1178
  // setpoints, job 3 keeps 6283. The window and hold equalities above are unchanged.
  struct Expected {
    std::uint64_t by_default, hold_150, nine;
    std::size_t setpoints;
  };
  const std::array<Expected, 4> expected{{
      {0x6c541b7221dae59dull, 0x986f2b605069261dull, 0xf2e8fb1c8f761f23ull, 721},
      {0xd872d927f1046462ull, 0xc96f7c8999510aa1ull, 0xd872d927f1046462ull, 3198},
      {0xdaf1bd078f4e3032ull, 0x6d02cf46143c1dbcull, 0x800516bb4a6b3bceull, 1178},
      {0xa25c2122766e1cc2ull, 0x037ccb2804fe08f7ull, 0xa25c2122766e1cc2ull, 6283},
  }};
  const MachineLimits m = fast_machine();
  const auto jobs = window_jobs();
  REQUIRE(jobs.size() == expected.size());
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    INFO("job " << j);
    const auto by_default = run<Q16_16, 32, 16>(jobs[j], m, 0);
    CHECK(by_default.size() == expected[j].setpoints);
    CHECK(digest(by_default) == expected[j].by_default);
    CHECK(digest(run<Q16_16, 32, 16>(jobs[j], m, 0, 150)) == expected[j].hold_150);
    CHECK(digest(run<Q16_16, 32, 16>(jobs[j], m, 9)) == expected[j].nine);
    CHECK(digest(run<Q16_16, 16, 9>(jobs[j], m, 0)) == expected[j].nine);
  }
}

TEST_CASE("lookahead: invalid windows and changes while moving are refused", "[core][motion][lookahead]") {
  MotionController<double, 32, 16> c;
  CHECK(c.set_lookahead(0).error() == Error::InvalidArgument);
  CHECK(c.set_lookahead(17).error() == Error::InvalidArgument);
  CHECK(c.set_lookahead(static_cast<std::size_t>(-1)).error() == Error::InvalidArgument);
  CHECK(c.lookahead_window() == 16);
  REQUIRE(c.set_lookahead(1).has_value());
  CHECK(c.lookahead_window() == 1);
  REQUIRE(c.set_lookahead(16).has_value());
  CHECK(c.lookahead_window() == 16);
  REQUIRE(c.set_lookahead(9).has_value());

  REQUIRE(c.configure(fast_machine()).has_value());
  REQUIRE(c.try_push(line(mp(0, 0), mp(10, 0)), 0).has_value());
  c.end_of_job();
  REQUIRE(c.start().has_value());
  (void)c.next_setpoint();
  CHECK(c.set_lookahead(4).error() == Error::InvalidState);
  c.hold();
  CHECK(c.set_lookahead(4).error() == Error::InvalidState);
  CHECK(c.lookahead_window() == 9);
  while (c.state() == ControllerState::Holding) (void)c.next_setpoint();
  CHECK(c.set_lookahead(4).error() == Error::InvalidState);  // Held: still on a job
  c.abort();
  REQUIRE(c.set_lookahead(4).has_value());
  c.reset();
  CHECK(c.lookahead_window() == 4);  // kept by reset, like the configuration

  MotionController<double, 16, 9> small;
  CHECK(small.set_lookahead(10).error() == Error::InvalidArgument);
  CHECK(small.set_lookahead(9).has_value());
}
