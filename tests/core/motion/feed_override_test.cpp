// SPDX-License-Identifier: MIT
// Feed and rapid override (MotionController::set_override): 100 % is no override bit for bit, any
// change at any tick keeps the speed, acceleration and jerk measured from the setpoints (finite
// differences, independent of the planner) within the limits, and the speeds and times follow the
// override as hand computations say.
#include <cmath>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "motion_test_support.hpp"

using namespace curvestep;
using namespace curvestep::testing;

namespace {

/// An override to set just before the setpoint of `tick`.
struct OverrideAt {
  std::uint64_t tick;
  FeedOverride value;
};

/// Runs a job, setting each override before the setpoint of its tick (as sim --override-at and the
/// firmware do: between two ticks). Returns the setpoints; `taken` gets the tick each took effect.
std::vector<Setpoint<double>> run_with_overrides(const std::vector<PathSegment>& job, const MachineLimits& machine,
                                                 const std::vector<OverrideAt>& overrides,
                                                 std::vector<std::uint64_t>* taken = nullptr) {
  MotionController<double, 32, 16> c;
  REQUIRE(c.configure(machine).has_value());
  std::size_t next = 0;
  auto fill = [&] {
    while (next < job.size() && !c.queue_full()) {
      REQUIRE(c.try_push(job[next], static_cast<std::uint32_t>(next)).has_value());
      ++next;
    }
    if (next == job.size()) c.end_of_job();
  };
  std::size_t next_override = 0;
  auto apply = [&](std::uint64_t tick) {
    while (next_override < overrides.size() && overrides[next_override].tick == tick) {
      REQUIRE(c.set_override(overrides[next_override].value).has_value());
      ++next_override;
    }
  };
  fill();
  apply(0);
  REQUIRE(c.start().has_value());
  std::vector<Setpoint<double>> out;
  std::uint64_t effective = c.override_tick();
  while (!c.finished() && out.size() < 2000000) {
    fill();
    apply(c.tick());
    const auto sp = c.next_setpoint();
    REQUIRE(sp.has_value());
    out.push_back(sp.value());
    if (taken != nullptr && c.override_tick() != effective) taken->push_back(c.override_tick());
    effective = c.override_tick();
  }
  REQUIRE(c.finished());
  return out;
}

std::vector<PathSegment> long_line() { return {line(mp(0, 0), mp(300, 0))}; }

/// 400 collinear lines of 0.25 mm: a micro-segment job (slowing down spans many segments).
std::vector<PathSegment> micro_segments() {
  std::vector<PathSegment> job;
  for (int k = 0; k < 400; ++k) job.push_back(line(mp(0.25 * k, 0), mp(0.25 * (k + 1), 0)));
  return job;
}

/// Lines, arcs and curves: the acceptance jobs, a job with a rapid, and the micro-segments.
std::vector<std::vector<PathSegment>> override_jobs() {
  auto jobs = acceptance_jobs();
  auto travel = line(mp(0, 20), mp(0, 0));
  travel.set_rapid(true);
  jobs.push_back({line(mp(0, 0), mp(0, 20)), travel, arc(mp(0, 0), mp(40, 0), mp(20, 0), ArcDirection::Clockwise)});
  jobs.push_back(micro_segments());
  return jobs;
}

}  // namespace

TEST_CASE("feed override: 100 percent set before the start and at many ticks gives the setpoints of no override bit for bit",
          "[core][motion][override]") {
  const MachineLimits m = test_machine();
  for (const auto& job : override_jobs()) {
    const auto plain = run_job<double>(job, m);
    std::vector<OverrideAt> hundreds;
    for (std::uint64_t tick = 0; tick < plain.size(); tick += 37) hundreds.push_back({tick, FeedOverride{}});
    const auto with = run_with_overrides(job, m, hundreds);
    REQUIRE(with.size() == plain.size());
    bool identical = true;
    for (std::size_t i = 0; i < plain.size(); ++i) identical = identical && with[i] == plain[i];
    CHECK(identical);
  }
}

