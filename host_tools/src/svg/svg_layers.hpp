// SPDX-License-Identifier: MIT
// Internal: Inkscape layers — which are drawn, grouped layer by layer in document order.
#pragma once

#include <string>
#include <vector>

#include "svg_diagnostics.hpp"
#include "svg_machine.hpp"

namespace curvestep::host::svg {

/// A top-level Inkscape layer (<g inkscape:groupmode="layer">), or what is drawn outside layers.
struct Layer {
  std::string label;     ///< inkscape:label (else the id, else "layer N"); empty outside layers
  bool inkscape = true;  ///< false: the content outside any layer
};

/// The name a LayerChange event gives `layer`: its label, or "(outside layers)".
[[nodiscard]] std::string layer_text(const Layer& layer);

/// Keeps the subpaths of the layers labelled in `selected` (all when it is empty; the content outside
/// layers only then) and groups them layer by layer in document order, keeping the order within a
/// layer. LoadError for a selected label no layer has (listing the layers there are), or when the
/// selected layers draw nothing.
void select_layers(const Diagnostics& diagnostics, const std::vector<Layer>& layers, const std::vector<std::string>& selected,
                   std::vector<DrawnSubpath>& drawn);

}  // namespace curvestep::host::svg
