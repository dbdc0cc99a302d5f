// SPDX-License-Identifier: MIT
// Length attributes, font sizes and the root's page size (svg_lengths.hpp).
#include "svg_lengths.hpp"

#include <algorithm>
#include <cmath>

#include "svg_attributes.hpp"

namespace curvestep::host::svg {
namespace {

Length parsed(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const char* attribute, const std::string& text) {
  try {
    return parse_length(text);
  } catch (const SyntaxError& error) {
    diagnostics.fail_syntax(element, attribute, error);
  }
}

/// The reference of `%` for `axis` in user units.
double percent_base(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const char* attribute,
                    const LengthContext& context, LengthAxis axis) {
  const double w = context.viewport_width;
  const double h = context.viewport_height;
  const double base = axis == LengthAxis::X ? w : axis == LengthAxis::Y ? h : std::sqrt((w * w + h * h) / 2);
  if (!(base > 0) || (axis == LengthAxis::Other && !(w > 0 && h > 0))) {
    diagnostics.fail(element, attribute,
                     "a percentage needs the viewport's size, and the root <svg> has no width, height or viewBox to give it");
  }
  return base;
}

/// The reference of vw/vh/vmin/vmax (the root viewport's side in px, / 100 applied by the caller).
double viewport_base(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const char* attribute,
                     const LengthContext& context, const std::string& unit) {
  const double w = context.root_width;
  const double h = context.root_height;
  const double base = unit == "vw" ? w : unit == "vh" ? h : unit == "vmin" ? std::min(w, h) : std::max(w, h);
  if (!(w > 0 && h > 0)) {
    diagnostics.fail(element, attribute,
                     "\"" + unit + "\" needs the root viewport's size, and the root <svg> has no width, height or viewBox to give it");
  }
  return base;
}

}  // namespace

std::optional<double> mm_per_unit(const std::string& unit) {
  if (unit.empty() || unit == "px") return mm_per_px;
  if (unit == "mm") return 1.0;
  if (unit == "cm") return 10.0;
  if (unit == "in") return mm_per_inch;
  if (unit == "pt") return mm_per_inch / 72;
  if (unit == "pc") return mm_per_inch / 6;
  if (unit == "Q") return 0.25;
  return std::nullopt;
}

double length_value(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const char* attribute,
                    const std::string& text, const LengthContext& context, LengthAxis axis) {
  const Length value = parsed(diagnostics, element, attribute, text);
  if (value.unit.empty()) return value.value;
  if (const auto scale = mm_per_unit(value.unit)) return value.value * *scale / mm_per_px;
  if (value.unit == "%") return value.value / 100 * percent_base(diagnostics, element, attribute, context, axis);
  if (value.unit == "em") return value.value * context.font_size;
  if (value.unit == "ex") return value.value * context.font_size / 2;
  if (value.unit == "vw" || value.unit == "vh" || value.unit == "vmin" || value.unit == "vmax") {
    return value.value / 100 * viewport_base(diagnostics, element, attribute, context, value.unit);
  }
  diagnostics.fail(element, attribute,
                   "unsupported unit \"" + value.unit + "\" (use px, mm, cm, in, pt, pc, Q, %, em, ex, vw, vh, vmin, vmax or none)");
}

double length(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const char* attribute, double fallback,
              const LengthContext& context, LengthAxis axis) {
  const char* raw = element.Attribute(attribute);
  if (raw == nullptr) return fallback;
  return length_value(diagnostics, element, attribute, raw, context, axis);
}

std::optional<double> size(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const char* attribute,
                           const LengthContext& context, LengthAxis axis) {
  if (element.Attribute(attribute) == nullptr) return std::nullopt;
  if (trim(element.Attribute(attribute)) == "auto") return std::nullopt;
  const double value = length(diagnostics, element, attribute, 0, context, axis);
  if (value < 0) diagnostics.fail(element, attribute, "must not be negative, got " + std::string(element.Attribute(attribute)));
  return value;
}

double font_size(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const std::string& text, double parent,
                 const LengthContext& context) {
  const std::string value = trim(text);
  if (value.empty() || value == "inherit") return parent;
  static constexpr std::pair<const char*, double> keywords[] = {{"xx-small", 9},  {"x-small", 10}, {"small", 13},
                                                                {"medium", 16},   {"large", 18},   {"x-large", 24},
                                                                {"xx-large", 32}, {"xxx-large", 48}};
  for (const auto& [name, px] : keywords) {
    if (value == name) return px;
  }
  if (value == "larger") return parent * 1.2;
  if (value == "smaller") return parent / 1.2;
  // em, ex and % of a font-size are of the parent's font-size.
  LengthContext of_parent = context;
  of_parent.font_size = parent;
  const Length length = parsed(diagnostics, element, "font-size", value);
  const double px = length.unit == "%" ? length.value / 100 * parent
                                       : length_value(diagnostics, element, "font-size", value, of_parent, LengthAxis::Other);
  if (px < 0) diagnostics.fail(element, "font-size", "must not be negative, got " + value);
  return px;
}

std::optional<double> page_size_mm(const Diagnostics& diagnostics, const tinyxml2::XMLElement& root, const char* attribute,
                                   double font_size) {
  const char* raw = root.Attribute(attribute);
  if (raw == nullptr || trim(raw) == "auto") return std::nullopt;
  const Length value = parsed(diagnostics, root, attribute, raw);
  if (value.unit == "%" || value.unit == "vw" || value.unit == "vh" || value.unit == "vmin" || value.unit == "vmax") {
    return std::nullopt;  // relative to the viewer's window: no page size
  }
  double mm = 0;
  if (value.unit == "em" || value.unit == "ex") {
    mm = value.value * font_size * (value.unit == "ex" ? 0.5 : 1.0) * mm_per_px;
  } else {
    const auto scale = mm_per_unit(value.unit);
    if (!scale) {
      diagnostics.fail(root, attribute, "unsupported unit \"" + value.unit + "\" (use px, mm, cm, in, pt, pc, Q, em, ex or none)");
    }
    mm = value.value * *scale;
  }
  if (!(value.value > 0)) {
    diagnostics.fail(root, attribute, "the page " + std::string(attribute) + " must be positive, got " + std::string(raw));
  }
  return mm;
}

}  // namespace curvestep::host::svg
