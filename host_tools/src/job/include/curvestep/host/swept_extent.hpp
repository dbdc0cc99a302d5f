// SPDX-License-Identifier: MIT
// The box a segment sweeps (arcs: their extreme angles; Béziers: the control hull), and the load-time
// check that every segment of a job stays inside the Q16.16 range.
#pragma once

#include <string>

#include <curvestep/core/motion/path_segment.hpp>
#include <curvestep/core/motion/segment_bounds.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/machine_file.hpp>

namespace curvestep::host {

/// An axis-aligned box: low[axis] <= high[axis] (the core's SegmentBounds, which a controller checks too).
using SweptBox = SegmentBounds;

/// A box holding every point `segment` passes through: exact for lines and arcs (their ends and the
/// axis-direction angles inside the sweep), the control-point hull for (rational) Béziers, which
/// contains the curve since the weights are positive.
[[nodiscard]] SweptBox swept_box(const PathSegment& segment);

/// Throws LoadError (FixedOverflow, naming the job file, line and segment) for the first segment of
/// `job` whose swept box leaves the Q16.16 range (-32768 .. 32767.99998 mm), so that no job starts
/// that the controller would refuse halfway (issue 19 item 3).
void check_swept_extent(const Job& job);
/// The same check for one segment of `job` that comes from its file segment `source` (a streamed load).
void check_swept_extent(const PathSegment& segment, const Job& job, std::size_t source);

/// Throws LoadError (OutsideTravel, naming the job file, line and segment, the axis and by how much)
/// for the first segment of `job` whose swept box leaves `travel` (issue 22.5: soft limits checked
/// before anything moves, arcs by their extremes, curves by their control hull).
/// `machine_file` names the travel's file in the message.
void check_travel(const Job& job, const MachineTravel& travel, const std::string& machine_file);
/// The same check for one segment of `job` that comes from its file segment `source` (a streamed load).
void check_travel(const PathSegment& segment, const Job& job, std::size_t source, const MachineTravel& travel,
                  const std::string& machine_file);
/// True if `segment`'s swept box stays inside `travel` (what check_travel checks, without a message).
[[nodiscard]] bool within_travel(const PathSegment& segment, const MachineTravel& travel);

}  // namespace curvestep::host
