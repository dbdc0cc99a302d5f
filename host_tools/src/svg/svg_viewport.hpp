// SPDX-License-Identifier: MIT
// Internal: viewports (viewBox, preserveAspectRatio) and the root's map to machine millimetres.
#pragma once

#include <optional>
#include <vector>

#include <tinyxml2.h>

#include "svg_diagnostics.hpp"
#include "svg_geometry.hpp"
#include "svg_lengths.hpp"

namespace curvestep::host::svg {

/// The element's viewBox (min-x, min-y, width, height), nullopt if absent; LoadError if malformed.
[[nodiscard]] std::optional<std::vector<double>> view_box(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element);

/// The map from the viewBox `box` to a viewport of width × height (in the target units), following
/// the element's preserveAspectRatio.
[[nodiscard]] Affine viewbox_map(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element,
                                 const std::vector<double>& box, double width, double height);

/// The root viewport: its map to machine mm and what its children's lengths refer to.
struct RootViewport {
  Affine map;                        ///< root user space -> machine mm, y up (y_machine = H - y_mm, H the page height)
  std::optional<double> width_mm;    ///< the page width, if known
  std::optional<double> height_mm;   ///< the page height, if known
  LengthContext lengths;             ///< viewport size in user units, root size in px, the root's font-size
};

/// The root's viewport from width, height, viewBox, preserveAspectRatio, font-size and transform.
[[nodiscard]] RootViewport root_viewport(const Diagnostics& diagnostics, const tinyxml2::XMLElement& root);

}  // namespace curvestep::host::svg
