// SPDX-License-Identifier: MIT
// The machine file's "pen" section (machine_pen.hpp).
#include "machine_pen.hpp"

#include <cmath>
#include <string>

#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/host/csv.hpp>
#include <curvestep/host/wire_value.hpp>

namespace curvestep::host::detail {
namespace {

/// A height in mm on the Q16.16 grid (the wire's), or a LoadError naming the field.
double height(const Reader& reader, const Node& node) {
  const double value = reader.number(node);  // finite
  const auto q = Q16_16::from_double(value);
  if (!q) reader.fail(node, "value " + format_number(value) + " mm is outside the Q16.16 range (-32768 to 32768 mm)", Error::FixedOverflow);
  return q.value().to_double();
}

/// A number within [low, high], or a LoadError naming the field and the range.
double within(const Reader& reader, const Node& node, double low, double high, const char* unit) {
  const double value = reader.number(node);
  if (!(value >= low && value <= high)) {
    reader.fail(node, "value " + format_number(value) + " " + unit + " is outside " + format_number(low) + " .. " + format_number(high));
  }
  return value;
}

/// {"axis": "servo", "line": NAME, "up_pulse_us": US, "down_pulse_us": US, "settle": S}.
PenModel parse_servo_pen(const Reader& reader, const Node& pen) {
  reader.check_keys(pen, {"axis", "line", "up_pulse_us", "down_pulse_us", "settle"});
  PenModel model;
  model.servo = true;
  const Node line = reader.require(pen, "line");
  model.line = reader.string(line);
  if (model.line.empty()) reader.fail(line, "the servo's line name is empty");
  model.up_pulse_us = within(reader, reader.require(pen, "up_pulse_us"), 500, 2500, "us");
  const Node down = reader.require(pen, "down_pulse_us");
  model.down_pulse_us = within(reader, down, 500, 2500, "us");
  if (model.up_pulse_us == model.down_pulse_us) {
    reader.fail(down, "value " + format_number(model.down_pulse_us) + " equals \"up_pulse_us\" (the servo must move between them)");
  }
  model.settle_s = within(reader, reader.require(pen, "settle"), 0, 10, "s");
  return model;
}

}  // namespace

PenModel parse_pen(const Reader& reader, const Node& pen) {
  if (const auto axis = reader.optional(pen, "axis")) {
    const std::string name = reader.string(*axis);
    if (name == "servo") return parse_servo_pen(reader, pen);
    if (name != "z") reader.fail(*axis, "unsupported pen axis \"" + name + "\" (\"z\" or \"servo\")");
  }
  reader.check_keys(pen, {"axis", "up", "down", "feed"});
  PenModel model;
  model.up_mm = height(reader, reader.require(pen, "up"));
  const Node down = reader.require(pen, "down");
  model.down_mm = height(reader, down);
  if (model.up_mm == model.down_mm) {
    reader.fail(down, "value " + format_number(model.down_mm) + " equals \"up\" (the pen must move between them)");
  }
  const Node feed = reader.require(pen, "feed");
  const double value = reader.positive(feed);
  const auto rounded = round_for_wire(value, WireQuantity::Feed);
  if (!rounded) reader.fail(feed, rounded.problem, rounded.code);
  model.feed_mm_per_s = rounded.value;
  return model;
}

}  // namespace curvestep::host::detail
