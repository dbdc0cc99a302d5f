// SPDX-License-Identifier: MIT
// The motion side of job events: which joints of a job are passed at rest, and for how many
// control ticks (core JointStop). The simulator pushes these with the segments; the wire format
// carries them to the controller (QueueSegment's stop and rest fields), so both plan the same.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <curvestep/core/motion/joint_stop.hpp>
#include <curvestep/host/job.hpp>

namespace curvestep::host {

/// True for the events that need the machine at rest where they happen: Dwell, ProgramPause,
/// ToolChange, LayerChange (a plotter's pen change).
[[nodiscard]] bool needs_rest(JobEventKind kind) noexcept;

/// The control ticks of a dwell of `seconds` at `rate_hz`: the nearest whole tick, a half tick
/// rounded up (G4 P0.5 at 1 kHz: 500; P0.0015 at 1 kHz: 2). Throws std::invalid_argument for a
/// negative or non-finite time, or one longer than 2^32 - 1 ticks.
[[nodiscard]] std::uint32_t dwell_ticks(double seconds, double rate_hz);

/// Machine events (QueueEvents: not dwells, not operator messages) a joint may have and still be
/// passed at speed. A joint with more is an exact stop: a controller whose event ring cannot hold
/// them all before the segment after it waits for that segment at the joint (docs/protocol.md,
/// "Credit"), and at an exact stop waiting changes nothing, so it moves as `sim` plans.
inline constexpr std::size_t max_events_passed_at_speed = 16;

/// The JointStop of each joint of a job of `segments` segments: the entry into each segment, and one
/// more for the job's end. Held only where the job has events (the rest are passed at speed), so a
/// streamed job's millions of segments cost nothing here.
class JointStops {
 public:
  explicit JointStops(std::size_t segments = 0) : segments_(segments) {}
  /// The joint into segment `joint`, or the job's end for joint >= the segment count; {} where
  /// nothing happens.
  [[nodiscard]] JointStop operator[](std::size_t joint) const;
  /// The job's end: its rest_ticks are the dwells after the last move.
  [[nodiscard]] JointStop at_end() const { return (*this)[segments_]; }
  /// Segments + 1: one per segment and the end.
  [[nodiscard]] std::size_t size() const noexcept { return segments_ + 1; }
  /// The stop at `joint` (past the last segment: the end), made {} if there was none.
  [[nodiscard]] JointStop& edit(std::size_t joint);

 private:
  std::size_t segments_;
  std::map<std::size_t, JointStop> stops_;
};

/// The joint stops of `job` from its events at the control rate `rate_hz`: a stop where needs_rest()
/// or where more than max_events_passed_at_speed machine events are, plus the dwells' ticks (each
/// dwell rounded by dwell_ticks, then added); at the job's end the rest_ticks are the dwells after
/// the last move (the rest at its end point, MotionController::end_of_job). Throws
/// std::runtime_error naming the job file and line of a dwell dwell_ticks refuses.
[[nodiscard]] JointStops joint_stops(const Job& job, double rate_hz);
/// The same for a job of `segments` segments known by its events and `name` only (a streamed job).
[[nodiscard]] JointStops joint_stops(const std::vector<JobEvent>& events, std::size_t segments, const std::string& name, double rate_hz);

}  // namespace curvestep::host
