// SPDX-License-Identifier: MIT
// Helpers for the chunked-interpolation tests: run a job with a given longest chunk, and compare a
// stepped setpoint stream with the exact per-tick one (set_max_chunk_ticks(1), the old path).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "motion_test_support.hpp"

namespace curvestep::testing {

template <class S>
struct ChunkRun {
  std::vector<Setpoint<S>> setpoints;
  std::vector<std::uint32_t> chunk_ticks;  ///< per setpoint: N of its chunk, 1 if evaluated exactly
  typename MotionController<S>::InterpolatorStats stats;
};

/// Runs `job` (pushing as the queue drains) with chunks of at most `max_chunk` ticks; calls
/// on_setpoint(controller, setpoint) after each setpoint.
template <class S, class OnSetpoint = void (*)(const MotionController<S>&, const Setpoint<S>&)>
ChunkRun<S> run_chunked(const std::vector<PathSegment>& job, const MachineLimits& machine, std::uint32_t max_chunk,
                        OnSetpoint on_setpoint = [](const MotionController<S>&, const Setpoint<S>&) {},
                        const std::vector<JointStop>& entries = {}) {
  MotionController<S> controller;
  REQUIRE(controller.configure(machine).has_value());
  REQUIRE(controller.set_max_chunk_ticks(max_chunk).has_value());
  std::size_t next = 0;
  auto fill = [&] {
    while (next < job.size() && !controller.queue_full()) {
      const JointStop entry = next < entries.size() ? entries[next] : JointStop{};
      REQUIRE(controller.try_push(job[next], static_cast<std::uint32_t>(next), entry).has_value());
      ++next;
    }
    if (next == job.size()) controller.end_of_job();
  };
  fill();
  REQUIRE(controller.start().has_value());
  ChunkRun<S> r;
  while (!controller.finished() && r.setpoints.size() < 3000000) {
    fill();
    const auto sp = controller.next_setpoint();
    REQUIRE(sp.has_value());
    r.setpoints.push_back(sp.value());
    r.chunk_ticks.push_back(controller.last_chunk_ticks());
    on_setpoint(controller, sp.value());
  }
  REQUIRE(controller.finished());
  r.stats = controller.interpolator_stats();
  return r;
}

/// How a stepped stream differs from the exact one.
struct StreamComparison {
  double worst_ratio = 0;           ///< largest |stepped - exact| / chunk_error_bound(N) over stepped ticks and axes
  double worst_position = 0;        ///< largest |stepped - exact| per axis (mm)
  std::size_t stepped = 0;          ///< setpoints produced by stepping
  bool exact_ticks_identical = true;  ///< every setpoint not stepped is the exact stream's bit for bit
  bool same_shape = true;           ///< same length, ticks, segments and speeds
};

/// Compares a stepped run with the exact run (set_max_chunk_ticks(1)) of the same job.
template <class S>
StreamComparison compare_streams(const ChunkRun<S>& stepped, const ChunkRun<S>& exact, const MachineLimits& machine) {
  StreamComparison c;
  if (stepped.setpoints.size() != exact.setpoints.size()) {
    c.same_shape = false;
    return c;
  }
  for (std::size_t i = 0; i < stepped.setpoints.size(); ++i) {
    const auto& a = stepped.setpoints[i];
    const auto& b = exact.setpoints[i];
    c.same_shape = c.same_shape && a.tick == b.tick && a.segment == b.segment && a.speed_mm_per_s == b.speed_mm_per_s;
    const std::uint32_t n = stepped.chunk_ticks[i];
    if (n == 1) {
      c.exact_ticks_identical = c.exact_ticks_identical && a.position == b.position;
      continue;
    }
    ++c.stepped;
    const double bound = chunk_error_bound(n, machine);
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      const double e = std::fabs(to_double(a.position[axis]) - to_double(b.position[axis]));
      c.worst_position = std::fmax(c.worst_position, e);
      c.worst_ratio = std::fmax(c.worst_ratio, e / bound);
    }
  }
  return c;
}

}  // namespace curvestep::testing
