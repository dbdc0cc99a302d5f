// SPDX-License-Identifier: MIT
// SVG documents (tinyxml2) -> machine-space subpaths -> a host Job, optionally reordered.
//
// Coordinates: user space is mapped to millimetres with y down by the root viewport (width,
// height, viewBox, preserveAspectRatio; user units are px = 1/96 in without a viewBox), then
// flipped to machine coordinates with y up about the page's bottom edge: y_machine = H - y_mm, H the
// page height in mm (y_machine = -y_mm when the page has no height), so the page's bottom-left
// corner is the machine origin. Each element's affine map is that root map ∘ the transforms of its
// ancestors and its own; pieces are mapped point by point (exact for Béziers and rational Béziers).
//
// The work is split by job: svg_lengths (units), svg_viewport (viewBox, the root map, transforms),
// svg_walk (the element tree), svg_shapes (basic shapes), path_data (path data and arcs), text/ (<text>
// in the Hershey single-stroke font),
// svg_machine (machine mm on the Q16.16 grid), svg_job_builder (order, rapids, the Job).
#include <curvestep/host/svg_import.hpp>

#include <algorithm>
#include <string>
#include <utility>

#include <tinyxml2.h>

#include "svg_attributes.hpp"
#include "svg_diagnostics.hpp"
#include "svg_job_builder.hpp"
#include "svg_layers.hpp"
#include "svg_viewport.hpp"
#include "svg_walk.hpp"

namespace curvestep::host {
namespace {

/// Plain words for tinyxml2's error ids.
std::string xml_error_text(tinyxml2::XMLError error) {
  switch (error) {
    case tinyxml2::XML_ERROR_EMPTY_DOCUMENT: return "the file is empty";
    case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT: return "an end tag does not match its start tag";
    case tinyxml2::XML_ERROR_PARSING_ELEMENT: return "malformed element (an unclosed tag or a missing end tag)";
    case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE: return "malformed attribute (attribute values need quotes)";
    case tinyxml2::XML_ERROR_PARSING_TEXT: return "malformed text";
    case tinyxml2::XML_ERROR_PARSING_CDATA: return "malformed CDATA section";
    case tinyxml2::XML_ERROR_PARSING_COMMENT: return "malformed comment";
    case tinyxml2::XML_ERROR_PARSING_DECLARATION: return "malformed declaration";
    case tinyxml2::XML_ERROR_PARSING_UNKNOWN: return "malformed <!...> construct";
    default: return "malformed XML";
  }
}

SvgImport read_document(std::string_view text, std::string name, const SvgOptions& options) {
  svg::Diagnostics diagnostics(std::move(name));
  tinyxml2::XMLDocument document;
  document.Parse(text.data(), text.size());
  if (document.Error()) {
    std::string detail;
    if (const char* raw = document.ErrorStr()) {
      const std::string all = raw;
      const auto colon = all.find(": ", all.find("Line number="));
      if (all.find("Line number=") != std::string::npos && colon != std::string::npos) detail = " (" + all.substr(colon + 2) + ")";
    }
    diagnostics.fail_at(static_cast<std::size_t>(std::max(document.ErrorLineNum(), 0)), "",
                        "invalid XML: " + xml_error_text(document.ErrorID()) + detail);
  }
  const tinyxml2::XMLElement* root = document.RootElement();
  if (root == nullptr) diagnostics.fail_at(1, "", "invalid XML: no root element");
  if (svg::local_name(*root) != "svg") {
    diagnostics.fail(*root, "", "the root element is <" + std::string(root->Name()) + ">, expected <svg>");
  }
  svg::ElementWalk walk(diagnostics, options.strict);
  const svg::RootViewport viewport = svg::root_viewport(diagnostics, *root);
  svg::Scope root_scope;
  root_scope.map = viewport.map;
  root_scope.lengths = viewport.lengths;
  walk.walk(*root, root_scope);
  if (walk.drawn().empty()) {  // say what was there but not drawn: an Inkscape <flowRoot>, invisible shapes, ...
    const std::vector<std::string> skipped = diagnostics.take_warnings();
    std::string why;
    constexpr std::size_t named = 3;  // the first of them: one may be a mere note (font-family) beside the cause
    for (std::size_t i = 0; i < skipped.size() && i < named; ++i) why += (i == 0 ? " (" : "; ") + skipped[i];
    if (skipped.size() > named) {
      const std::size_t more = skipped.size() - named;
      why += "; and " + std::to_string(more) + (more == 1 ? " more warning" : " more warnings");
    }
    if (!why.empty()) why += ")";
    diagnostics.fail(*root, "", "the drawing has no paths or shapes to draw" + why);
  }
  svg::select_layers(diagnostics, walk.layers(), options.layers, walk.drawn());
  SvgImport imported = svg::build_import(diagnostics, std::move(walk.drawn()), options, diagnostics.take_warnings(), walk.layers());
  imported.page_width_mm = viewport.width_mm;
  imported.page_height_mm = viewport.height_mm;
  return imported;
}

}  // namespace

SvgImport parse_svg(std::string_view text, std::string name, const SvgOptions& options) {
  return read_document(text, std::move(name), options);
}

SvgImport load_svg(const std::filesystem::path& path, const SvgOptions& options) {
  return parse_svg(read_text_file(path), path.string(), options);
}

Job import_svg(const std::filesystem::path& path, const SvgOptions& options) { return load_svg(path, options).job; }

Job parse_svg_job(std::string_view text, std::string name, const SvgOptions& options) {
  return parse_svg(text, std::move(name), options).job;
}

}  // namespace curvestep::host
