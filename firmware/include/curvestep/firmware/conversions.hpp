// SPDX-License-Identifier: MIT
// Wire messages to planner inputs: MachineConfiguration -> MachineLimits, QueueSegment -> PathSegment,
// QueuePiece -> PlannedPiece (a board without a planner).
//
// Both conversions are exact: a Q16.16 raw value r becomes the double r / 65536, which a double
// holds exactly, and the configuration's binary64 limits are the host's doubles bit for bit. A host that
// wants to predict the firmware bit for bit (curvestep sim, curvestep stream --compare) calls
// these same functions on the messages it sends, so both ends plan from identical numbers.
#pragma once

#include <array>
#include <cstddef>
#include <cmath>
#include <cstdint>
#include <span>

#include <curvestep/core/motion/deterministic_math.hpp>
#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/core/motion/path_segment.hpp>
#include <curvestep/core/motion/segment_bounds.hpp>
#include <curvestep/core/motion/planned_piece.hpp>
#include <curvestep/core/result.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::firmware {

/// Largest difference of the start and end radii of a wire arc, in mm (as the host's job loader).
inline constexpr double arc_radius_tolerance_mm = 0.002;

/// A Q16.16 raw value in millimetres as a double (exact).
[[nodiscard]] constexpr double wire_to_mm(std::int32_t raw) noexcept { return static_cast<double>(raw) / 65536.0; }

/// A wire point as a machine point; with two axes Z is 0.
[[nodiscard]] constexpr MachinePoint wire_to_point(const protocol::WirePoint& p, std::size_t axes) noexcept {
  MachinePoint out{};
  for (std::size_t a = 0; a < axes && a < motion_axes; ++a) out[a] = wire_to_mm(p[a]);
  return out;
}

/// A machine point as a wire point (Q16.16 raw, rounded as a Q16.16 setpoint is); the error of
/// from_double<Q16_16> (index = axis) if a coordinate does not fit.
[[nodiscard]] inline Result<protocol::WirePoint> to_wire_point(const MachinePoint& p) noexcept {
  protocol::WirePoint out{};
  for (std::size_t a = 0; a < motion_axes && a < protocol::max_axes; ++a) {
    const auto q = from_double<Q16_16>(p[a]);
    if (!q) return fail(q.error(), static_cast<std::uint16_t>(a));
    out[a] = q.value().raw();
  }
  return out;
}

/// A decoded QueuePiece as the executor's PlannedPiece (the binary64 values are the host's doubles,
/// so the replay is the host's plan bit for bit).
[[nodiscard]] constexpr PlannedPiece to_planned_piece(const protocol::QueuePiece& m) noexcept {
  PlannedPiece piece;
  piece.ticks = m.ticks;
  piece.segment = m.segment;
  piece.end_of_job = m.end_of_job;
  piece.exact_run = m.exact_run;
  piece.rest = m.rest;
  for (std::size_t a = 0; a < motion_axes && a < protocol::max_axes; ++a) {
    piece.end[a] = m.end[a];
    for (std::size_t i = 0; i < m.controls.size(); ++i) piece.controls[i][a] = m.controls[i][a];
  }
  return piece;
}

/// The planner's limits from a MachineConfiguration; every value is checked by MachineLimits::validate
/// (InvalidLimit, InvalidRate with the LimitField as index). Travel limits are not planning data.
[[nodiscard]] constexpr Result<MachineLimits> to_machine_limits(const protocol::MachineConfiguration& c) noexcept {
  if (c.axis_count != 2 && c.axis_count != 3) return fail(Error::InvalidArgument, 0);
  MachineLimits m;
  m.v_max_mm_per_s = c.max_velocity_mm_per_s;
  m.a_max_mm_per_s2 = c.max_acceleration_mm_per_s2;
  m.j_max_mm_per_s3 = c.max_jerk_mm_per_s3;
  m.feed_mm_per_s = wire_to_mm(c.default_feed_mm_per_s);
  m.rapid_mm_per_s = wire_to_mm(c.rapid_mm_per_s);
  m.tolerance_mm = c.tolerance_mm;
  m.junction_deviation_mm = c.junction_deviation_mm;
  m.max_step_rate_hz = c.max_step_rate_hz;
  m.jerk_limited = c.profile == protocol::ProfileKind::SCurve;
  m.rate_hz = static_cast<double>(c.control_rate_hz);
  for (std::size_t a = 0; a < c.axis_count; ++a) {
    m.axes[a].steps_per_mm = c.axes[a].steps_per_mm;
    m.axes[a].v_max_mm_per_s = c.axes[a].max_velocity_mm_per_s;
    m.axes[a].a_max_mm_per_s2 = c.axes[a].max_acceleration_mm_per_s2;
  }
  CURVESTEP_CHECK(m.validate());
  return m;
}

/// Where a wire segment starts (its first point).
[[nodiscard]] constexpr protocol::WirePoint segment_start(const protocol::QueueSegment& s) noexcept {
  return s.points[0];
}

