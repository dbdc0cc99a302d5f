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

/// Runs every segment through a controller (pushing as the queue drains) and returns the setpoints.
template <class S, std::size_t Queue = 32, std::size_t Lookahead = 16>
std::vector<Setpoint<S>> run_job(const std::vector<PathSegment>& job, const MachineLimits& machine, std::size_t max_ticks = 2000000) {
  MotionController<S, Queue, Lookahead> controller;
  REQUIRE(controller.configure(machine).has_value());
  std::size_t next = 0;
  auto fill = [&] {
    while (next < job.size() && !controller.queue_full()) {
      const auto pushed = controller.try_push(job[next], static_cast<std::uint32_t>(next));
      REQUIRE(pushed.has_value());
      ++next;
    }
    if (next == job.size()) controller.end_of_job();
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
