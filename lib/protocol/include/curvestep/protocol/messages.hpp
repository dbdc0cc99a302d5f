// SPDX-License-Identifier: MIT
// Message structs, their payload encoders and decoders, and the tagged Message that holds any one.
//
// Every payload is a fixed sequence of little-endian fields (docs/protocol.md has the byte
// tables). Coordinates, feeds and weights travel as Q16.16 raw int32 (value * 65536): exact,
// and what the firmware computes with, so no conversion happens on the controller. The machine
// configuration, sent once per job, carries its planning limits as IEEE 754 binary64, so the
// planner on the controller gets exactly the doubles the host planned with. Decoders
// check structure (lengths, counts, enum values, reserved bits, positive weights) and return
// BadPayload with the byte offset of the offending field; the firmware validates meaning
// (limits, rates, continuity) with the planner's own error codes.
// Memory: a Message is about 300 bytes (the union's largest member is SetpointBatch). A
// controller short of stack can check Frame::type and call decode<QueueSegment> (156 bytes)
// or decode<QueuePiece> (160 bytes) directly instead of decode_message.
// Code size: each endpoint names the messages it receives or sends as a MessageSet
// (HostToController, ControllerToHost, or a smaller set of its own), and decode_message<Set>,
// encode<Set>(const Message&) and encode_frame<Set> instantiate only those codecs; the
// defaults (AllMessages) take every type. The firmware thus links no decoder of a report and no
// encoder of a command. A type outside the set is refused like an undefined one.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>

#include <curvestep/core/contract.hpp>
#include <curvestep/core/curve/circular_arc.hpp>
#include <curvestep/core/error.hpp>
#include <curvestep/core/result.hpp>
#include <curvestep/protocol/byte_io.hpp>
#include <curvestep/protocol/limits.hpp>
#include <curvestep/protocol/wire_layout.hpp>

namespace curvestep::protocol {

/// Message type: the first byte of every frame.
enum class MessageType : std::uint8_t {
  Hello = 0x01,                 ///< host -> controller: open a session (version, session number)
  Capabilities = 0x02,          ///< controller -> host: the controller's limits, answer to Hello
  Ack = 0x03,                   ///< either way: cumulative acknowledgement (and, to the host, credit)
  Nak = 0x04,                   ///< either way: negative acknowledgement (expected sequence, reason)
  MachineConfiguration = 0x10,  ///< host -> controller: limits, feed, tolerance, rate, axes
  QueueSegment = 0x11,          ///< host -> controller: one path segment for the queue
  Start = 0x12,                 ///< host -> controller: start executing the queue
  FeedHold = 0x13,              ///< host -> controller: decelerate to a stop on the path
  Resume = 0x14,                ///< host -> controller: continue after a feed hold
  Abort = 0x15,                 ///< host -> controller: stop at once and flush the queue
  StatusRequest = 0x16,         ///< host -> controller: ask for a status report
  QueuePiece = 0x17,            ///< host -> controller: one host-planned piece (controller without a planner)
  QueueEvent = 0x18,            ///< host -> controller: a machine event (spindle, coolant, output, pen, ...) at a joint
  FeedOverride = 0x19,          ///< host -> controller: feed and rapid override in percent, from now on
  SeekSwitch = 0x1A,            ///< host -> controller: the next job stops at once when this limit switch closes (homing)
  SetPosition = 0x1B,           ///< host -> controller: the machine stands at these coordinates (homing), at rest
  StatusReport = 0x20,          ///< controller -> host: state, queue depth, position, error
  SetpointBatch = 0x21,         ///< controller -> host: delta-encoded setpoints (sequenced, acknowledged)
  ErrorReport = 0x22,           ///< controller -> host: an error with index and sequence number
  PauseReport = 0x23,           ///< controller -> host: the job paused for the operator (M0/M1, M6, a pen change)
  SwitchReport = 0x24,          ///< controller -> host: a SeekSwitch job stopped: where the switch closed
};

/// True for the types this protocol version defines.
[[nodiscard]] constexpr bool is_known(std::uint8_t type) noexcept {
  return (type >= 0x01 && type <= 0x04) || (type >= 0x10 && type <= 0x1B) || (type >= 0x20 && type <= 0x24);
}

/// The two ends of the link.
enum class Endpoint : std::uint8_t {
  Host,        ///< the PC or Raspberry Pi running `curvestep`
  Controller,  ///< the firmware
};

/// True for host commands (0x10 .. 0x1B): the host-to-controller reliable stream.
[[nodiscard]] constexpr bool is_command(MessageType type) noexcept {
  const auto value = static_cast<std::uint8_t>(type);
  return value >= 0x10 && value <= 0x1B;
}

/// True for messages that travel in a reliable, sequenced stream: host commands one way,
/// SetpointBatch the other way. Every other frame carries a free-running diagnostic counter in
/// its sequence byte and is never acknowledged.
[[nodiscard]] constexpr bool is_sequenced(MessageType type) noexcept {
  return is_command(type) || type == MessageType::SetpointBatch;
}

/// True if `type` travels in the sequenced stream toward `receiver`. Unknown types are taken
/// as commands from a newer host (so the controller answers UnknownMessage in order).
[[nodiscard]] constexpr bool is_sequenced_toward(Endpoint receiver, std::uint8_t type) noexcept {
  if (receiver == Endpoint::Host) return type == static_cast<std::uint8_t>(MessageType::SetpointBatch);
  return !is_known(type) || is_command(static_cast<MessageType>(type));
}

/// True for messages that take one slot of the controller's queue or event ring (and so one
/// credit): QueueSegment, QueuePiece and QueueEvent.
[[nodiscard]] constexpr bool consumes_credit(MessageType type) noexcept {
  return type == MessageType::QueueSegment || type == MessageType::QueuePiece || type == MessageType::QueueEvent;
}

/// One point on the wire: X, Y, Z as Q16.16 raw values (Z unused with two axes).
using WirePoint = std::array<std::int32_t, max_axes>;

/// Opens a session; resent unchanged until Capabilities arrives.
struct Hello {
  static constexpr MessageType type = MessageType::Hello;  ///< message type
  std::uint16_t version = protocol_version;                ///< the host's protocol version
  std::uint16_t session = 0;                               ///< host-chosen session number (random per connect)
};

/// The controller's limits; the host reads them at connect and never hard-codes them.
struct Capabilities {
  static constexpr MessageType type = MessageType::Capabilities;  ///< message type
  std::uint16_t version = protocol_version;                       ///< the controller's protocol version
  std::uint16_t session = 0;                                      ///< echo of Hello::session
  std::uint16_t max_payload = max_payload_size;                   ///< largest payload the controller accepts
  std::uint16_t queue_capacity = 0;                               ///< segment queue slots
  std::uint16_t credit_end = 0;                                   ///< initial credit limit (see Ack)
  std::uint8_t fixed_total_bits = 32;                             ///< fixed-point word size in bits
  std::uint8_t fixed_fraction_bits = 16;                          ///< fixed-point fraction bits
  std::uint8_t axis_count = 3;                                    ///< axes the controller drives (2 or 3)
  std::uint8_t max_degree = max_segment_degree;                   ///< highest Bézier degree accepted
  std::uint32_t tick_rate_hz = 0;                                 ///< step timer tick rate
  /// Segments the planner looks ahead (`curvestep sim --lookahead` plans the same); 0: no
  /// planner on board, the host plans and sends QueuePiece (never QueueSegment).
  std::uint16_t lookahead = 1;
};

/// Cumulative acknowledgement: every sequence before `next_expected` arrived.
struct Ack {
  static constexpr MessageType type = MessageType::Ack;  ///< message type
  std::uint8_t next_expected = 0;                        ///< next sequence number the controller expects
  std::uint16_t credit_end = 0;  ///< the host may send segments while (segments sent) mod 2^16 is before this
};

/// Negative acknowledgement: resend from `expected`, or (for some reasons) give up.
struct Nak {
  static constexpr MessageType type = MessageType::Nak;  ///< message type
  std::uint8_t expected = 0;                             ///< next sequence number the controller expects
  Error reason = Error::SequenceError;                   ///< why: SequenceError, BadCrc, BadFraming, QueueFull, NotConnected, VersionMismatch
};

/// Limits of one axis.
struct AxisConfiguration {
  double steps_per_mm = 0;                        ///< steps per millimetre
  double max_velocity_mm_per_s = 0;               ///< axis speed limit (0: none)
  double max_acceleration_mm_per_s2 = 0;          ///< axis acceleration limit (0: none)
  std::int32_t min_position_mm = 0;               ///< Q16.16 travel limit, low end
  std::int32_t max_position_mm = 0;               ///< Q16.16 travel limit, high end
};

/// Speed profile shape (MachineConfiguration flag bit 0).
enum class ProfileKind : std::uint8_t {
  SCurve = 0,     ///< jerk-limited (S-curve) speed profiles
  Trapezoid = 1,  ///< acceleration-limited (trapezoidal) speed profiles
};

/// MachineConfiguration flag bit 0: trapezoidal profiles (else S-curve).
inline constexpr std::uint8_t configuration_flag_trapezoid = 0x01;
/// Payload bytes of a MachineConfiguration before the axes.
inline constexpr std::size_t configuration_header_size = 62;
/// Payload bytes of one axis in a MachineConfiguration.
inline constexpr std::size_t configuration_axis_size = 32;

/// The flags byte of a MachineConfiguration is the profile: only bit 0 (trapezoid) may be set.
[[nodiscard]] constexpr bool valid_wire_value(const ProfileKind& profile) noexcept {
  return static_cast<std::uint8_t>(profile) <= configuration_flag_trapezoid;
}

/// Machine configuration; the firmware validates the values (InvalidLimit, InvalidRate).
/// Planning limits are binary64 (exact); feeds are Q16.16 like segment feeds.
struct MachineConfiguration {
  static constexpr MessageType type = MessageType::MachineConfiguration;  ///< message type
  std::uint8_t axis_count = 3;                            ///< 2 or 3
  ProfileKind profile = ProfileKind::SCurve;              ///< speed profile shape
  double max_velocity_mm_per_s = 0;                       ///< path speed limit
  double max_acceleration_mm_per_s2 = 0;                  ///< path acceleration limit
  double max_jerk_mm_per_s3 = 0;                          ///< path jerk limit
  double tolerance_mm = 0;                                ///< path (chord) tolerance
  double junction_deviation_mm = 0;                       ///< junction deviation for corners
  double max_step_rate_hz = 0;                            ///< fastest step train an axis driver follows
  std::int32_t default_feed_mm_per_s = 0;                 ///< Q16.16 feed for segments without one
  std::int32_t rapid_mm_per_s = 0;                        ///< Q16.16 speed of rapid moves (0: max velocity)
  std::uint32_t control_rate_hz = 0;                      ///< setpoint rate
  std::array<AxisConfiguration, max_axes> axes{};         ///< per axis, first axis_count used
};

/// Geometry of a queue segment.
enum class SegmentKind : std::uint8_t {
  Line = 0,            ///< points: start, end
  Arc = 1,             ///< points: start, end, centre (XY); Z of start/end makes it helical
  Bezier = 2,          ///< degree + 1 control points
  RationalBezier = 3,  ///< degree + 1 control points and degree + 1 weights
};

/// One path segment. B-splines and NURBS are split into (rational) Bézier spans on the host.
struct QueueSegment {
  static constexpr MessageType type = MessageType::QueueSegment;  ///< message type
  SegmentKind kind = SegmentKind::Line;                           ///< geometry kind
  std::uint8_t axis_count = 2;                                    ///< 2 or 3 coordinates per point
  std::uint8_t degree = 1;  ///< Bézier degree 1..7 (Line: 1, Arc: 2, fixed by kind)
  bool rapid = false;       ///< rapid move (G0): feed is the machine maximum
  bool has_feed = false;    ///< feed_mm_per_s is given (else the configured default)
  bool end_of_job = false;  ///< the last segment of the job: the controller may start without a full look-ahead
  ArcDirection direction = ArcDirection::CounterClockwise;  ///< Arc only
  std::uint32_t turns = 0;  ///< Arc only: extra full turns beyond the sweep from start to end (a helix)
  bool stop_before = false;     ///< an exact stop at the joint into this segment (a job event there)
  std::uint32_t rest_ticks = 0; ///< control ticks of rest at that joint (a G4 dwell); > 0 implies the stop
  std::uint32_t end_rest_ticks = 0;  ///< end_of_job only: control ticks of rest at the job's end point (a dwell after the last move)
  std::int32_t feed_mm_per_s = 0;                           ///< Q16.16 feed, if has_feed
  std::array<WirePoint, max_segment_degree + 1> points{};  ///< Q16.16 points, point_count() used
  std::array<std::int32_t, max_segment_degree + 1> weights{};  ///< Q16.16 weights > 0, RationalBezier only

