// SPDX-License-Identifier: MIT
// Internal: an element's transform attribute about its transform-origin (SVG 2 / CSS Transforms).
//
// With a transform-origin (ox, oy) the element's matrix is translate(ox, oy) · transform ·
// translate(-ox, -oy). The origin is one or two of: the keywords left, center, right, top, bottom,
// lengths, and percentages of the nearest viewport's width (x) and height (y), measured from the
// user-space origin (transform-box view-box, the default for SVG elements); a third value (z)
// must be a length and is ignored. Without transform-origin the origin is (0, 0).
#pragma once

#include <tinyxml2.h>

#include "svg_diagnostics.hpp"
#include "svg_geometry.hpp"
#include "svg_lengths.hpp"

namespace curvestep::host::svg {

/// The transform-origin of the element in user units; LoadError if malformed.
[[nodiscard]] Point2 transform_origin(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element,
                                      const std::string& text, const LengthContext& context);

/// `parent` ∘ the element's transform (about its transform-origin); parent alone if it has none.
[[nodiscard]] Affine with_transform(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const Affine& parent,
                                    const LengthContext& context);

}  // namespace curvestep::host::svg
