// SPDX-License-Identifier: MIT
// Nurbs<S, Dim, MaxDegree, MaxControlPoints>: a rational B-spline (NURBS) curve, no heap.
//
// r(u) = Σ w_i N_{i,p}(u) P_i / Σ w_i N_{i,p}(u) with positive weights: the central projection of
// the polynomial B-spline H(u) = Σ N_{i,p}(u) (w_i P_i, w_i) in Dim+1 dimensions (its "preimage",
// seed 004 §1.2). Because all weights are positive, w(u) = Σ N_i w_i never vanishes and r stays
// in the convex hull of the P_i.
//
// Evaluation, blossoms (for Bézier extraction) and Boehm knot insertion run de Boor's steps on H
// but keep the points Cartesian and combine only the weights (detail/rational.hpp): in fixed point
// the weights are carried with about 30 significant bits, so the error does not grow with the
// distance of the curve from the origin as a Q16.16 homogeneous coordinate would make it.
//
// Derivatives come from Leibniz's rule on A = w·(r − O), O = a control point of the span:
//     w·r^(k) = A^(k) − Σ_{i=1..k} C(k,i) w^(i) r^(k−i),   k >= 1,
// with A^(k), w^(k) the B-spline derivatives of the local homogeneous points (w_i (P_i − O), w_i)
// (checked: FixedOverflow / NotFinite). Subtracting O keeps the products small.
//
// Fixed point: a weight that is not a multiple of the resolution (√2/2) is rounded on input, which
// changes the curve slightly (conics.hpp bounds it for the circle); knot insertion stores the new
// weights rounded to the format as well.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <span>

#include <curvestep/core/bspline/bspline.hpp>
#include <curvestep/core/bspline/detail/ratio.hpp>
#include <curvestep/core/bspline/detail/rational.hpp>
#include <curvestep/core/curve/rational_bezier.hpp>
#include <curvestep/core/detail/binomial.hpp>
#include <curvestep/core/detail/checked.hpp>

namespace curvestep {

/// A NURBS curve of runtime degree 1..MaxDegree with up to MaxControlPoints weighted control
/// points in Dim dimensions on the domain [u_p, u_{n+1}]. Satisfies ParametricCurve.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxControlPoints>
class Nurbs {
 public:
  using scalar_type = S;
  using Point = Vec<S, Dim>;
  using Spline = BSpline<S, Dim, MaxDegree, MaxControlPoints>;  ///< control points and knots
  static constexpr std::size_t dimension = Dim;
  static constexpr std::size_t max_degree = MaxDegree;
  static constexpr std::size_t capacity = MaxControlPoints;
  /// Highest derivative order derivative_at accepts (InvalidArgument above).
  static constexpr std::size_t max_derivative_order = MaxDegree + 4;

  /// An empty curve: every evaluation fails with EmptyControlPolygon.
  constexpr Nurbs() = default;

  /// From control points, their weights, knots and degree. Errors: InvalidArgument (weight
  /// count differs; index = weights.size()), NotFinite / NonPositiveWeight (index = weight), then
  /// every error of BSpline::create (CapacityExceeded, knots, NotFinite for a point, ...).
  [[nodiscard]] static constexpr Result<Nurbs> create(std::span<const Point> control, std::span<const S> weights,
                                                      std::span<const S> knots, std::size_t degree) noexcept {
    CURVESTEP_CHECK(check_weights(control.size(), weights));
    Nurbs curve;
    CURVESTEP_TRY(curve.spline_, Spline::create(control, knots, degree));
    for (std::size_t i = 0; i < weights.size(); ++i) curve.weights_[i] = weights[i];
    return curve;
  }

  /// Convenience: create({p0, ...}, {w0, ...}, {u0, ...}, degree).
  [[nodiscard]] static constexpr Result<Nurbs> create(std::initializer_list<Point> control,
                                                      std::initializer_list<S> weights,
                                                      std::initializer_list<S> knots, std::size_t degree) noexcept {
    return create(std::span<const Point>(control.begin(), control.size()),
                  std::span<const S>(weights.begin(), weights.size()), std::span<const S>(knots.begin(), knots.size()),
                  degree);
  }

  /// A closed (periodic) NURBS through N weighted points with uniform knot spacing, domain
  /// [start, start + N·spacing]; errors as create and BSpline::closed.
  [[nodiscard]] static constexpr Result<Nurbs> closed(std::span<const Point> control, std::span<const S> weights,
                                                      std::size_t degree, S start = S{},
                                                      S spacing = from_int<S>(1)) noexcept {
    CURVESTEP_CHECK(check_weights(control.size(), weights));
    Nurbs curve;
    CURVESTEP_TRY(curve.spline_, Spline::closed(control, degree, start, spacing));
    for (std::size_t i = 0; i < curve.size(); ++i) curve.weights_[i] = weights[i % weights.size()];
    return curve;
  }

  /// A polynomial B-spline as a NURBS (all weights 1).
  [[nodiscard]] static constexpr Nurbs from_bspline(const Spline& spline) noexcept {
    Nurbs curve;
    curve.spline_ = spline;
    for (std::size_t i = 0; i < spline.size(); ++i) curve.weights_[i] = from_int<S>(1);
    return curve;
  }

