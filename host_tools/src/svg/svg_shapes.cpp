// SPDX-License-Identifier: MIT
// The basic shapes as subpaths in user space (svg_shapes.hpp).
#include "svg_shapes.hpp"

#include <algorithm>
#include <string>

#include "svg_lengths.hpp"

namespace curvestep::host::svg {

std::vector<Subpath> rect_outline(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element,
                                  const LengthContext& context) {
  const double x = length(diagnostics, element, "x", 0, context, LengthAxis::X);
  const double y = length(diagnostics, element, "y", 0, context, LengthAxis::Y);
  const double w = size(diagnostics, element, "width", context, LengthAxis::X).value_or(0);
  const double h = size(diagnostics, element, "height", context, LengthAxis::Y).value_or(0);
  if (w == 0 || h == 0) return {};  // not rendered
  auto rx = size(diagnostics, element, "rx", context, LengthAxis::X);
  auto ry = size(diagnostics, element, "ry", context, LengthAxis::Y);
  if (!rx) rx = ry;
  if (!ry) ry = rx;
  const double r_x = std::min(rx.value_or(0), w / 2);
  const double r_y = std::min(ry.value_or(0), h / 2);
  Subpath outline;
  if (r_x == 0 || r_y == 0) {
    outline.start = {x, y};
    append_line(outline, {x + w, y});
    append_line(outline, {x + w, y + h});
    append_line(outline, {x, y + h});
    append_line(outline, {x, y});
  } else {
    outline.start = {x + r_x, y};
    append_line(outline, {x + w - r_x, y});
    append_quarter(outline, {x + w - r_x, y + r_y}, {0, -r_y}, {r_x, 0});
    append_line(outline, {x + w, y + h - r_y});
    append_quarter(outline, {x + w - r_x, y + h - r_y}, {r_x, 0}, {0, r_y});
    append_line(outline, {x + r_x, y + h});
    append_quarter(outline, {x + r_x, y + h - r_y}, {0, r_y}, {-r_x, 0});
    append_line(outline, {x, y + r_y});
    append_quarter(outline, {x + r_x, y + r_y}, {-r_x, 0}, {0, -r_y});
  }
  outline.closed = true;
  return {outline};
}

std::vector<Subpath> ellipse_outline(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, bool circle,
                                      const LengthContext& context) {
  const double cx = length(diagnostics, element, "cx", 0, context, LengthAxis::X);
  const double cy = length(diagnostics, element, "cy", 0, context, LengthAxis::Y);
  double rx = 0;
  double ry = 0;
  if (circle) {
    rx = ry = size(diagnostics, element, "r", context, LengthAxis::Other).value_or(0);
  } else {
    auto a = size(diagnostics, element, "rx", context, LengthAxis::X);
    auto b = size(diagnostics, element, "ry", context, LengthAxis::Y);
    if (!a) a = b;
    if (!b) b = a;
    rx = a.value_or(0);
    ry = b.value_or(0);
  }
  if (rx == 0 || ry == 0) return {};  // not rendered
  // Starts at (cx + rx, cy) and runs through (cx, cy + ry): positive angles in user space.
  Subpath outline{{cx + rx, cy}, {}, true};
  const Point2 c{cx, cy};
  append_quarter(outline, c, {rx, 0}, {0, ry});
  append_quarter(outline, c, {0, ry}, {-rx, 0});
  append_quarter(outline, c, {-rx, 0}, {0, -ry});
  append_quarter(outline, c, {0, -ry}, {rx, 0});
  return {outline};
}

std::vector<Subpath> line_outline(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element,
                                  const LengthContext& context) {
  const double x1 = length(diagnostics, element, "x1", 0, context, LengthAxis::X);
  const double y1 = length(diagnostics, element, "y1", 0, context, LengthAxis::Y);
  const double x2 = length(diagnostics, element, "x2", 0, context, LengthAxis::X);
  const double y2 = length(diagnostics, element, "y2", 0, context, LengthAxis::Y);
  Subpath line{{x1, y1}, {}, false};
  append_line(line, {x2, y2});
  return {line};
}

std::vector<Subpath> poly_outline(Diagnostics& diagnostics, const tinyxml2::XMLElement& element, bool closed, bool strict) {
  const char* raw = element.Attribute("points");
  if (raw == nullptr) return {};
  NumberList list = parse_number_list_until_error(raw);
  std::vector<double>& numbers = list.numbers;
  if (list.error) {
    if (strict) diagnostics.fail_syntax(element, "points", *list.error);
    diagnostics.warn_at(element, "points",
                        "at character " + std::to_string(list.error->position()) + ": " + list.error->what() +
                            " (drawn with the " + std::to_string(numbers.size() - numbers.size() % 2) +
                            " numbers before it, as SVG renders; strict import refuses the file)");
  } else if (numbers.size() % 2 != 0) {
    const std::string count = "an odd count (" + std::to_string(numbers.size()) + " numbers)";
    if (strict) diagnostics.fail(element, "points", "expected pairs of coordinates, got " + count);
    diagnostics.warn_at(element, "points",
                        count + ": the last number is dropped, as SVG does (strict import refuses the file)");
  }
  numbers.resize(numbers.size() - numbers.size() % 2);
  if (numbers.empty()) return {};
  Subpath outline{{numbers[0], numbers[1]}, {}, closed};
  for (std::size_t i = 2; i < numbers.size(); i += 2) append_line(outline, {numbers[i], numbers[i + 1]});
  if (closed) append_line(outline, outline.start);
  return {outline};
}

}  // namespace curvestep::host::svg
