// SPDX-License-Identifier: MIT
// Viewports and the root's map to machine millimetres (svg_viewport.hpp).
#include "svg_viewport.hpp"

#include <algorithm>
#include <string>

#include "svg_attributes.hpp"
#include "svg_lengths.hpp"
#include "svg_transform.hpp"

namespace curvestep::host::svg {

Affine viewbox_map(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const std::vector<double>& box,
                   double width, double height) {
  const double sx = width / box[2];
  const double sy = height / box[3];
  std::string aspect = trim(element.Attribute("preserveAspectRatio") ? element.Attribute("preserveAspectRatio") : "");
  if (aspect.rfind("defer", 0) == 0) aspect = trim(aspect.substr(5));
  std::string align = aspect.substr(0, aspect.find(' '));
  const std::string mode = aspect.find(' ') == std::string::npos ? "meet" : trim(aspect.substr(aspect.find(' ')));
  if (align.empty()) align = "xMidYMid";
  if (align == "none") return Affine{sx, 0, 0, sy, -box[0] * sx, -box[1] * sy};
  if (align.size() != 8 || align[0] != 'x' || align[4] != 'Y' || (mode != "meet" && mode != "slice")) {
    diagnostics.fail(element, "preserveAspectRatio",
                     "expected none or x(Min|Mid|Max)Y(Min|Mid|Max) [meet|slice], got \"" + aspect + "\"");
  }
  const double s = mode == "meet" ? std::min(sx, sy) : std::max(sx, sy);
  auto offset = [&](const std::string& where, double room) {
    if (where == "Min") return 0.0;
    if (where == "Mid") return room / 2;
    if (where == "Max") return room;
    diagnostics.fail(element, "preserveAspectRatio", "expected Min, Mid or Max in \"" + align + "\"");
  };
  const double tx = offset(align.substr(1, 3), width - box[2] * s);
  const double ty = offset(align.substr(5, 3), height - box[3] * s);
  return Affine{s, 0, 0, s, tx - box[0] * s, ty - box[1] * s};
}

std::optional<std::vector<double>> view_box(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element) {
  const char* raw = element.Attribute("viewBox");
  if (raw == nullptr) return std::nullopt;
  std::vector<double> box;
  try {
    box = parse_number_list(raw);
  } catch (const SyntaxError& error) {
    diagnostics.fail_syntax(element, "viewBox", error);
  }
  if (box.size() != 4) {
    diagnostics.fail(element, "viewBox", "expected 4 numbers (min-x min-y width height), got " + std::to_string(box.size()));
  }
  if (!(box[2] > 0 && box[3] > 0)) diagnostics.fail(element, "viewBox", "width and height must be positive");
  return box;
}

RootViewport root_viewport(const Diagnostics& diagnostics, const tinyxml2::XMLElement& root) {
  RootViewport viewport;
  viewport.lengths.font_size = font_size(diagnostics, root, property(root, "font-size"), default_font_size_px, viewport.lengths);
  auto width = page_size_mm(diagnostics, root, "width", viewport.lengths.font_size);
  auto height = page_size_mm(diagnostics, root, "height", viewport.lengths.font_size);
  const auto box = view_box(diagnostics, root);
  Affine to_mm{mm_per_px, 0, 0, mm_per_px, 0, 0};
  if (box) {
    const double aspect = (*box)[3] / (*box)[2];
    if (!width && height) width = *height / aspect;
    if (width && !height) height = *width * aspect;
    if (!width) width = (*box)[2] * mm_per_px;
    if (!height) height = (*box)[3] * mm_per_px;
    to_mm = viewbox_map(diagnostics, root, *box, *width, *height);
  }
  viewport.width_mm = width;
  viewport.height_mm = height;
  viewport.lengths.root_width = width.value_or(0) / mm_per_px;
  viewport.lengths.root_height = height.value_or(0) / mm_per_px;
  viewport.lengths.viewport_width = box ? (*box)[2] : viewport.lengths.root_width;
  viewport.lengths.viewport_height = box ? (*box)[3] : viewport.lengths.root_height;
  const Affine flip = height ? Affine{1, 0, 0, -1, 0, *height} : Affine{1, 0, 0, -1, 0, 0};
  viewport.map = flip * with_transform(diagnostics, root, to_mm, viewport.lengths);
  return viewport;
}

}  // namespace curvestep::host::svg