  /// Degree p.
  [[nodiscard]] constexpr std::size_t degree() const noexcept { return spline_.degree(); }
  /// Number of stored control points.
  [[nodiscard]] constexpr std::size_t size() const noexcept { return spline_.size(); }
  /// The control points P_i.
  [[nodiscard]] constexpr std::span<const Point> control_points() const noexcept { return spline_.control_points(); }
  /// The weights w_i.
  [[nodiscard]] constexpr std::span<const S> weights() const noexcept {
    return std::span<const S>(weights_.data(), size());
  }
  /// Weight w_i; contract i < size().
  [[nodiscard]] constexpr S weight(std::size_t i) const {
    CURVESTEP_EXPECTS(i < size());
    return weights_[i];
  }
  /// The knot vector.
  [[nodiscard]] constexpr std::span<const S> knots() const noexcept { return spline_.knots(); }
  /// The control points and knots as a polynomial B-spline (the curve with all weights 1).
  [[nodiscard]] constexpr const Spline& control_spline() const noexcept { return spline_; }
  /// Clamped, unclamped or periodic.
  [[nodiscard]] constexpr KnotLayout layout() const noexcept { return spline_.layout(); }
  /// Domain [u_p, u_{n+1}]; contract: not empty.
  [[nodiscard]] constexpr S domain_start() const { return spline_.domain_start(); }
  [[nodiscard]] constexpr S domain_end() const { return spline_.domain_end(); }
  /// Number of non-empty knot spans (rational Bézier pieces).
  [[nodiscard]] constexpr std::size_t span_count() const noexcept { return spline_.span_count(); }
  /// The knot span holding u (right end: the last non-empty span).
  [[nodiscard]] constexpr Result<std::size_t> find_span(S u) const noexcept { return spline_.find_span(u); }

  /// r(u). EmptyControlPolygon, NotFinite, ParameterOutOfRange.
  [[nodiscard]] constexpr Result<Point> evaluate(S u) const { return detail::evaluate_in_span(*this, u); }

  /// r(u); contract: u in the domain.
  [[nodiscard]] constexpr Point point_at(S u) const { return detail::point_in_found_span(*this, u); }

  /// r(u) for u in knot span `span` (contract as BSpline::point_in_span).
  [[nodiscard]] constexpr Point point_in_span(std::size_t span, S u) const {
    CURVESTEP_EXPECTS(span >= degree() && span < size() && !(u < knots()[span]) && !(knots()[span + 1] < u));
    const int shift = local_shift(span);
    return rational_de_boor(span, shift, [u](std::size_t) { return u; }).point;
  }

  /// r^(order)(u) (order 0: the point), order <= max_derivative_order (else InvalidArgument).
  /// Errors as evaluate, plus FixedOverflow/NotFinite for a derivative out of range.
  [[nodiscard]] constexpr Result<Point> derivative_at(S u, std::size_t order = 1) const {
    if (order > max_derivative_order) return fail(Error::InvalidArgument);
    CURVESTEP_TRY(const std::size_t span, find_span(u));
    if (order == 0) return point_in_span(span, u);
    const std::size_t p = degree();
    const Point origin = control_points()[span];
    std::array<Vec<S, Dim + 1>, MaxDegree + 1> local{};
    for (std::size_t j = 0; j <= p; ++j) {
      const std::size_t i = span - p + j;
      for (std::size_t axis = 0; axis < Dim; ++axis) {
        CURVESTEP_TRY(const S offset, checked_sub(control_points()[i][axis], origin[axis]));
        CURVESTEP_TRY(local[j][axis], checked_mul(offset, weights_[i]));
      }
      local[j][Dim] = weights_[i];
    }
    std::array<Vec<S, Dim + 1>, max_derivative_order + 1> h{};  // A^(k), w^(k)
    for (std::size_t k = 0; k <= order && k <= p; ++k) {
      CURVESTEP_TRY(h[k], detail::derivative_in_span(local, p, knots(), span, u, k));
    }
    std::array<Point, max_derivative_order + 1> r{};  // r^(k) − (k == 0 ? O : 0)
    const detail::Checked<S> w(h[0][Dim]);
    for (std::size_t k = 0; k <= order; ++k) {
      for (std::size_t axis = 0; axis < Dim; ++axis) {
        detail::Checked<S> numerator(h[k][axis]);
        for (std::size_t i = 1; i <= k; ++i) {
          const detail::Checked<S> product = detail::Checked<S>(h[i][Dim]) * detail::Checked<S>(r[k - i][axis]);
          numerator = numerator - scale_by_binomial(product, k, i);
        }
        CURVESTEP_TRY(r[k][axis], (numerator / w).result());
      }
    }
    return r[order];
  }

