// SPDX-License-Identifier: MIT
// The element walk (svg_walk.hpp).
#include "svg_walk.hpp"

#include <algorithm>

#include <curvestep/host/printable.hpp>
#include <curvestep/host/svg_import.hpp>

#include "svg_attributes.hpp"
#include "svg_lengths.hpp"
#include "svg_shapes.hpp"
#include "svg_viewport.hpp"

namespace curvestep::host::svg {

void ElementWalk::walk(const tinyxml2::XMLElement& root, const Affine& root_map) {
  index_ids(root);
  visit_children(root, root_map);
}

void ElementWalk::index_ids(const tinyxml2::XMLElement& element) {
  if (const char* id = element.Attribute("id")) ids_.emplace(id, &element);
  for (const auto* child = element.FirstChildElement(); child != nullptr; child = child->NextSiblingElement()) index_ids(*child);
}

void ElementWalk::visit_children(const tinyxml2::XMLElement& parent, const Affine& map) {
  for (const auto* child = parent.FirstChildElement(); child != nullptr; child = child->NextSiblingElement()) visit(*child, map);
}

void ElementWalk::visit(const tinyxml2::XMLElement& element, const Affine& parent_map) {
  // Nested <use> fans out geometrically (a 1.3 KB file drew billions of elements): bound the total.
  if (!active_uses_.empty() && ++expanded_elements_ > max_svg_expanded_elements) {
    const tinyxml2::XMLElement& outer = *active_uses_.front();
    diagnostics_.fail(outer, outer.Attribute("href") != nullptr ? "href" : "xlink:href",
                      "<use> references expand to more than " + std::to_string(max_svg_expanded_elements) +
                          " elements (the limit for SVG files)");
  }
  const std::string full_name = element.Name();
  if (full_name.find(':') != std::string::npos && full_name.rfind("svg:", 0) != 0) return;  // editor metadata
  const std::string name = local_name(element);
  static constexpr const char* not_rendered[] = {"defs", "symbol", "clipPath", "mask", "marker", "pattern", "linearGradient",
                                                 "radialGradient", "style", "title", "desc", "metadata", "script", "filter"};
  for (const char* skip : not_rendered) {
    if (name == skip) return;
  }
  if (property(element, "display") == "none") return;
  if (name == "g" || name == "a" || name == "switch") {
    visit_children(element, with_transform(diagnostics_, element, parent_map));
    return;
  }
  if (name == "svg") {  // a nested viewport: x, y and its own viewBox
    Affine map = with_transform(diagnostics_, element, parent_map) *
                 Affine{1, 0, 0, 1, length(diagnostics_, element, "x", 0), length(diagnostics_, element, "y", 0)};
    if (const auto box = view_box(diagnostics_, element)) {
      const auto width = size(diagnostics_, element, "width");
      const auto height = size(diagnostics_, element, "height");
      map = map * viewbox_map(diagnostics_, element, *box, width.value_or((*box)[2]), height.value_or((*box)[3]));
    }
    visit_children(element, map);
    return;
  }
  const Affine map = with_transform(diagnostics_, element, parent_map);
  std::vector<Subpath> subpaths;
  if (name == "path") {
    const char* data = element.Attribute("d");
    if (data == nullptr) return;  // no d: nothing to draw
    try {
      subpaths = parse_path_data(data);
    } catch (const SyntaxError& error) {
      diagnostics_.fail_syntax(element, "d", error);
    }
  } else if (name == "rect") {
    subpaths = rect_outline(diagnostics_, element);
  } else if (name == "circle" || name == "ellipse") {
    subpaths = ellipse_outline(diagnostics_, element, name == "circle");
  } else if (name == "line") {
    subpaths = line_outline(diagnostics_, element);
  } else if (name == "polyline" || name == "polygon") {
    subpaths = poly_outline(diagnostics_, element, name == "polygon");
  } else if (name == "use") {
    use(element, map);
    return;
  } else if (name == "text" || name == "image" || name == "foreignObject") {
    diagnostics_.warn(element, name == "text" ? "is not drawn (convert text to paths first)" : "is not drawn");
    return;
  } else {
    diagnostics_.warn(element, "is not drawn (unknown element)");
    return;
  }
  append_machine_subpaths(diagnostics_, element, name == "path" ? "d" : "", map, subpaths, drawn_);
}

void ElementWalk::use(const tinyxml2::XMLElement& element, const Affine& map) {
  const char* attribute = element.Attribute("href") != nullptr ? "href" : "xlink:href";
  const char* raw = element.Attribute(attribute);
  if (raw == nullptr) return;  // nothing referenced: nothing drawn
  const std::string reference = trim(raw);
  if (reference.empty() || reference.front() != '#') {
    diagnostics_.fail(element, attribute,
                      "only references into the same file (\"#id\") are supported, got \"" + quoted_excerpt(reference) + "\"");
  }
  const auto found = ids_.find(reference.substr(1));
  if (found == ids_.end()) diagnostics_.fail(element, attribute, "no element has id \"" + quoted_excerpt(reference.substr(1)) + "\"");
  const tinyxml2::XMLElement& target = *found->second;
  if (std::find(active_uses_.begin(), active_uses_.end(), &element) != active_uses_.end() || active_uses_.size() > 64) {
    diagnostics_.fail(element, attribute, "the reference \"" + quoted_excerpt(reference) + "\" refers back to itself");
  }
  active_uses_.push_back(&element);
  const Affine placed = map * Affine{1, 0, 0, 1, length(diagnostics_, element, "x", 0), length(diagnostics_, element, "y", 0)};
  if (local_name(target) == "symbol") {
    Affine inner = with_transform(diagnostics_, target, placed);
    if (const auto box = view_box(diagnostics_, target)) {
      const auto width = size(diagnostics_, element, "width");
      const auto height = size(diagnostics_, element, "height");
      inner = inner * viewbox_map(diagnostics_, target, *box, width.value_or((*box)[2]), height.value_or((*box)[3]));
    }
    visit_children(target, inner);
  } else {
    visit(target, placed);
  }
  active_uses_.pop_back();
}

}  // namespace curvestep::host::svg
