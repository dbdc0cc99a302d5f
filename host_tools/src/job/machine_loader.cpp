// SPDX-License-Identifier: MIT
// Machine files: JSON -> MachineLimits, validated, with errors that name the key.
#include <curvestep/host/machine_file.hpp>

#include <array>
#include <cmath>
#include <map>
#include <string>

#include <curvestep/core/error_text.hpp>
#include <curvestep/host/csv.hpp>
#include <curvestep/host/job.hpp>

#include "json_document.hpp"
#include "machine_pen.hpp"

namespace curvestep::host {
namespace {

using detail::Node;
using detail::Reader;

constexpr std::array<const char*, motion_axes> axis_names{"x", "y", "z"};

/// The node a LimitField names, for the error's line.
Node limit_node(const Node& root, LimitField field, std::size_t axis) {
  switch (field) {
    case LimitField::AxisStepsPerMm: return root.member("axes").member(axis_names[axis]).member("steps_per_mm");
    case LimitField::AxisVMax: return root.member("axes").member(axis_names[axis]).member("v_max");
    case LimitField::AxisAMax: return root.member("axes").member(axis_names[axis]).member("a_max");
    default: return root.member(machine_field_name(field).substr(1, machine_field_name(field).size() - 2));
  }
}

/// Whether zero is a valid value of `field` (it then means "none" or "no separate limit"); the
/// ranges of the others are the core's limit_range() (MachineLimits::validate, docs/errors.md).
bool may_be_zero(LimitField field) {
  return field == LimitField::JunctionDeviation || field == LimitField::Rapid || field == LimitField::AxisStepsPerMm ||
         field == LimitField::AxisVMax || field == LimitField::AxisAMax;
}

/// Line names of a "gpio" section, each used once.
class LineNames {
 public:
  explicit LineNames(const Reader& reader) : reader_(reader) {}
  /// The non-empty line name at `node`, which the key `here` names in messages.
  std::string take(const Node& node, const std::string& here) {
    std::string name = reader_.string(node);
    if (name.empty()) reader_.fail(node, "the line name must not be empty (gpioinfo lists the names)");
    if (const auto twice = used_.find(name); twice != used_.end()) {
      reader_.fail(node, "line \"" + name + "\" is already used by " + twice->second);
    }
    used_.emplace(name, here);
    return name;
  }
  /// The line at optional key `key` of `section` (the key `here`), or "" when absent.
  std::string optional(const Node& section, const char* key, const std::string& here) {
    const auto node = reader_.optional(section, key);
    return node ? take(*node, here + ".\"" + key + "\"") : std::string{};
  }

