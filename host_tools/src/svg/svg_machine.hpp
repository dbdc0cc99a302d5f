// SPDX-License-Identifier: MIT
// Internal: user-space subpaths mapped onto machine millimetres (y up) on the Q16.16 grid.
#pragma once

#include <cstddef>
#include <vector>

#include <tinyxml2.h>

#include <curvestep/core/motion/path_segment.hpp>
#include <curvestep/host/job.hpp>

#include "svg_diagnostics.hpp"
#include "svg_geometry.hpp"

namespace curvestep::host::svg {

/// One drawn piece in machine coordinates (mm, on the Q16.16 grid).
struct MachinePiece {
  SegmentType type = SegmentType::Line;
  std::vector<MachinePoint> points;
  std::vector<double> weights;  ///< rational pieces only
};

/// One pen-down stretch.
struct DrawnSubpath {
  std::vector<MachinePiece> pieces;
  std::size_t line = 0;   ///< line of the element in the file
  std::size_t layer = 0;  ///< index of its layer in the walk's layers (svg_layers.hpp)
  [[nodiscard]] const MachinePoint& start() const { return pieces.front().points.front(); }
  [[nodiscard]] const MachinePoint& end() const { return pieces.back().points.back(); }
  [[nodiscard]] bool closed() const { return start() == end(); }
  /// Traces the same curve backwards.
  void reverse();
};

/// Maps `subpaths` of `element` through `map` (user units -> machine mm) and appends the pieces that
/// do not vanish on the grid to `out`. LoadError for a point outside Q16.16 or not finite, or a weight
/// the wire cannot carry (`attribute` names the path data, if any).
void append_machine_subpaths(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const char* attribute,
                             const Affine& map, const std::vector<Subpath>& subpaths, std::vector<DrawnSubpath>& out);

}  // namespace curvestep::host::svg
