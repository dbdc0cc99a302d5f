// SPDX-License-Identifier: MIT
// flatten: any curve (Bézier, rational Bézier, arc, composite, B-spline, NURBS) to a polyline within a chord tolerance.
//
// Why this bound. The polyline replaces the piece of curve on [a,b] by the chord from p(a) to
// p(b). With positive weights every point of a (rational) Bézier piece is a convex combination
// of its control points, and the distance to a segment is a convex function, so
//     dist(p(t), chord) <= max_i dist(q_i, chord)        for every t in [a,b]
// for the piece's control points q_i. This is the control-polygon bound (seed_001 §8.2: the
// polygon is within (⌊n/2⌋⌈n/2⌉/(2n)) max‖Δ²b_i‖ of the curve, and Δ² shrinks 4x per halving),
// made sharper by applying it to the two halves of the piece (split at its midpoint): the
// curve lies in the union of the halves' hulls. For a parabola the result is the exact
// deviation; for small pieces of any curve it tends to the true one, so the tolerance is
// used almost fully. It is a true bound, not a midpoint test.
//
// Choice of pieces. Greedy from t = 0: the next vertex is the farthest parameter b found for
// which the bound is <= the tolerance, searched with the h² scaling of the bound (secant in
// √F, then bisection inside the bracket) until b is within 8% of the first failing value.
// Greedy covering is optimal for a monotone criterion, so the count stays close to the
// minimum ∫ κ / (2 acos(1 - κ ε)) ds that an arc of the same curvature needs.
//
// Arithmetic. The search runs in double on exact copies of the control points (homogeneous
// (w b, w) for rational curves; Fixed values are exact doubles), so its own error is ~1e-15
// relative. The vertices are the double points rounded to S once; that rounding (half a raw
// unit per coordinate for Fixed, half an ulp for float) is added to the bound before it is
// compared with the tolerance. Output goes to a callback or a caller's buffer: no heap.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <type_traits>

#include <curvestep/core/bspline/bezier_extraction.hpp>
#include <curvestep/core/curve/bezier.hpp>
#include <curvestep/core/curve/composite_bezier.hpp>
#include <curvestep/core/curve/rational_bezier.hpp>
#include <curvestep/core/result.hpp>