 private:
  const Reader& reader_;
  std::map<std::string, std::string> used_;  // line name -> the key that uses it
};

/// The machine outputs of a "gpio" section: "spindle", "coolant", "outputs".
void parse_output_lines(const Reader& reader, const Node& gpio, LineNames& names, GpioWiring& wiring) {
  if (const auto spindle = reader.optional(gpio, "spindle")) {
    reader.check_keys(*spindle, {"enable", "direction"});
    wiring.spindle_enable = names.optional(*spindle, "enable", "\"gpio\".\"spindle\"");
    wiring.spindle_direction = names.optional(*spindle, "direction", "\"gpio\".\"spindle\"");
  }
  if (const auto coolant = reader.optional(gpio, "coolant")) {
    reader.check_keys(*coolant, {"mist", "flood"});
    wiring.coolant_mist = names.optional(*coolant, "mist", "\"gpio\".\"coolant\"");
    wiring.coolant_flood = names.optional(*coolant, "flood", "\"gpio\".\"coolant\"");
  }
  if (const auto outputs = reader.optional(gpio, "outputs")) {
    const std::vector<Node> lines = reader.array(*outputs, 1, max_digital_outputs);
    for (std::size_t k = 0; k < lines.size(); ++k) {
      wiring.outputs.push_back(names.take(lines[k], "\"gpio\".\"outputs\"[" + std::to_string(k) + "]"));
    }
  }
}

/// The "gpio" section: {"chip": NAME, "x": {"step": LINE, "dir": LINE, "invert_dir": BOOL}, "y": ..., "z": ...,
/// "spindle": {...}, "coolant": {...}, "outputs": [...]}.
GpioWiring parse_gpio(const Reader& reader, const Node& gpio) {
  reader.check_keys(gpio, {"chip", "x", "y", "z", "spindle", "coolant", "outputs"});
  GpioWiring wiring;
  const Node chip = reader.require(gpio, "chip");
  wiring.chip = reader.string(chip);
  if (wiring.chip.empty()) reader.fail(chip, "the chip name must not be empty (e.g. \"gpiochip0\"; gpiodetect lists them)");
  LineNames names(reader);
  bool any = false;
  for (std::size_t axis = 0; axis < motion_axes; ++axis) {
    const auto entry = reader.optional(gpio, axis_names[axis]);
    if (!entry) continue;
    reader.check_keys(*entry, {"step", "dir", "invert_dir"});
    GpioAxisWiring lines;
    const auto line = [&](const char* key) {
      return names.take(reader.require(*entry, key), std::string("\"gpio\".\"") + axis_names[axis] + "\".\"" + key + "\"");
    };
    lines.step = line("step");
    lines.dir = line("dir");
    if (const auto invert = reader.optional(*entry, "invert_dir")) lines.invert_dir = reader.boolean(*invert);
    wiring.axes[axis] = lines;
    any = true;
  }
  if (!any) reader.fail(gpio, "wires no axis (expected at least one of \"x\", \"y\", \"z\" with \"step\" and \"dir\")");
  parse_output_lines(reader, gpio, names, wiring);
  return wiring;
}

}  // namespace

std::string machine_field_name(LimitField field, std::size_t axis) {
  const std::string axis_prefix = std::string("\"axes\".\"") + axis_names[axis < motion_axes ? axis : 0] + "\".";
  switch (field) {
    case LimitField::VMax: return "\"v_max\"";
    case LimitField::AMax: return "\"a_max\"";
    case LimitField::JMax: return "\"j_max\"";
    case LimitField::Feed: return "\"feed\"";
    case LimitField::Rapid: return "\"rapid\"";
    case LimitField::Tolerance: return "\"tolerance\"";
    case LimitField::RateHz: return "\"rate_hz\"";
    case LimitField::JunctionDeviation: return "\"junction_deviation\"";
    case LimitField::MaxStepRate: return "\"max_step_rate\"";
    case LimitField::AxisStepsPerMm: return axis_prefix + "\"steps_per_mm\"";
    case LimitField::AxisVMax: return axis_prefix + "\"v_max\"";
    case LimitField::AxisAMax: return axis_prefix + "\"a_max\"";
  }
  return "\"?\"";
}

namespace {

/// A length inside the Q16.16 range the controller works in, mm.
double machine_length(const Reader& reader, const Node& node) {
  const double value = reader.number(node);
  if (!(std::fabs(value) <= 32767.0)) reader.fail(node, "value " + format_number(value) + " mm is outside -32767 .. 32767 mm");
  return value;
}

/// "travel": [low, high] with low < high.
AxisTravel parse_travel(const Reader& reader, const Node& node) {
  const auto ends = reader.array(node, 2, 2);
  AxisTravel travel{machine_length(reader, ends[0]), machine_length(reader, ends[1])};
  if (!(travel.low_mm < travel.high_mm)) reader.fail(node, "the low end must be below the high end ([low, high] in mm)");
  return travel;
}

/// "g28" / "g30": [x, y, z] (z may be left out: 0).
MachinePoint parse_position(const Reader& reader, const Node& node) {
  const auto coordinates = reader.array(node, 2, motion_axes);
  MachinePoint p{};
  for (std::size_t axis = 0; axis < coordinates.size(); ++axis) p[axis] = machine_length(reader, coordinates[axis]);
  return p;
}

/// "tools": [{"number": n, "length": mm, "diameter": mm}, ...], each number once.
std::map<int, MachineTool> parse_tools(const Reader& reader, const Node& node) {
  std::map<int, MachineTool> tools;
  for (const Node& entry : reader.array(node, 0, max_tool_table_size)) {
    reader.check_keys(entry, {"number", "length", "diameter"});
    const auto number = static_cast<int>(reader.integer(reader.require(entry, "number"), 0, max_tool_number));
    MachineTool tool;
    if (const auto length = reader.optional(entry, "length")) tool.length_mm = machine_length(reader, *length);
    if (const auto diameter = reader.optional(entry, "diameter")) {
      const double d = reader.number(*diameter);
      if (!(d >= 0 && d <= 1000)) reader.fail(*diameter, "value " + format_number(d) + " mm is outside 0 .. 1000 mm");
      tool.diameter_mm = d;
    }
    if (!tools.emplace(number, tool).second) reader.fail(entry, "tool " + std::to_string(number) + " is listed twice");
  }
  return tools;
}

}  // namespace

MachineFile parse_machine_file(std::string_view text, std::string name) {
  const detail::JsonDocument document(text, std::move(name), Error::InvalidMachine);
  const Reader reader(document, Error::InvalidMachine);
  const Node root = reader.root();
  reader.check_keys(root, {"version", "v_max", "a_max", "j_max", "feed", "rapid", "tolerance", "rate_hz",
                           "junction_deviation", "max_step_rate", "profile", "axes", "gpio", "blend_tolerance", "tools", "g28", "g30",
                           "pen"});
  MachineFile file;
  file.name = document.name();
  if (const auto version = reader.optional(root, "version")) {
    const auto value = reader.integer(*version, 0, 1000000);
    if (value != 1) reader.fail(*version, "unsupported version " + std::to_string(value) + " (this program reads version 1)");
  }
  MachineLimits& limits = file.limits;
  // Required keys are read as plain numbers; validate() below judges their values, so a zero or
  // negative limit is reported with the same wording as the core uses.
  limits.v_max_mm_per_s = reader.number(reader.require(root, "v_max"));
  limits.a_max_mm_per_s2 = reader.number(reader.require(root, "a_max"));
  limits.j_max_mm_per_s3 = reader.number(reader.require(root, "j_max"));
  limits.feed_mm_per_s = reader.number(reader.require(root, "feed"));
  limits.tolerance_mm = reader.number(reader.require(root, "tolerance"));
  limits.rate_hz = reader.number(reader.require(root, "rate_hz"));
  if (const auto node = reader.optional(root, "junction_deviation")) limits.junction_deviation_mm = reader.number(*node);
  if (const auto node = reader.optional(root, "max_step_rate")) limits.max_step_rate_hz = reader.number(*node);
  if (const auto node = reader.optional(root, "rapid")) {
    limits.rapid_mm_per_s = reader.positive(*node);
  }
  if (const auto node = reader.optional(root, "profile")) {
    const std::string profile = reader.string(*node);
    if (profile == "scurve") {
      limits.jerk_limited = true;
    } else if (profile == "trapezoid") {
      limits.jerk_limited = false;
    } else {
      reader.fail(*node, "unknown profile \"" + profile + "\" (expected \"scurve\" or \"trapezoid\")");
    }
  }
  if (const auto axes = reader.optional(root, "axes")) {
    reader.check_keys(*axes, {"x", "y", "z"});
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      const auto entry = reader.optional(*axes, axis_names[axis]);
      if (!entry) continue;
      reader.check_keys(*entry, {"steps_per_mm", "v_max", "a_max", "travel"});
      AxisLimits& limit = limits.axes[axis];
      if (const auto node = reader.optional(*entry, "steps_per_mm")) limit.steps_per_mm = reader.number(*node);
      if (const auto node = reader.optional(*entry, "v_max")) limit.v_max_mm_per_s = reader.number(*node);
      if (const auto node = reader.optional(*entry, "a_max")) limit.a_max_mm_per_s2 = reader.number(*node);
      if (const auto node = reader.optional(*entry, "travel")) file.travel[axis] = parse_travel(reader, *node);
    }
  }
  const auto valid = limits.validate();
  if (!valid) {
    const std::size_t index = valid.where();
    LimitField field = static_cast<LimitField>(index);
    std::size_t axis = 0;
    for (const LimitField base : {LimitField::AxisStepsPerMm, LimitField::AxisVMax, LimitField::AxisAMax}) {
      const auto first = static_cast<std::size_t>(base);
      if (index >= first && index < first + motion_axes) {
        field = base;
        axis = index - first;
      }
    }
    Node at = limit_node(root, field, axis);
    at.field = machine_field_name(field, axis);
    std::string message = at.json != nullptr && at.json->is_number() ? "value " + format_number(at.json->get<double>()) + " " : "";
    if (valid.error() == Error::InvalidRate) {
      message += "is outside 100 Hz .. 100 kHz";
    } else {
      const LimitRange range = limit_range(field);
      const double value = at.json != nullptr && at.json->is_number() ? at.json->get<double>() : 0.0;
      if (may_be_zero(field) ? value < 0 : value <= 0) {
        message += std::string(may_be_zero(field) ? "must not be negative" : "must be positive");
      } else {
        message += "is outside the plausible range " + format_number(range.low) + " .. " + format_number(range.high) +
                   (may_be_zero(field) ? " (or 0 for none)" : "");
      }
      message += " (" + std::string(describe(valid.error())) + ")";
    }
    reader.fail(at, message, valid.error());
  }
  if (const auto gpio = reader.optional(root, "gpio")) file.gpio = parse_gpio(reader, *gpio);
  if (const auto tools = reader.optional(root, "tools")) file.tools = parse_tools(reader, *tools);
  if (const auto node = reader.optional(root, "g28")) file.g28_position = parse_position(reader, *node);
  if (const auto node = reader.optional(root, "g30")) file.g30_position = parse_position(reader, *node);
  if (const auto pen = reader.optional(root, "pen")) file.pen = detail::parse_pen(reader, *pen);
  if (const auto node = reader.optional(root, "blend_tolerance")) {
    const double value = reader.number(*node);
    if (!(value >= 0 && value <= max_blend_tolerance_mm)) {
      reader.fail(*node, "value " + format_number(value) + " is outside 0 .. " + format_number(max_blend_tolerance_mm) +
                             " mm (0 turns path smoothing off)");
    }
    file.blend_tolerance_mm = value;
  }
  return file;
}

MachineWiring load_machine_wiring(const std::filesystem::path& path) {
  const detail::JsonDocument document(read_text_file(path), path.string(), Error::InvalidMachine);
  const Reader reader(document, Error::InvalidMachine);
  const Node root = reader.root();
  MachineWiring wiring;
  if (const auto gpio = reader.optional(root, "gpio")) wiring.gpio = parse_gpio(reader, *gpio);
  if (const auto pen = reader.optional(root, "pen")) wiring.pen = detail::parse_pen(reader, *pen);
  return wiring;
}

MachineLimits parse_machine(std::string_view text, std::string name) { return parse_machine_file(text, std::move(name)).limits; }

MachineFile load_machine_file(const std::filesystem::path& path) { return parse_machine_file(read_text_file(path), path.string()); }

MachineLimits load_machine(const std::filesystem::path& path) { return load_machine_file(path).limits; }

}  // namespace curvestep::host
