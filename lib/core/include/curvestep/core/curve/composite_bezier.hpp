// SPDX-License-Identifier: MIT
// CompositeBezier: segments joined end to end, each on its own global interval [u_j, u_{j+1}].
//
// Segment j maps the global parameter u to its local t = (u - u_j) / (u_{j+1} - u_j), so its
// r-th derivative with respect to u is its local derivative divided by (u_{j+1} - u_j)^r. The
// interval lengths therefore decide the continuity class (C^r) of a given control polygon,
// while its shape stays the same. Segment lookup is a binary search over the breakpoints.
#pragma once

#include <array>
#include <cstddef>

#include <curvestep/core/curve/bezier.hpp>

namespace curvestep {

/// Up to MaxSegments Bézier segments of degree <= MaxDegree with increasing breakpoints.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxSegments>
class CompositeBezier {
  static_assert(MaxSegments > 0, "a composite curve needs room for at least one segment");

 public:
  using scalar_type = S;
  using Point = Vec<S, Dim>;
  using Segment = Bezier<S, Dim, MaxDegree>;

  /// Where a global parameter falls: the segment and the local parameter in [0,1].
  struct Location {
    std::size_t segment = 0;  ///< segment index
    S local{};                ///< local parameter t in [0,1]
  };

  /// An empty curve whose first segment will start at global parameter `start`.
  constexpr explicit CompositeBezier(S start = S{}) noexcept { breakpoints_[0] = start; }

  /// Appends a segment on [last breakpoint, end]. InvalidInterval if end is not after the last
  /// breakpoint, FixedOverflow if the width end - last breakpoint is not representable (every
  /// lookup and derivative divides by it), CapacityExceeded when full. Continuity is not required
  /// (check it with continuity()). The index is the segment's.
  [[nodiscard]] constexpr Result<void> try_append(const Segment& segment, S end) noexcept {
    if (count_ == MaxSegments) return fail(Error::CapacityExceeded, count_);
    if (!(breakpoints_[count_] < end)) return fail(Error::InvalidInterval, count_);
    if (const auto width = checked_sub(end, breakpoints_[count_]); !width) return fail(width.error(), count_);
    segments_[count_] = segment;
    breakpoints_[++count_] = end;
    return ok();
  }

  [[nodiscard]] constexpr std::size_t size() const noexcept { return count_; }
  [[nodiscard]] static constexpr std::size_t capacity() noexcept { return MaxSegments; }
  [[nodiscard]] constexpr bool full() const noexcept { return count_ == MaxSegments; }
  [[nodiscard]] constexpr std::size_t available() const noexcept { return MaxSegments - count_; }
  /// Segment j; contract j < size().
  [[nodiscard]] constexpr const Segment& segment(std::size_t j) const {
    CURVESTEP_EXPECTS(j < count_);
    return segments_[j];
  }
  /// Breakpoint u_j, j <= size().
  [[nodiscard]] constexpr S breakpoint(std::size_t j) const {
    CURVESTEP_EXPECTS(j <= count_);
    return breakpoints_[j];
  }
  /// The global domain [u_0, u_m].
  [[nodiscard]] constexpr S domain_start() const noexcept { return breakpoints_[0]; }
  [[nodiscard]] constexpr S domain_end() const noexcept { return breakpoints_[count_]; }

  /// The segment containing u and the local parameter (u on a breakpoint belongs to the later
  /// segment, except at the end). ParameterOutOfRange outside the domain or when empty.
  [[nodiscard]] constexpr Result<Location> locate(S u) const {
    if (count_ == 0 || !(domain_start() <= u && u <= domain_end())) return fail(Error::ParameterOutOfRange);  // NaN too
    std::size_t low = 0;
    std::size_t high = count_;  // invariant: breakpoints_[low] <= u, answer in [low, high)
    while (high - low > 1) {
      const std::size_t middle = low + (high - low) / 2;
      if (breakpoints_[middle] <= u) {
        low = middle;
      } else {
        high = middle;
      }
    }
    const S width = breakpoints_[low + 1] - breakpoints_[low];
    S t = (u - breakpoints_[low]) / width;
    if (from_int<S>(1) < t) t = from_int<S>(1);
    return Location{low, t};
  }

  /// s(u) for u in the domain.
  [[nodiscard]] constexpr Result<Point> evaluate(S u) const {
    CURVESTEP_TRY(const auto where, locate(u));
    return segments_[where.segment].point_at(where.local);
  }

  /// s^(order)(u): the local derivative scaled by 1 / (segment width)^order.
  [[nodiscard]] constexpr Result<Point> derivative_at(S u, std::size_t order = 1) const {
    CURVESTEP_TRY(const auto where, locate(u));
    return segment_derivative(where.segment, where.local, order);
  }

  /// Derivative of segment j at its local t with respect to the global parameter.
  [[nodiscard]] constexpr Result<Point> segment_derivative(std::size_t j, S t, std::size_t order) const {
    CURVESTEP_EXPECTS(j < count_);
    CURVESTEP_TRY(auto d, segments_[j].derivative_at(t, order));
    const S width = breakpoints_[j + 1] - breakpoints_[j];
    for (std::size_t k = 0; k < order; ++k) {
      for (std::size_t axis = 0; axis < Dim; ++axis) {
        CURVESTEP_TRY(d[axis], checked_div(d[axis], width));
      }
    }
    return d;
  }

 private:
  std::array<Segment, MaxSegments> segments_{};
  std::array<S, MaxSegments + 1> breakpoints_{};
  std::size_t count_ = 0;
};

}  // namespace curvestep
