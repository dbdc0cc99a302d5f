// SPDX-License-Identifier: MIT
// Chunked interpolation (quintic Hermite chunks stepped by forward differencing, hermite_chunk.hpp):
// the stepped setpoints stay within the documented bound of the exact per-tick evaluation (the
// old path, set_max_chunk_ticks(1)), chunks are really used, and hold, resume, abort and a starved
// queue still behave.
#include <algorithm>
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "chunk_test_support.hpp"

using namespace curvestep;
using namespace curvestep::testing;

namespace {
/// The acceptance jobs of motion_controller_test.cpp and a long gentle cubic.
std::vector<std::vector<PathSegment>> jobs() {
  auto out = acceptance_jobs();
  out.push_back({cubic(mp(0, 0), mp(130, 60), mp(270, -60), mp(400, 0))});
  return out;
}

/// Checks a stepped run against the exact one: bound, shape, and measured limits.
void check_against_exact(const ChunkRun<double>& stepped, const ChunkRun<double>& exact, const MachineLimits& m) {
  const auto c = compare_streams(stepped, exact, m);
  CHECK(c.same_shape);
  CHECK(c.exact_ticks_identical);
  CHECK(c.stepped == stepped.stats.stepped_ticks);
  CHECK(c.worst_ratio <= 1.0);
  CHECK(c.worst_position <= 1e-3 * m.tolerance_mm);
  // The numerically differentiated limits move by at most 10⁻³ of the limit per axis (√3 for the vector).
  const auto ps = measure(stepped.setpoints, m.rate_hz);
  const auto pe = measure(exact.setpoints, m.rate_hz);
  const double slack = std::sqrt(3.0) * 1e-3;
  CHECK(ps.speed <= pe.speed + slack * m.v_max_mm_per_s);
  CHECK(ps.acceleration <= pe.acceleration + slack * m.a_max_mm_per_s2);
  if (m.jerk_limited) CHECK(ps.jerk <= pe.jerk + slack * m.j_max_mm_per_s3);
}
}  // namespace

TEST_CASE("motion: stepped setpoints stay within chunk_error_bound of the exact per-tick evaluation", "[core][motion][chunks]") {
  std::vector<MachineLimits> machines;
  machines.push_back(test_machine());
  MachineLimits fast = test_machine();
  fast.rate_hz = 10000;
  machines.push_back(fast);
  MachineLimits trapezoid = test_machine();
  trapezoid.jerk_limited = false;
  machines.push_back(trapezoid);
  MachineLimits loose = test_machine();
  loose.tolerance_mm = 0.1;
  loose.j_max_mm_per_s3 = 200000;
  machines.push_back(loose);
  int machine_number = 0;
  for (const auto& m : machines) {
    int job_number = 0;
    for (const auto& job : jobs()) {
      INFO("machine " << machine_number << " job " << job_number++);
      check_against_exact(run_chunked<double>(job, m, HermiteChunk::max_ticks), run_chunked<double>(job, m, 1), m);
    }
    ++machine_number;
  }
  // 100 kHz, where short chunks' checks fall below the evaluation's rounding and are not tried.
  MachineLimits fastest = test_machine();
  fastest.rate_hz = 100000;
  for (const std::size_t job_number : {std::size_t{4}, std::size_t{5}}) {
    INFO("100 kHz, job " << job_number);
    const auto stepped = run_chunked<double>(jobs()[job_number], fastest, HermiteChunk::max_ticks);
    check_against_exact(stepped, run_chunked<double>(jobs()[job_number], fastest, 1), fastest);
    CHECK(stepped.stats.exact_evaluations * 20 <= stepped.setpoints.size());
  }
}

