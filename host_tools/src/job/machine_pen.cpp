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

}  // namespace

PenModel parse_pen(const Reader& reader, const Node& pen) {
  reader.check_keys(pen, {"axis", "up", "down", "feed"});
  if (const auto axis = reader.optional(pen, "axis")) {
    const std::string name = reader.string(*axis);
    if (name != "z") reader.fail(*axis, "unsupported pen axis \"" + name + "\" (only \"z\"; a servo pen is not supported)");
  }
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
