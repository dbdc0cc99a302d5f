// SPDX-License-Identifier: MIT
// A run of short lines into a sharp corner, without path smoothing: each 1 mm line is entered at
// about the speed from which a stop fits into the next one, so the last line before the corner has
// to stop within its own length. A slow-down with zero acceleration at both ends is not monotone
// in its end speed (a stop from v0 is shorter than a slow-down to about v0 / 3, velocity_profile.hpp,
// highest_reachable_slower): the corner's tiny junction speed was "out of reach" where a stop was
// not, and the controller slowed down only "as far as it goes" on the wrong side, passing the 90°
// corner at 22.8 mm/s (25 000 mm/s² measured against 2 000). Expected values are the machine's
// limits and a hand computation, not the code under test.
#include <cmath>
#include <cstddef>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/motion/velocity_profile.hpp>

#include "motion_test_support.hpp"

using namespace curvestep;
using namespace curvestep::testing;

namespace {

/// `count` lines of `step` mm along +x, then a 90° corner and 10 mm along +y.
std::vector<PathSegment> lines_into_corner(int count, double step) {
  std::vector<PathSegment> job;
  for (int k = 0; k < count; ++k) job.push_back(line(mp(k * step, 0), mp((k + 1) * step, 0)));
  job.push_back(line(mp(count * step, 0), mp(count * step, 10)));
  return job;
}

MachineLimits fast_feed_machine() {
  MachineLimits m = test_machine();
  m.feed_mm_per_s = 200;
  return m;
}

/// The speed of the setpoint stream where it first leaves y = 0 (the corner), from positions.
template <class S>
double corner_speed(const std::vector<Setpoint<S>>& sp, double rate_hz) {
  for (std::size_t i = 1; i < sp.size(); ++i) {
    if (to_double(sp[i].position[1]) > 0) {
      const double dx = to_double(sp[i - 1].position[0]) - to_double(sp[i - 2].position[0]);
      return std::fabs(dx) * rate_hz;
    }
  }
  return -1;
}

}  // namespace

TEST_CASE("short lines into a corner: a stop is shorter than a partial slow-down, by hand", "[core][motion][junction]") {
  // Triangular S-curve (peak acceleration sqrt(u j) below a_max): a change of u takes
  // T = 2 sqrt(u / j) at the mean speed, D = (v0 + v1) sqrt(u / j). From v0 = 36 with j = 50 000:
  // a stop takes 36 · 0.0268328 = 0.96598 mm, a slow-down to 12 (u = 24) 48 · 0.0219089 = 1.05163 mm.
  const ProfileLimits limits{200, 2000, 50000, true};
  CHECK(speed_change_distance(0, 36, limits) == Approx(0.96598).epsilon(1e-4));
  CHECK(speed_change_distance(12, 36, limits) == Approx(1.05163).epsilon(1e-4));
  // Within 1 mm from 36 mm/s, 12 mm/s is out of reach but a stop is not: the largest speed <= 12
  // reached is the low side's, D(v, 36) = 1 on [0, 12].
  const double slower = highest_reachable_slower(36, 12, 1.0, limits);
  REQUIRE(slower >= 0);
  CHECK(slower < 12);
  CHECK(speed_change_distance(slower, 36, limits) <= 1.0);
  CHECK(speed_change_distance(slower + 1e-6, 36, limits) > 1.0);
  // Nothing fits within 0.9 mm from 36 mm/s: not even a stop.
  CHECK(highest_reachable_slower(36, 12, 0.9, limits) < 0);
}

TEST_CASE("short lines into a corner: windows of 1, 4 and 16 pass a 90 degree corner within the limits", "[core][motion][junction]") {
  const MachineLimits machine = fast_feed_machine();
  for (const double step : {0.5, 1.0, 2.0}) {
    const auto job = lines_into_corner(20, step);
    INFO("lines of " << step << " mm");
    // Jerk from third differences only on exact positions: Q16.16's rounding (2^-16 mm) alone makes
    // up to about 6e4 mm/s^3 of it at 1 kHz.
    const auto check = [&](const auto& sp, bool exact) {
      const MeasuredPeaks peaks = measure(sp, machine.rate_hz);
      CHECK(peaks.acceleration <= machine.a_max_mm_per_s2 * 1.01);
      if (exact) CHECK(peaks.jerk <= machine.j_max_mm_per_s3 * 1.01);
      // The corner's velocity jump within one tick stays within a_max · dt (here 2 mm/s at the
      // most, far below the 22.8 mm/s that broke the limit).
      CHECK(corner_speed(sp, machine.rate_hz) < machine.a_max_mm_per_s2 / machine.rate_hz);
    };
    check(run_job<double, 32, 1>(job, machine), true);
    check(run_job<double, 32, 4>(job, machine), true);
    check(run_job<double, 32, 16>(job, machine), true);
    check(run_job<Q16_16, 32, 16>(job, machine), false);
  }
}