  /// The same curve with u inserted `times` more times (rational Boehm); errors as
  /// BSpline::insert_knot. The new weights are rounded to S.
  [[nodiscard]] constexpr Result<Nurbs> insert_knot(S u, std::size_t times = 1) const {
    CURVESTEP_TRY(const Spline checked, spline_.insert_knot(u, times));  // validation and the new knots
    const int shift = detail::weight_shift(weights());
    std::array<Item, MaxControlPoints> items{};
    for (std::size_t i = 0; i < size(); ++i) items[i] = Item{control_points()[i], detail::scale_weight(weights_[i], shift)};
    std::array<S, Spline::knot_capacity> scratch{};
    for (std::size_t i = 0; i < knots().size(); ++i) scratch[i] = knots()[i];
    for (std::size_t k = 0; k < times; ++k) {
      detail::boehm_insert(std::span<Item>(items), size() + k, std::span<S>(scratch), degree(), u,
                           [](const Item& a, const Item& b, S num, S den) { return detail::rational_lerp(a, b, num, den); });
    }
    std::array<Point, MaxControlPoints> points{};
    Nurbs curve;
    for (std::size_t i = 0; i < checked.size(); ++i) {
      points[i] = items[i].point;
      curve.weights_[i] = detail::unscale_weight<S>(items[i].weight, shift);
    }
    CURVESTEP_TRY(curve.spline_, Spline::create(std::span<const Point>(points.data(), checked.size()), checked.knots(), degree()));
    return curve;
  }

  /// The rational Bézier form of the piece on knot span `knot_span` (a non-empty span of the
  /// domain; InvalidArgument otherwise). Its end points are evaluate(u_s) and evaluate(u_{s+1})
  /// exactly; the inner points and all weights come from the rational blossom.
  [[nodiscard]] constexpr Result<RationalBezier<S, Dim, MaxDegree>> bezier_piece(std::size_t knot_span) const {
    if (size() == 0) return fail(Error::EmptyControlPolygon);
    const std::size_t p = degree();
    if (knot_span < p || knot_span >= size() || !(knots()[knot_span] < knots()[knot_span + 1])) {
      return fail(Error::InvalidArgument, knot_span);
    }
    const S left = knots()[knot_span];
    const S right = knots()[knot_span + 1];
    const int shift = local_shift(knot_span);
    std::array<Point, MaxDegree + 1> points{};
    std::array<S, MaxDegree + 1> piece_weights{};
    for (std::size_t k = 0; k <= p; ++k) {
      const Item b = rational_de_boor(knot_span, shift, [&](std::size_t r) { return r <= p - k ? left : right; });
      points[k] = b.point;
      piece_weights[k] = detail::unscale_weight<S>(b.weight, shift);
    }
    points[p] = point_at(right);  // the next span's value at the joint (evaluate's rule)
    return RationalBezier<S, Dim, MaxDegree>::create(std::span<const Point>(points.data(), p + 1),
                                                     std::span<const S>(piece_weights.data(), p + 1));
  }

  /// The box of the control points; with positive weights it contains the curve.
  [[nodiscard]] constexpr BoundingBox<S, Dim> bounding_box() const { return spline_.bounding_box(); }

 private:
  using Item = detail::WeightedPoint<S, Dim>;

  [[nodiscard]] static constexpr Result<void> check_weights(std::size_t count, std::span<const S> weights) noexcept {
    if (weights.size() != count) return fail(Error::InvalidArgument, weights.size());
    for (std::size_t i = 0; i < weights.size(); ++i) {
      if (!is_finite(weights[i])) return fail(Error::NotFinite, i);
      if (!(S{} < weights[i])) return fail(Error::NonPositiveWeight, i);
    }
    return ok();
  }

  /// The weight scaling for the p+1 weights of a span.
  [[nodiscard]] constexpr int local_shift(std::size_t span) const noexcept {
    return detail::weight_shift(std::span<const S>(weights_.data() + span - degree(), degree() + 1));
  }

  /// de Boor's triangle on the weighted points of `span`, level r at parameter(r).
  template <class Parameter>
  [[nodiscard]] constexpr Item rational_de_boor(std::size_t span, int shift, Parameter parameter) const {
    const std::size_t p = degree();
    const auto k = knots();
    std::array<Item, MaxDegree + 1> d{};
    for (std::size_t j = 0; j <= p; ++j) {
      const std::size_t i = span - p + j;
      d[j] = Item{control_points()[i], detail::scale_weight(weights_[i], shift)};
    }
    for (std::size_t r = 1; r <= p; ++r) {
      const S u = parameter(r);
      for (std::size_t j = p; j >= r; --j) {
        const std::size_t i = span - p + j;
        d[j] = detail::rational_lerp(d[j - 1], d[j], u - k[i], k[i + p + 1 - r] - k[i]);
      }
    }
    return d[p];
  }

  [[nodiscard]] static constexpr detail::Checked<S> scale_by_binomial(const detail::Checked<S>& value, std::size_t k,
                                                                      std::size_t i) noexcept {
    return detail::Checked<S>::combine(value, detail::Checked<S>{}, [k, i](S x, S) {
      return detail::scale_ratio(x, detail::binomial(k, i), 1);
    });
  }

  Spline spline_{};
  std::array<S, MaxControlPoints> weights_{};
};

}  // namespace curvestep
