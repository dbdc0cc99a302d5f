// SPDX-License-Identifier: MIT
// Internal: length attributes in user units (every SVG 1.1/2 unit), font sizes, and the root's
// page size in millimetres.
//
// Absolute units convert at 96 px per inch with px = 1 user unit (SVG's rule inside any viewBox).
// `%` is of the nearest viewport's size in user units (its viewBox, else its width and height):
// the width for x-ish attributes, the height for y-ish ones, sqrt((w² + h²)/2) for the rest (r).
// `em` is the element's computed font-size (16 px unless set), `ex` half of it; vw, vh, vmin and
// vmax are 1% of the root viewport's width, height, smaller and larger side in px.
#pragma once

#include <optional>
#include <string>

#include <tinyxml2.h>

#include "svg_diagnostics.hpp"

namespace curvestep::host::svg {

inline constexpr double mm_per_inch = 25.4;
inline constexpr double mm_per_px = mm_per_inch / 96;
/// CSS's initial font-size ("medium"), px.
inline constexpr double default_font_size_px = 16;

/// Which viewport dimension a percentage refers to.
enum class LengthAxis { X, Y, Other };

/// What relative lengths of one element refer to (all in user units = px; 0: unknown).
struct LengthContext {
  double viewport_width = 0;            ///< nearest viewport: its viewBox width, else its width
  double viewport_height = 0;           ///< nearest viewport: its viewBox height, else its height
  double font_size = default_font_size_px;  ///< the element's computed font-size
  double root_width = 0;                ///< the root viewport's width in px (vw)
  double root_height = 0;               ///< the root viewport's height in px (vh)
};

/// Millimetres per unit, for the absolute units SVG knows ("" and px: 1/96 in); nullopt otherwise.
[[nodiscard]] std::optional<double> mm_per_unit(const std::string& unit);

/// A length attribute in user units; `fallback` if absent. LoadError for a malformed length, an
/// unknown unit or a relative unit whose reference is unknown.
[[nodiscard]] double length(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const char* attribute,
                            double fallback, const LengthContext& context, LengthAxis axis);

/// The length text `text` of `attribute` in user units (as length()).
[[nodiscard]] double length_value(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const char* attribute,
                                  const std::string& text, const LengthContext& context, LengthAxis axis);

/// A length that must not be negative; nullopt when absent or "auto".
[[nodiscard]] std::optional<double> size(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element,
                                         const char* attribute, const LengthContext& context, LengthAxis axis);

/// The computed font-size (px) for the font-size value `text` (attribute or style; "" = inherit)
/// with the parent's computed font-size `parent`: lengths, em/ex/% of the parent's, the CSS keywords.
[[nodiscard]] double font_size(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const std::string& text,
                               double parent, const LengthContext& context);

/// A root width or height in mm; nullopt when absent, "auto" or relative to the viewport itself (%, vw, vh, vmin, vmax).
[[nodiscard]] std::optional<double> page_size_mm(const Diagnostics& diagnostics, const tinyxml2::XMLElement& root,
                                                 const char* attribute, double font_size);

}  // namespace curvestep::host::svg
