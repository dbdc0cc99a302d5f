// SPDX-License-Identifier: MIT
// Internal: length attributes in user units, and the root's page size in millimetres.
#pragma once

#include <optional>
#include <string>

#include <tinyxml2.h>

#include "svg_diagnostics.hpp"

namespace curvestep::host::svg {

inline constexpr double mm_per_inch = 25.4;
inline constexpr double mm_per_px = mm_per_inch / 96;

/// Millimetres per unit, for the absolute units SVG knows ("" and px: 1/96 in); nullopt otherwise.
[[nodiscard]] std::optional<double> mm_per_unit(const std::string& unit);

/// A length attribute in user units (absolute units converted at 96 px per inch); `fallback` if absent.
[[nodiscard]] double length(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const char* attribute,
                            double fallback);

/// A length that must not be negative; nullopt when absent or "auto".
[[nodiscard]] std::optional<double> size(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element,
                                         const char* attribute);

/// A root width or height in mm; nullopt when absent, "auto" or relative (%).
[[nodiscard]] std::optional<double> page_size_mm(const Diagnostics& diagnostics, const tinyxml2::XMLElement& root,
                                                 const char* attribute);

}  // namespace curvestep::host::svg
