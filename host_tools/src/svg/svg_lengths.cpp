// SPDX-License-Identifier: MIT
// Length attributes and the root's page size (svg_lengths.hpp).
#include "svg_lengths.hpp"

#include "svg_attributes.hpp"

namespace curvestep::host::svg {

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

double length(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const char* attribute, double fallback) {
  const char* raw = element.Attribute(attribute);
  if (raw == nullptr) return fallback;
  Length value;
  try {
    value = parse_length(raw);
  } catch (const SyntaxError& error) {
    diagnostics.fail_syntax(element, attribute, error);
  }
  if (value.unit.empty()) return value.value;
  const auto scale = mm_per_unit(value.unit);
  if (!scale) {
    diagnostics.fail(element, attribute, "unsupported unit \"" + value.unit + "\" (use px, mm, cm, in, pt, pc, Q or none)");
  }
  return value.value * *scale / mm_per_px;
}

std::optional<double> size(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const char* attribute) {
  if (element.Attribute(attribute) == nullptr) return std::nullopt;
  if (trim(element.Attribute(attribute)) == "auto") return std::nullopt;
  const double value = length(diagnostics, element, attribute, 0);
  if (value < 0) diagnostics.fail(element, attribute, "must not be negative, got " + std::string(element.Attribute(attribute)));
  return value;
}

std::optional<double> page_size_mm(const Diagnostics& diagnostics, const tinyxml2::XMLElement& root, const char* attribute) {
  const char* raw = root.Attribute(attribute);
  if (raw == nullptr || trim(raw) == "auto") return std::nullopt;
  Length value;
  try {
    value = parse_length(raw);
  } catch (const SyntaxError& error) {
    diagnostics.fail_syntax(root, attribute, error);
  }
  if (value.unit == "%") return std::nullopt;
  const auto scale = mm_per_unit(value.unit);
  if (!scale) diagnostics.fail(root, attribute, "unsupported unit \"" + value.unit + "\" (use px, mm, cm, in, pt, pc or Q)");
  if (!(value.value > 0)) {
    diagnostics.fail(root, attribute, "the page " + std::string(attribute) + " must be positive, got " + std::string(raw));
  }
  return value.value * *scale;
}

}  // namespace curvestep::host::svg
