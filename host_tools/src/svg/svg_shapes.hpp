// SPDX-License-Identifier: MIT
// Internal: the basic shapes (rect, circle, ellipse, line, polyline, polygon) as subpaths in user space.
#pragma once

#include <vector>

#include <tinyxml2.h>

#include "svg_diagnostics.hpp"
#include "svg_geometry.hpp"
#include "svg_lengths.hpp"

namespace curvestep::host::svg {

/// A rect's outline (rounded corners as quarter arcs); empty if a size is zero.
[[nodiscard]] std::vector<Subpath> rect_outline(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element,
                                   const LengthContext& context);

/// A circle's (`circle`) or ellipse's outline: four quarter arcs from (cx + rx, cy); empty if a radius is zero.
[[nodiscard]] std::vector<Subpath> ellipse_outline(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, bool circle,
                                      const LengthContext& context);

/// A line from (x1, y1) to (x2, y2).
[[nodiscard]] std::vector<Subpath> line_outline(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element,
                                   const LengthContext& context);

/// A polyline or (`closed`) polygon from its points. A malformed list or an odd count is an error
/// if `strict`; otherwise the numbers before the error are used, an odd last one dropped, with a warning.
[[nodiscard]] std::vector<Subpath> poly_outline(Diagnostics& diagnostics, const tinyxml2::XMLElement& element, bool closed,
                                                bool strict);

}  // namespace curvestep::host::svg
