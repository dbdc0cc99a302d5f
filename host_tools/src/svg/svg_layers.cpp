// SPDX-License-Identifier: MIT
// Inkscape layers (svg_layers.hpp).
#include "svg_layers.hpp"

#include <algorithm>

#include <curvestep/host/printable.hpp>

namespace curvestep::host::svg {
namespace {

std::string layer_list(const std::vector<Layer>& layers) {
  std::string list;
  for (const auto& layer : layers) {
    if (!layer.inkscape) continue;
    list += (list.empty() ? "\"" : ", \"") + quoted_excerpt(layer.label) + "\"";
  }
  return list.empty() ? "the drawing has no Inkscape layers" : "the layers are " + list;
}

}  // namespace

std::string layer_text(const Layer& layer) { return layer.inkscape ? layer.label : "(outside layers)"; }

void select_layers(const Diagnostics& diagnostics, const std::vector<Layer>& layers, const std::vector<std::string>& selected,
                   std::vector<DrawnSubpath>& drawn) {
  std::vector<bool> keep(layers.size(), selected.empty());
  for (const auto& name : selected) {
    bool found = false;
    for (std::size_t i = 0; i < layers.size(); ++i) {
      if (layers[i].inkscape && layers[i].label == name) keep[i] = found = true;
    }
    if (!found) diagnostics.fail_at(0, "layers", "no layer is labelled \"" + quoted_excerpt(name) + "\" (" + layer_list(layers) + ")");
  }
  std::erase_if(drawn, [&](const DrawnSubpath& subpath) { return subpath.layer >= keep.size() || !keep[subpath.layer]; });
  std::stable_sort(drawn.begin(), drawn.end(), [](const DrawnSubpath& a, const DrawnSubpath& b) { return a.layer < b.layer; });
  if (drawn.empty() && !selected.empty()) diagnostics.fail_at(0, "layers", "the selected layers draw nothing");
}

}  // namespace curvestep::host::svg
