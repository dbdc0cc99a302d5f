// SPDX-License-Identifier: MIT
#include "machine_homing.hpp"

#include <array>
#include <cmath>
#include <string>

#include <curvestep/host/csv.hpp>

namespace curvestep::host::detail {
namespace {

constexpr std::array<const char*, motion_axes> axis_names{"x", "y", "z"};

/// A length inside the Q16.16 range, mm; `positive`: also > 0.
double length(const Reader& reader, const Node& node, bool positive) {
  const double value = positive ? reader.positive(node) : reader.number(node);
  if (!(std::fabs(value) <= 32767.0)) reader.fail(node, "value " + format_number(value) + " mm is outside -32767 .. 32767 mm");
  return value;
}

HomingAxis parse_axis(const Reader& reader, const Node& entry, std::size_t axis, const MachineTravel& travel) {
  reader.check_keys(entry, {"switch", "seek", "locate", "pull_off", "position", "distance"});
  HomingAxis a;
  const Node side = reader.require(entry, "switch");
  const std::string name = reader.string(side);
  if (name != "min" && name != "max") reader.fail(side, "expected \"min\" or \"max\" (the switch homing seeks), got \"" + name + "\"");
  a.max_side = name == "max";
  a.seek_mm_per_s = reader.positive(reader.require(entry, "seek"));
  const Node locate = reader.require(entry, "locate");
  a.locate_mm_per_s = reader.positive(locate);
  if (a.locate_mm_per_s > a.seek_mm_per_s) {
    reader.fail(locate, "value " + format_number(a.locate_mm_per_s) + " mm/s is above \"seek\" (" + format_number(a.seek_mm_per_s) +
                            " mm/s): the second approach is the slow, precise one");
  }
  a.pull_off_mm = length(reader, reader.require(entry, "pull_off"), true);
  if (const auto position = reader.optional(entry, "position")) a.position_mm = length(reader, *position, false);
  if (const auto distance = reader.optional(entry, "distance")) {
    a.distance_mm = length(reader, *distance, true);
  } else if (travel[axis]) {
    a.distance_mm = 1.5 * (travel[axis]->high_mm - travel[axis]->low_mm);
  } else {
    reader.fail(entry, std::string("no \"distance\" (the longest seek, mm) and no \"axes\".\"") + axis_names[axis] +
                           "\".\"travel\" to derive it from");
  }
  return a;
}

}  // namespace

HomingCycle parse_homing(const Reader& reader, const Node& homing, const MachineTravel& travel) {
  reader.check_keys(homing, {"order", "x", "y", "z"});
  HomingCycle cycle;
  for (std::size_t axis = 0; axis < motion_axes; ++axis) {
    if (const auto entry = reader.optional(homing, axis_names[axis])) cycle.axes[axis] = parse_axis(reader, *entry, axis, travel);
  }
  if (const auto order = reader.optional(homing, "order")) {
    for (const Node& item : reader.array(*order, 1, motion_axes)) {
      const std::string name = reader.string(item);
      std::size_t axis = 0;
      while (axis < motion_axes && name != axis_names[axis]) ++axis;
      if (axis == motion_axes || !cycle.axes[axis]) {
        reader.fail(item, "\"" + name + "\" is no axis of the \"homing\" section (\"x\", \"y\", \"z\" with an entry)");
      }
      for (const std::size_t earlier : cycle.order) {
        if (earlier == axis) reader.fail(item, "axis \"" + name + "\" is listed twice");
      }
      cycle.order.push_back(axis);
    }
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      bool listed = false;
      for (const std::size_t a : cycle.order) listed = listed || a == axis;
      if (cycle.axes[axis] && !listed) reader.fail(*order, std::string("axis \"") + axis_names[axis] + "\" homes but is not in the order");
    }
  } else {
    for (const std::size_t axis : {std::size_t{2}, std::size_t{0}, std::size_t{1}}) {
      if (cycle.axes[axis]) cycle.order.push_back(axis);  // z first (clear of the work), then x, y
    }
  }
  if (cycle.order.empty()) reader.fail(homing, "homes no axis (expected at least one of \"x\", \"y\", \"z\")");
  return cycle;
}

}  // namespace curvestep::host::detail
