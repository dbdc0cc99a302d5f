// SPDX-License-Identifier: MIT
// The element walk (svg_walk.hpp).
#include "svg_walk.hpp"

#include <algorithm>
#include <cctype>
#include <optional>
#include <string_view>

#include <curvestep/host/printable.hpp>
#include <curvestep/host/svg_import.hpp>

#include "svg_attributes.hpp"
#include "svg_lengths.hpp"
#include "svg_shapes.hpp"
#include "svg_transform.hpp"
#include "svg_viewport.hpp"

namespace curvestep::host::svg {

void ElementWalk::walk(const tinyxml2::XMLElement& root, const Scope& root_scope) {
  index_ids(root);
  collect_style_sheets(root);
  std::optional<std::size_t> outside;  // the layer of what is drawn outside Inkscape layers
  for (const auto* child = root.FirstChildElement(); child != nullptr; child = child->NextSiblingElement()) {
    const char* mode = child->Attribute("inkscape:groupmode");
    const bool layer = local_name(*child) == "g" && mode != nullptr && std::string_view(mode) == "layer";
    std::optional<std::size_t> index;
    if (layer) {
      const char* label = child->Attribute("inkscape:label");
      if (label == nullptr) label = child->Attribute("id");
      layers_.push_back(Layer{label != nullptr ? std::string(label) : "layer " + std::to_string(layers_.size() + 1), true});
      index = layers_.size() - 1;
    }
    const std::size_t first = drawn_.size();
    visit(*child, root_scope);
    if (!index && drawn_.size() > first) {
      if (!outside) {
        layers_.push_back(Layer{"", false});
        outside = layers_.size() - 1;
      }
      index = outside;
    }
    for (std::size_t i = first; i < drawn_.size(); ++i) drawn_[i].layer = index.value_or(0);
  }
  text_.missing_glyphs_note();
}

void ElementWalk::collect_style_sheets(const tinyxml2::XMLElement& element) {
  if (local_name(element) == "style" && element.GetText() != nullptr) styles_.add(element.GetText());
  for (const auto* child = element.FirstChildElement(); child != nullptr; child = child->NextSiblingElement()) {
    collect_style_sheets(*child);
  }
}

const tinyxml2::XMLElement* ElementWalk::switch_choice(const tinyxml2::XMLElement& element) {
  for (const auto* child = element.FirstChildElement(); child != nullptr; child = child->NextSiblingElement()) {
    const std::string full_name = child->Name();
    if (full_name.find(':') != std::string::npos && full_name.rfind("svg:", 0) != 0) continue;  // another namespace
    const std::string name = local_name(*child);
    if (name == "title" || name == "desc" || name == "metadata") continue;
    if (child->Attribute("requiredExtensions") != nullptr) continue;
    return child;
  }
  return nullptr;
}

void ElementWalk::index_ids(const tinyxml2::XMLElement& element) {
  if (const char* id = element.Attribute("id")) ids_.emplace(id, &element);
  for (const auto* child = element.FirstChildElement(); child != nullptr; child = child->NextSiblingElement()) index_ids(*child);
}

void ElementWalk::visit_children(const tinyxml2::XMLElement& parent, const Scope& scope) {
  for (const auto* child = parent.FirstChildElement(); child != nullptr; child = child->NextSiblingElement()) visit(*child, scope);
}

void ElementWalk::visit(const tinyxml2::XMLElement& element, const Scope& parent, const ViewportSize& use_size) {
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
  if (styles_.property(element, "display") == "none") return;
  Scope scope = parent;
  scope.lengths.font_size =
      font_size(diagnostics_, element, styles_.property(element, "font-size"), parent.lengths.font_size, parent.lengths);
  if (const std::string visibility = styles_.property(element, "visibility"); !visibility.empty() && visibility != "inherit") {
    scope.visible = visibility == "visible";
  }
  if (const std::string stroke = styles_.property(element, "stroke"); !stroke.empty() && stroke != "inherit") scope.stroke = stroke;
  if (const std::string fill = styles_.property(element, "fill"); !fill.empty() && fill != "inherit") scope.fill = fill;
  for (const char* property : {"marker", "marker-start", "marker-mid", "marker-end"}) {  // the shorthand first
    const std::string value = styles_.property(element, property);
    if (value.empty() || value == "inherit") continue;
    scope.marker = value == "none" ? std::string() : std::string(property) + " " + value;
  }
  if (name == "g" || name == "a") {
    scope.map = with_transform(diagnostics_, element, parent.map, scope.lengths);
    visit_children(element, scope);
    return;
  }
  if (name == "switch") {
    scope.map = with_transform(diagnostics_, element, parent.map, scope.lengths);
    if (const auto* chosen = switch_choice(element)) visit(*chosen, scope);
    return;
  }
  if (name == "svg") {
    viewport(element, scope, with_transform(diagnostics_, element, parent.map, scope.lengths), use_size);
    return;
  }
  scope.map = with_transform(diagnostics_, element, parent.map, scope.lengths);
  const LengthContext& lengths = scope.lengths;
  const bool shape = name == "path" || name == "rect" || name == "circle" || name == "ellipse" || name == "line" ||
                     name == "polyline" || name == "polygon" || name == "text";
  if (shape && name != "text" && !scope.visible) return;  // visibility: hidden / collapse (a tspan may be visible again)
  if (shape && scope.stroke == "none" && scope.fill == "none") {
    diagnostics_.warn(element, "is not drawn (stroke and fill are none: invisible)");
    return;
  }
  if (shape) note_unseen_style(element, scope);
  std::vector<Subpath> subpaths;
  if (name == "path") {
    const char* data = element.Attribute("d");
    if (data == nullptr) return;  // no d: nothing to draw
    PathData parsed = parse_path_data_until_error(data);
    if (parsed.error) {  // SVG's error rule: render up to the error (strict: refuse the file)
      if (strict_) diagnostics_.fail_syntax(element, "d", *parsed.error);
      const std::string at = std::to_string(parsed.error->position());
      diagnostics_.warn_at(element, "d",
                           "at character " + at + ": " + parsed.error->what() + " (drawn up to character " + at +
                               ", as SVG renders; strict import refuses the file)");
    }
    subpaths = std::move(parsed.subpaths);
  } else if (name == "rect") {
    subpaths = rect_outline(diagnostics_, element, lengths);
  } else if (name == "circle" || name == "ellipse") {
    subpaths = ellipse_outline(diagnostics_, element, name == "circle", lengths);
  } else if (name == "line") {
    subpaths = line_outline(diagnostics_, element, lengths);
  } else if (name == "polyline" || name == "polygon") {
    subpaths = poly_outline(diagnostics_, element, name == "polygon", strict_);
  } else if (name == "use") {
    use(element, scope);
    return;
  } else if (name == "text") {
    subpaths = text_.strokes(element, lengths, scope.visible);
  } else if (name == "image" || name == "foreignObject") {
    diagnostics_.warn(element, "is not drawn");
    return;
  } else {
    diagnostics_.warn(element, "is not drawn (unknown element)");
    return;
  }
  append_machine_subpaths(diagnostics_, element, name == "path" ? "d" : "", scope.map, subpaths, drawn_);
}

namespace {

/// White as a fill colour: "white", "#fff", "#ffffff", "rgb(255, 255, 255)" in any case.
bool is_white(std::string colour) {
  colour.erase(std::remove_if(colour.begin(), colour.end(), [](unsigned char c) { return std::isspace(c) != 0; }), colour.end());
  std::transform(colour.begin(), colour.end(), colour.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return colour == "white" || colour == "#fff" || colour == "#ffffff" || colour == "rgb(255,255,255)";
}

}  // namespace

void ElementWalk::note_unseen_style(const tinyxml2::XMLElement& element, const Scope& scope) {
  const std::string name = local_name(element);
  const bool marked = name == "path" || name == "line" || name == "polyline" || name == "polygon";  // the shapes markers apply to
  if (!marker_noted_ && marked && !scope.marker.empty()) {
    diagnostics_.warn(element, scope.marker + ": markers (arrowheads, dots) are not drawn (noted once per file)");
    marker_noted_ = true;
  }
  if (!white_fill_noted_ && name != "text" && scope.stroke == "none" && is_white(scope.fill)) {  // text is drawn in strokes
    diagnostics_.warn(element, "has a white fill and no stroke, invisible on white paper, and is drawn as an outline "
                               "(a background? noted once per file)");
    white_fill_noted_ = true;
  }
}

void ElementWalk::viewport(const tinyxml2::XMLElement& element, const Scope& scope, const Affine& placed, const ViewportSize& size) {
  const LengthContext& outer = scope.lengths;
  const double x = length(diagnostics_, element, "x", 0, outer, LengthAxis::X);
  const double y = length(diagnostics_, element, "y", 0, outer, LengthAxis::Y);
  const auto box = view_box(diagnostics_, element);
  // width and height: the use's, else the element's own, else 100% (the viewBox size if that is unknown).
  auto width = size.width ? size.width : svg::size(diagnostics_, element, "width", outer, LengthAxis::X);
  auto height = size.height ? size.height : svg::size(diagnostics_, element, "height", outer, LengthAxis::Y);
  if (!width && outer.viewport_width > 0) width = outer.viewport_width;
  if (!height && outer.viewport_height > 0) height = outer.viewport_height;
  Scope inner = scope;
  inner.map = placed * Affine{1, 0, 0, 1, x, y};
  if (box) {
    inner.map = inner.map * viewbox_map(diagnostics_, element, *box, width.value_or((*box)[2]), height.value_or((*box)[3]));
    inner.lengths.viewport_width = (*box)[2];
    inner.lengths.viewport_height = (*box)[3];
  } else {
    inner.lengths.viewport_width = width.value_or(0);
    inner.lengths.viewport_height = height.value_or(0);
  }
  visit_children(element, inner);
}

void ElementWalk::use(const tinyxml2::XMLElement& element, const Scope& scope) {
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
  const LengthContext& lengths = scope.lengths;
  const ViewportSize given{svg::size(diagnostics_, element, "width", lengths, LengthAxis::X),
                           svg::size(diagnostics_, element, "height", lengths, LengthAxis::Y)};
  Scope placed = scope;
  placed.map = scope.map * Affine{1, 0, 0, 1, length(diagnostics_, element, "x", 0, lengths, LengthAxis::X),
                                  length(diagnostics_, element, "y", 0, lengths, LengthAxis::Y)};
  if (local_name(target) == "symbol") {
    if (styles_.property(target, "display") != "none") {
      Scope symbol = placed;
      symbol.lengths.font_size =
          font_size(diagnostics_, target, styles_.property(target, "font-size"), placed.lengths.font_size, placed.lengths);
      viewport(target, symbol, with_transform(diagnostics_, target, placed.map, symbol.lengths), given);
    }
  } else {
    visit(target, placed, given);
  }
  active_uses_.pop_back();
}

}  // namespace curvestep::host::svg