  /// Number of points used by this kind (Line 2, Arc 3, Bézier degree + 1).
  [[nodiscard]] constexpr std::size_t point_count() const noexcept {
    switch (kind) {
      case SegmentKind::Line: return 2;
      case SegmentKind::Arc: return 3;
      default: return static_cast<std::size_t>(degree) + 1;
    }
  }
};

/// One piece of host-planned motion (core PlannedPiece) for a controller without a planner
/// (Capabilities::lookahead == 0), which only replays the pieces: `ticks` == 1 is one exact
/// setpoint at `end`; `ticks` == N (a power of two, 2..256) is a chunk, the N - 1 quintic
/// Hermite setpoints of `controls` (relative to the previous setpoint) and then `end`.
struct QueuePiece {
  static constexpr MessageType type = MessageType::QueuePiece;  ///< message type
  std::uint8_t axis_count = 3;  ///< 2 or 3 coordinates per point (with 2, every z is 0)
  std::uint16_t ticks = 1;      ///< control ticks covered: 1 (exact), a power of two 2..256 (chunk), 2..6 (exact run)
  bool exact_run = false;       ///< flag bit 1: `ticks` exact setpoints, controls[0..ticks-2] then `end`
  bool rest = false;            ///< flag bit 2: `ticks` (1..65535) setpoints at `end`, a rest at a joint
  bool end_of_job = false;      ///< the job's last piece
  std::uint32_t segment = 0;    ///< the job segment index the piece belongs to (reports)
  std::array<double, max_axes> end{};  ///< unrounded position of the piece's last setpoint (mm, binary64)
  /// Chunk only (0 for an exact piece): the Hermite control points q1..q5 relative to the
  /// previous setpoint's unrounded position (mm, binary64); q0 = 0 is not sent.
  std::array<std::array<double, max_axes>, 5> controls{};

