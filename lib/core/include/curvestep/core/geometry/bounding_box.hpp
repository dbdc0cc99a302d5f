// SPDX-License-Identifier: MIT
// BoundingBox: the axis-aligned box of a set of points (a curve lies in its control points' box).
#pragma once

#include <cstddef>
#include <span>

#include <curvestep/core/contract.hpp>
#include <curvestep/core/geometry/vec.hpp>

namespace curvestep {

/// An axis-aligned box [low, high].
template <Scalar S, std::size_t Dim>
struct BoundingBox {
  Vec<S, Dim> low{};   ///< smallest coordinate on each axis
  Vec<S, Dim> high{};  ///< largest coordinate on each axis

  /// True if p lies in the box, boundary included.
  [[nodiscard]] constexpr bool contains(const Vec<S, Dim>& p) const {
    for (std::size_t i = 0; i < Dim; ++i) {
      if (p[i] < low[i] || high[i] < p[i]) return false;
    }
    return true;
  }
  /// Grows the box to include p.
  constexpr void include(const Vec<S, Dim>& p) {
    for (std::size_t i = 0; i < Dim; ++i) {
      if (p[i] < low[i]) low[i] = p[i];
      if (high[i] < p[i]) high[i] = p[i];
    }
  }
};

/// The box of a non-empty set of points.
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr BoundingBox<S, Dim> bounding_box(std::span<const Vec<S, Dim>> points) {
  CURVESTEP_EXPECTS(!points.empty());
  BoundingBox<S, Dim> box{points[0], points[0]};
  for (const auto& p : points) box.include(p);
  return box;
}

}  // namespace curvestep
