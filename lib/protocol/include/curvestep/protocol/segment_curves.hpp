// SPDX-License-Identifier: MIT
// Conversions between wire QueueSegments and the core's Q16.16 Bézier and rational Bézier curves.
//
// The wire carries Q16.16 raw values, so these conversions are exact in both directions: the
// host builds a segment from the same curve the simulator plans, and the controller gets that
// curve back bit for bit. Arcs stay arcs on the wire (centre, end, direction); turning them
// into rational spans is the controller's planner's job, because one rational quadratic covers
// at most 180 degrees.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/core/curve/bezier.hpp>
#include <curvestep/core/curve/circular_arc.hpp>
#include <curvestep/core/curve/rational_bezier.hpp>
#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/core/geometry/vec.hpp>
#include <curvestep/core/result.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::protocol {

/// The first Dim coordinates of a wire point as a Q16.16 point.
template <std::size_t Dim>
  requires(Dim == 2 || Dim == 3)
[[nodiscard]] constexpr Vec<Q16_16, Dim> to_point(const WirePoint& p) noexcept {
  Vec<Q16_16, Dim> out;
  for (std::size_t a = 0; a < Dim; ++a) out[a] = Q16_16::from_raw(p[a]);
  return out;
}

/// A Q16.16 point as a wire point (Z = 0 for 2D).
template <std::size_t Dim>
  requires(Dim == 2 || Dim == 3)
[[nodiscard]] constexpr WirePoint to_wire(const Vec<Q16_16, Dim>& p) noexcept {
  WirePoint out{};
  for (std::size_t a = 0; a < Dim; ++a) out[a] = p[a].raw();
  return out;
}

/// A Line (as degree 1) or Bezier segment as a polynomial Bézier. InvalidArgument (index 0) for
/// other kinds, (index 1) if the segment's axis count is not Dim; DegreeAboveCapacity if the
/// degree exceeds MaxDegree.
template <std::size_t Dim, std::size_t MaxDegree = max_segment_degree>
  requires(Dim == 2 || Dim == 3)
[[nodiscard]] constexpr Result<Bezier<Q16_16, Dim, MaxDegree>> to_bezier(const QueueSegment& s) noexcept {
  if (s.kind != SegmentKind::Line && s.kind != SegmentKind::Bezier) return fail(Error::InvalidArgument, 0);
  if (s.axis_count != Dim) return fail(Error::InvalidArgument, 1);
  const std::size_t count = s.point_count();
  if (count > MaxDegree + 1) return fail(Error::DegreeAboveCapacity, count - 1);
  std::array<Vec<Q16_16, Dim>, max_segment_degree + 1> points{};
  for (std::size_t i = 0; i < count; ++i) points[i] = to_point<Dim>(s.points[i]);
  return Bezier<Q16_16, Dim, MaxDegree>::create(std::span<const Vec<Q16_16, Dim>>(points.data(), count));
}

/// A Line, Bezier (weights 1) or RationalBezier segment as a rational Bézier. Errors as
/// to_bezier; NonPositiveWeight from the core for a weight <= 0.
template <std::size_t Dim, std::size_t MaxDegree = max_segment_degree>
  requires(Dim == 2 || Dim == 3)
[[nodiscard]] constexpr Result<RationalBezier<Q16_16, Dim, MaxDegree>> to_rational_bezier(
    const QueueSegment& s) noexcept {
  using Curve = RationalBezier<Q16_16, Dim, MaxDegree>;
  if (s.kind != SegmentKind::RationalBezier) {
    CURVESTEP_TRY(const auto polynomial, (to_bezier<Dim, MaxDegree>(s)));
    return Curve::from_polynomial(polynomial);
  }
  if (s.axis_count != Dim) return fail(Error::InvalidArgument, 1);
  const std::size_t count = s.point_count();
  if (count > MaxDegree + 1) return fail(Error::DegreeAboveCapacity, count - 1);
  std::array<Vec<Q16_16, Dim>, max_segment_degree + 1> points{};
  std::array<Q16_16, max_segment_degree + 1> weights{};
  for (std::size_t i = 0; i < count; ++i) {
    points[i] = to_point<Dim>(s.points[i]);
    weights[i] = Q16_16::from_raw(s.weights[i]);
  }
  return Curve::create(std::span<const Vec<Q16_16, Dim>>(points.data(), count),
                       std::span<const Q16_16>(weights.data(), count));
}