  /// Field-wise equality (binary64 ==: a NaN is unequal to itself, -0.0 equals 0.0).
  friend constexpr bool operator==(const QueuePiece&, const QueuePiece&) = default;
};

/// What a QueueEvent does on the controller's board (the job's non-motion events that a board
/// acts on; docs/protocol.md, "QueueEvent").
enum class MachineEventKind : std::uint8_t {
  SpindleOn = 1,      ///< M3 / M4: `value` rev/min, `flag` counter-clockwise (M4)
  SpindleOff = 2,     ///< M5
  SpindleSpeed = 3,   ///< S while the spindle turns: `value` rev/min
  CoolantMist = 4,    ///< M7
  CoolantFlood = 5,   ///< M8
  CoolantOff = 6,     ///< M9
  DigitalOutput = 7,  ///< M62-M65: `value` output number, `flag` on
  PenUp = 8,          ///< plotter pen lifted (a servo pen)
  PenDown = 9,        ///< plotter pen lowered (a servo pen)
  ToolChange = 10,    ///< M6: `value` tool number
  ProgramPause = 11,  ///< M0 / M1
  LayerChange = 12,   ///< a plotter's pen change between layers
  ProgramEnd = 13,    ///< M2 / M30
};
/// Name of a machine event kind, for logs ("spindle_on", ...; "unknown" for another value).
[[nodiscard]] constexpr const char* machine_event_name(MachineEventKind kind) noexcept {
  switch (kind) {
    case MachineEventKind::SpindleOn: return "spindle_on";
    case MachineEventKind::SpindleOff: return "spindle_off";
    case MachineEventKind::SpindleSpeed: return "spindle_speed";
    case MachineEventKind::CoolantMist: return "coolant_mist";
    case MachineEventKind::CoolantFlood: return "coolant_flood";
    case MachineEventKind::CoolantOff: return "coolant_off";
    case MachineEventKind::DigitalOutput: return "digital_output";
    case MachineEventKind::PenUp: return "pen_up";
    case MachineEventKind::PenDown: return "pen_down";
    case MachineEventKind::ToolChange: return "tool_change";
    case MachineEventKind::ProgramPause: return "program_pause";
    case MachineEventKind::LayerChange: return "layer_change";
    case MachineEventKind::ProgramEnd: return "program_end";
  }
  return "unknown";
}
/// The kinds this protocol version defines (1 .. 13).
[[nodiscard]] constexpr bool valid_wire_value(const MachineEventKind& kind) noexcept {
  return static_cast<std::uint8_t>(kind) >= 1 && static_cast<std::uint8_t>(kind) <= 13;
}

/// A machine event at a joint of the job: the controller acts on it (a board hook) when its
/// motion reaches the joint into job segment `segment` (its setpoints' segment number: the
/// QueueSegment count before it, or the QueuePiece segment), `after_rest_ticks` ticks into the
/// rest there (0: at the joint; the events after a G4 dwell come at its end).
struct QueueEvent {
  static constexpr MessageType type = MessageType::QueueEvent;  ///< message type
  std::uint32_t segment = 0;                                    ///< the job segment it precedes
  std::uint32_t after_rest_ticks = 0;                           ///< ticks into the rest at that joint
  MachineEventKind kind = MachineEventKind::SpindleOff;         ///< what to do
  bool flag = false;                                            ///< counter-clockwise (SpindleOn), on (DigitalOutput)
  std::uint32_t value = 0;                                      ///< rev/min, output or tool number (see kind)
};

/// Start executing the queue.
struct Start {
  static constexpr MessageType type = MessageType::Start;  ///< message type
};
/// Decelerate to a stop on the path and hold.
struct FeedHold {
  static constexpr MessageType type = MessageType::FeedHold;  ///< message type
};
/// Continue after a feed hold.
struct Resume {
  static constexpr MessageType type = MessageType::Resume;  ///< message type
};
/// Stop at once and flush the queue.
struct Abort {
  static constexpr MessageType type = MessageType::Abort;  ///< message type
};
/// Feed and rapid override from now on (MotionController::set_override): the controller's planner
/// takes it at its next point of zero acceleration. A controller refuses values outside 10..200
/// (feed) and 10..100 (rapid) as InvalidArgument at their byte offset (0, 2), and a controller
/// without a planner as NotSupported (the host's planner applies it).
struct FeedOverride {
  static constexpr MessageType type = MessageType::FeedOverride;  ///< message type
  std::uint16_t feed_percent = 100;                                ///< feed override, percent of the programmed feed
  std::uint16_t rapid_percent = 100;                               ///< rapid override, percent of the rapid speed
};
/// Ask for a StatusReport.
struct StatusRequest {
  static constexpr MessageType type = MessageType::StatusRequest;  ///< message type
};

/// What the controller is doing (a progress state, kept apart from Error).
enum class MachineState : std::uint8_t {
  Idle = 0,     ///< not moving, accepts configuration and segments
  Running = 1,  ///< executing the queue
  Holding = 2,  ///< stopped by feed hold, resumable
  Fault = 3,    ///< stopped by an error (see StatusReport::error), needs Abort
};

/// The states a StatusReport may carry (0..3).
[[nodiscard]] constexpr bool valid_wire_value(const MachineState& state) noexcept {
  return static_cast<std::uint8_t>(state) <= 3;
}

/// Name of a state, for logs ("idle", "running", "holding", "fault"; "unknown" for another value).
[[nodiscard]] constexpr const char* machine_state_name(MachineState state) noexcept {
  switch (state) {
    case MachineState::Idle: return "idle";
    case MachineState::Running: return "running";
    case MachineState::Holding: return "holding";
    case MachineState::Fault: return "fault";
  }
  return "unknown";
}

/// The controller's state.
struct StatusReport {
  static constexpr MessageType type = MessageType::StatusReport;  ///< message type
  MachineState state = MachineState::Idle;                        ///< progress state
  std::uint8_t error = 0;               ///< last Error code, 0 if none
  std::uint8_t axis_count = 3;          ///< coordinates in `position`
  std::uint16_t queue_depth = 0;        ///< segments waiting in the queue
  std::uint16_t max_queue_depth = 0;    ///< deepest the queue has been this session (soak diagnostics)
  std::uint32_t setpoint_index = 0;     ///< index of the current setpoint since start
  std::uint8_t limit_switches = 0;      ///< limit switches closed now: bit 2 x axis (min), 2 x axis + 1 (max)
  std::uint32_t tick_overruns = 0;      ///< ticks this session that started a period late or ran longer than one (TickWatch)
  std::uint32_t worst_tick_us = 0;      ///< the longest tick this session, microseconds (0: ticks not timed)
  std::uint16_t feed_override_percent = 100;   ///< the feed override last set (FeedOverride)
  std::uint16_t rapid_override_percent = 100;  ///< the rapid override last set
  std::uint32_t override_index = 0;     ///< it was handed to the planner before this setpoint (sim --override-at)
  WirePoint position{};                 ///< Q16.16 commanded position
};

/// Setpoints on the controller's control-rate grid, delta-encoded on the wire.
struct SetpointBatch {
  static constexpr MessageType type = MessageType::SetpointBatch;  ///< message type
  std::uint32_t first_index = 0;                                   ///< setpoint index of setpoints[0]
  std::uint8_t axis_count = 3;                                     ///< 2 or 3
  std::uint8_t count = 0;                                          ///< setpoints used, 1..max_setpoints_per_batch
  std::array<WirePoint, max_setpoints_per_batch> setpoints{};      ///< Q16.16 positions
};

/// An error the controller met, tied to the frame that caused it.
struct ErrorReport {
  static constexpr MessageType type = MessageType::ErrorReport;  ///< message type
  Error code = Error::InvalidArgument;                           ///< what went wrong
  std::uint16_t index = no_index;                                ///< input at fault (point, byte offset), or no_index
  std::uint8_t sequence = 0;                                     ///< sequence number of the offending frame
};

/// The job stopped at a pause event (ProgramPause, ToolChange, LayerChange) and waits for Resume.
struct PauseReport {
  static constexpr MessageType type = MessageType::PauseReport;  ///< message type
  std::uint32_t setpoint_index = 0;                              ///< the setpoint it stopped at
  MachineEventKind kind = MachineEventKind::ProgramPause;        ///< what for
  std::uint32_t value = 0;                                       ///< the tool number for a tool change
};

/// Homing: the job started next stops at once, without braking and keeping its edges, when the
/// limit switch `limit_switch` closes (any motion), and the controller answers SwitchReport.
struct SeekSwitch {
  static constexpr MessageType type = MessageType::SeekSwitch;  ///< message type
  std::uint8_t limit_switch = 0;                                ///< switch bit: 2 x axis, + 1 for the max switch
};

/// Homing: the machine stands at these coordinates (the axes in `axes`; the others keep theirs).
/// Only at rest with an empty queue; the next job starts there without moving.
struct SetPosition {
  static constexpr MessageType type = MessageType::SetPosition;  ///< message type
  std::uint8_t axes = 0;                                         ///< bit a: set axis a
  std::int32_t x = 0;                                            ///< Q16.16 raw, mm
  std::int32_t y = 0;                                            ///< Q16.16 raw, mm
  std::int32_t z = 0;                                            ///< Q16.16 raw, mm
};

/// A SeekSwitch job stopped: the switch closed with the edges of this setpoint, at this position
/// (where the machine stands). The job is ended (Idle) as by Abort, not a fault.
struct SwitchReport {
  static constexpr MessageType type = MessageType::SwitchReport;  ///< message type
  std::uint8_t limit_switch = 0;                                  ///< the switch bit armed by SeekSwitch
  std::uint32_t setpoint_index = 0;                               ///< the setpoint whose steps closed it
  std::int32_t x = 0;                                             ///< Q16.16 raw, mm
  std::int32_t y = 0;                                             ///< Q16.16 raw, mm
  std::int32_t z = 0;                                             ///< Q16.16 raw, mm
};

// The fixed-field messages, each described once (wire_layout.hpp derives encode, decode, size).
/// Hello: version, session (4 bytes).
template <>
struct WireFields<Hello> : WireLayout<&Hello::version, &Hello::session> {};
/// Ack: next expected sequence, credit end (3 bytes).
template <>
struct WireFields<Ack> : WireLayout<&Ack::next_expected, &Ack::credit_end> {};
/// Nak: expected sequence, reason (2 bytes; reason 0 is BadPayload at 1).
template <>
struct WireFields<Nak> : WireLayout<&Nak::expected, &Nak::reason> {};
/// ErrorReport: code, index, sequence (4 bytes; code 0 is BadPayload at 0).
template <>
struct WireFields<ErrorReport> : WireLayout<&ErrorReport::code, &ErrorReport::index, &ErrorReport::sequence> {};
/// PauseReport: setpoint index, kind, value (9 bytes).
template <>
struct WireFields<PauseReport> : WireLayout<&PauseReport::setpoint_index, &PauseReport::kind, &PauseReport::value> {};
/// FeedOverride: feed percent, rapid percent (4 bytes).
template <>
struct WireFields<FeedOverride> : WireLayout<&FeedOverride::feed_percent, &FeedOverride::rapid_percent> {};
/// QueueEvent: segment, after_rest_ticks, kind, flag, value (14 bytes).
template <>
struct WireFields<QueueEvent> : WireLayout<&QueueEvent::segment, &QueueEvent::after_rest_ticks, &QueueEvent::kind,
                                           &QueueEvent::flag, &QueueEvent::value> {};
/// Capabilities: version, session, max payload, queue capacity, credit end, fixed-point bits
/// (total, fraction), axis count, max degree, tick rate, look-ahead (20 bytes).
template <>
struct WireFields<Capabilities>
    : WireLayout<&Capabilities::version, &Capabilities::session, &Capabilities::max_payload, &Capabilities::queue_capacity,
                 &Capabilities::credit_end, &Capabilities::fixed_total_bits, &Capabilities::fixed_fraction_bits,
                 &Capabilities::axis_count, &Capabilities::max_degree, &Capabilities::tick_rate_hz,
                 &Capabilities::lookahead> {};
/// Capabilities' rules across fields: 2 or 3 axes (byte 12); a degree up to max_segment_degree,
/// and degree 0 (no segments) only from a controller without a planner (look-ahead 0; byte 13).
[[nodiscard]] constexpr std::size_t first_invalid_field(const Capabilities& m) noexcept {
  if (m.axis_count != 2 && m.axis_count != 3) return 12;
  if (m.max_degree > max_segment_degree || (m.max_degree == 0 && m.lookahead != 0)) return 13;
  return all_fields_valid;
}
/// StatusReport's fixed head (28 bytes); the position follows, 4 bytes per axis (axis_count).
/// Not a WireFields: the position's length depends on axis_count, so encode/decode are written
/// out below around this one description of the fixed fields.
using StatusReportHead = WireLayout<&StatusReport::state, &StatusReport::error, &StatusReport::axis_count,
                                    &StatusReport::queue_depth, &StatusReport::max_queue_depth,
                                    &StatusReport::setpoint_index, &StatusReport::limit_switches,
                                    &StatusReport::tick_overruns, &StatusReport::worst_tick_us,
                                    &StatusReport::feed_override_percent, &StatusReport::rapid_override_percent,
                                    &StatusReport::override_index>;
/// MachineConfiguration's fixed head (62 bytes: axis count, profile as the flags byte, the
/// limits, feeds and rate); axis_count AxisConfigurationLayouts follow.
using MachineConfigurationHead =
    WireLayout<&MachineConfiguration::axis_count, &MachineConfiguration::profile, &MachineConfiguration::max_velocity_mm_per_s,
               &MachineConfiguration::max_acceleration_mm_per_s2, &MachineConfiguration::max_jerk_mm_per_s3,
               &MachineConfiguration::tolerance_mm, &MachineConfiguration::junction_deviation_mm,
               &MachineConfiguration::max_step_rate_hz, &MachineConfiguration::default_feed_mm_per_s,
               &MachineConfiguration::rapid_mm_per_s, &MachineConfiguration::control_rate_hz>;
/// One axis of a MachineConfiguration (32 bytes).
using AxisConfigurationLayout =
    WireLayout<&AxisConfiguration::steps_per_mm, &AxisConfiguration::max_velocity_mm_per_s,
               &AxisConfiguration::max_acceleration_mm_per_s2, &AxisConfiguration::min_position_mm,
               &AxisConfiguration::max_position_mm>;
static_assert(MachineConfigurationHead::size == configuration_header_size && AxisConfigurationLayout::size == configuration_axis_size);
/// SeekSwitch: switch bit (1 byte).
template <>
struct WireFields<SeekSwitch> : WireLayout<&SeekSwitch::limit_switch> {};
/// SetPosition: axes mask, x, y, z (13 bytes).
template <>
struct WireFields<SetPosition> : WireLayout<&SetPosition::axes, &SetPosition::x, &SetPosition::y, &SetPosition::z> {};
/// SwitchReport: switch bit, setpoint index, x, y, z (17 bytes).
template <>
struct WireFields<SwitchReport> : WireLayout<&SwitchReport::limit_switch, &SwitchReport::setpoint_index, &SwitchReport::x,
                                             &SwitchReport::y, &SwitchReport::z> {};

namespace detail {

/// The member of `T, Rest...` whose type byte is `type`: `on_type(std::type_identity<T>{})`, or
/// `otherwise()` if none has it (an if-chain the compiler turns into a switch).
template <class T, class... Rest, class OnType, class Otherwise>
constexpr decltype(auto) select_type(std::uint8_t type, OnType& on_type, Otherwise& otherwise) {
  if (type == static_cast<std::uint8_t>(T::type)) return on_type(std::type_identity<T>{});
  if constexpr (sizeof...(Rest) == 0) {
    return otherwise();
  } else {
    return select_type<Rest...>(type, on_type, otherwise);
  }
}

}  // namespace detail

/// A compile-time set of message types (the structs above): the messages one endpoint
/// receives or sends. decode_message<Set>, encode<Set>(const Message&) and
/// encode_frame<Set>(const Message&) instantiate the decoders or encoders of the set's types
/// only, so a firmware image links no code for messages it never receives or sends. A type
/// outside the set is refused as if this protocol version did not define it: UnknownMessage
/// (index = type) when decoding, InvalidArgument (index = type) when encoding.
template <class... Ts>
struct MessageSet {
  static_assert((std::is_same_v<decltype(Ts::type), const MessageType> && ...), "MessageSet holds message structs");

