// SPDX-License-Identifier: MIT
// Nurbs<S, Dim, MaxDegree, MaxControlPoints>: a rational B-spline through homogeneous coordinates.
//
// r(u) = Σ w_i N_{i,p}(u) P_i / Σ w_i N_{i,p}(u) with positive weights. The curve is stored as the
// polynomial B-spline H(u) = Σ N_{i,p}(u) (w_i P_i, w_i) in Dim+1 dimensions (its "preimage",
// seed 004 §1.2): r is H's central projection, r = A/w with A the first Dim coordinates and w the
// last. Evaluation is de Boor on H and one division; knot insertion and Bézier extraction are
// done on H, which leaves the projected curve unchanged. Since all weights are positive, w(u) is a
// convex combination of positive numbers and never reaches zero, and r stays in the convex hull
// of the P_i.
//
// Derivatives come from Leibniz's rule on A = w·r:
//     w·r^(k) = A^(k) − Σ_{i=1..k} C(k,i) w^(i) r^(k−i),
// with A^(k) and w^(k) the B-spline derivatives of H (checked: FixedOverflow / NotFinite).
//
// Fixed point: the stored homogeneous points w_i·P_i are rounded once; the projection adds one
// rounding per coordinate. A weight that is not a multiple of the resolution (√2/2 in a circle) is
// rounded too, which perturbs the curve by at most about |P|·(relative weight error): for Q16.16 and
// weights near 1, about 2^-17·|P| (conics.hpp gives the sharper bound for the circle).
#pragma once

#include <array>
#include <cstddef>
#include <initializer_list>
#include <span>

#include <curvestep/core/bspline/bspline.hpp>
#include <curvestep/core/bspline/detail/ratio.hpp>
#include <curvestep/core/detail/binomial.hpp>
#include <curvestep/core/detail/checked.hpp>

namespace curvestep {

/// A NURBS curve of runtime degree 1..MaxDegree with up to MaxControlPoints weighted control
/// points in Dim dimensions. Satisfies ParametricCurve.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxControlPoints>
class Nurbs {
 public:
  using scalar_type = S;
  using Point = Vec<S, Dim>;
  using Homogeneous = BSpline<S, Dim + 1, MaxDegree, MaxControlPoints>;  ///< the curve (w P, w)
  static constexpr std::size_t dimension = Dim;
  static constexpr std::size_t max_degree = MaxDegree;
  static constexpr std::size_t capacity = MaxControlPoints;
  /// Highest derivative order derivative_at accepts (InvalidArgument above).
  static constexpr std::size_t max_derivative_order = MaxDegree + 4;

  /// An empty curve: every evaluation fails with EmptyControlPolygon.
  constexpr Nurbs() = default;

