// SPDX-License-Identifier: MIT
// Polyline jobs for the smoothing tests, built from vertices on the Q16.16 grid (as importers do).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/host/job.hpp>

namespace curvestep::testing {

constexpr double pi = 3.14159265358979323846;

/// p with every coordinate on the Q16.16 grid.
inline MachinePoint grid(MachinePoint p) {
  for (std::size_t axis = 0; axis < motion_axes; ++axis) p[axis] = Q16_16::from_double(p[axis]).value().to_double();
  return p;
}

/// A job of feed lines through `vertices` (consecutive duplicates dropped), each its own source.
inline host::Job polyline_job(const std::vector<MachinePoint>& vertices, double feed_mm_per_s = 50, std::string name = "polyline") {
  host::Job job;
  job.name = std::move(name);
  MachinePoint previous = grid(vertices.front());
  for (std::size_t i = 1; i < vertices.size(); ++i) {
    const MachinePoint next = grid(vertices[i]);
    if (next == previous) continue;
    auto line = PathSegment::make_line(previous, next).value();
    line.set_feed_mm_per_s(feed_mm_per_s);
    job.source_index.push_back(job.sources.size());
    host::SourceSegment source;
    source.points = {previous, next};
    source.degree = 1;
    source.first_piece = job.segments.size();
    source.breaks = {0.0, 1.0};
    job.sources.push_back(source);
    job.segments.push_back(line);
    previous = next;
  }
  return job;
}

/// The vertices of n chords of a circle of radius r about the origin, starting at (r, 0).
inline std::vector<MachinePoint> circle_chords(std::size_t n, double r = 20) {
  std::vector<MachinePoint> v;
  for (std::size_t i = 0; i <= n; ++i) {
    const double a = 2 * pi * static_cast<double>(i) / static_cast<double>(n);
    v.push_back(MachinePoint{{r * std::cos(a), r * std::sin(a), 0}});
  }
  return v;
}

/// An Archimedean spiral of `points` vertices, 5 turns, radius 2 to 40 mm.
inline std::vector<MachinePoint> spiral(std::size_t points) {
  std::vector<MachinePoint> v;
  for (std::size_t i = 0; i < points; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(points - 1);
    const double a = t * 5 * 2 * pi;
    const double r = 2 + 38 * t;
    v.push_back(MachinePoint{{r * std::cos(a), r * std::sin(a), 0}});
  }
  return v;
}

/// A 3-axis finishing raster: rows in x at `step` mm, z = 2 sin(x/8) cos(y/10), step-over 0.5 mm in y.
inline std::vector<MachinePoint> raster(std::size_t rows, double step = 0.25, double width = 50) {
  std::vector<MachinePoint> v;
  const auto count = static_cast<std::size_t>(width / step);
  for (std::size_t row = 0; row < rows; ++row) {
    const double y = 0.5 * static_cast<double>(row);
    for (std::size_t i = 0; i <= count; ++i) {
      const double x = step * static_cast<double>(row % 2 == 0 ? i : count - i);
      v.push_back(MachinePoint{{x, y, 2 * std::sin(x / 8) * std::cos(y / 10)}});
    }
  }
  return v;
}

/// A walk of `steps` lines of `length` mm turning by the given angles (degrees) in turn.
inline std::vector<MachinePoint> turning_walk(const std::vector<double>& turns_deg, std::size_t steps, double length) {
  std::vector<MachinePoint> v{MachinePoint{}};
  double heading = 0;
  for (std::size_t i = 0; i < steps; ++i) {
    v.push_back(v.back() + MachinePoint{{length * std::cos(heading), length * std::sin(heading), 0}});
    heading += turns_deg[i % turns_deg.size()] * pi / 180;
  }
  return v;
}

}  // namespace curvestep::testing
