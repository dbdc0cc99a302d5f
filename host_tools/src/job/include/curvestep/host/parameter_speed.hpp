// SPDX-License-Identifier: MIT
// Load-time check that the controller's arc-length table can follow each rational curve's
// parameter speed (issue 19 item 1): a curve it cannot follow is refused with its file:line.
#pragma once

#include <curvestep/core/motion/path_segment.hpp>
#include <curvestep/host/job.hpp>

namespace curvestep::host {

/// The largest factor by which the path speed exceeds the planned speed on `segment` when the
/// controller follows it through its PathLengthTable: max |p'(u)| / S'(u) over the table (S the
/// table's arc length), sampled 16 times per table piece. 1 for a table that follows the curve.
[[nodiscard]] double table_speed_factor(const PathSegment& segment);

/// The most table_speed_factor() a job's segment may have: 5 % above the planned speed.
inline constexpr double max_table_speed_factor = 1.05;

/// Throws LoadError (InvalidJob, naming the job file, line and segment) for the first rational
/// segment of `job` whose table_speed_factor() exceeds max_table_speed_factor: the machine would
/// move faster than planned, up to a jump of the whole curve in one tick (weights 1, 100, 1).
void check_parameter_speed(const Job& job);
/// The same check for one segment of `job` that comes from its file segment `source` (a streamed load).
void check_parameter_speed(const PathSegment& segment, const Job& job, std::size_t source);

}  // namespace curvestep::host