  /// From control points, their weights, knots and degree. Errors: InvalidArgument (weight count
  /// differs; index = weights.size()), NotFinite (index = weight, then control point),
  /// NonPositiveWeight (index = weight), FixedOverflow (w_i·P_i out of range; index = point), then
  /// every error of BSpline::create.
  [[nodiscard]] static constexpr Result<Nurbs> create(std::span<const Point> control, std::span<const S> weights,
                                                      std::span<const S> knots, std::size_t degree) noexcept {
    std::array<Vec<S, Dim + 1>, MaxControlPoints> homogeneous{};
    CURVESTEP_CHECK(weigh(control, weights, std::span<Vec<S, Dim + 1>>(homogeneous)));
    Nurbs curve;
    CURVESTEP_TRY(curve.homogeneous_,
                  Homogeneous::create(std::span<const Vec<S, Dim + 1>>(homogeneous.data(), control.size()), knots, degree));
    for (std::size_t i = 0; i < control.size(); ++i) curve.points_[i] = control[i];
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

  /// A closed (periodic) NURBS through N weighted points, uniform knot spacing, domain
  /// [start, start + N·spacing]; errors as create and BSpline::closed.
  [[nodiscard]] static constexpr Result<Nurbs> closed(std::span<const Point> control, std::span<const S> weights,
                                                      std::size_t degree, S start = S{},
                                                      S spacing = from_int<S>(1)) noexcept {
    std::array<Vec<S, Dim + 1>, MaxControlPoints> homogeneous{};
    CURVESTEP_CHECK(weigh(control, weights, std::span<Vec<S, Dim + 1>>(homogeneous)));
    Nurbs curve;
    CURVESTEP_TRY(curve.homogeneous_, Homogeneous::closed(std::span<const Vec<S, Dim + 1>>(homogeneous.data(), control.size()),
                                                          degree, start, spacing));
    for (std::size_t i = 0; i < curve.size(); ++i) curve.points_[i] = control[i % control.size()];
    return curve;
  }

  /// A polynomial B-spline as a NURBS (all weights 1).
  [[nodiscard]] static constexpr Nurbs from_bspline(const BSpline<S, Dim, MaxDegree, MaxControlPoints>& spline) noexcept {
    std::array<Vec<S, Dim + 1>, MaxControlPoints> homogeneous{};
    for (std::size_t i = 0; i < spline.size(); ++i) {
      for (std::size_t axis = 0; axis < Dim; ++axis) homogeneous[i][axis] = spline.control_points()[i][axis];
      homogeneous[i][Dim] = from_int<S>(1);
    }
    Nurbs curve;
    if (spline.size() == 0) return curve;
    curve.homogeneous_ = Homogeneous::create(std::span<const Vec<S, Dim + 1>>(homogeneous.data(), spline.size()),
                                             spline.knots(), spline.degree())
                             .value();
    for (std::size_t i = 0; i < spline.size(); ++i) curve.points_[i] = spline.control_points()[i];
    return curve;
  }

  /// Degree p.
  [[nodiscard]] constexpr std::size_t degree() const noexcept { return homogeneous_.degree(); }
  /// Number of stored control points.
  [[nodiscard]] constexpr std::size_t size() const noexcept { return homogeneous_.size(); }
  /// The control points P_i (as given, or as produced by knot insertion).
  [[nodiscard]] constexpr std::span<const Point> control_points() const noexcept {
    return std::span<const Point>(points_.data(), size());
  }
  /// Weight w_i; contract i < size().
  [[nodiscard]] constexpr S weight(std::size_t i) const {
    CURVESTEP_EXPECTS(i < size());
    return homogeneous_.control_points()[i][Dim];
  }
  /// The knot vector.
  [[nodiscard]] constexpr std::span<const S> knots() const noexcept { return homogeneous_.knots(); }
  /// Clamped, unclamped or periodic.
  [[nodiscard]] constexpr KnotLayout layout() const noexcept { return homogeneous_.layout(); }
  /// The homogeneous B-spline (w P, w).
  [[nodiscard]] constexpr const Homogeneous& homogeneous() const noexcept { return homogeneous_; }
  /// Domain [u_p, u_{n+1}]; contract: not empty.
  [[nodiscard]] constexpr S domain_start() const { return homogeneous_.domain_start(); }
  [[nodiscard]] constexpr S domain_end() const { return homogeneous_.domain_end(); }
  /// Number of non-empty knot spans (rational Bézier pieces).
  [[nodiscard]] constexpr std::size_t span_count() const noexcept { return homogeneous_.span_count(); }
  /// The knot span holding u (right end: the last non-empty span).
  [[nodiscard]] constexpr Result<std::size_t> find_span(S u) const noexcept { return homogeneous_.find_span(u); }

  /// r(u). EmptyControlPolygon, NotFinite, ParameterOutOfRange; FixedOverflow/NotFinite if the
  /// projection leaves the range (only possible within a rounding of the format's limits).
  [[nodiscard]] constexpr Result<Point> evaluate(S u) const {
    CURVESTEP_TRY(const auto h, homogeneous_.evaluate(u));
    return project(h);
  }

  /// r(u); contract: u in the domain and the result representable.
  [[nodiscard]] constexpr Point point_at(S u) const {
    const auto p = evaluate(u);
    CURVESTEP_EXPECTS(p.has_value());
    return p.value();
  }

  /// r^(order)(u) (order 0: the point), order <= max_derivative_order (else InvalidArgument).
  /// Errors as evaluate, plus FixedOverflow/NotFinite for a derivative out of range.
  [[nodiscard]] constexpr Result<Point> derivative_at(S u, std::size_t order = 1) const {
    if (order > max_derivative_order) return fail(Error::InvalidArgument);
    std::array<Vec<S, Dim + 1>, max_derivative_order + 1> h{};
    for (std::size_t k = 0; k <= order; ++k) {
      CURVESTEP_TRY(h[k], homogeneous_.derivative_at(u, k));
    }
    std::array<Point, max_derivative_order + 1> r{};
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

  /// The same curve with u inserted `times` more times; errors as BSpline::insert_knot.
  [[nodiscard]] constexpr Result<Nurbs> insert_knot(S u, std::size_t times = 1) const {
    Nurbs curve;
    CURVESTEP_TRY(curve.homogeneous_, homogeneous_.insert_knot(u, times));
    for (std::size_t i = 0; i < curve.size(); ++i) {
      CURVESTEP_TRY(curve.points_[i], project(curve.homogeneous_.control_points()[i]));
    }
    return curve;
  }

  /// The box of the control points; with positive weights it contains the curve.
  [[nodiscard]] constexpr BoundingBox<S, Dim> bounding_box() const {
    return curvestep::bounding_box<S, Dim>(control_points());
  }

 private:
  /// Fills (w_i P_i, w_i) after checking counts, finiteness, signs and range.
  [[nodiscard]] static constexpr Result<void> weigh(std::span<const Point> control, std::span<const S> weights,
                                                    std::span<Vec<S, Dim + 1>> out) noexcept {
    if (weights.size() != control.size()) return fail(Error::InvalidArgument, weights.size());
    if (control.size() > out.size()) return fail(Error::CapacityExceeded, control.size());
    for (std::size_t i = 0; i < weights.size(); ++i) {
      if (!is_finite(weights[i])) return fail(Error::NotFinite, i);
      if (!(S{} < weights[i])) return fail(Error::NonPositiveWeight, i);
    }
    for (std::size_t i = 0; i < control.size(); ++i) {
      for (std::size_t axis = 0; axis < Dim; ++axis) {
        if (!is_finite(control[i][axis])) return fail(Error::NotFinite, i);
        const auto c = checked_mul(control[i][axis], weights[i]);
        if (!c) return fail(c.error(), i);
        out[i][axis] = c.value();
      }
      out[i][Dim] = weights[i];
    }
    return ok();
  }

  [[nodiscard]] static constexpr detail::Checked<S> scale_by_binomial(const detail::Checked<S>& value, std::size_t k,
                                                                      std::size_t i) noexcept {
    if (!value.ok) return value;
    const auto scaled = detail::scale_ratio(value.value, detail::binomial(k, i), 1);
    detail::Checked<S> r;
    if (!scaled) {
      r.ok = false;
      r.error = scaled.error();
      return r;
    }
    r.value = scaled.value();
    return r;
  }

  [[nodiscard]] static constexpr Result<Point> project(const Vec<S, Dim + 1>& h) noexcept {
    Point p;
    for (std::size_t axis = 0; axis < Dim; ++axis) {
      CURVESTEP_TRY(p[axis], checked_div(h[axis], h[Dim]));
    }
    return p;
  }

  Homogeneous homogeneous_{};
  std::array<Point, MaxControlPoints> points_{};
};

}  // namespace curvestep