namespace curvestep {

/// One polyline vertex: the point (rounded to S) and the curve parameter it was taken at.
template <Scalar S, std::size_t Dim>
struct FlattenVertex {
  Vec<S, Dim> point{};    ///< the vertex
  double parameter = 0;  ///< curve parameter of the vertex (local t for Bézier, knot u for B-splines)
};

namespace detail {

template <std::size_t Dim>
using DoublePoint = std::array<double, Dim>;

/// Homogeneous double copy of a curve piece: (w b, w) per control point.
template <std::size_t Dim, std::size_t Capacity>
struct FlattenPolygon {
  std::array<DoublePoint<Dim + 1>, Capacity> points{};
  std::size_t degree = 0;
};

/// The polygon of the same curve on [a, b] within [0, 1] (two de Casteljau splits in double).
template <std::size_t Dim, std::size_t Capacity>
[[nodiscard]] inline FlattenPolygon<Dim, Capacity> sub_polygon(const FlattenPolygon<Dim, Capacity>& curve, double a,
                                                               double b) noexcept {
  const std::size_t n = curve.degree;
  auto work = curve.points;
  std::array<DoublePoint<Dim + 1>, Capacity> left{};
  left[0] = work[0];
  for (std::size_t r = 1; r <= n; ++r) {
    for (std::size_t i = 0; i + r <= n; ++i) {
      for (std::size_t k = 0; k <= Dim; ++k) work[i][k] += (work[i + 1][k] - work[i][k]) * b;
    }
    left[r] = work[0];
  }
  const double s = b > 0 ? a / b : 0.0;
  FlattenPolygon<Dim, Capacity> sub;
  sub.degree = n;
  work = left;
  sub.points[n] = work[n];
  for (std::size_t r = 1; r <= n; ++r) {
    for (std::size_t i = 0; i + r <= n; ++i) {
      for (std::size_t k = 0; k <= Dim; ++k) work[i][k] += (work[i + 1][k] - work[i][k]) * s;
    }
    sub.points[n - r] = work[n - r];
  }
  return sub;
}

template <std::size_t Dim>
[[nodiscard]] inline DoublePoint<Dim> project(const DoublePoint<Dim + 1>& h) noexcept {
  DoublePoint<Dim> p{};
  for (std::size_t k = 0; k < Dim; ++k) p[k] = h[k] / h[Dim];
  return p;
}

/// Euclidean distance from q to the segment [a, b].
template <std::size_t Dim>
[[nodiscard]] inline double distance_to_segment(const DoublePoint<Dim>& q, const DoublePoint<Dim>& a,
                                                const DoublePoint<Dim>& b) noexcept {
  double dd = 0;
  double vd = 0;
  for (std::size_t k = 0; k < Dim; ++k) {
    dd += (b[k] - a[k]) * (b[k] - a[k]);
    vd += (q[k] - a[k]) * (b[k] - a[k]);
  }
  double s = dd > 0 ? vd / dd : 0.0;
  s = s < 0 ? 0 : (s > 1 ? 1 : s);
  double d2 = 0;
  for (std::size_t k = 0; k < Dim; ++k) {
    const double e = q[k] - (a[k] + s * (b[k] - a[k]));
    d2 += e * e;
  }
  return std::sqrt(d2);
}

/// Upper bound of the distance from the piece of curve to the chord between its end points:
/// the farthest control point of its two halves.
template <std::size_t Dim, std::size_t Capacity>
[[nodiscard]] inline double chord_deviation_bound(const FlattenPolygon<Dim, Capacity>& piece) noexcept {
  const std::size_t n = piece.degree;
  const auto start = project<Dim>(piece.points[0]);
  const auto end = project<Dim>(piece.points[n]);
  auto work = piece.points;
  double bound = 0;
  // Level r of de Casteljau at 1/2: work[0] is the left half's point r, work[n-r] the right's.
  for (std::size_t r = 0; r <= n; ++r) {
    if (r > 0) {
      for (std::size_t i = 0; i + r <= n; ++i) {
        for (std::size_t k = 0; k <= Dim; ++k) work[i][k] = (work[i][k] + work[i + 1][k]) / 2;
      }
    }
    bound = std::fmax(bound, distance_to_segment<Dim>(project<Dim>(work[0]), start, end));
    bound = std::fmax(bound, distance_to_segment<Dim>(project<Dim>(work[n - r]), start, end));
  }
  return bound;
}

template <class Sink, class Vertex>
[[nodiscard]] Result<bool> call_flatten_sink(Sink& sink, const Vertex& vertex) {
  using Returned = std::invoke_result_t<Sink&, const Vertex&>;
  if constexpr (std::is_void_v<Returned>) {
    sink(vertex);
    return true;
  } else if constexpr (std::is_same_v<Returned, bool>) {
    return sink(vertex);
  } else {
    static_assert(std::is_same_v<Returned, Result<void>>, "the sink returns void, bool or Result<void>");
    const Result<void> r = sink(vertex);
    if (!r) return r.failure();
    return true;
  }
}

/// Rounding of a double point to S, as a Euclidean distance bound (the vertex error).
template <Scalar S, std::size_t Dim>
[[nodiscard]] inline double vertex_rounding(double largest_coordinate, std::size_t degree) noexcept {
  const double root_dim = std::sqrt(static_cast<double>(Dim));
  const double computation = 8.0 * static_cast<double>(degree + 1) * std::numeric_limits<double>::epsilon() * (largest_coordinate + 1);
  if constexpr (FixedPoint<S>) {
    return root_dim * to_double(resolution<S>()) / 2 + computation;
  } else {
    return root_dim * static_cast<double>(std::numeric_limits<S>::epsilon()) / 2 * largest_coordinate + computation;
  }
}

/// Flattens one piece given in homogeneous double form; parameters map t -> start + t (end - start).
/// Emits the first vertex only if `emit_first`. Returns false if the sink asked to stop.
template <Scalar S, std::size_t Dim, std::size_t Capacity, class Sink>
[[nodiscard]] Result<bool> flatten_polygon(const FlattenPolygon<Dim, Capacity>& curve, double tolerance, double start,
                                           double end, bool emit_first, Sink& sink, std::size_t& count) {
  double largest = 0;
  for (std::size_t i = 0; i <= curve.degree; ++i) {
    const auto p = project<Dim>(curve.points[i]);
    for (std::size_t k = 0; k < Dim; ++k) largest = std::fmax(largest, std::fabs(p[k]));
  }
  const double rounding = vertex_rounding<S, Dim>(largest, curve.degree);
  const double budget = tolerance - rounding;
  if (!(budget > rounding)) return fail(Error::InvalidTolerance);
  const auto emit = [&](const DoublePoint<Dim + 1>& h, double t) -> Result<bool> {
    const auto p = project<Dim>(h);
    FlattenVertex<S, Dim> vertex;
    CURVESTEP_TRY(vertex.point, (vec_from_doubles<S, Dim>(p)));
    vertex.parameter = start + t * (end - start);
    ++count;
    return call_flatten_sink(sink, vertex);
  };
  if (emit_first) {
    CURVESTEP_TRY(const bool go_on, emit(curve.points[0], 0.0));
    if (!go_on) return false;
  }
  if (curve.degree == 0) return true;
  constexpr int iteration_limit = 64;
  double t = 0;
  double guess = 1;
  while (t < 1) {
    const double remaining = 1 - t;
    double feasible = 0;  // largest step known to satisfy the bound
    double infeasible = std::numeric_limits<double>::infinity();
    double h = guess < remaining ? guess : remaining;
    FlattenPolygon<Dim, Capacity> accepted{};
    for (int iteration = 0;; ++iteration) {
      if (iteration == iteration_limit) return fail(Error::IterationLimit);
      const double b = h >= remaining ? 1.0 : t + h;
      const auto piece = sub_polygon(curve, t, b);
      const double bound = chord_deviation_bound(piece);
      if (bound <= budget) {
        feasible = h;
        accepted = piece;
        if (h >= remaining) break;
      } else {
        infeasible = h;
      }
      if (feasible > 0 && feasible >= 0.92 * infeasible) break;
      // The bound scales like h²: aim just inside the budget, then bisect inside the bracket.
      // Without a failing step yet, grow by at least 8% so that a bracket is found quickly.
      double scale = bound > 0 ? 0.98 * std::sqrt(budget / bound) : 4.0;
      if (scale > 4.0) scale = 4.0;
      const bool bracketed = infeasible < std::numeric_limits<double>::infinity();
      if (!bracketed && scale < 1.08) scale = 1.08;
      double next = h * scale;
      if (bracketed && feasible > 0) {
        // Stay at least a fifth of the bracket away from both ends: guaranteed progress.
        const double gap = infeasible - feasible;
        if (next < feasible + 0.2 * gap) next = feasible + 0.2 * gap;
        if (next > infeasible - 0.2 * gap) next = infeasible - 0.2 * gap;
      } else if (bracketed && !(next < infeasible)) {
        next = infeasible / 4;
      }
      if (next > remaining) next = remaining;
      if (!(next > 0) || t + next == t) return fail(Error::InvalidTolerance);  // below double resolution
      h = next;
    }
    const double b = feasible >= remaining ? 1.0 : t + feasible;
    CURVESTEP_TRY(const bool go_on, emit(accepted.points[accepted.degree], b));
    if (!go_on) return false;
    guess = feasible;
    t = b;
  }
  return true;
}

template <Scalar S, std::size_t Dim, std::size_t MaxDegree>
[[nodiscard]] FlattenPolygon<Dim, MaxDegree + 1> flatten_polygon_of(const Bezier<S, Dim, MaxDegree>& curve) noexcept {
  FlattenPolygon<Dim, MaxDegree + 1> polygon;
  polygon.degree = curve.degree();
  for (std::size_t i = 0; i <= curve.degree(); ++i) {
    for (std::size_t k = 0; k < Dim; ++k) polygon.points[i][k] = to_double(curve[i][k]);
    polygon.points[i][Dim] = 1.0;
  }
  return polygon;
}

template <Scalar S, std::size_t Dim, std::size_t MaxDegree>
[[nodiscard]] FlattenPolygon<Dim, MaxDegree + 1> flatten_polygon_of(const RationalBezier<S, Dim, MaxDegree>& curve) noexcept {
  FlattenPolygon<Dim, MaxDegree + 1> polygon;
  polygon.degree = curve.degree();
  for (std::size_t i = 0; i <= curve.degree(); ++i) {
    const double w = to_double(curve.weight(i));
    // From the control points and weights (not the rounded homogeneous copy), so the double
    // curve is the exact one the caller described.
    for (std::size_t k = 0; k < Dim; ++k) polygon.points[i][k] = to_double(curve.control_points()[i][k]) * w;
    polygon.points[i][Dim] = w;
  }
  return polygon;
}

}  // namespace detail

/// Flattens a Bézier or rational Bézier curve (including circular arcs) into a polyline whose
/// distance from the curve is at most `tolerance` everywhere. Calls sink(FlattenVertex) for each
/// vertex from p(0) to p(1); the sink returns void, bool (false stops) or Result<void>.
/// Returns the number of vertices. InvalidTolerance if tolerance is not positive or below what
/// S can represent (about twice the vertex rounding); IterationLimit never in practice.
template <class Curve, class Sink>
  requires requires(const Curve& c) { detail::flatten_polygon_of(c); }
[[nodiscard]] Result<std::size_t> flatten(const Curve& curve, typename Curve::scalar_type tolerance, Sink&& sink) {
  using S = typename Curve::scalar_type;
  if (!(S{} < tolerance) || !is_finite(tolerance)) return fail(Error::InvalidTolerance);
  std::size_t count = 0;
  const auto polygon = detail::flatten_polygon_of(curve);
  CURVESTEP_TRY(const bool finished, (detail::flatten_polygon<S, Curve::dimension>(polygon, to_double(tolerance), 0.0, 1.0,
                                                                                     true, sink, count)));
  static_cast<void>(finished);
  return count;
}

/// Flattens a B-spline or NURBS curve (through its Bézier pieces) into one polyline within
/// `tolerance`; vertex parameters are knot values u. Errors as flatten() and as Bézier extraction.
template <class Curve, class Sink>
  requires requires(const Curve& c) { bezier_span(c, std::size_t{}); }
[[nodiscard]] Result<std::size_t> flatten(const Curve& curve, typename Curve::scalar_type tolerance, Sink&& sink) {
  using S = typename Curve::scalar_type;
  if (!(S{} < tolerance) || !is_finite(tolerance)) return fail(Error::InvalidTolerance);
  std::size_t count = 0;
  bool first = true;
  bool stopped = false;
  CURVESTEP_CHECK(for_each_bezier(curve, [&](const auto& piece) -> Result<void> {
    if (stopped) return ok();
    const auto polygon = detail::flatten_polygon_of(piece.curve);
    CURVESTEP_TRY(const bool go_on, (detail::flatten_polygon<S, Curve::dimension>(polygon, to_double(tolerance), to_double(piece.start),
                                                                                   to_double(piece.end), first, sink, count)));
    first = false;
    stopped = !go_on;
    return ok();
  }));
  return count;
}

/// Flattens a composite Bézier curve segment by segment into one polyline within `tolerance`;
/// vertex parameters are global u. EmptyControlPolygon for no segments, NotContinuous (index =
/// segment) if a segment does not start where the previous one ends; errors as flatten().
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxSegments, class Sink>
[[nodiscard]] Result<std::size_t> flatten(const CompositeBezier<S, Dim, MaxDegree, MaxSegments>& curve, S tolerance, Sink&& sink) {
  if (!(S{} < tolerance) || !is_finite(tolerance)) return fail(Error::InvalidTolerance);
  if (curve.size() == 0) return fail(Error::EmptyControlPolygon);
  for (std::size_t j = 1; j < curve.size(); ++j) {
    if (!(curve.segment(j).front() == curve.segment(j - 1).back())) return fail(Error::NotContinuous, j);
  }
  std::size_t count = 0;
  for (std::size_t j = 0; j < curve.size(); ++j) {
    const auto polygon = detail::flatten_polygon_of(curve.segment(j));
    CURVESTEP_TRY(const bool go_on, (detail::flatten_polygon<S, Dim>(polygon, to_double(tolerance), to_double(curve.breakpoint(j)),
                                                                     to_double(curve.breakpoint(j + 1)), j == 0, sink, count)));
    if (!go_on) break;
  }
  return count;
}

/// Flattens any curve flatten() accepts into `out`; returns the number of vertices written.
/// BufferTooSmall (index = out.size()) if the polyline needs more vertices than `out` holds.
template <class Curve>
[[nodiscard]] Result<std::size_t> flatten_into(const Curve& curve, typename Curve::scalar_type tolerance,
                                               std::span<typename Curve::Point> out) {
  using S = typename Curve::scalar_type;
  std::size_t written = 0;
  const auto result = flatten(curve, tolerance, [&](const FlattenVertex<S, Curve::Point::dimension>& vertex) -> Result<void> {
    if (written == out.size()) return fail(Error::BufferTooSmall, out.size());
    out[written++] = vertex.point;
    return ok();
  });
  if (!result) return result.failure();
  return written;
}

}  // namespace curvestep
