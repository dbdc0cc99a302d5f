// SPDX-License-Identifier: MIT
// Shared input checks and output assembly for the interpolating splines (internal).
#pragma once

#include <cstddef>
#include <span>

#include <curvestep/core/curve/composite_bezier.hpp>
#include <curvestep/core/detail/checked.hpp>
#include <curvestep/core/interpolation/hermite.hpp>

namespace curvestep::detail {

/// NotFinite (index = point) for NaN/inf coordinates.
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr Result<void> check_interpolation_points(std::span<const Vec<S, Dim>> points) noexcept {
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t axis = 0; axis < Dim; ++axis) {
      if (!is_finite(points[i][axis])) return fail(Error::NotFinite, i);
    }
  }
  return ok();
}

/// InvalidArgument (index = knot count) for the wrong count; InvalidInterval (index = knot) if
/// the knots are not strictly increasing; NotFinite for NaN/inf.
template <Scalar S>
[[nodiscard]] constexpr Result<void> check_interpolation_knots(std::span<const S> knots, std::size_t expected_count) noexcept {
  if (knots.size() != expected_count) return fail(Error::InvalidArgument, knots.size());
  for (std::size_t i = 0; i < knots.size(); ++i) {
    if (!is_finite(knots[i])) return fail(Error::NotFinite, i);
    if (i > 0 && !(knots[i - 1] < knots[i])) return fail(Error::InvalidInterval, i);
  }
  return ok();
}

/// The uniform knot u_j = j (FixedOverflow past the Q range).
template <Scalar S>
[[nodiscard]] constexpr Result<S> uniform_knot(std::size_t j) noexcept {
  if constexpr (FixedPoint<S>) {
    return S::from_integer(static_cast<long long>(j));
  } else {
    return static_cast<S>(j);
  }
}

/// Interval width u_{i+1} − u_i, checked.
template <Scalar S>
[[nodiscard]] constexpr Result<S> knot_interval(std::span<const S> knots, std::size_t i) noexcept {
  const auto h = checked_sub(knots[i + 1], knots[i]);
  if (!h) return fail(h.error(), i);
  return h.value();
}

/// Replaces `out` with the Hermite segments through points[i] → points[(i+1) mod n] with
/// tangents (derivatives in u) tangents[i], on [knots[i], knots[i+1]], i < segment_count.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxSegments>
[[nodiscard]] constexpr Result<void> assemble_hermite(std::span<const Vec<S, Dim>> points, std::span<const Vec<S, Dim>> tangents,
                                                      std::span<const S> knots, std::size_t segment_count,
                                                      CompositeBezier<S, Dim, MaxDegree, MaxSegments>& out) noexcept {
  using Curve = CompositeBezier<S, Dim, MaxDegree, MaxSegments>;
  out = Curve(knots[0]);  // written in place (no second copy on the stack); emptied on failure
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < segment_count; ++i) {
    const std::size_t next = i + 1 == n ? 0 : i + 1;
    const auto segment = hermite_to_bezier<S, Dim, MaxDegree>(points[i], points[next], tangents[i], tangents[next], knots[i],
                                                              knots[i + 1]);
    if (!segment) {
      out = Curve(knots[0]);
      return fail(segment.error(), i);
    }
    if (auto appended = out.try_append(segment.value(), knots[i + 1]); !appended) {
      out = Curve(knots[0]);
      return appended.failure();
    }
  }
  return ok();
}

}  // namespace curvestep::detail
