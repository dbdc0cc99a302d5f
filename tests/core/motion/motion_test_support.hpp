// SPDX-License-Identifier: MIT
// Helpers for motion tests: run a job through a controller and measure the setpoint stream.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/motion/motion_controller.hpp>

namespace curvestep::testing {

inline MachinePoint mp(double x, double y, double z = 0) { return MachinePoint{{x, y, z}}; }

/// Segment builders for tests (valid input: value() on the Result).
inline PathSegment line(MachinePoint a, MachinePoint b) { return PathSegment::make_line(a, b).value(); }
inline PathSegment cubic(MachinePoint a, MachinePoint b, MachinePoint c, MachinePoint d) {
  const std::array<MachinePoint, 4> pts{a, b, c, d};
  return PathSegment::make_bezier(pts).value();
}
inline PathSegment arc(MachinePoint a, MachinePoint b, MachinePoint c, ArcDirection dir) {
  return PathSegment::make_arc(a, b, c, dir, 0, 1e-6).value();
}

/// Jobs covering every segment kind: tight curves, a cusp, tangent-continuous chains, sharp corners, long lines.
inline std::vector<std::vector<PathSegment>> acceptance_jobs() {
  std::vector<std::vector<PathSegment>> jobs;
  jobs.push_back({line(mp(0, 0), mp(300, 0))});
  jobs.push_back({line(mp(0, 0), mp(50, 0)), line(mp(50, 0), mp(50, 50)), line(mp(50, 50), mp(0, 0))});  // corners
  jobs.push_back({cubic(mp(0, 0), mp(20, 40), mp(40, -40), mp(60, 0)), cubic(mp(60, 0), mp(80, 40), mp(100, -40), mp(120, 0))});
  jobs.push_back({line(mp(0, 0), mp(20, 0)), arc(mp(20, 0), mp(20, 20), mp(20, 10), ArcDirection::CounterClockwise),
                  line(mp(20, 20), mp(0, 20))});  // tangent-continuous line-arc-line
  jobs.push_back({cubic(mp(0, 0), mp(30, 30), mp(0, 30), mp(30, 0))});  // cusp-like loop
  {
    const std::array<MachinePoint, 3> q{mp(10, 0), mp(10, 10), mp(0, 10)};
    const std::array<double, 3> w{1, std::sqrt(0.5), 1};
    jobs.push_back({PathSegment::make_rational_bezier(q, w).value()});
  }
  jobs.push_back({PathSegment::make_arc(mp(5, 0, 0), mp(5, 0, 4), mp(0, 0), ArcDirection::Clockwise, 1, 1e-9).value()});  // helix
  return jobs;
}

/// A machine for tests: 1 kHz, S-curve.
inline MachineLimits test_machine() {
  MachineLimits m;
  m.v_max_mm_per_s = 200;
  m.a_max_mm_per_s2 = 2000;
  m.j_max_mm_per_s3 = 50000;
  m.feed_mm_per_s = 50;
  m.tolerance_mm = 0.01;
  m.rate_hz = 1000;
  m.junction_deviation_mm = 0.05;
  return m;
}

/// Runs every segment through a controller (pushing as the queue drains, segment k with
/// entries[k] when given) and returns the setpoints.
template <class S, std::size_t Queue = 32, std::size_t Lookahead = 16>
std::vector<Setpoint<S>> run_job(const std::vector<PathSegment>& job, const MachineLimits& machine, std::size_t max_ticks = 2000000,
                                 const std::vector<JointStop>& entries = {}) {
  MotionController<S, Queue, Lookahead> controller;
  REQUIRE(controller.configure(machine).has_value());
  std::size_t next = 0;
  auto fill = [&] {
    while (next < job.size() && !controller.queue_full()) {
      const auto pushed = controller.try_push(job[next], static_cast<std::uint32_t>(next), next < entries.size() ? entries[next] : JointStop{});
      REQUIRE(pushed.has_value());
      ++next;
    }
    // entries[job.size()], if given, is the rest after the last move (its rest_ticks).
    if (next == job.size()) controller.end_of_job(entries.size() > job.size() ? entries[job.size()].rest_ticks : 0);
  };
  fill();
  REQUIRE(controller.start().has_value());
  std::vector<Setpoint<S>> out;
  while (!controller.finished() && out.size() < max_ticks) {
    fill();
    const auto sp = controller.next_setpoint();
    REQUIRE(sp.has_value());
    out.push_back(sp.value());
  }
  REQUIRE(controller.finished());
  return out;
}

/// Peak speed, acceleration and jerk (vector magnitudes) from finite differences of positions.
struct MeasuredPeaks {
  double speed = 0;
  double acceleration = 0;
  double jerk = 0;
};

template <class S>
MeasuredPeaks measure(const std::vector<Setpoint<S>>& sp, double rate_hz) {
  MeasuredPeaks peaks;
  const double dt = 1.0 / rate_hz;
  auto p = [&](std::size_t i, std::size_t axis) { return to_double(sp[i].position[axis]); };
  for (std::size_t i = 3; i < sp.size(); ++i) {
    double v2 = 0, a2 = 0, j2 = 0;
    for (std::size_t axis = 0; axis < 3; ++axis) {
      const double d1 = p(i, axis) - p(i - 1, axis);
      const double d2 = p(i, axis) - 2 * p(i - 1, axis) + p(i - 2, axis);
      const double d3 = p(i, axis) - 3 * p(i - 1, axis) + 3 * p(i - 2, axis) - p(i - 3, axis);
      v2 += d1 * d1;
      a2 += d2 * d2;
      j2 += d3 * d3;
    }
    peaks.speed = std::fmax(peaks.speed, std::sqrt(v2) / dt);
    peaks.acceleration = std::fmax(peaks.acceleration, std::sqrt(a2) / (dt * dt));
    peaks.jerk = std::fmax(peaks.jerk, std::sqrt(j2) / (dt * dt * dt));
  }
  return peaks;
}

}  // namespace curvestep::testing
