// SPDX-License-Identifier: MIT
// Internal: the element walk — groups, nested viewports, <use>, shapes and paths, each drawn through
// its affine map into machine subpaths.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include <tinyxml2.h>

#include "svg_diagnostics.hpp"
#include "svg_geometry.hpp"
#include "svg_machine.hpp"

namespace curvestep::host::svg {

/// Walks a document's elements and collects what they draw.
class ElementWalk {
 public:
  explicit ElementWalk(Diagnostics& diagnostics) : diagnostics_(diagnostics) {}

  /// Draws the root's children through `root_map` (root user space -> machine mm).
  void walk(const tinyxml2::XMLElement& root, const Affine& root_map);

  /// What was drawn, in document order.
  [[nodiscard]] std::vector<DrawnSubpath>& drawn() noexcept { return drawn_; }

 private:
  void index_ids(const tinyxml2::XMLElement& element);
  void visit_children(const tinyxml2::XMLElement& parent, const Affine& map);
  void visit(const tinyxml2::XMLElement& element, const Affine& parent_map);
  void use(const tinyxml2::XMLElement& element, const Affine& map);

  Diagnostics& diagnostics_;
  std::vector<DrawnSubpath> drawn_;
  std::map<std::string, const tinyxml2::XMLElement*> ids_;
  std::vector<const tinyxml2::XMLElement*> active_uses_;
  std::size_t expanded_elements_ = 0;  ///< elements visited through <use>, all uses together
};

}  // namespace curvestep::host::svg