  /// True if message struct T is in the set.
  template <class T>
  static constexpr bool contains = (std::is_same_v<T, Ts> || ...);

  /// True if the raw type byte names a type in the set.
  [[nodiscard]] static constexpr bool contains_type(std::uint8_t type) noexcept {
    return ((type == static_cast<std::uint8_t>(Ts::type)) || ...);
  }

  /// Calls `on_type(std::type_identity<T>{})` for the T of the set whose type byte is `type`
  /// and returns its result, or returns `otherwise()` if the set has no such type. Only the
  /// set's types instantiate `on_type`.
  template <class OnType, class Otherwise>
  static constexpr decltype(auto) select(std::uint8_t type, OnType&& on_type, Otherwise&& otherwise) {
    if constexpr (sizeof...(Ts) == 0) {
      return otherwise();
    } else {
      return detail::select_type<Ts...>(type, on_type, otherwise);
    }
  }
};

/// Every message of this protocol version (the default of the set-taking functions; host
/// tools, tests and fuzzers).
using AllMessages = MessageSet<Hello, Capabilities, Ack, Nak, MachineConfiguration, QueueSegment, Start, FeedHold,
                               Resume, Abort, StatusRequest, QueuePiece, QueueEvent, FeedOverride, SeekSwitch, SetPosition,
                               StatusReport, SetpointBatch, ErrorReport, PauseReport, SwitchReport>;

/// What a host sends and a controller receives: the handshake, the commands, and Ack / Nak of
/// the controller's setpoint stream.
using HostToController = MessageSet<Hello, Ack, Nak, MachineConfiguration, QueueSegment, Start, FeedHold, Resume,
                                    Abort, StatusRequest, QueuePiece, QueueEvent, FeedOverride, SeekSwitch, SetPosition>;

/// What a controller sends and a host receives: the handshake answer, Ack / Nak of the host's
/// commands, reports, and the setpoint stream.
using ControllerToHost = MessageSet<Capabilities, Ack, Nak, StatusReport, SetpointBatch, ErrorReport, PauseReport, SwitchReport>;

namespace detail {

[[nodiscard]] constexpr bool valid_axis_count(std::uint8_t count) noexcept { return count == 2 || count == 3; }

constexpr void write_point(ByteWriter& writer, const WirePoint& point, std::size_t axes) noexcept {
  for (std::size_t a = 0; a < axes; ++a) writer.i32(point[a]);
}

constexpr void read_point(ByteReader& reader, WirePoint& point, std::size_t axes) noexcept {
  point = WirePoint{};
  for (std::size_t a = 0; a < axes; ++a) point[a] = reader.i32();
}

}  // namespace detail

// --- encoders: each writes the payload only and returns its length (BufferTooSmall if it does not fit) ---


/// Encodes a MachineConfiguration payload (62 + 32 per axis bytes); InvalidArgument for 0/1/4+ axes.
[[nodiscard]] constexpr Result<std::size_t> encode(const MachineConfiguration& m, std::span<std::byte> out) noexcept {
  if (!detail::valid_axis_count(m.axis_count)) return fail(Error::InvalidArgument, 0);
  if (static_cast<std::uint8_t>(m.profile) > 1) return fail(Error::InvalidArgument, 1);
  ByteWriter w(out);
  MachineConfigurationHead::write(w, m);
  for (std::size_t a = 0; a < m.axis_count; ++a) AxisConfigurationLayout::write(w, m.axes[a]);
  return w.finish();
}

/// Segment flag bits (byte 1 of a QueueSegment payload).
inline constexpr std::uint8_t segment_flag_rapid = 0x01;      ///< rapid move
inline constexpr std::uint8_t segment_flag_feed = 0x02;       ///< a feed field follows
inline constexpr std::uint8_t segment_flag_three_axes = 0x04; ///< points have X, Y, Z (else X, Y)
inline constexpr std::uint8_t segment_flag_clockwise = 0x08;  ///< Arc only: clockwise (G2)
inline constexpr std::uint8_t segment_flag_end_of_job = 0x10; ///< the last segment of the job
inline constexpr std::uint8_t segment_flag_turns = 0x20;      ///< Arc only: a u32 count of extra full turns follows
inline constexpr std::uint8_t segment_flag_stop_before = 0x40; ///< an exact stop at the joint into the segment
inline constexpr std::uint8_t segment_flag_rest = 0x80;       ///< a u32 count of rest ticks at that joint follows
/// Bit 7 of a QueueSegment's kind byte (byte 0): a u32 `end_rest_ticks` follows (end of job only).
inline constexpr std::uint8_t segment_kind_end_rest = 0x80;

/// Encodes a QueueSegment payload; InvalidArgument (index = field number) for an impossible segment.
[[nodiscard]] constexpr Result<std::size_t> encode(const QueueSegment& m, std::span<std::byte> out) noexcept {
  if (static_cast<std::uint8_t>(m.kind) > 3) return fail(Error::InvalidArgument, 0);
  if (!detail::valid_axis_count(m.axis_count)) return fail(Error::InvalidArgument, 1);
  const bool bezier = m.kind == SegmentKind::Bezier || m.kind == SegmentKind::RationalBezier;
  if (bezier && (m.degree < 1 || m.degree > max_segment_degree)) return fail(Error::InvalidArgument, 2);
  std::uint8_t flags = 0;
  if (m.rapid) flags |= segment_flag_rapid;
  if (m.has_feed) flags |= segment_flag_feed;
  if (m.axis_count == 3) flags |= segment_flag_three_axes;
  if (m.kind == SegmentKind::Arc && m.direction == ArcDirection::Clockwise) flags |= segment_flag_clockwise;
  if (m.end_of_job) flags |= segment_flag_end_of_job;
  if (m.turns != 0 && m.kind != SegmentKind::Arc) return fail(Error::InvalidArgument, 3);
  if (m.turns != 0) flags |= segment_flag_turns;
  if (m.stop_before) flags |= segment_flag_stop_before;
  if (m.rest_ticks != 0) flags |= segment_flag_rest;
  if (m.end_rest_ticks != 0 && !m.end_of_job) return fail(Error::InvalidArgument, 0);
  ByteWriter w(out);
  w.u8(static_cast<std::uint8_t>(static_cast<std::uint8_t>(m.kind) | (m.end_rest_ticks != 0 ? segment_kind_end_rest : 0)));
  w.u8(flags);
  if (bezier) w.u8(m.degree);
  if (m.has_feed) w.i32(m.feed_mm_per_s);
  if (m.turns != 0) w.u32(m.turns);
  if (m.rest_ticks != 0) w.u32(m.rest_ticks);
  if (m.end_rest_ticks != 0) w.u32(m.end_rest_ticks);
  if (m.kind == SegmentKind::Arc) {
    detail::write_point(w, m.points[0], m.axis_count);
    detail::write_point(w, m.points[1], m.axis_count);
    detail::write_point(w, m.points[2], 2);
  } else {
    for (std::size_t i = 0; i < m.point_count(); ++i) detail::write_point(w, m.points[i], m.axis_count);
  }
  if (m.kind == SegmentKind::RationalBezier) {
    for (std::size_t i = 0; i < m.point_count(); ++i) {
      if (m.weights[i] <= 0) return fail(Error::NonPositiveWeight, i);
      w.i32(m.weights[i]);
    }
  }
  return w.finish();
}

/// QueuePiece flag bit 0 (byte 0): the job's last piece.
inline constexpr std::uint8_t piece_flag_end_of_job = 0x01;
/// QueuePiece flag bit 1: an exact run (ticks 2..6 exact setpoints).
inline constexpr std::uint8_t piece_flag_exact_run = 0x02;
/// QueuePiece flag bit 2: a rest (ticks 1..65535 setpoints at the end point); bits 3-7 reserved, 0.
inline constexpr std::uint8_t piece_flag_rest = 0x04;
/// Most exact setpoints one exact run carries (core's max_exact_run).
inline constexpr std::uint32_t max_piece_exact_run = 6;
/// Payload bytes of a QueuePiece before its points (flags, axis_count, ticks, segment).
inline constexpr std::size_t piece_header_size = 8;
/// Hermite control points a chunk carries (q1..q5; q0 = 0 is not sent).
inline constexpr std::size_t piece_control_count = 5;

/// Most control ticks one QueuePiece covers (core's HermiteChunk::max_ticks).
inline constexpr std::uint32_t max_piece_ticks = 256;

/// True if `ticks` is a valid QueuePiece length: 1 or a power of two up to max_piece_ticks (the
/// rule of core's valid_piece_ticks, which this header does not include: core's motion headers
/// bring names such as curvestep::SegmentKind that would clash with this namespace's).
/// For an exact run: 2..max_piece_exact_run; for a rest 1..65535 (not with an exact run).
[[nodiscard]] constexpr bool valid_queue_piece_ticks(std::uint32_t ticks, bool exact_run = false, bool rest = false) noexcept {
  if (rest) return !exact_run && ticks >= 1 && ticks <= 0xFFFFu;
  if (exact_run) return ticks >= 2 && ticks <= max_piece_exact_run;
  return ticks >= 1 && ticks <= max_piece_ticks && (ticks & (ticks - 1)) == 0;
}

/// Points a QueuePiece carries after its header: 1 (exact, rest), 6 (chunk: end, q1..q5), or ticks
/// (exact run: end, then the earlier setpoints in time order).
[[nodiscard]] constexpr std::size_t queue_piece_points(std::uint32_t ticks, bool exact_run, bool rest = false) noexcept {
  if (rest) return 1;
  if (exact_run) return ticks;
  return ticks > 1 ? 1 + piece_control_count : 1;
}

/// Payload bytes of a QueuePiece: 8 + 8 x axes x its points.
[[nodiscard]] constexpr std::size_t queue_piece_size(std::size_t axis_count, std::uint32_t ticks, bool exact_run = false,
                                                    bool rest = false) noexcept {
  return piece_header_size + 8 * axis_count * queue_piece_points(ticks, exact_run, rest);
}
static_assert(queue_piece_size(max_axes, 256) == 152 && queue_piece_size(max_axes, 256) <= max_message_size,
              "docs/protocol.md: a 3-axis chunk is 152 bytes");

namespace detail {

/// True unless the binary64 `value` is a NaN or an infinity (exponent bits all ones), decided on
/// the bit pattern so it holds in constant expressions and under any floating-point flags.
[[nodiscard]] constexpr bool finite_binary64(double value) noexcept {
  return ((std::bit_cast<std::uint64_t>(value) >> 52) & 0x7FFu) != 0x7FFu;
}

/// Byte offset of point `k` (0 end, 1..5 q1..q5) in a QueuePiece payload.
[[nodiscard]] constexpr std::size_t piece_point_offset(std::size_t axis_count, std::size_t k) noexcept {
  return piece_header_size + 8 * axis_count * k;
}

/// Checks one QueuePiece point before encoding: NotFinite (index = the byte offset of the value) for
/// a NaN or infinite coordinate, InvalidArgument (index = the point's byte offset) for a non-zero
/// coordinate that is not sent (z with two axes, any control point of an exact piece).
[[nodiscard]] constexpr Result<void> check_piece_point(const std::array<double, max_axes>& point, std::size_t sent_axes,
                                                       std::size_t at) noexcept {
  for (std::size_t a = 0; a < max_axes; ++a) {
    const double value = point[a];
    if (a < sent_axes && !finite_binary64(value)) return fail(Error::NotFinite, at + 8 * a);
    if (a >= sent_axes && value != 0.0) return fail(Error::InvalidArgument, at);
  }
  return ok();
}

}  // namespace detail

/// Encodes a QueuePiece payload (queue_piece_size bytes). It never writes what the decoder
/// refuses: InvalidArgument for axis_count not 2 or 3 (index 1), ticks not 1 or a power of two
/// <= 256 (for an exact run: not 2..6) (index 2), or a non-zero value that would not be sent
/// (index = the byte offset of its point: z with two axes, controls of an exact piece, points
/// of an exact run beyond its ticks); NotFinite (index = the byte offset of
/// the value) for a NaN or infinite coordinate.
[[nodiscard]] constexpr Result<std::size_t> encode(const QueuePiece& m, std::span<std::byte> out) noexcept {
  if (!detail::valid_axis_count(m.axis_count)) return fail(Error::InvalidArgument, 1);
  if (!valid_queue_piece_ticks(m.ticks, m.exact_run, m.rest)) return fail(Error::InvalidArgument, 2);
  const std::size_t axes = m.axis_count;
  const std::size_t sent = queue_piece_points(m.ticks, m.exact_run, m.rest) - 1;  // of the control slots
  CURVESTEP_CHECK(detail::check_piece_point(m.end, axes, detail::piece_point_offset(axes, 0)));
  for (std::size_t k = 0; k < piece_control_count; ++k) {
    CURVESTEP_CHECK(detail::check_piece_point(m.controls[k], k < sent ? axes : 0, detail::piece_point_offset(axes, k + 1)));
  }
  ByteWriter w(out);
  w.u8(static_cast<std::uint8_t>((m.end_of_job ? piece_flag_end_of_job : 0) | (m.exact_run ? piece_flag_exact_run : 0) |
                                 (m.rest ? piece_flag_rest : 0)));
  w.u8(m.axis_count);
  w.u16(m.ticks);
  w.u32(m.segment);
  for (std::size_t a = 0; a < axes; ++a) w.f64(m.end[a]);
  for (std::size_t k = 0; k < sent; ++k) {
    for (std::size_t a = 0; a < axes; ++a) w.f64(m.controls[k][a]);
  }
  return w.finish();
}

/// The messages with an empty payload.
template <class M>
concept EmptyMessage = std::is_same_v<M, Start> || std::is_same_v<M, FeedHold> || std::is_same_v<M, Resume> ||
                       std::is_same_v<M, Abort> || std::is_same_v<M, StatusRequest>;

/// Encodes a message described by WireFields (Hello, Ack, Nak, ErrorReport, QueueEvent).
template <DescribedMessage M>
[[nodiscard]] constexpr Result<std::size_t> encode(const M& m, std::span<std::byte> out) noexcept {
  return WireFields<M>::encode(m, out);
}

/// Encodes an empty payload (Start, FeedHold, Resume, Abort, StatusRequest).
template <EmptyMessage Empty>
[[nodiscard]] constexpr Result<std::size_t> encode(const Empty&, std::span<std::byte>) noexcept {
  return std::size_t{0};
}

/// Encodes a StatusReport payload (its described head, then 4 bytes per axis of position).
[[nodiscard]] constexpr Result<std::size_t> encode(const StatusReport& m, std::span<std::byte> out) noexcept {
  if (!detail::valid_axis_count(m.axis_count)) return fail(Error::InvalidArgument, 2);
  ByteWriter w(out);
  StatusReportHead::write(w, m);
  detail::write_point(w, m.position, m.axis_count);
  return w.finish();
}

/// Encodes a SetpointBatch payload: header, the first setpoint absolute, then per later setpoint
/// and axis the zig-zag LEB128 varint of the difference to the previous setpoint.
[[nodiscard]] constexpr Result<std::size_t> encode(const SetpointBatch& m, std::span<std::byte> out) noexcept {
  if (!detail::valid_axis_count(m.axis_count)) return fail(Error::InvalidArgument, 1);
  if (m.count < 1 || m.count > max_setpoints_per_batch) return fail(Error::InvalidArgument, 2);
  ByteWriter w(out);
  w.u32(m.first_index);
  w.u8(m.axis_count);
  w.u8(m.count);
  detail::write_point(w, m.setpoints[0], m.axis_count);
  for (std::size_t k = 1; k < m.count; ++k) {
    for (std::size_t a = 0; a < m.axis_count; ++a) {
      const std::int64_t delta = std::int64_t{m.setpoints[k][a]} - std::int64_t{m.setpoints[k - 1][a]};
      w.varint(zigzag_encode(delta));
    }
  }
  return w.finish();
}

/// Payload bytes of the first `count` setpoints of `m` (to size batches before encoding).
[[nodiscard]] constexpr std::size_t encoded_size(const SetpointBatch& m, std::size_t count) noexcept {
  std::size_t size = 6 + 4 * std::size_t{m.axis_count};
  for (std::size_t k = 1; k < count; ++k) {
    for (std::size_t a = 0; a < m.axis_count; ++a) {
      size += varint_size(zigzag_encode(std::int64_t{m.setpoints[k][a]} - std::int64_t{m.setpoints[k - 1][a]}));
    }
  }
  return size;
}

// --- decoders: each reads a whole payload; BadPayload (index = byte offset) if malformed ---

/// Decodes the payload of message type T. This primary template decodes the messages described
/// by WireFields (their one description) and the empty payloads (Start, FeedHold, Resume, Abort,
/// StatusRequest); the other types have their specialisations below.
template <class T>
[[nodiscard]] constexpr Result<T> decode(std::span<const std::byte> payload) noexcept {
  if constexpr (DescribedMessage<T>) {
    return WireFields<T>::template decode<T>(payload);
  } else {
    static_assert(EmptyMessage<T>, "decode<T>: T is not a message type");
    if (!payload.empty()) return fail(Error::BadPayload, 0);
    return T{};
  }
}

/// Decodes a MachineConfiguration payload.
template <>
[[nodiscard]] constexpr Result<MachineConfiguration> decode<MachineConfiguration>(
    std::span<const std::byte> payload) noexcept {
  ByteReader r(payload);
  MachineConfiguration m;
  // The axis count comes first and says how long the payload is: refused before anything else.
  if (!payload.empty() && !detail::valid_axis_count(std::to_integer<std::uint8_t>(payload[0]))) r.reject_at(Error::BadPayload, 0);
  MachineConfigurationHead::read(r, m);
  for (std::size_t a = 0; a < m.axis_count && !r.failed(); ++a) AxisConfigurationLayout::read(r, m.axes[a]);
  CURVESTEP_CHECK(r.finish());
  return m;
}

/// Decodes a QueueSegment payload.
template <>
[[nodiscard]] constexpr Result<QueueSegment> decode<QueueSegment>(std::span<const std::byte> payload) noexcept {
  ByteReader r(payload);
  QueueSegment m;
  const std::uint8_t kind_byte = r.u8();
  const std::uint8_t kind = kind_byte & static_cast<std::uint8_t>(~segment_kind_end_rest);
  if (kind > 3) r.reject_at(Error::BadPayload, 0);
  m.kind = static_cast<SegmentKind>(kind);
  const std::uint8_t flags = r.u8();
  const bool end_rest = (kind_byte & segment_kind_end_rest) != 0;
  if (end_rest && (flags & segment_flag_end_of_job) == 0) r.reject_at(Error::BadPayload, 0);  // end of job only
  const std::uint8_t allowed = static_cast<std::uint8_t>(
      segment_flag_rapid | segment_flag_feed | segment_flag_three_axes | segment_flag_end_of_job | segment_flag_stop_before |
      segment_flag_rest | (m.kind == SegmentKind::Arc ? segment_flag_clockwise | segment_flag_turns : 0));
  if ((flags & ~allowed) != 0) r.reject_at(Error::BadPayload, 1);
  m.rapid = (flags & segment_flag_rapid) != 0;
  m.has_feed = (flags & segment_flag_feed) != 0;
  m.end_of_job = (flags & segment_flag_end_of_job) != 0;
  m.stop_before = (flags & segment_flag_stop_before) != 0;
  m.axis_count = (flags & segment_flag_three_axes) != 0 ? 3 : 2;
  m.direction = (flags & segment_flag_clockwise) != 0 ? ArcDirection::Clockwise : ArcDirection::CounterClockwise;
  if (m.kind == SegmentKind::Line) m.degree = 1;
  if (m.kind == SegmentKind::Arc) m.degree = 2;
  if (m.kind == SegmentKind::Bezier || m.kind == SegmentKind::RationalBezier) {
    const std::size_t at = r.offset();
    m.degree = r.u8();
    if (m.degree < 1 || m.degree > max_segment_degree) r.reject_at(Error::BadPayload, at);
  }
  if (r.failed()) return r.finish().failure();
  if (m.has_feed) m.feed_mm_per_s = r.i32();
  if ((flags & segment_flag_turns) != 0) {
    const std::size_t at = r.offset();
    m.turns = r.u32();
    if (!r.failed() && m.turns == 0) r.reject_at(Error::BadPayload, at);  // the flag means "some"
  }
  if ((flags & segment_flag_rest) != 0) {
    const std::size_t at = r.offset();
    m.rest_ticks = r.u32();
    if (!r.failed() && m.rest_ticks == 0) r.reject_at(Error::BadPayload, at);  // the flag means "some"
  }
  if (end_rest) {
    const std::size_t at = r.offset();
    m.end_rest_ticks = r.u32();
    if (!r.failed() && m.end_rest_ticks == 0) r.reject_at(Error::BadPayload, at);  // the bit means "some"
  }
  if (m.kind == SegmentKind::Arc) {
    detail::read_point(r, m.points[0], m.axis_count);
    detail::read_point(r, m.points[1], m.axis_count);
    detail::read_point(r, m.points[2], 2);
  } else {
    for (std::size_t i = 0; i < m.point_count(); ++i) detail::read_point(r, m.points[i], m.axis_count);
  }
  if (m.kind == SegmentKind::RationalBezier) {
    for (std::size_t i = 0; i < m.point_count(); ++i) {
      const std::size_t at = r.offset();
      m.weights[i] = r.i32();
      if (!r.failed() && m.weights[i] <= 0) r.reject_at(Error::BadPayload, at);
    }
  }
  CURVESTEP_CHECK(r.finish());
  return m;
}

/// Decodes a QueuePiece payload: BadPayload at byte 0 for a reserved flag bit, at 1 for an
/// axis_count not 2 or 3, at 2 for ticks not 1 or a power of two <= 256 (an exact run: not
/// 2..6), and for a length other than queue_piece_size(axis_count, ticks, exact_run) at the
/// first missing or extra byte; NotFinite (index
/// = its byte offset) for a NaN or infinite coordinate. Unsent values (z with two axes, the
/// controls of an exact piece) are 0.
template <>
[[nodiscard]] constexpr Result<QueuePiece> decode<QueuePiece>(std::span<const std::byte> payload) noexcept {
  ByteReader r(payload);
  QueuePiece m;
  const std::uint8_t flags = r.u8();
  if ((flags & ~(piece_flag_end_of_job | piece_flag_exact_run | piece_flag_rest)) != 0) r.reject_at(Error::BadPayload, 0);
  m.end_of_job = (flags & piece_flag_end_of_job) != 0;
  m.exact_run = (flags & piece_flag_exact_run) != 0;
  m.rest = (flags & piece_flag_rest) != 0;
  m.axis_count = r.u8();
  if (!detail::valid_axis_count(m.axis_count)) r.reject_at(Error::BadPayload, 1);
  m.ticks = r.u16();
  if (!r.failed() && !valid_queue_piece_ticks(m.ticks, m.exact_run, m.rest)) r.reject_at(Error::BadPayload, 2);
  m.segment = r.u32();
  if (r.failed()) return r.finish().failure();
  const std::size_t axes = m.axis_count;
  const std::size_t expected = queue_piece_size(axes, m.ticks, m.exact_run, m.rest);
  if (payload.size() != expected) return fail(Error::BadPayload, payload.size() < expected ? payload.size() : expected);
  const auto read_point = [&r, axes](std::array<double, max_axes>& point) {
    for (std::size_t a = 0; a < axes; ++a) {
      const std::size_t at = r.offset();
      point[a] = r.f64();
      if (!r.failed() && !detail::finite_binary64(point[a])) r.reject_at(Error::NotFinite, at);
    }
  };
  read_point(m.end);
  const std::size_t sent = queue_piece_points(m.ticks, m.exact_run, m.rest) - 1;
  for (std::size_t k = 0; k < sent; ++k) read_point(m.controls[k]);
  CURVESTEP_CHECK(r.finish());
  return m;
}

/// Decodes a StatusReport payload.
template <>
[[nodiscard]] constexpr Result<StatusReport> decode<StatusReport>(std::span<const std::byte> payload) noexcept {
  ByteReader r(payload);
  StatusReport m;
  StatusReportHead::read(r, m);
  if (!r.failed() && !detail::valid_axis_count(m.axis_count)) r.reject_at(Error::BadPayload, 2);
  if (!r.failed()) detail::read_point(r, m.position, m.axis_count);
  CURVESTEP_CHECK(r.finish());
  return m;
}

/// Decodes a SetpointBatch payload; a delta that leaves the int32 range is BadPayload.
template <>
[[nodiscard]] constexpr Result<SetpointBatch> decode<SetpointBatch>(std::span<const std::byte> payload) noexcept {
  ByteReader r(payload);
  SetpointBatch m;
  m.first_index = r.u32();
  m.axis_count = r.u8();
  if (!detail::valid_axis_count(m.axis_count)) r.reject_at(Error::BadPayload, 4);
  m.count = r.u8();
  if (m.count < 1 || m.count > max_setpoints_per_batch) r.reject_at(Error::BadPayload, 5);
  if (r.failed()) return r.finish().failure();
  detail::read_point(r, m.setpoints[0], m.axis_count);
  for (std::size_t k = 1; k < m.count && !r.failed(); ++k) {
    m.setpoints[k] = WirePoint{};
    for (std::size_t a = 0; a < m.axis_count; ++a) {
      const std::size_t at = r.offset();
      const std::int64_t value = std::int64_t{m.setpoints[k - 1][a]} + zigzag_decode(r.varint(5));
      if (value < std::numeric_limits<std::int32_t>::min() || value > std::numeric_limits<std::int32_t>::max()) r.reject_at(Error::BadPayload, at);
      m.setpoints[k][a] = static_cast<std::int32_t>(value);
    }
  }
  CURVESTEP_CHECK(r.finish());
  return m;
}

namespace detail {

/// A union of `T, Rest...` built by recursion: `head` holds a T, `rest` any of the others. Each
/// constructor starts the lifetime of exactly one member, so no inactive member is ever assigned
/// (that would be undefined for members with default member initializers).
template <class... Ts>
union MessageUnion;

template <>
union MessageUnion<> {};

template <class T, class... Rest>
union MessageUnion<T, Rest...> {
  /// Holds a default T.
  constexpr MessageUnion() noexcept : head{} {}
  /// Holds `m`.
  constexpr explicit MessageUnion(const T& m) noexcept : head(m) {}
  /// Holds `m`, one of Rest.
  template <class U>
    requires(std::is_same_v<U, Rest> || ...)
  constexpr explicit MessageUnion(const U& m) noexcept : rest(m) {}

