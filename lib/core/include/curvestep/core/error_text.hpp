// SPDX-License-Identifier: MIT
// describe(Error): one sentence per error code, for host tools and logs. Firmware sends only the
// number (keep this header off the MCU unless its flash can afford the strings).
#pragma once

#include <string_view>

#include <curvestep/core/error.hpp>

namespace curvestep {

/// The symbolic name of an error code ("ParameterOutOfRange"); "Unknown" for unlisted values.
[[nodiscard]] constexpr std::string_view error_name(Error e) noexcept {
  switch (e) {
    case Error::EmptyControlPolygon: return "EmptyControlPolygon";
    case Error::ParameterOutOfRange: return "ParameterOutOfRange";
    case Error::NotFinite: return "NotFinite";
    case Error::NonPositiveWeight: return "NonPositiveWeight";
    case Error::DegenerateCurve: return "DegenerateCurve";
    case Error::InvalidInterval: return "InvalidInterval";
    case Error::DegreeMismatch: return "DegreeMismatch";
    case Error::KnotsNotNondecreasing: return "KnotsNotNondecreasing";
    case Error::WrongKnotCount: return "WrongKnotCount";
    case Error::KnotMultiplicityTooHigh: return "KnotMultiplicityTooHigh";
    case Error::DegreeTooLow: return "DegreeTooLow";
    case Error::TooFewPoints: return "TooFewPoints";
    case Error::SingularSystem: return "SingularSystem";
    case Error::EvenClosedQuadratic: return "EvenClosedQuadratic";
    case Error::NotContinuous: return "NotContinuous";
    case Error::InvalidTolerance: return "InvalidTolerance";
    case Error::InvalidStep: return "InvalidStep";
    case Error::InvalidMask: return "InvalidMask";
    case Error::SweepTooLarge: return "SweepTooLarge";
    case Error::InvalidArgument: return "InvalidArgument";
    case Error::DegreeAboveCapacity: return "DegreeAboveCapacity";
    case Error::CapacityExceeded: return "CapacityExceeded";
    case Error::QueueFull: return "QueueFull";
    case Error::BufferTooSmall: return "BufferTooSmall";
    case Error::IterationLimit: return "IterationLimit";
    case Error::FixedOverflow: return "FixedOverflow";
    case Error::DivisionByZero: return "DivisionByZero";
    case Error::StepCountOverflow: return "StepCountOverflow";
    case Error::InvalidLimit: return "InvalidLimit";
    case Error::SegmentsNotConnected: return "SegmentsNotConnected";
    case Error::StepRateTooHigh: return "StepRateTooHigh";
    case Error::InvalidRate: return "InvalidRate";
    case Error::UnknownSegmentType: return "UnknownSegmentType";
    case Error::InvalidJob: return "InvalidJob";
    case Error::InvalidMachine: return "InvalidMachine";
    case Error::PlannerBusy: return "PlannerBusy";
    case Error::NothingQueued: return "NothingQueued";
    case Error::BadCrc: return "BadCrc";
    case Error::BadFraming: return "BadFraming";
    case Error::FrameTooLong: return "FrameTooLong";
    case Error::FrameTooShort: return "FrameTooShort";
    case Error::UnknownMessage: return "UnknownMessage";
    case Error::BadPayload: return "BadPayload";
    case Error::SequenceError: return "SequenceError";
    case Error::VersionMismatch: return "VersionMismatch";
    case Error::LinkTimeout: return "LinkTimeout";
    case Error::NotConnected: return "NotConnected";
    case Error::RetransmitLimit: return "RetransmitLimit";
    case Error::DeviceRestarted: return "DeviceRestarted";
    case Error::GcodeUnsupportedWord: return "GcodeUnsupportedWord";
    case Error::GcodeBadNumber: return "GcodeBadNumber";
    case Error::GcodeMissingWord: return "GcodeMissingWord";
    case Error::GcodeArcRadiusMismatch: return "GcodeArcRadiusMismatch";
    case Error::GcodeSplineNotG17: return "GcodeSplineNotG17";
    case Error::GcodeSplineNoTangent: return "GcodeSplineNoTangent";
    case Error::GcodeSyntax: return "GcodeSyntax";
    case Error::GcodeConflictingWords: return "GcodeConflictingWords";
    case Error::GcodeNurbsBlock: return "GcodeNurbsBlock";
    case Error::InvalidState: return "InvalidState";
    case Error::QueueUnderrun: return "QueueUnderrun";
    case Error::HardFault: return "HardFault";
    case Error::ConfigurationMissing: return "ConfigurationMissing";
  }
  return "Unknown";
}

/// What the error code means, as one lower-case phrase; "unknown error" for unlisted values.
[[nodiscard]] constexpr std::string_view describe(Error e) noexcept {
  switch (e) {
    case Error::EmptyControlPolygon: return "a curve needs at least one control point";
    case Error::ParameterOutOfRange: return "curve parameter outside its domain ([0,1] for Bézier)";
    case Error::NotFinite: return "NaN or infinity in an input or a result";
    case Error::NonPositiveWeight: return "rational weight is zero or negative (index names the weight)";
    case Error::DegenerateCurve: return "zero-length tangent, coincident points, zero radius";
    case Error::InvalidInterval: return "parameter interval empty or breakpoints not increasing";
    case Error::DegreeMismatch: return "curves that must share a degree do not";
    case Error::KnotsNotNondecreasing: return "knot vector decreases at the index given";
    case Error::WrongKnotCount: return "knot count is not control points + degree + 1";
    case Error::KnotMultiplicityTooHigh: return "interior knot repeated more than degree times";
    case Error::DegreeTooLow: return "degree 0 where a curve of degree >= 1 is needed, or order too small";
    case Error::TooFewPoints: return "fewer data or control points than the construction needs";
    case Error::SingularSystem: return "linear system is singular or too ill-conditioned to solve";
    case Error::EvenClosedQuadratic: return "closed C1 quadratic interpolation needs an odd number of points";
    case Error::NotContinuous: return "segments do not join with the requested continuity";
    case Error::InvalidTolerance: return "tolerance is zero, negative or too small for the scalar type";
    case Error::InvalidStep: return "step size or step count is zero, negative or too large";
    case Error::InvalidMask: return "subdivision mask stencils do not sum to one";
    case Error::SweepTooLarge: return "arc sweep beyond what one segment can represent exactly";
    case Error::InvalidArgument: return "an argument is outside its documented range";
    case Error::DegreeAboveCapacity: return "curve degree larger than the type's compile-time maximum";
    case Error::CapacityExceeded: return "more points/segments than the container's compile-time capacity";
    case Error::QueueFull: return "segment or byte queue is full; retry after it drains";
    case Error::BufferTooSmall: return "caller-provided output buffer is too small";
    case Error::IterationLimit: return "adaptive algorithm hit its fixed work limit before reaching tolerance";
    case Error::FixedOverflow: return "value or intermediate result outside the fixed-point range";
    case Error::DivisionByZero: return "division by zero";
    case Error::StepCountOverflow: return "step count beyond 32 bits";
    case Error::InvalidLimit: return "velocity/acceleration/jerk/feed limit is not positive or not finite";
    case Error::SegmentsNotConnected: return "segment does not start where the previous one ended";
    case Error::StepRateTooHigh: return "job needs more steps per second than the machine allows";
    case Error::InvalidRate: return "control rate outside 100 Hz .. 100 kHz";
    case Error::UnknownSegmentType: return "segment type not known";
    case Error::InvalidJob: return "job file malformed (the message names the field)";
    case Error::InvalidMachine: return "machine file malformed (the message names the field)";
    case Error::PlannerBusy: return "operation not allowed while the planner is running";
    case Error::NothingQueued: return "start requested with an empty queue";
    case Error::BadCrc: return "frame CRC does not match";
    case Error::BadFraming: return "COBS decoding failed";
    case Error::FrameTooLong: return "frame exceeds the maximum frame size";
    case Error::FrameTooShort: return "frame shorter than its header";
    case Error::UnknownMessage: return "message type not known";
    case Error::BadPayload: return "payload length or content wrong for its message type";
    case Error::SequenceError: return "sequence number out of window";
    case Error::VersionMismatch: return "protocol versions differ";
    case Error::LinkTimeout: return "no valid frame within the timeout";
    case Error::NotConnected: return "no handshake yet";
    case Error::RetransmitLimit: return "frame retransmitted too often without acknowledgement";
    case Error::DeviceRestarted: return "the device restarted mid-job (handshake seen again)";
    case Error::GcodeUnsupportedWord: return "word not supported (named in the message)";
    case Error::GcodeBadNumber: return "number malformed or out of range";
    case Error::GcodeMissingWord: return "a required word is missing";
    case Error::GcodeArcRadiusMismatch: return "arc radius to start and end differ beyond tolerance";
    case Error::GcodeSplineNotG17: return "G5 family used outside the XY plane";
    case Error::GcodeSplineNoTangent: return "G5 without I J as the first of a series";
    case Error::GcodeSyntax: return "malformed line";
    case Error::GcodeConflictingWords: return "words that cannot appear together";
    case Error::GcodeNurbsBlock: return "G5.2/G5.3 block malformed";
    case Error::InvalidState: return "command not allowed in the current machine state";
    case Error::QueueUnderrun: return "planner ran out of segments while moving";
    case Error::HardFault: return "the controller faulted and reported it";
    case Error::ConfigurationMissing: return "motion requested before machine configuration";
  }
  return "unknown error";
}

/// Every defined error code, in numeric order (for documentation and tests).
inline constexpr Error all_errors[] = {
    Error::EmptyControlPolygon,
    Error::ParameterOutOfRange,
    Error::NotFinite,
    Error::NonPositiveWeight,
    Error::DegenerateCurve,
    Error::InvalidInterval,
    Error::DegreeMismatch,
    Error::KnotsNotNondecreasing,
    Error::WrongKnotCount,
    Error::KnotMultiplicityTooHigh,
    Error::DegreeTooLow,
    Error::TooFewPoints,
    Error::SingularSystem,
    Error::EvenClosedQuadratic,
    Error::NotContinuous,
    Error::InvalidTolerance,
    Error::InvalidStep,
    Error::InvalidMask,
    Error::SweepTooLarge,
    Error::InvalidArgument,
    Error::DegreeAboveCapacity,
    Error::CapacityExceeded,
    Error::QueueFull,
    Error::BufferTooSmall,
    Error::IterationLimit,
    Error::FixedOverflow,
    Error::DivisionByZero,
    Error::StepCountOverflow,
    Error::InvalidLimit,
    Error::SegmentsNotConnected,
    Error::StepRateTooHigh,
    Error::InvalidRate,
    Error::UnknownSegmentType,
    Error::InvalidJob,
    Error::InvalidMachine,
    Error::PlannerBusy,
    Error::NothingQueued,
    Error::BadCrc,
    Error::BadFraming,
    Error::FrameTooLong,
    Error::FrameTooShort,
    Error::UnknownMessage,
    Error::BadPayload,
    Error::SequenceError,
    Error::VersionMismatch,
    Error::LinkTimeout,
    Error::NotConnected,
    Error::RetransmitLimit,
    Error::DeviceRestarted,
    Error::GcodeUnsupportedWord,
    Error::GcodeBadNumber,
    Error::GcodeMissingWord,
    Error::GcodeArcRadiusMismatch,
    Error::GcodeSplineNotG17,
    Error::GcodeSplineNoTangent,
    Error::GcodeSyntax,
    Error::GcodeConflictingWords,
    Error::GcodeNurbsBlock,
    Error::InvalidState,
    Error::QueueUnderrun,
    Error::HardFault,
    Error::ConfigurationMissing,
};

}  // namespace curvestep
