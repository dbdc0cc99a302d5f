// SPDX-License-Identifier: MIT
// Error codes shared by every curvestep layer: stable numbers, grouped by layer.
#pragma once

#include <cstdint>

namespace curvestep {

/// Why an operation failed. The numbers are stable: they travel over the wire and are listed in
/// docs/errors.md. Groups: 1-49 input and geometry, 50-59 capacity, 60-69 numeric range,
/// 70-99 motion planning and jobs, 100-139 protocol, 140-169 G-code, 170-199 firmware.
enum class Error : std::uint8_t {
  // --- input and geometry (1-49) ---
  EmptyControlPolygon = 1,      ///< a curve needs at least one control point
  ParameterOutOfRange = 2,      ///< curve parameter outside its domain ([0,1] for Bézier)
  NotFinite = 3,                ///< NaN or infinity in an input or a result
  NonPositiveWeight = 4,        ///< rational weight is zero or negative (index names the weight)
  DegenerateCurve = 5,          ///< zero-length tangent, coincident points, zero radius
  InvalidInterval = 6,          ///< parameter interval empty or breakpoints not increasing
  DegreeMismatch = 7,           ///< curves that must share a degree do not
  KnotsNotNondecreasing = 8,    ///< knot vector decreases at the index given
  WrongKnotCount = 9,           ///< knot count is not control points + degree + 1
  KnotMultiplicityTooHigh = 10, ///< interior knot repeated more than degree times
  DegreeTooLow = 11,            ///< degree 0 where a curve of degree >= 1 is needed, or order too small
  TooFewPoints = 12,            ///< fewer data or control points than the construction needs
  SingularSystem = 13,          ///< linear system is singular or too ill-conditioned to solve
  EvenClosedQuadratic = 14,     ///< closed C1 quadratic interpolation needs an odd number of points
  NotContinuous = 15,           ///< segments do not join with the requested continuity
  InvalidTolerance = 16,        ///< tolerance is zero, negative or too small for the scalar type
  InvalidStep = 17,             ///< step size or step count is zero, negative or too large
  InvalidMask = 18,             ///< subdivision mask stencils do not sum to one
  SweepTooLarge = 19,           ///< arc sweep beyond what one segment can represent exactly
  InvalidArgument = 20,         ///< an argument is outside its documented range

  // --- capacity (50-59) ---
  DegreeAboveCapacity = 50, ///< curve degree larger than the type's compile-time maximum
  CapacityExceeded = 51,    ///< more points/segments than the container's compile-time capacity
  QueueFull = 52,           ///< segment or byte queue is full; retry after it drains
  BufferTooSmall = 53,      ///< caller-provided output buffer is too small
  IterationLimit = 54,      ///< adaptive algorithm hit its fixed work limit before reaching tolerance

  // --- numeric range (60-69) ---
  FixedOverflow = 60,  ///< value or intermediate result outside the fixed-point range
  DivisionByZero = 61, ///< division by zero
  StepCountOverflow = 62, ///< step count beyond 32 bits

  // --- motion planning and jobs (70-99) ---
  InvalidLimit = 70,           ///< a machine limit is not finite or outside its documented range
  SegmentsNotConnected = 71,   ///< segment does not start where the previous one ended
  StepRateTooHigh = 72,        ///< job needs more steps per second than the machine allows
  InvalidRate = 73,            ///< control rate outside 100 Hz .. 100 kHz, or one the step timer cannot hold
  UnknownSegmentType = 74,     ///< segment type not known
  InvalidJob = 75,             ///< job file malformed (the message names the field)
  InvalidMachine = 76,         ///< machine file malformed (the message names the field)
  PlannerBusy = 77,            ///< operation not allowed while the planner is running
  NothingQueued = 78,          ///< start requested with an empty queue
  StepsLost = 79,              ///< step/dir edges were lost (the board's edge buffer was full): the machine position is unknown

  // --- protocol (100-139) ---
  BadCrc = 100,              ///< frame CRC does not match
  BadFraming = 101,          ///< COBS decoding failed
  FrameTooLong = 102,        ///< frame exceeds the maximum frame size
  FrameTooShort = 103,       ///< frame shorter than its header
  UnknownMessage = 104,      ///< message type not known
  BadPayload = 105,          ///< payload length or content wrong for its message type
  SequenceError = 106,       ///< sequence number out of window
  VersionMismatch = 107,     ///< protocol versions differ
  LinkTimeout = 108,         ///< no valid frame within the timeout
  NotConnected = 109,        ///< no handshake yet
  RetransmitLimit = 110,     ///< frame retransmitted too often without acknowledgement
  DeviceRestarted = 111,     ///< the device restarted mid-job (handshake seen again)

  // --- G-code (140-169) ---
  GcodeUnsupportedWord = 140,   ///< word not supported (named in the message)
  GcodeBadNumber = 141,         ///< number malformed or out of range
  GcodeMissingWord = 142,       ///< a required word is missing
  GcodeArcRadiusMismatch = 143, ///< arc radius to start and end differ beyond tolerance
  GcodeSplineNotG17 = 144,      ///< G5 family used outside the XY plane
  GcodeSplineNoTangent = 145,   ///< G5 without I J as the first of a series
  GcodeSyntax = 146,            ///< malformed line
  GcodeConflictingWords = 147,  ///< words that cannot appear together
  GcodeNurbsBlock = 148,        ///< G5.2/G5.3 block malformed
  GcodeCannedCycle = 149,       ///< canned cycle words inconsistent (R below Z, Q or P missing, spindle stopped)
  GcodeCutterCompensation = 150, ///< cutter radius compensation impossible (gouge, arc exit move, entry the tool cannot start, tool without diameter, already on)

  // --- firmware (170-199) ---
  InvalidState = 170,      ///< command not allowed in the current machine state
  QueueUnderrun = 171,     ///< the queue ran out of segments (or planned pieces) while moving
  HardFault = 172,         ///< the controller faulted and reported it
  ConfigurationMissing = 173, ///< motion requested before machine configuration
  OutsideTravel = 174,     ///< a segment leaves the configured travel range of an axis (index = axis)
  NotSupported = 175,      ///< this controller cannot do that (FeedOverride without an on-board planner, a machine event on an image built without them)
  TickDeadlineMissed = 176, ///< a control tick started more than the tolerated periods late: its step edges came too late (index = periods late)
  HardLimit = 177,         ///< a limit switch closed while its axis moved toward it: stopped at once (index = switch: 2 x axis, + 1 for max)
};

/// The index of the offending input (control point, weight, knot, segment); `no_index` if none.
inline constexpr std::uint16_t no_index = 0xFFFF;

}  // namespace curvestep
