// SPDX-License-Identifier: MIT
// Bézier extraction: a B-spline (or NURBS) as the sequence of its polynomial (rational) pieces.
//
// On a non-empty knot span [u_s, u_{s+1}] a degree-p B-spline is one polynomial; its Bézier
// control points are values of the blossom of that piece (Ramshaw):
//     b_k = blossom_s(u_s, ..., u_s, u_{s+1}, ..., u_{s+1})   (p−k copies of u_s, k of u_{s+1}),
// each computed by de Boor's triangle with u_s on some levels and u_{s+1} on the others. Every
// ratio in that triangle lies in [0,1], so the Bézier points are convex combinations of the
// span's control points: no overflow in fixed point, at most p/2 units of rounding each.
// This gives the same points as inserting every interior knot until its multiplicity is p
// (Boehm), without needing room for the extra control points. A NURBS piece is formed the same
// way from the weighted points (Nurbs::bezier_piece) and comes out as a RationalBezier.
//
// The end points b_0 and b_p are the curve's own values s(u_s) and s(u_{s+1}) as evaluate()
// computes them, so consecutive pieces share their joint bit for bit in every scalar type:
// a sampler that flattens piece by piece never opens a gap.
//
// Usage (e.g. for flattening):
//     for_each_bezier(spline, [&](const auto& piece) { /* piece.curve on [piece.start, piece.end] */ });
//     std::array<BezierSpan<S, 2, 3>, 16> pieces;  auto count = extract_bezier(spline, std::span(pieces));
// The callback may return void, bool (false stops) or Result<void> (a failure stops and is returned).
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <type_traits>

#include <curvestep/core/bspline/bspline.hpp>
#include <curvestep/core/bspline/nurbs.hpp>
#include <curvestep/core/curve/bezier.hpp>
#include <curvestep/core/curve/rational_bezier.hpp>

namespace curvestep {

/// One polynomial piece of a B-spline: the Bézier curve (local t in [0,1]) on [start, end],
/// where u = start + t·(end − start).
template <Scalar S, std::size_t Dim, std::size_t MaxDegree>
struct BezierSpan {
  Bezier<S, Dim, MaxDegree> curve{};  ///< the piece in Bézier form
  S start{};                          ///< knot u_s where the piece begins (t = 0)
  S end{};                            ///< knot u_{s+1} where it ends (t = 1)
  std::size_t knot_span = 0;          ///< the index s of the knot span
};

/// One rational piece of a NURBS curve, as BezierSpan.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree>
struct RationalBezierSpan {
  RationalBezier<S, Dim, MaxDegree> curve{};  ///< the piece in rational Bézier form
  S start{};                                  ///< knot u_s where the piece begins (t = 0)
  S end{};                                    ///< knot u_{s+1} where it ends (t = 1)
  std::size_t knot_span = 0;                  ///< the index s of the knot span
};

/// The Bézier piece on knot span `knot_span` (a non-empty span of the domain, degree <= s <= n).
/// InvalidArgument (index = knot_span) otherwise, EmptyControlPolygon for an empty curve.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxControlPoints>
[[nodiscard]] constexpr Result<BezierSpan<S, Dim, MaxDegree>> bezier_span(
    const BSpline<S, Dim, MaxDegree, MaxControlPoints>& spline, std::size_t knot_span) {
  if (spline.size() == 0) return fail(Error::EmptyControlPolygon);
  const std::size_t p = spline.degree();
  const auto knots = spline.knots();
  if (knot_span < p || knot_span >= spline.size() || !(knots[knot_span] < knots[knot_span + 1])) {
    return fail(Error::InvalidArgument, knot_span);
  }
  const S left = knots[knot_span];
  const S right = knots[knot_span + 1];
  std::array<Vec<S, Dim>, MaxDegree + 1> points{};
  std::array<S, MaxDegree> parameters{};
  points[0] = spline.point_in_span(knot_span, left);
  for (std::size_t k = 1; k < p; ++k) {
    for (std::size_t r = 0; r < p; ++r) parameters[r] = r < p - k ? left : right;
    points[k] = spline.blossom(knot_span, std::span<const S>(parameters.data(), p));
  }
  points[p] = spline.point_at(right);  // the next span's value at the joint (evaluate's rule)
  BezierSpan<S, Dim, MaxDegree> piece;
  CURVESTEP_TRY(piece.curve, (Bezier<S, Dim, MaxDegree>::create(std::span<const Vec<S, Dim>>(points.data(), p + 1))));
  piece.start = left;
  piece.end = right;
  piece.knot_span = knot_span;
  return piece;
}

/// The rational Bézier piece of a NURBS curve on knot span `knot_span`; errors as bezier_span.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxControlPoints>
[[nodiscard]] constexpr Result<RationalBezierSpan<S, Dim, MaxDegree>> bezier_span(
    const Nurbs<S, Dim, MaxDegree, MaxControlPoints>& curve, std::size_t knot_span) {
  RationalBezierSpan<S, Dim, MaxDegree> piece;
  CURVESTEP_TRY(piece.curve, curve.bezier_piece(knot_span));
  piece.start = curve.knots()[knot_span];
  piece.end = curve.knots()[knot_span + 1];
  piece.knot_span = knot_span;
  return piece;
}

namespace detail {
template <class Callback, class Piece>
[[nodiscard]] constexpr Result<bool> invoke_piece_callback(Callback& callback, const Piece& piece) {
  using Returned = std::invoke_result_t<Callback&, const Piece&>;
  if constexpr (std::is_void_v<Returned>) {
    callback(piece);
    return true;
  } else if constexpr (std::is_same_v<Returned, bool>) {
    return callback(piece);
  } else {
    static_assert(std::is_same_v<Returned, Result<void>>, "the callback returns void, bool or Result<void>");
    const Result<void> r = callback(piece);
    if (!r) return r.failure();
    return true;
  }
}
}  // namespace detail

/// Calls callback(piece) for every Bézier piece, in parameter order. The callback returns void,
/// bool (false stops early) or Result<void> (a failure stops and is returned).
template <class Curve, class Callback>
  requires requires(const Curve& c) { bezier_span(c, std::size_t{}); }
[[nodiscard]] constexpr Result<void> for_each_bezier(const Curve& curve, Callback&& callback) {
  if (curve.size() == 0) return fail(Error::EmptyControlPolygon);
  const auto knots = curve.knots();
  for (std::size_t s = curve.degree(); s < curve.size(); ++s) {
    if (!(knots[s] < knots[s + 1])) continue;
    CURVESTEP_TRY(const auto piece, bezier_span(curve, s));
    CURVESTEP_TRY(const bool go_on, detail::invoke_piece_callback(callback, piece));
    if (!go_on) break;
  }
  return ok();
}

/// Writes every Bézier piece into `out` (one per non-empty knot span, in order) and returns how
/// many. BufferTooSmall (index = pieces needed) if `out` has fewer than curve.span_count() places;
/// nothing is written then.
template <class Curve, class Piece, std::size_t Extent>
  requires requires(const Curve& c) { bezier_span(c, std::size_t{}); }
[[nodiscard]] constexpr Result<std::size_t> extract_bezier(const Curve& curve, std::span<Piece, Extent> out) {
  const std::size_t needed = curve.span_count();
  if (out.size() < needed) return fail(Error::BufferTooSmall, needed);
  std::size_t written = 0;
  CURVESTEP_CHECK(for_each_bezier(curve, [&](const Piece& piece) { out[written++] = piece; }));
  return written;
}

}  // namespace curvestep
