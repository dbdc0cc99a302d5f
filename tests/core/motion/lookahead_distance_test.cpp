// SPDX-License-Identifier: MIT
// MotionController::set_lookahead_distance: off by default (the count window alone, bit for bit);
// on a path of short collinear lines, a window of 16 segments cannot see the braking distance and
// crawls, the distance window is much faster; limits hold; bad values and changes while moving are
// refused.
#include <cmath>
#include <cstdint>
#include <vector>

#include <catch2/catch.hpp>

#include "motion_test_support.hpp"

using namespace curvestep;
using namespace curvestep::testing;

namespace {

/// A straight 60 mm path of 0.1 mm lines: collinear joints, so only the window limits the speed.
std::vector<PathSegment> short_lines() {
  std::vector<PathSegment> job;
  for (int i = 0; i < 600; ++i) job.push_back(line(mp(0.1 * i, 0), mp(0.1 * (i + 1), 0)));
  return job;
}

template <std::size_t Queue, std::size_t Lookahead>
std::vector<Setpoint<double>> run(const std::vector<PathSegment>& job, const MachineLimits& machine, double distance_mm) {
  MotionController<double, Queue, Lookahead> c;
  REQUIRE(c.configure(machine).has_value());
  REQUIRE(c.set_lookahead(16).has_value());
  REQUIRE(c.set_lookahead_distance(distance_mm).has_value());
  std::size_t next = 0;
  const auto fill = [&] {
    while (next < job.size() && !c.queue_full()) {
      REQUIRE(c.try_push(job[next], static_cast<std::uint32_t>(next)).has_value());
      ++next;
    }
    if (next == job.size()) c.end_of_job();
  };
  fill();
  REQUIRE(c.start().has_value());
  std::vector<Setpoint<double>> out;
  while (!c.finished() && out.size() < 1000000) {
    fill();
    const auto sp = c.next_setpoint();
    REQUIRE(sp.has_value());
    out.push_back(sp.value());
  }
  return out;
}

}  // namespace

TEST_CASE("lookahead distance: off by default, and 0 gives the count window's setpoints bit for bit", "[core][motion][lookahead]") {
  CHECK(MotionController<double, 300, 256>{}.lookahead_distance_mm() == 0);
  const MachineLimits m = test_machine();
  const auto job = short_lines();
  const auto wide = run<300, 256>(job, m, 0);
  const auto narrow = run<24, 16>(job, m, 0);
  REQUIRE(wide.size() == narrow.size());
  for (std::size_t i = 0; i < wide.size(); ++i) REQUIRE(wide[i].position == narrow[i].position);
}

TEST_CASE("lookahead distance: on short lines the distance window is faster than 16 segments, within the limits",
          "[core][motion][lookahead]") {
  MachineLimits m = test_machine();  // feed 50 mm/s, a 2000, j 50000: braking from 50 mm/s takes about 1.7 mm
  const auto job = short_lines();
  const auto by_count = run<300, 256>(job, m, 0);
  const auto by_distance = run<300, 256>(job, m, 10);
  const auto peak = [](const std::vector<Setpoint<double>>& sp) {
    double v = 0;
    for (const auto& s : sp) v = std::fmax(v, s.speed_mm_per_s);
    return v;
  };
  INFO("count window: " << by_count.size() << " setpoints, peak " << peak(by_count) << " mm/s; distance window: "
                        << by_distance.size() << " setpoints, peak " << peak(by_distance) << " mm/s");
  // 16 lines of 0.1 mm = 1.6 mm: that window must end at rest, so the speed stays low; 10 mm do not.
  // (Every segment's profile starts and ends at zero acceleration, so even the distance window
  // stays below the feed on 0.1 mm lines: path smoothing merges such runs into long segments.)
  CHECK(peak(by_distance) > 1.5 * peak(by_count));
  CHECK(static_cast<double>(by_distance.size()) < 0.75 * static_cast<double>(by_count.size()));
  const auto peaks = measure(by_distance, m.rate_hz);
  CHECK(peaks.acceleration <= m.a_max_mm_per_s2 * 1.01);
  CHECK(peaks.jerk <= m.j_max_mm_per_s3 * 1.01);
}

TEST_CASE("lookahead distance: negative or non-finite distances and changes while moving are refused", "[core][motion][lookahead]") {
  MotionController<double, 32, 16> c;
  CHECK(c.set_lookahead_distance(-1).error() == Error::InvalidArgument);
  CHECK(c.set_lookahead_distance(std::nan("")).error() == Error::InvalidArgument);
  CHECK(c.set_lookahead_distance(INFINITY).error() == Error::InvalidArgument);
  REQUIRE(c.configure(test_machine()).has_value());
  REQUIRE(c.try_push(line(mp(0, 0), mp(10, 0)), 0).has_value());
  c.end_of_job();
  REQUIRE(c.start().has_value());
  CHECK(c.set_lookahead_distance(5).error() == Error::InvalidState);
}
