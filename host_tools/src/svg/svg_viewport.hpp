// SPDX-License-Identifier: MIT
// Internal: viewports (viewBox, preserveAspectRatio), the root's map to machine millimetres, and
// an element's transform attribute.
#pragma once

#include <optional>
#include <vector>

#include <tinyxml2.h>

#include "svg_diagnostics.hpp"
#include "svg_geometry.hpp"

namespace curvestep::host::svg {

/// The element's viewBox (min-x, min-y, width, height), nullopt if absent; LoadError if malformed.
[[nodiscard]] std::optional<std::vector<double>> view_box(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element);

/// The map from the viewBox `box` to a viewport of width × height (in the target units), following
/// the element's preserveAspectRatio.
[[nodiscard]] Affine viewbox_map(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element,
                                 const std::vector<double>& box, double width, double height);

/// `parent` ∘ the element's transform attribute (parent alone if it has none).
[[nodiscard]] Affine with_transform(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const Affine& parent);

/// User space of the root -> machine mm, y up (y_machine = H - y_mm, H the page height).
[[nodiscard]] Affine root_viewport(const Diagnostics& diagnostics, const tinyxml2::XMLElement& root);

}  // namespace curvestep::host::svg
