// SPDX-License-Identifier: MIT
// User space -> machine millimetres on the Q16.16 grid (svg_machine.hpp).
//
// Wire grid: the wire carries coordinates, weights and feeds as Q16.16, so all three are rounded
// to the nearest Q16.16 value here, by the same Q16_16::from_double the job loader and the G-code
// importer use (docs/job_format.md, "Weights and feeds"): the simulator then sees the job exactly
// as a device receives it. An arc's middle weight is cos(δ/2) with δ ≤ 90°, so it lies in
// [√2/2, 1] and rounds by at most 2^-17; the weight √2/2 of quarter arcs becomes 46341/65536.
#include "svg_machine.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/host/csv.hpp>
#include <curvestep/host/wire_value.hpp>

namespace curvestep::host::svg {
namespace {

MachinePoint machine_point(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const Affine& map, Point2 user) {
  const Point2 mm = map.apply(user);
  MachinePoint p{};
  const double values[2] = {mm.x, mm.y};
  for (std::size_t axis = 0; axis < 2; ++axis) {
    const auto q = Q16_16::from_double(values[axis]);
    if (!std::isfinite(values[axis])) {
      diagnostics.fail(element, "",
                       "the point (" + format_number(user.x) + ", " + format_number(user.y) +
                           ") in user units has no finite image (an arc or a transform too large for double precision)",
                       Error::NotFinite);
    }
    if (!q) {
      diagnostics.fail(element, "",
                       "the point (" + format_number(user.x) + ", " + format_number(user.y) + ") in user units lands at (" +
                           format_number(mm.x) + ", " + format_number(mm.y) +
                           ") mm, outside the Q16.16 range (-32768 to 32768 mm)",
                       Error::FixedOverflow);
    }
    p[axis] = q.value().to_double();
  }
  return p;
}

/// A conic's middle weight on the Q16.16 grid, as the wire carries it; the job loader's errors
/// for a weight out of range or rounding to 0, at the element (and the path command) of the piece.
double wire_weight(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const char* attribute, const Piece& piece) {
  const double weight = piece.weight;
  std::string cause;
  Error code = Error::NonPositiveWeight;
  if (!(weight > 0) || !std::isfinite(weight)) {
    cause = "weight " + format_number(weight) + " is not a finite positive number";
    if (!std::isfinite(weight)) code = Error::NotFinite;
  } else {
    auto rounded = round_for_wire(weight, WireQuantity::Weight);
    if (rounded) return rounded.value;
    cause = std::move(rounded.problem);
    code = rounded.code;
  }
  const Point2 from = piece.points[0];
  const Point2 to = piece.points[piece.count - 1];
  const std::string where = piece.position > 0 ? "at character " + std::to_string(piece.position) + ": " : "";
  diagnostics.fail(element, attribute,
                   where + "the arc from (" + format_number(from.x) + ", " + format_number(from.y) + ") to (" +
                       format_number(to.x) + ", " + format_number(to.y) + ") in user units: " + cause,
                   code);
}

}  // namespace

void DrawnSubpath::reverse() {
  std::reverse(pieces.begin(), pieces.end());
  for (auto& piece : pieces) {
    std::reverse(piece.points.begin(), piece.points.end());
    std::reverse(piece.weights.begin(), piece.weights.end());
  }
}

void append_machine_subpaths(const Diagnostics& diagnostics, const tinyxml2::XMLElement& element, const char* attribute,
                             const Affine& map, const std::vector<Subpath>& subpaths, std::vector<DrawnSubpath>& out) {
  for (const auto& subpath : subpaths) {
    DrawnSubpath drawn;
    drawn.line = static_cast<std::size_t>(element.GetLineNum());
    for (const auto& piece : subpath.pieces) {
      MachinePiece machine;
      for (std::size_t i = 0; i < piece.count; ++i) machine.points.push_back(machine_point(diagnostics, element, map, piece.points[i]));
      if (std::all_of(machine.points.begin(), machine.points.end(), [&](const MachinePoint& p) { return p == machine.points.front(); })) {
        continue;  // vanished on the Q16.16 grid
      }
      switch (piece.kind) {
        case PieceKind::Line: machine.type = SegmentType::Line; break;
        case PieceKind::Quadratic:
        case PieceKind::Cubic: machine.type = SegmentType::Bezier; break;
        case PieceKind::Conic:
          machine.type = SegmentType::RationalBezier;
          machine.weights = {1.0, wire_weight(diagnostics, element, attribute, piece), 1.0};
          break;
      }
      drawn.pieces.push_back(std::move(machine));
    }
    if (!drawn.pieces.empty()) out.push_back(std::move(drawn));
  }
}

}  // namespace curvestep::host::svg
