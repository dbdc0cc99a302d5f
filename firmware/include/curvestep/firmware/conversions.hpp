// SPDX-License-Identifier: MIT
// Wire messages to planner inputs: MachineConfiguration -> MachineLimits, QueueSegment -> PathSegment.
//
// Both conversions are exact: a Q16.16 raw value r becomes the double r / 65536, which a double
// holds exactly, and whole-number accelerations and jerks become doubles exactly. A host that
// wants to predict the firmware bit for bit (curvestep sim, curvestep stream --compare) calls
// these same functions on the messages it sends, so both ends plan from identical numbers.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/core/motion/path_segment.hpp>
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

/// The planner's limits from a MachineConfiguration; every value is checked by MachineLimits::validate
/// (InvalidLimit, InvalidRate with the LimitField as index). Travel limits are not planning data.
[[nodiscard]] constexpr Result<MachineLimits> to_machine_limits(const protocol::MachineConfiguration& c) noexcept {
  if (c.axis_count != 2 && c.axis_count != 3) return fail(Error::InvalidArgument, 0);
  MachineLimits m;
  m.v_max_mm_per_s = wire_to_mm(c.max_velocity_mm_per_s);
  m.a_max_mm_per_s2 = static_cast<double>(c.max_acceleration_mm_per_s2);
  m.j_max_mm_per_s3 = static_cast<double>(c.max_jerk_mm_per_s3);
  m.feed_mm_per_s = wire_to_mm(c.default_feed_mm_per_s);
  m.tolerance_mm = wire_to_mm(c.tolerance_mm);
  m.junction_deviation_mm = wire_to_mm(c.junction_deviation_mm);
  m.rate_hz = static_cast<double>(c.control_rate_hz);
  for (std::size_t a = 0; a < c.axis_count; ++a) {
    m.axes[a].steps_per_mm = wire_to_mm(c.axes[a].steps_per_mm);
    m.axes[a].v_max_mm_per_s = wire_to_mm(c.axes[a].max_velocity_mm_per_s);
    m.axes[a].a_max_mm_per_s2 = static_cast<double>(c.axes[a].max_acceleration_mm_per_s2);
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
[[nodiscard]] inline Result<PathSegment> to_path_segment(const protocol::QueueSegment& s) noexcept {
  const std::size_t axes = s.axis_count;
  std::array<MachinePoint, protocol::max_segment_degree + 1> points{};
  const std::size_t count = s.point_count();
  for (std::size_t i = 0; i < count; ++i) points[i] = wire_to_point(s.points[i], axes);
  Result<PathSegment> made = fail(Error::UnknownSegmentType, static_cast<std::size_t>(s.kind));
  switch (s.kind) {
    case protocol::SegmentKind::Line: made = PathSegment::make_line(points[0], points[1]); break;
    case protocol::SegmentKind::Arc:
      made = PathSegment::make_arc(points[0], points[1], wire_to_point(s.points[2], 2), s.direction, 0,
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
  if (!made) return made;
  PathSegment segment = made.value();
  segment.set_rapid(s.rapid);
  if (s.has_feed) {
    if (s.feed_mm_per_s <= 0) return fail(Error::InvalidLimit, static_cast<std::size_t>(LimitField::Feed));
    segment.set_feed_mm_per_s(wire_to_mm(s.feed_mm_per_s));
  }
  return segment;
}

}  // namespace curvestep::firmware