  /// The held U (the caller knows which member is active).
  template <class U>
  [[nodiscard]] constexpr const U& get() const noexcept {
    if constexpr (std::is_same_v<U, T>) {
      return head;
    } else {
      return rest.template get<U>();
    }
  }

  T head;
  MessageUnion<Rest...> rest;
};

/// The union of the message structs of a MessageSet.
template <class Set>
struct MessageUnionOf;
template <class... Ts>
struct MessageUnionOf<MessageSet<Ts...>> {
  using type = MessageUnion<Ts...>;
};

}  // namespace detail

/// Any one message of AllMessages: a type tag and a union of the message structs (no RTTI, no
/// heap). The list of types is AllMessages's alone: a message added there is held, got and
/// visited here without another line.
class Message {
 public:
  /// A Hello with default fields.
  constexpr Message() noexcept : type_(MessageType::Hello), body_(Hello{}) {}
  /// Holds `m` (any message struct of AllMessages).
  template <class T>
    requires(AllMessages::contains<T>)
  constexpr Message(const T& m) noexcept : type_(T::type), body_(m) {}  // NOLINT: a message converts to a Message

  /// Which message this is.
  [[nodiscard]] constexpr MessageType type() const noexcept { return type_; }
  /// True if this holds a T.
  template <class T>
  [[nodiscard]] constexpr bool holds() const noexcept {
    return type_ == T::type;
  }
  /// The held T; asking for another type is a contract violation.
  template <class T>
    requires(AllMessages::contains<T>)
  [[nodiscard]] constexpr const T& get() const noexcept {
    CURVESTEP_EXPECTS(type_ == T::type);
    return body_.template get<T>();
  }