/// A Line segment from `start` to `end` (feed and rapid left at their defaults).
template <std::size_t Dim>
  requires(Dim == 2 || Dim == 3)
[[nodiscard]] constexpr QueueSegment line_segment(const Vec<Q16_16, Dim>& start, const Vec<Q16_16, Dim>& end) noexcept {
  QueueSegment s;
  s.kind = SegmentKind::Line;
  s.axis_count = static_cast<std::uint8_t>(Dim);
  s.degree = 1;
  s.points[0] = to_wire<Dim>(start);
  s.points[1] = to_wire<Dim>(end);
  return s;
}

/// An Arc segment from `start` to `end` about `center` (XY) in `direction`; a different Z of
/// start and end makes it helical.
template <std::size_t Dim>
  requires(Dim == 2 || Dim == 3)
[[nodiscard]] constexpr QueueSegment arc_segment(const Vec<Q16_16, Dim>& start, const Vec<Q16_16, Dim>& end,
                                                 const Vec2<Q16_16>& center, ArcDirection direction) noexcept {
  QueueSegment s;
  s.kind = SegmentKind::Arc;
  s.axis_count = static_cast<std::uint8_t>(Dim);
  s.degree = 2;
  s.direction = direction;
  s.points[0] = to_wire<Dim>(start);
  s.points[1] = to_wire<Dim>(end);
  s.points[2] = to_wire<2>(center);
  return s;
}

/// A Bezier segment from a polynomial Bézier; DegreeAboveCapacity above degree 7.
template <std::size_t Dim, std::size_t MaxDegree>
  requires(Dim == 2 || Dim == 3)
[[nodiscard]] constexpr Result<QueueSegment> bezier_segment(const Bezier<Q16_16, Dim, MaxDegree>& curve) noexcept {
  if (curve.degree() > max_segment_degree) return fail(Error::DegreeAboveCapacity, curve.degree());
  if (curve.degree() < 1) return fail(Error::DegreeTooLow, 0);
  QueueSegment s;
  s.kind = SegmentKind::Bezier;
  s.axis_count = static_cast<std::uint8_t>(Dim);
  s.degree = static_cast<std::uint8_t>(curve.degree());
  for (std::size_t i = 0; i <= curve.degree(); ++i) s.points[i] = to_wire<Dim>(curve[i]);
  return s;
}

/// A RationalBezier segment from a rational Bézier; DegreeAboveCapacity above degree 7.
template <std::size_t Dim, std::size_t MaxDegree>
  requires(Dim == 2 || Dim == 3)
[[nodiscard]] constexpr Result<QueueSegment> rational_bezier_segment(
    const RationalBezier<Q16_16, Dim, MaxDegree>& curve) noexcept {
  if (curve.degree() > max_segment_degree) return fail(Error::DegreeAboveCapacity, curve.degree());
  if (curve.degree() < 1) return fail(Error::DegreeTooLow, 0);
  QueueSegment s;
  s.kind = SegmentKind::RationalBezier;
  s.axis_count = static_cast<std::uint8_t>(Dim);
  s.degree = static_cast<std::uint8_t>(curve.degree());
  for (std::size_t i = 0; i <= curve.degree(); ++i) {
    s.points[i] = to_wire<Dim>(curve.control_points()[i]);
    s.weights[i] = curve.weight(i).raw();
  }
  return s;
}

}  // namespace curvestep::protocol