TEST_CASE("feed override: changes at any tick keep speed, acceleration and jerk within the limits", "[core][motion][override]") {
  MachineLimits m = test_machine();
  m.rapid_mm_per_s = 2 * m.feed_mm_per_s;
  const std::uint16_t feeds[] = {200, 10, 150, 50, 120, 30, 200, 100};
  const std::uint16_t rapids[] = {25, 100, 50, 10};
  int job_number = 0;
  for (const auto& job : override_jobs()) {
    const auto plain = run_job<double>(job, m);
    for (const std::uint64_t spacing : {29u, 113u, 401u}) {
      INFO("job " << job_number << ", a change every " << spacing << " ticks");
      std::vector<OverrideAt> changes;
      std::size_t k = 0;
      for (std::uint64_t tick = spacing; tick < 3 * plain.size(); tick += spacing, ++k) {
        changes.push_back({tick, FeedOverride{feeds[k % 8], rapids[k % 4]}});
      }
      std::vector<std::uint64_t> taken;
      auto sp = run_with_overrides(job, m, changes, &taken);
      const auto peaks = measure(sp, m.rate_hz);
      CHECK(peaks.speed <= m.v_max_mm_per_s * 1.01);
      CHECK(peaks.speed <= 2 * m.feed_mm_per_s * 1.01);  // the feed at 200 %, and the rapid speed
      CHECK(peaks.acceleration <= m.a_max_mm_per_s2 * 1.01);
      CHECK(peaks.jerk <= m.j_max_mm_per_s3 * 1.01);
      if (sp.size() > spacing + 300) CHECK_FALSE(taken.empty());
      // The job still ends exactly on its end point.
      for (std::size_t axis = 0; axis < 3; ++axis) CHECK(sp.back().position[axis] == job.back().end()[axis]);
    }
    ++job_number;
  }
}

TEST_CASE("feed override: a line at 50 percent takes the hand-computed jerk-limited time", "[core][motion][override]") {
  MachineLimits m = test_machine();
  m.feed_mm_per_s = 100;
  const auto sp = run_with_overrides(long_line(), m, {{0, FeedOverride{50, 100}}});
  // Rest to rest cruising at v = 50 mm/s. v < a²/j = 80 mm/s, so each ramp takes T_r = 2 sqrt(v/j)
  // and covers v T_r / 2: T = (L - v T_r)/v + 2 T_r = L/v + 2 sqrt(v/j).
  const double v = 50;
  const double a = m.a_max_mm_per_s2;
  const double j = m.j_max_mm_per_s3;
  REQUIRE(v < a * a / j);
  const double analytic = 300 / v + 2 * std::sqrt(v / j);
  const double duration = static_cast<double>(sp.back().tick) / m.rate_hz;
  CHECK(std::fabs(duration - analytic) <= 2.0 / m.rate_hz);
  const auto peaks = measure(sp, m.rate_hz);
  CHECK(peaks.speed == Approx(v).epsilon(0.001));
}

TEST_CASE("feed override: lowered and raised while cruising on a long line, the speed follows within the limits",
          "[core][motion][override]") {
  const MachineLimits m = test_machine();  // feed 50, v_max 200
  std::vector<std::uint64_t> taken;
  const auto sp = run_with_overrides(long_line(), m, {{1000, FeedOverride{50, 100}}, {3000, FeedOverride{200, 100}}}, &taken);
  REQUIRE(taken.size() == 2);
  // In the cruise an override takes effect at the next chunk end (at most 256 ticks later).
  CHECK(taken[0] >= 1000);
  CHECK(taken[0] <= 1000 + 256);
  CHECK(taken[1] >= 3000);
  CHECK(taken[1] <= 3000 + 256);
  auto speed_at = [&](std::size_t i) { return std::fabs(sp[i].position[0] - sp[i - 1].position[0]) * m.rate_hz; };
  CHECK(speed_at(900) == Approx(50).epsilon(1e-6));
  CHECK(speed_at(2900) == Approx(25).epsilon(1e-6));
  CHECK(speed_at(taken[1] + 200) == Approx(100).epsilon(1e-6));
  const auto peaks = measure(sp, m.rate_hz);
  CHECK(peaks.acceleration <= m.a_max_mm_per_s2 * 1.01);
  CHECK(peaks.jerk <= m.j_max_mm_per_s3 * 1.01);
}