 private:
  MessageType type_;
  detail::MessageUnionOf<AllMessages>::type body_;
};

static_assert(std::is_trivially_copyable_v<Message>, "Message is copied as bytes into queues");

/// Calls `visitor(const T&)` with the message held by `m`; returns what the visitor returns.
template <class Visitor>
constexpr decltype(auto) visit(Visitor&& visitor, const Message& m) {
  return AllMessages::select(
      static_cast<std::uint8_t>(m.type()),
      [&]<class T>(std::type_identity<T>) -> decltype(auto) { return visitor(m.get<T>()); },
      [&]() -> decltype(auto) { return visitor(m.get<ErrorReport>()); });  // not reached: a Message holds a known type
}

/// Encodes the payload of whatever `m` holds, if its type is in `Set` (only the encoders of the
/// set's types are instantiated); InvalidArgument (index = type) for a type outside the set.
template <class Set = AllMessages>
[[nodiscard]] constexpr Result<std::size_t> encode(const Message& m, std::span<std::byte> out) noexcept {
  const auto type = static_cast<std::uint8_t>(m.type());
  return Set::select(
      type, [&]<class T>(std::type_identity<T>) -> Result<std::size_t> { return encode(m.get<T>(), out); },
      [type]() -> Result<std::size_t> { return fail(Error::InvalidArgument, type); });
}

/// Decodes a payload of the given raw message type if the type is in `Set` (only the decoders
/// of the set's types are instantiated); UnknownMessage (index = type) for a type outside the
/// set, as for a type this version does not define. A controller decodes HostToController, a
/// host ControllerToHost; the default decodes every type.
template <class Set = AllMessages>
[[nodiscard]] constexpr Result<Message> decode_message(std::uint8_t type, std::span<const std::byte> payload) noexcept {
  return Set::select(
      type,
      [payload]<class T>(std::type_identity<T>) -> Result<Message> {
        const Result<T> result = decode<T>(payload);
        if (!result) return result.failure();
        return Message(result.value());
      },
      [type]() -> Result<Message> { return fail(Error::UnknownMessage, type); });
}

}  // namespace curvestep::protocol
