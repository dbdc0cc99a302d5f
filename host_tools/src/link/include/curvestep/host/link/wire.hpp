// SPDX-License-Identifier: MIT
// Jobs and machines as wire messages: PathSegments -> QueueSegments, MachineLimits ->
// MachineConfiguration, with a note for every value the wire cannot carry exactly; and planned
// pieces -> QueuePieces for a controller without a planner (binary64 coordinates, exact).
//
// Coordinates of a loaded job are already Q16.16 (job.hpp quantises them), so they travel
// exactly. The machine's planning limits (speeds, accelerations, jerk, tolerance, junction
// deviation, step rate, profile kind) travel as binary64 and so exactly; the default feed and
// the rapid speed are Q16.16 like segment feeds, and weights and segment feeds may not be
// representable either. Every such loss is listed in `notes`, because a device then plans with
// different numbers than `curvestep sim` does. Arcs carry their extra full turns (helices).
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <curvestep/core/motion/joint_stop.hpp>
#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/core/motion/planned_piece.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/readable_job.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::host::link {

/// A machine as a MachineConfiguration, and what did not travel exactly.
struct WireMachine {
  protocol::MachineConfiguration configuration;  ///< the message
  std::vector<std::string> notes;                ///< one line per value changed or dropped
};

/// `machine` for a controller with `axis_count` axes (2 or 3).
[[nodiscard]] WireMachine to_wire(const MachineLimits& machine, std::size_t axis_count);

/// A job as queue segments, and what did not travel exactly.
struct WireJob {
  std::vector<protocol::QueueSegment> segments;  ///< one per PathSegment of the job, in order
  std::vector<std::string> notes;                ///< one line per value changed
};

/// The job's PathSegments for a controller with `axis_count` axes running at `rate_hz`, each with
/// the exact stop and rest its events ask for (joint_stops). Throws std::runtime_error
/// naming the job file and segment for what the wire cannot express (a Z move on a 2-axis
/// controller, a coordinate outside Q16.16), or the line of a dwell joint_stops refuses.
[[nodiscard]] WireJob to_wire(const Job& job, std::size_t axis_count, double rate_hz);
/// One segment of a job as to_wire(job) makes it, with its joint stop `entry` (end_rest_ticks
/// left 0: the caller sets it on the last one); `where` (wire_segment_where) starts its messages,
/// and the notes of what the wire rounds are appended to `notes`.
[[nodiscard]] protocol::QueueSegment to_wire(const PathSegment& segment, const JointStop& entry, std::size_t axis_count,
                                             const std::string& where, std::vector<std::string>& notes);
/// "job.ngc: segment 12: ", the start of a wire message about file segment `file_index`.
[[nodiscard]] std::string wire_segment_where(const std::string& job_name, std::size_t file_index);

/// The job's events that a controller acts on, as QueueEvents in program order (G4 dwells are
/// motion, JointStop; operator messages stay on the host); `job` gives their name and events only
/// (its PathSegments and source_index need not be held). Each is keyed by the setpoints' segment
/// number where it happens: its joint's label in `labels` (ReadableJob::event_labels, the one rule
/// for a job held whole, readable(), and a streamed one: the job-file index of the segment after
/// the joint, which host-planned pieces carry; after the last move the last segment's + 1, the
/// label of the setpoints of the rest at the job's end: a dwell after the last move, without one
/// the events are left for the job's end). std::logic_error if an event's joint has no label.
/// `after_rest_ticks` adds the dwells at its joint before it (joint_stops' rounding). Spindle
/// speeds round to whole rev/min; output and tool numbers must be whole and >= 0 (else
/// std::runtime_error naming the job file and line).
[[nodiscard]] std::vector<protocol::QueueEvent> to_wire_events(const Job& job, double rate_hz, const std::map<std::size_t, std::size_t>& labels);
/// The same with the label of the joint into each segment k (past the last: the job's end) from
/// `label_of` (a planner on board numbers the segments as they arrive: k, the end the segment count).
[[nodiscard]] std::vector<protocol::QueueEvent> to_wire_events(const Job& job, double rate_hz,
                                                               const std::function<std::size_t(std::size_t)>& label_of);

/// A planned piece (plan_pieces) as a QueuePiece for a controller with `axis_count` axes (2 or
/// 3), for a controller without a planner. Coordinates travel as binary64, exactly. Throws
/// std::runtime_error naming the piece's job segment for what the wire cannot express: a Z
/// coordinate other than 0 on a 2-axis controller, a length that is not 1 or a power of two up
/// to 256 (an exact run: not 2 to 6).
[[nodiscard]] protocol::QueuePiece to_wire(const PlannedPiece& piece, std::size_t axis_count);

/// `value` in Q16.16 raw units, rounded to nearest with ties away from zero (Q16_16::from_double, the
/// rule of docs/protocol.md); sets `exact` false if rounding changed it.
/// Throws std::out_of_range outside the Q16.16 range.
[[nodiscard]] std::int32_t to_q16(double value, bool& exact);

/// The job and machine exactly as a controller with motion_axes axes will plan them: through the
/// wire format and the firmware's own conversions (firmware/conversions.hpp). Simulating these
/// gives the device's setpoints, so a comparison cannot be fooled by rounding on the wire.
/// Throws std::runtime_error naming the machine or the job's segment the firmware would refuse.
[[nodiscard]] std::pair<Job, MachineLimits> as_device_sees(const Job& job, const MachineLimits& machine);
/// The machine alone as the controller sees it.
[[nodiscard]] MachineLimits as_device_sees(const MachineLimits& machine);
/// A job read rather than held, each segment converted as it is read (errors name its file segment).
[[nodiscard]] ReadableJob as_device_sees(const ReadableJob& job);

}  // namespace curvestep::host::link
