// SPDX-License-Identifier: MIT
// Swept extent of a job's segments, checked at load time.
//
// Why: the loaders check the numbers a file gives (end points, centres, control points), but an
// arc's circle can reach far past them: `G3 I29991` has its ends and centre in range and sweeps to
// 60 000 mm. The controller works in Q16.16 and refuses such a segment only when it reaches it, so
// the machine would stop halfway through the job. Each segment's box is computed exactly where that
// is cheap (lines, arcs: the circle's extremes lie at the axis-direction angles inside the sweep)
// and conservatively for Béziers (the control points' hull holds the curve), and checked here once.
#include <curvestep/host/swept_extent.hpp>

#include <curvestep/core/motion/segment_bounds.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <functional>
#include <string>

#include <curvestep/host/csv.hpp>
#include <curvestep/host/load_error.hpp>

namespace curvestep::host {
namespace {

/// The Q16.16 range in mm: [-2^15, 2^15 - 2^-16].
constexpr double q16_low = -32768.0;
constexpr double q16_high = 32768.0 - 1.0 / 65536.0;

/// "x = 59982 mm" for the first coordinate of `box` outside the Q16.16 range, empty if none.
std::string outside_q16(const SweptBox& box) {
  constexpr const char* names[] = {"x", "y", "z"};
  for (std::size_t axis = 0; axis < motion_axes; ++axis) {
    if (!(box.low[axis] >= q16_low)) return std::string(names[axis]) + " = " + format_number(box.low[axis]) + " mm";
    if (!(box.high[axis] <= q16_high)) return std::string(names[axis]) + " = " + format_number(box.high[axis]) + " mm";
  }
  return {};
}

std::string_view kind_name(SegmentKind kind) {
  switch (kind) {
    case SegmentKind::Arc: return "arc";
    case SegmentKind::RationalBezier: return "rational Bezier";
    default: return "curve";
  }
}

}  // namespace

SweptBox swept_box(const PathSegment& segment) { return segment_bounds(segment); }

namespace {

/// The first axis along which `box` leaves `travel`, and whether below it.
struct TravelBreach {
  std::size_t axis = 0;
  bool below = false;
};
std::optional<TravelBreach> first_breach(const SweptBox& box, const MachineTravel& travel) {
  for (std::size_t axis = 0; axis < motion_axes; ++axis) {
    if (!travel[axis]) continue;
    if (box.low[axis] < travel[axis]->low_mm) return TravelBreach{axis, true};
    if (box.high[axis] > travel[axis]->high_mm) return TravelBreach{axis, false};
  }
  return std::nullopt;
}

void check_travel(const PathSegment& segment, const MachineTravel& travel, const std::string& machine_file,
                  const std::function<SourceLocation()>& where) {
  constexpr const char* names[] = {"x", "y", "z"};
  const SweptBox box = swept_box(segment);
  const std::optional<TravelBreach> breach = first_breach(box, travel);
  if (!breach) return;
  const std::size_t axis = breach->axis;
  const AxisTravel& range = *travel[axis];
  const double reached = breach->below ? box.low[axis] : box.high[axis];
  const double beyond = breach->below ? range.low_mm - reached : reached - range.high_mm;
  throw LoadError(where(),
                  "the " + std::string(kind_name(segment.kind())) + " reaches " + names[axis] + " = " + format_number(reached) +
                      " mm, " + format_number(beyond) + " mm " + (breach->below ? "below" : "beyond") + " the machine's travel " +
                      format_number(range.low_mm) + " .. " + format_number(range.high_mm) + " mm (\"axes\".\"" + names[axis] +
                      "\".\"travel\" in " + machine_file + ")",
                  Error::OutsideTravel);
}

}  // namespace

void check_travel(const Job& job, const MachineTravel& travel, const std::string& machine_file) {
  for (std::size_t k = 0; k < job.segments.size(); ++k) {
    check_travel(job.segments[k], travel, machine_file, [&] { return piece_location(job, k); });
  }
}

void check_travel(const PathSegment& segment, const Job& job, std::size_t source, const MachineTravel& travel,
                  const std::string& machine_file) {
  check_travel(segment, travel, machine_file, [&] { return source_location(job, source); });
}

bool within_travel(const PathSegment& segment, const MachineTravel& travel) {
  return !first_breach(swept_box(segment), travel).has_value();
}

namespace {

void check_swept_extent(const PathSegment& segment, const std::function<SourceLocation()>& where) {
  const std::string outside = outside_q16(swept_box(segment));
  if (outside.empty()) return;
  throw LoadError(where(),
                  "the " + std::string(kind_name(segment.kind())) + " reaches " + outside +
                      ", outside the Q16.16 range (-32768 to 32768 mm) the controller works in",
                  Error::FixedOverflow);
}

}  // namespace

void check_swept_extent(const Job& job) {
  for (std::size_t k = 0; k < job.segments.size(); ++k) check_swept_extent(job.segments[k], [&] { return piece_location(job, k); });
}

void check_swept_extent(const PathSegment& segment, const Job& job, std::size_t source) {
  check_swept_extent(segment, [&] { return source_location(job, source); });
}

}  // namespace curvestep::host