TEST_CASE("motion: chunks replace most exact evaluations, the exact mode evaluates every tick", "[core][motion][chunks]") {
  const MachineLimits m = test_machine();
  // The gentle 400 mm cubic and the line-arc-line chain.
  for (const std::size_t job_number : {std::size_t{3}, std::size_t{7}}) {
    INFO("job " << job_number);
    const auto job = jobs()[job_number];
    const auto stepped = run_chunked<double>(job, m, HermiteChunk::max_ticks);
    const auto exact = run_chunked<double>(job, m, 1);
    const auto ticks = stepped.setpoints.size();
    // The exact mode: one evaluation per tick except the last (the end point, emitted as it is).
    CHECK(exact.stats.exact_evaluations == ticks - 1);
    CHECK(exact.stats.stepped_ticks == 0);
    CHECK(exact.stats.chunks == 0);
    // Chunked: at least 5 stepped ticks per exact evaluation, and chunks average >= 8 ticks.
    CHECK(stepped.stats.exact_evaluations * 5 <= stepped.stats.stepped_ticks);
    CHECK(stepped.stats.stepped_ticks + stepped.stats.exact_evaluations >= ticks - 1);
    CHECK(stepped.stats.chunks * 8 <= stepped.stats.stepped_ticks + stepped.stats.chunks);
  }
  // A straight line: the Hermite reproduces it, so no chunk is ever rejected.
  const auto straight = run_chunked<double>(jobs()[0], m, HermiteChunk::max_ticks);
  CHECK(straight.stats.rejected_chunks == 0);
  CHECK(straight.stats.exact_evaluations * 20 <= straight.setpoints.size());
}

TEST_CASE("motion: the longest chunk is configurable, 1 is the exact path", "[core][motion][chunks]") {
  MotionController<double> c;
  REQUIRE(c.configure(test_machine()).has_value());
  CHECK(c.max_chunk_ticks() == HermiteChunk::max_ticks);
  CHECK(c.set_max_chunk_ticks(0).error() == Error::InvalidArgument);
  CHECK(c.set_max_chunk_ticks(3).error() == Error::InvalidArgument);
  CHECK(c.set_max_chunk_ticks(2 * HermiteChunk::max_ticks).error() == Error::InvalidArgument);
  REQUIRE(c.set_max_chunk_ticks(HermiteChunk::max_ticks).has_value());
  REQUIRE(c.set_max_chunk_ticks(1).has_value());
  REQUIRE(c.try_push(PathSegment::make_line(mp(0, 0), mp(10, 0)).value(), 0).has_value());
  REQUIRE(c.start().has_value());
  CHECK(c.set_max_chunk_ticks(8).error() == Error::InvalidState);
  CHECK(c.max_chunk_ticks() == 1);
}

TEST_CASE("motion: stepped Q16.16 setpoints round the same as the exact ones within one raw unit", "[core][motion][chunks]") {
  const MachineLimits m = test_machine();
  for (const auto& job : jobs()) {
    const auto stepped = run_chunked<Q16_16>(job, m, HermiteChunk::max_ticks);
    const auto exact = run_chunked<Q16_16>(job, m, 1);
    REQUIRE(stepped.setpoints.size() == exact.setpoints.size());
    std::int64_t worst = 0;
    bool exact_identical = true;
    for (std::size_t i = 0; i < stepped.setpoints.size(); ++i) {
      for (std::size_t axis = 0; axis < 3; ++axis) {
        const std::int64_t d = static_cast<std::int64_t>(stepped.setpoints[i].position[axis].raw()) - exact.setpoints[i].position[axis].raw();
        worst = std::max(worst, d < 0 ? -d : d);
      }
      if (stepped.chunk_ticks[i] == 1) exact_identical = exact_identical && stepped.setpoints[i] == exact.setpoints[i];
    }
    CHECK(worst <= 1);  // the bound (<= 1e-5 mm) is below one raw unit (1.5e-5 mm): at most one rounding flips
    CHECK(exact_identical);
    CHECK(stepped.setpoints.back() == exact.setpoints.back());
  }
}