/// Where a wire segment ends (Arc: the second point; others: the last point).
[[nodiscard]] constexpr protocol::WirePoint segment_end(const protocol::QueueSegment& s) noexcept {
  if (s.kind == protocol::SegmentKind::Arc) return s.points[1];
  return s.points[s.point_count() - 1];
}

/// The planner's segment for a wire segment: geometry, rapid flag and feed. Errors from the
/// PathSegment::make_* validators (DegenerateCurve, InvalidArgument for arc radii that differ by
/// more than arc_radius_tolerance_mm, ...); InvalidLimit (LimitField::Feed) for a feed <= 0.
[[nodiscard, gnu::noinline]] inline Result<PathSegment> to_path_segment(const protocol::QueueSegment& s) noexcept {
  const std::size_t axes = s.axis_count;
  std::array<MachinePoint, protocol::max_segment_degree + 1> points{};
  const std::size_t count = s.point_count();
  for (std::size_t i = 0; i < count; ++i) points[i] = wire_to_point(s.points[i], axes);
  Result<PathSegment> made = fail(Error::UnknownSegmentType, static_cast<std::size_t>(s.kind));
  switch (s.kind) {
    case protocol::SegmentKind::Line: made = PathSegment::make_line(points[0], points[1]); break;
    case protocol::SegmentKind::Arc:
      made = PathSegment::make_arc(points[0], points[1], wire_to_point(s.points[2], 2), s.direction, s.turns,
                                   arc_radius_tolerance_mm);
      break;
    case protocol::SegmentKind::Bezier:
      made = PathSegment::make_bezier(std::span<const MachinePoint>(points.data(), count));
      break;
    case protocol::SegmentKind::RationalBezier: {
      std::array<double, protocol::max_segment_degree + 1> weights{};
      for (std::size_t i = 0; i < count; ++i) weights[i] = wire_to_mm(s.weights[i]);
      made = PathSegment::make_rational_bezier(std::span<const MachinePoint>(points.data(), count),
                                               std::span<const double>(weights.data(), count));
      break;
    }
  }
  // The segment is finished inside `made` and returned by name: no second copy on the stack.
  if (made) {
    made.value().set_rapid(s.rapid);
    if (s.has_feed) {
      if (s.feed_mm_per_s <= 0) {
        made = fail(Error::InvalidLimit, static_cast<std::size_t>(LimitField::Feed));
      } else {
        made.value().set_feed_mm_per_s(wire_to_mm(s.feed_mm_per_s));
      }
    }
  }
  return made;
}

/// Travel range of one axis in mm; min == max == 0 means the axis is not limited.
struct TravelRange {
  double min_mm = 0;  ///< lowest position
  double max_mm = 0;  ///< highest position

  /// False for the "not limited" range (0, 0).
  [[nodiscard]] constexpr bool limited() const noexcept { return !(min_mm == 0 && max_mm == 0); }
};

/// Travel ranges of x, y, z (axes beyond the configuration's axis count are not limited).
using TravelLimits = std::array<TravelRange, motion_axes>;

/// The travel ranges of a MachineConfiguration; InvalidArgument (index = byte offset of the axis'
/// min_position_mm field: 62 + 32 k + 24) if min > max.
[[nodiscard]] constexpr Result<TravelLimits> to_travel_limits(const protocol::MachineConfiguration& c) noexcept {
  TravelLimits travel{};
  for (std::size_t a = 0; a < c.axis_count && a < motion_axes; ++a) {
    if (c.axes[a].min_position_mm > c.axes[a].max_position_mm) {
      return fail(Error::InvalidArgument,
                  protocol::configuration_header_size + protocol::configuration_axis_size * a + 24);
    }
    travel[a] = TravelRange{wire_to_mm(c.axes[a].min_position_mm), wire_to_mm(c.axes[a].max_position_mm)};
  }
  return travel;
}

/// OutsideTravel (index = axis) if the box `b` leaves a limited axis' travel range.
[[nodiscard]] constexpr Result<void> check_travel(const SegmentBounds& b, const TravelLimits& travel) noexcept {
  for (std::size_t a = 0; a < motion_axes; ++a) {
    if (!travel[a].limited()) continue;
    if (b.low[a] < travel[a].min_mm || b.high[a] > travel[a].max_mm) return fail(Error::OutsideTravel, a);
  }
  return ok();
}

/// OutsideTravel (index = axis) if the segment's bounds leave a limited axis' travel range.
[[nodiscard]] inline Result<void> check_travel(const PathSegment& s, const TravelLimits& travel) noexcept {
  return check_travel(segment_bounds(s), travel);
}

/// OutsideTravel (index = axis) if the point `p` (an exact setpoint of a planned piece) leaves a
/// limited axis' travel range.
[[nodiscard]] constexpr Result<void> check_travel(const MachinePoint& p, const TravelLimits& travel) noexcept {
  return check_travel(SegmentBounds{p, p}, travel);
}

}  // namespace curvestep::firmware