TEST_CASE("feed override: the rapid override scales rapids only", "[core][motion][override]") {
  MachineLimits m = test_machine();
  m.rapid_mm_per_s = 100;
  auto travel = line(mp(0, 0), mp(200, 0));
  travel.set_rapid(true);
  const auto rapid = run_with_overrides({travel}, m, {{0, FeedOverride{200, 25}}});
  CHECK(measure(rapid, m.rate_hz).speed == Approx(25).epsilon(0.001));
  const auto feed = run_with_overrides(long_line(), m, {{0, FeedOverride{200, 25}}});
  CHECK(measure(feed, m.rate_hz).speed == Approx(100).epsilon(0.001));
}

TEST_CASE("feed override: values outside 10..200 and 10..100 percent are refused", "[core][motion][override]") {
  MotionController<double, 32, 16> c;
  REQUIRE(c.configure(test_machine()).has_value());
  CHECK(c.set_override(FeedOverride{9, 100}).error() == Error::InvalidArgument);
  CHECK(c.set_override(FeedOverride{201, 100}).error() == Error::InvalidArgument);
  CHECK(c.set_override(FeedOverride{100, 101}).error() == Error::InvalidArgument);
  CHECK(c.set_override(FeedOverride{100, 9}).error() == Error::InvalidArgument);
  CHECK(c.set_override(FeedOverride{10, 10}).has_value());
  CHECK(c.override_in_effect() == FeedOverride{10, 10});
}

TEST_CASE("feed override: lowered on micro-segments it takes effect at the next segment and slows down over many",
          "[core][motion][override]") {
  const MachineLimits m = test_machine();  // feed 50
  std::vector<PathSegment> job;
  for (int k = 0; k < 1200; ++k) job.push_back(line(mp(0.25 * k, 0), mp(0.25 * (k + 1), 0)));
  const auto plain = run_job<double>(job, m);
  std::vector<std::uint64_t> taken;
  const auto sp = run_with_overrides(job, m, {{1000, FeedOverride{10, 100}}}, &taken);
  REQUIRE(taken.size() == 1);
  // It takes effect where the next segment begins: within 0.25 mm at the speed there.
  const double plain_speed = std::fabs(plain[1000].position[0] - plain[999].position[0]) * m.rate_hz;
  REQUIRE(plain_speed > 5);
  CHECK(taken[0] >= 1000);
  CHECK(static_cast<double>(taken[0] - 1000) <= 0.25 / plain_speed * m.rate_hz + 2);
  // Once slowed down, no faster than 10 % of the feed (5 mm/s).
  double late_peak = 0;
  for (std::size_t i = taken[0] + 3000; i < sp.size(); ++i) late_peak = std::fmax(late_peak, std::fabs(sp[i].position[0] - sp[i - 1].position[0]) * m.rate_hz);
  CHECK(late_peak <= 5 * (1 + 1e-9));
  CHECK(late_peak >= 4.9);
  const auto peaks = measure(sp, m.rate_hz);
  CHECK(peaks.acceleration <= m.a_max_mm_per_s2 * 1.01);
  CHECK(peaks.jerk <= m.j_max_mm_per_s3 * 1.01);
}

TEST_CASE("feed override: with the trapezoid profile, changes keep the speed and acceleration within the limits",
          "[core][motion][override]") {
  MachineLimits m = test_machine();
  m.jerk_limited = false;
  for (const auto& job : override_jobs()) {
    const auto plain = run_job<double>(job, m);
    std::vector<OverrideAt> changes;
    const std::uint16_t feeds[] = {200, 10, 150, 50};
    std::size_t k = 0;
    for (std::uint64_t tick = 53; tick < 3 * plain.size(); tick += 97, ++k) changes.push_back({tick, FeedOverride{feeds[k % 4], 100}});
    const auto sp = run_with_overrides(job, m, changes);
    const auto peaks = measure(sp, m.rate_hz);
    CHECK(peaks.speed <= m.v_max_mm_per_s * 1.01);
    CHECK(peaks.acceleration <= m.a_max_mm_per_s2 * 1.01);
  }
}