namespace {
/// Runs a cubic, holds at tick `hold_at`, waits until held, resumes and finishes; returns the setpoints.
struct HoldRun {
  std::vector<Setpoint<double>> setpoints;
  std::vector<std::uint32_t> chunk_ticks;
  std::size_t hold_index = 0;    ///< index of the first setpoint after hold()
  std::size_t resume_index = 0;  ///< index of the first setpoint after resume()
  bool stepping_when_held = false;
};

HoldRun hold_and_resume(std::uint32_t max_chunk, std::size_t hold_at) {
  const MachineLimits m = test_machine();
  MotionController<double> c;
  REQUIRE(c.configure(m).has_value());
  REQUIRE(c.set_max_chunk_ticks(max_chunk).has_value());
  REQUIRE(c.try_push(cubic(mp(0, 0), mp(100, 100), mp(200, -100), mp(300, 0)), 0).has_value());
  c.end_of_job();
  REQUIRE(c.start().has_value());
  HoldRun r;
  auto tick = [&] {
    const auto sp = c.next_setpoint();
    REQUIRE(sp.has_value());
    r.setpoints.push_back(sp.value());
    r.chunk_ticks.push_back(c.last_chunk_ticks());
  };
  for (std::size_t i = 0; i < hold_at; ++i) tick();
  r.stepping_when_held = r.chunk_ticks.back() > 1;
  c.hold();
  REQUIRE(c.state() == ControllerState::Holding);
  r.hold_index = r.setpoints.size();
  for (int i = 0; i < 3000 && c.state() == ControllerState::Holding; ++i) tick();
  REQUIRE(c.state() == ControllerState::Held);
  for (int i = 0; i < 20; ++i) tick();
  REQUIRE(c.resume().has_value());
  r.resume_index = r.setpoints.size();
  while (!c.finished()) tick();
  return r;
}
}  // namespace

TEST_CASE("motion: feed hold in the middle of a chunk brakes like the exact path, and resume steps again", "[core][motion][chunks]") {
  const MachineLimits m = test_machine();
  const auto stepped = hold_and_resume(HermiteChunk::max_ticks, 1501);
  const auto exact = hold_and_resume(1, 1501);
  CHECK(stepped.stepping_when_held);  // the hold arrives while a chunk is being stepped
  REQUIRE(stepped.setpoints.size() == exact.setpoints.size());
  // Braking and holding are evaluated exactly: bit-identical to the exact run.
  for (std::size_t i = stepped.hold_index; i < stepped.resume_index; ++i) {
    CHECK(stepped.chunk_ticks[i] == 1);
    CHECK(stepped.setpoints[i] == exact.setpoints[i]);
  }
  // After resume, chunks again, within their bound.
  std::size_t stepped_after = 0;
  double worst_ratio = 0;
  for (std::size_t i = 0; i < stepped.setpoints.size(); ++i) {
    if (stepped.chunk_ticks[i] == 1) {
      CHECK(stepped.setpoints[i].position == exact.setpoints[i].position);
      continue;
    }
    if (i >= stepped.resume_index) ++stepped_after;
    for (std::size_t axis = 0; axis < 3; ++axis) {
      const double e = std::fabs(stepped.setpoints[i].position[axis] - exact.setpoints[i].position[axis]);
      worst_ratio = std::fmax(worst_ratio, e / chunk_error_bound(stepped.chunk_ticks[i], m));
    }
  }
  CHECK(stepped_after > (stepped.setpoints.size() - stepped.resume_index) / 2);
  CHECK(worst_ratio <= 1.0);
  const auto peaks = measure(stepped.setpoints, m.rate_hz);
  CHECK(peaks.acceleration <= m.a_max_mm_per_s2 * 1.01);
  CHECK(peaks.jerk <= m.j_max_mm_per_s3 * 1.01);
  CHECK(stepped.setpoints.back().position[0] == 300.0);
  CHECK(stepped.setpoints.back().position[1] == 0.0);
}

