// SPDX-License-Identifier: MIT
// RefinablePolygon: a fixed-capacity polygon refined in place, level after level, no heap.
//
// Repeated refinement needs the previous level while the next is written, so the polygon keeps
// two buffers of Capacity vertices and swaps them after each step (2·Capacity·Dim scalars).
// A closed polygon grows by the arity per step (N, aN, a²N, …); an open one a little less or
// more, depending on the boundary rule (see refine.hpp). A step whose result would not fit is
// refused with CapacityExceeded and leaves the polygon as it was.
#pragma once

#include <array>
#include <cstddef>
#include <span>

#include <curvestep/core/subdivision/refine.hpp>

namespace curvestep {

/// A polygon of at most Capacity vertices with its boundary rule, refined by try_refine().
template <Scalar S, std::size_t Dim, std::size_t Capacity>
class RefinablePolygon {
  static_assert(Capacity > 0, "a polygon needs room for at least one vertex");

 public:
  using Point = Vec<S, Dim>;

  /// An empty closed polygon.
  constexpr RefinablePolygon() = default;

  /// A polygon with the given vertices. CapacityExceeded (index = count) if they do not fit,
  /// TooFewPoints if the boundary rule needs more vertices, NotFinite (index = vertex).
  [[nodiscard]] static constexpr Result<RefinablePolygon> create(std::span<const Point> vertices, Boundary boundary) noexcept {
    if (vertices.size() > Capacity) return fail(Error::CapacityExceeded, vertices.size());
    if (vertices.size() < (boundary == Boundary::Closed ? 1u : 2u)) return fail(Error::TooFewPoints, vertices.size());
    RefinablePolygon polygon;
    polygon.boundary_ = boundary;
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      for (std::size_t axis = 0; axis < Dim; ++axis) {
        if (!is_finite(vertices[i][axis])) return fail(Error::NotFinite, i);
      }
      polygon.buffers_[0][i] = vertices[i];
    }
    polygon.count_ = vertices.size();
    return polygon;
  }

  /// Applies `steps` refinement steps. CapacityExceeded (index = vertices needed) if a level would
  /// not fit (the polygon keeps the last level that did); FixedOverflow/NotFinite from refine().
  [[nodiscard]] constexpr Result<void> try_refine(const SubdivisionMask& mask, std::size_t steps = 1) noexcept {
    for (std::size_t step = 0; step < steps; ++step) {
      CURVESTEP_TRY(const RefinedRange range, refined_range(mask, count_, boundary_));
      if (range.count > Capacity) return fail(Error::CapacityExceeded, range.count);
      auto& from = buffers_[current_];
      auto& to = buffers_[1 - current_];
      CURVESTEP_TRY(const RefinedRange written, refine(mask, std::span<const Point>(from.data(), count_), boundary_,
                                                       std::span<Point>(to.data(), Capacity)));
      current_ = 1 - current_;
      count_ = written.count;
    }
    return ok();
  }

  /// The current vertices.
  [[nodiscard]] constexpr std::span<const Point> vertices() const noexcept {
    return std::span<const Point>(buffers_[current_].data(), count_);
  }
  /// The boundary rule used by every step.
  [[nodiscard]] constexpr Boundary boundary() const noexcept { return boundary_; }
  /// Number of current vertices.
  [[nodiscard]] constexpr std::size_t size() const noexcept { return count_; }
  /// Most vertices a level may have.
  [[nodiscard]] static constexpr std::size_t capacity() noexcept { return Capacity; }

 private:
  std::array<std::array<Point, Capacity>, 2> buffers_{};
  std::size_t current_ = 0;
  std::size_t count_ = 0;
  Boundary boundary_ = Boundary::Closed;
};

}  // namespace curvestep
