// SPDX-License-Identifier: MIT
// Internal: the element walk — groups, nested viewports, <use>, shapes, paths and text, each drawn through
// its affine map into machine subpaths.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <tinyxml2.h>

#include "svg_css.hpp"
#include "svg_diagnostics.hpp"
#include "svg_geometry.hpp"
#include "svg_layers.hpp"
#include "svg_lengths.hpp"
#include "svg_machine.hpp"
#include "text/svg_text.hpp"

namespace curvestep::host::svg {

/// What an element inherits from its parent.
struct Scope {
  Affine map;             ///< user space -> machine mm
  LengthContext lengths;  ///< viewport, font-size and root size for relative lengths
  bool visible = true;    ///< computed visibility (inherited): hidden and collapse are not drawn
  std::string stroke = "none";   ///< computed stroke (inherited)
  std::string fill = "black";    ///< computed fill (inherited)
  std::string marker;            ///< "marker-end url(#a)": a marker property in force (inherited), empty if none
};

/// Width and height a <use> gives the <svg> or <symbol> it references (nullopt: not given).
struct ViewportSize {
  std::optional<double> width;   ///< user units of the use
  std::optional<double> height;  ///< user units of the use
};

/// Walks a document's elements and collects what they draw.
class ElementWalk {
 public:
  /// `strict`: a path-data or points error refuses the file (else: drawn up to the error, with a warning).
  ElementWalk(Diagnostics& diagnostics, bool strict) : diagnostics_(diagnostics), strict_(strict) {}

  /// Draws the root's children in the root's scope (its map to machine mm and its lengths).
  void walk(const tinyxml2::XMLElement& root, const Scope& root_scope);

  /// What was drawn, in document order.
  [[nodiscard]] std::vector<DrawnSubpath>& drawn() noexcept { return drawn_; }
  /// The top-level layers in document order (DrawnSubpath::layer indexes them); the content outside
  /// layers is one more entry, placed where the first of it is drawn.
  [[nodiscard]] const std::vector<Layer>& layers() const noexcept { return layers_; }

 private:
  void index_ids(const tinyxml2::XMLElement& element);
  void visit_children(const tinyxml2::XMLElement& parent, const Scope& scope);
  void visit(const tinyxml2::XMLElement& element, const Scope& parent, const ViewportSize& use_size = {});
  /// A nested viewport (<svg>, or a <symbol> through <use>) at x, y of width × height with its viewBox.
  void viewport(const tinyxml2::XMLElement& element, const Scope& scope, const Affine& placed, const ViewportSize& size);
  void use(const tinyxml2::XMLElement& element, const Scope& scope);
  void collect_style_sheets(const tinyxml2::XMLElement& element);
  /// One note per file for what a renderer shows and a pen does not (markers), or the reverse (a
  /// white fill without stroke: a matplotlib figure's background).
  void note_unseen_style(const tinyxml2::XMLElement& element, const Scope& scope);
  /// The child a <switch> renders: the first SVG element that is not title/desc/metadata and has no
  /// requiredExtensions (no extension is supported; every other condition passes).
  [[nodiscard]] static const tinyxml2::XMLElement* switch_choice(const tinyxml2::XMLElement& element);

  Diagnostics& diagnostics_;
  bool strict_ = false;
  std::vector<DrawnSubpath> drawn_;
  std::vector<Layer> layers_;
  StyleSheet styles_;
  TextLayout text_{diagnostics_, styles_};
  std::map<std::string, const tinyxml2::XMLElement*> ids_;
  std::vector<const tinyxml2::XMLElement*> active_uses_;
  std::size_t expanded_elements_ = 0;  ///< elements visited through <use>, all uses together
  bool marker_noted_ = false;
  bool white_fill_noted_ = false;
};

}  // namespace curvestep::host::svg