TEST_CASE("motion: abort in the middle of a chunk stops at once, after reset a job runs as on a fresh controller", "[core][motion][chunks]") {
  const MachineLimits m = test_machine();
  const auto job = jobs()[7];
  MotionController<double> c;
  REQUIRE(c.configure(m).has_value());
  REQUIRE(c.try_push(job[0], 0).has_value());
  c.end_of_job();
  REQUIRE(c.start().has_value());
  for (int i = 0; i < 700; ++i) REQUIRE(c.next_setpoint().has_value());
  CHECK(c.last_chunk_ticks() > 1);
  c.abort();
  CHECK(c.state() == ControllerState::Aborted);
  CHECK(c.queued() == 0);
  CHECK(c.next_setpoint().error() == Error::InvalidState);
  c.reset();
  CHECK(c.interpolator_stats().exact_evaluations == 0);
  CHECK(c.interpolator_stats().stepped_ticks == 0);
  REQUIRE(c.try_push(job[0], 0).has_value());
  c.end_of_job();
  REQUIRE(c.start().has_value());
  std::vector<Setpoint<double>> again;
  while (!c.finished()) again.push_back(c.next_setpoint().value());
  const auto fresh = run_chunked<double>(job, m, HermiteChunk::max_ticks);
  REQUIRE(again.size() == fresh.setpoints.size());
  bool identical = true;
  for (std::size_t i = 0; i < again.size(); ++i) identical = identical && again[i] == fresh.setpoints[i];
  CHECK(identical);
}

TEST_CASE("motion: a starved queue stops on the path with chunks and resumes when fed", "[core][motion][chunks]") {
  const MachineLimits m = test_machine();
  auto starve = [&](std::uint32_t max_chunk) {
    MotionController<double> c;
    REQUIRE(c.configure(m).has_value());
    REQUIRE(c.set_max_chunk_ticks(max_chunk).has_value());
    REQUIRE(c.try_push(cubic(mp(0, 0), mp(10, 10), mp(20, -10), mp(30, 0)), 0).has_value());
    REQUIRE(c.start().has_value());
    std::vector<Setpoint<double>> sp;
    for (int i = 0; i < 5000 && c.state() == ControllerState::Running; ++i) sp.push_back(c.next_setpoint().value());
    CHECK(c.state() == ControllerState::Starved);
    CHECK(sp.back().position[0] == 30.0);
    for (int i = 0; i < 10; ++i) sp.push_back(c.next_setpoint().value());
    REQUIRE(c.try_push(arc(mp(30, 0), mp(30, 20), mp(30, 10), ArcDirection::CounterClockwise), 1).has_value());
    c.end_of_job();
    REQUIRE(c.resume().has_value());
    while (!c.finished()) sp.push_back(c.next_setpoint().value());
    CHECK(sp.back().position[1] == 20.0);
    return std::make_pair(sp, c.interpolator_stats());
  };
  const auto [stepped, stats] = starve(HermiteChunk::max_ticks);
  const auto [exact, exact_stats] = starve(1);
  CHECK(stats.stepped_ticks * 2 > stepped.size());
  REQUIRE(stepped.size() == exact.size());
  double worst = 0;
  for (std::size_t i = 0; i < stepped.size(); ++i) {
    for (std::size_t axis = 0; axis < 3; ++axis) worst = std::fmax(worst, std::fabs(stepped[i].position[axis] - exact[i].position[axis]));
  }
  CHECK(worst <= 1e-3 * m.tolerance_mm);
  CHECK(measure(stepped, m.rate_hz).jerk <= m.j_max_mm_per_s3 * 1.01);
}

TEST_CASE("motion: feed hold at any tick of a chunk (ends, middles, one-tick chunks) brakes exactly", "[core][motion][chunks]") {
  std::size_t held_while_stepping = 0;
  for (std::size_t hold_at = 1480; hold_at < 1544; hold_at += 3) {
    INFO("hold after " << hold_at << " ticks");
    const auto stepped = hold_and_resume(HermiteChunk::max_ticks, hold_at);
    const auto exact = hold_and_resume(1, hold_at);
    if (stepped.stepping_when_held) ++held_while_stepping;
    REQUIRE(stepped.setpoints.size() == exact.setpoints.size());
    bool braking_identical = true;
    for (std::size_t i = stepped.hold_index; i < stepped.resume_index; ++i) braking_identical = braking_identical && stepped.setpoints[i] == exact.setpoints[i];
    CHECK(braking_identical);
    CHECK(stepped.setpoints.back() == exact.setpoints.back());
  }
  CHECK(held_while_stepping >= 10);
}
