// SPDX-License-Identifier: MIT
// Jobs for the look-ahead window tests: many short segments, so that 9 and 16 segments of
// look-ahead plan differently, and a digest of a setpoint stream.
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "motion_test_support.hpp"

namespace curvestep::testing::lookahead {

/// A machine fast enough that the braking distance (v²/2a = 10 mm at 200 mm/s) spans many short
/// segments: the window length then decides the speeds.
inline MachineLimits fast_machine() {
  MachineLimits m = test_machine();
  m.feed_mm_per_s = 200;
  return m;
}

/// Jobs of many short segments (so 9 and 16 segments of look-ahead plan differently), with every
/// segment kind, gentle and sharp junctions, and cusps (split into several queue slots).
inline std::vector<std::vector<PathSegment>> window_jobs() {
  std::vector<std::vector<PathSegment>> jobs;
  {  // 60 collinear 0.5 mm lines: the window limits the cruise speed
    std::vector<PathSegment> job;
    for (int i = 0; i < 60; ++i) job.push_back(line(mp(0.5 * i, 0), mp(0.5 * (i + 1), 0)));
    jobs.push_back(job);
  }
  {  // 60 chords of 0.5 mm on a circle of radius 500 mm (corners of 0.001 rad), then a sharp corner
    std::vector<PathSegment> job;
    const double radius = 500;
    const double step = 0.5 / radius;
    MachinePoint p = mp(0, 0);
    for (int i = 1; i <= 60; ++i) {
      const MachinePoint q = mp(radius * std::sin(i * step), radius - radius * std::cos(i * step));
      job.push_back(line(p, q));
      p = q;
    }
    job.push_back(line(p, mp(p[0], 10)));
    jobs.push_back(job);
  }
  {  // tangent-continuous chain of short, flat Béziers, then an arc
    std::vector<PathSegment> job;
    double x = 0;
    for (int i = 0; i < 16; ++i) {
      job.push_back(cubic(mp(x, 0), mp(x + 0.4, 0), mp(x + 0.6, 0.002), mp(x + 1.0, 0.002)));
      job.push_back(cubic(mp(x + 1.0, 0.002), mp(x + 1.4, 0.002), mp(x + 1.6, 0), mp(x + 2.0, 0)));
      x += 2.0;
    }
    job.push_back(line(mp(x, 0), mp(x + 2, 0)));
    job.push_back(arc(mp(x + 2, 0), mp(x + 2, 4), mp(x + 2, 2), ArcDirection::CounterClockwise));
    job.push_back(line(mp(x + 2, 4), mp(0, 4)));
    jobs.push_back(job);
  }
  {  // cusp loops between short lines (each loop takes several slots)
    std::vector<PathSegment> job;
    double x = 0;
    for (int i = 0; i < 6; ++i) {
      job.push_back(line(mp(x, 0), mp(x + 1, 0)));
      job.push_back(cubic(mp(x + 1, 0), mp(x + 4, 3), mp(x + 1, 3), mp(x + 4, 0)));
      x += 4;
    }
    jobs.push_back(job);
  }
  return jobs;
}

/// FNV-1a 64 over each setpoint's tick, segment, raw Q16.16 positions and speed bits.
inline std::uint64_t digest(const std::vector<Setpoint<Q16_16>>& setpoints) {
  std::uint64_t h = 14695981039346656037ull;
  auto mix = [&](std::uint64_t v) {
    for (int i = 0; i < 8; ++i) {
      h ^= (v >> (8 * i)) & 0xffu;
      h *= 1099511628211ull;
    }
  };
  for (const auto& sp : setpoints) {
    mix(sp.tick);
    mix(sp.segment);
    for (std::size_t axis = 0; axis < 3; ++axis) mix(static_cast<std::uint32_t>(sp.position[axis].raw()));
    mix(std::bit_cast<std::uint64_t>(sp.speed_mm_per_s));
  }
  return h;
}

}  // namespace curvestep::testing::lookahead
