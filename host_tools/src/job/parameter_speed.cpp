// SPDX-License-Identifier: MIT
// Does the controller's arc-length table follow the curve's parameter speed?
//
// Why: the controller (sim and device, the same code) moves along a segment through a table of
// 64 equal parameter pieces, s(u) cubic on each (PathLengthTable). The machine then moves at
// v |p'(u)| / S'(u), which is the planned v while the cubic's slope S' matches the true speed
// |p'|. A rational curve with a strong weight ratio (1, 100, 1) has nearly all its speed in a few
// pieces near its ends, where one cubic cannot follow it: the speed comes out hundreds of times
// too high and the machine jumps. The check runs the controller's own table (same bits as the
// device) and compares its slope with |p'(u)| at 16 points per piece, and the distance between the
// points it gives for 16 equal arc-length steps per piece with the step; a curve the table cannot
// follow within 5 % is refused at load time, where the message can name the file and line.
#include <curvestep/host/parameter_speed.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <functional>
#include <string>

#include <curvestep/core/motion/path_length_table.hpp>
#include <curvestep/host/load_error.hpp>

namespace curvestep::host {

double table_speed_factor(const PathSegment& segment) {
  constexpr std::size_t intervals = 64;  // the MotionController's TableIntervals
  constexpr std::size_t samples = 16 * intervals;
  const auto table = PathLengthTable<intervals>::build(segment);
  if (!table) return 1;  // a degenerate curve is refused elsewhere
  double worst = 1;
  const double length = table.value().length();
  for (std::size_t i = 0; i < samples; ++i) {
    const double s = length * (static_cast<double>(i) + 0.5) / static_cast<double>(samples);
    const auto located = table.value().locate(s);
    const double speed = norm(segment.derivative(located.u, 1));
    if (!(located.ds_du > 0)) {
      if (speed > 0) return std::numeric_limits<double>::infinity();
      continue;
    }
    worst = std::max(worst, speed / located.ds_du);
  }
  // The slopes above are compared at the table's own u: a curve whose speed is a spike too thin
  // for every sample (weights 2^-16, 1, 1: the first 5 mm in u < 1e-5) passes them, while the
  // table puts the machine 5 mm ahead at once. The distance between the points the table gives
  // for consecutive arc lengths catches that: the machine moves it while it plans `step`.
  const double step = length / static_cast<double>(samples);
  MachinePoint previous = segment.point(0);
  for (std::size_t i = 1; i <= samples; ++i) {
    const MachinePoint here = segment.point(table.value().locate(step * static_cast<double>(i)).u);
    worst = std::max(worst, norm(here - previous) / step);
    previous = here;
  }
  return worst;
}

namespace {

void check_parameter_speed(const PathSegment& segment, const std::function<SourceLocation()>& where) {
  if (segment.kind() != SegmentKind::RationalBezier) return;  // polynomial speeds are followed
  const double factor = table_speed_factor(segment);
  if (factor <= max_table_speed_factor) return;
  char digits[32];
  std::snprintf(digits, sizeof digits, "%.3g", factor);
  throw LoadError(where(),
                  "the weights vary too strongly: the controller's arc-length table cannot follow this curve's "
                  "parameter speed (the machine would move " + std::string(digits) +
                      " times faster than planned); lower the weight ratio or split the curve",
                  Error::InvalidJob);
}

}  // namespace

void check_parameter_speed(const Job& job) {
  for (std::size_t k = 0; k < job.segments.size(); ++k) check_parameter_speed(job.segments[k], [&] { return piece_location(job, k); });
}

void check_parameter_speed(const PathSegment& segment, const Job& job, std::size_t source) {
  check_parameter_speed(segment, [&] { return source_location(job, source); });
}

}  // namespace curvestep::host
