// SPDX-License-Identifier: MIT
// BSpline<S, Dim, MaxDegree, MaxControlPoints>: a B-spline curve with compile-time capacity, no heap.
//
// s(u) = Σ_{i=0..n} N_{i,p}(u) P_i on the domain [u_p, u_{n+1}] (see knot_vector.hpp for the
// layouts and the right-end rule).
//
// Evaluation is de Boor's algorithm. On the span u_s <= u < u_{s+1} only P_{s−p}..P_s matter;
// level r replaces d_i by (1−α) d_{i−1} + α d_i with α = (u − u_i)/(u_{i+p+1−r} − u_i) for
// i = s..s−p+r. Every α lies in [0,1], so every intermediate point is a convex combination of
// control points: nothing can overflow in fixed point, and each level costs at most half a unit
// of rounding (the ratio is applied exactly, see detail/ratio.hpp), p/2 units in all.
// Running the levels with different parameters gives the blossom, which Bézier extraction uses.
//
// Derivatives: s^(r)(u) = Σ N_{i+r,p−r}(u) P^(r)_i with
// P^(r)_i = (p−r+1)(P^(r−1)_{i+1} − P^(r−1)_i)/(u_{i+p+1} − u_{i+r}) on the same knots. Only the
// p+1−r local points of the span are formed, then de Boor runs at degree p−r. The differences
// can leave the control points' range, so they are checked (FixedOverflow / NotFinite).
// Orders above p give the zero vector.
//
// Knot insertion is Boehm's algorithm: inserting ū with u_s <= ū < u_{s+1} replaces
// P_{s−p+1}..P_s by Q_i = (1−a_i) P_{i−1} + a_i P_i, a_i = (ū − u_i)/(u_{i+p} − u_i), leaving the
// curve unchanged; inserting r times repeats it. Each new point is again a convex combination.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <span>

#include <curvestep/core/bspline/detail/ratio.hpp>
#include <curvestep/core/bspline/knot_vector.hpp>
#include <curvestep/core/contract.hpp>
#include <curvestep/core/geometry/bounding_box.hpp>
#include <curvestep/core/geometry/vec.hpp>
#include <curvestep/core/result.hpp>

namespace curvestep {

/// How a B-spline's knot vector is laid out (see knot_vector.hpp).
enum class KnotLayout : std::uint8_t {
  Clamped,    ///< end knots repeated degree+1 times: the curve starts at P_0 and ends at P_n
  Unclamped,  ///< any other valid knot vector
  Periodic,   ///< built by BSpline::closed: periodic knots, first `degree` points repeated at the end
};

namespace detail {
/// de Boor's triangle on the local points d[0..q] of span `span` (basis indices span−q..span),
/// level r using parameter(r) (all equal: the curve point; different: the blossom).
/// Contract: every parameter lies in [u_span, u_{span+1}].
template <Scalar S, std::size_t Dim, std::size_t N, class Parameter>
[[nodiscard]] constexpr Vec<S, Dim> de_boor(std::array<Vec<S, Dim>, N> d, std::size_t q, std::span<const S> knots,
                                            std::size_t span, Parameter parameter) {
  for (std::size_t r = 1; r <= q; ++r) {
    const S u = parameter(r);
    for (std::size_t j = q; j >= r; --j) {
      const std::size_t i = span - q + j;
      d[j] = ratio_lerp(d[j - 1], d[j], u - knots[i], knots[i + q + 1 - r] - knots[i]);
    }
  }
  return d[q];
}

/// s^(order)(u) from the local points d[0..p] of span `span` (basis indices span−p..span): forms
/// the local derivative control points P^(r) (checked) and runs de Boor at degree p − order.
/// Contract: order <= p, u in [u_span, u_{span+1}].
template <Scalar S, std::size_t Dim, std::size_t N>
[[nodiscard]] constexpr Result<Vec<S, Dim>> derivative_in_span(std::array<Vec<S, Dim>, N> d, std::size_t p,
                                                               std::span<const S> knots, std::size_t span, S u,
                                                               std::size_t order) {
  CURVESTEP_EXPECTS(order <= p);
  for (std::size_t r = 1; r <= order; ++r) {
    const int factor = static_cast<int>(p - r + 1);
    for (std::size_t j = 0; j + r <= p; ++j) {
      const std::size_t i = span - p + j;  // P^(r)_i
      const S width = knots[i + p + 1] - knots[i + r];
      for (std::size_t axis = 0; axis < Dim; ++axis) {
        CURVESTEP_TRY(d[j][axis], scaled_difference(d[j][axis], d[j + 1][axis], factor, width));
      }
    }
  }
  return de_boor(d, p - order, knots, span, [u](std::size_t) { return u; });
}

/// One Boehm insertion of u into items[0..count) with knots[0..count+p] (room for one more of
/// each): items i <= s−p stay, items s−p+1..s become combine(item_{i−1}, item_i, u − u_i,
/// u_{i+p} − u_i), later ones shift up by one, where s is the last knot index with u_s <= u.
/// Contract: u in the domain and below the last knot (the caller checked multiplicities).
template <Scalar S, class Item, class Combine>
constexpr void boehm_insert(std::span<Item> items, std::size_t count, std::span<S> knots, std::size_t p, S u,
                            Combine combine) {
  const std::size_t knot_total = count + p + 1;
  CURVESTEP_EXPECTS(items.size() > count && knots.size() > knot_total && u < knots[knot_total - 1]);
  std::size_t s = p;
  while (s + 1 < knot_total && !(u < knots[s + 1])) ++s;
  // From the back, so every source item is read before it is overwritten.
  for (std::size_t i = count; i > s; --i) items[i] = items[i - 1];
  for (std::size_t i = s; i + p > s; --i) {
    // u_i == u means a_i = 0 (this also covers i = n+1 when u is the domain's right end).
    items[i] = knots[i] == u ? items[i - 1] : combine(items[i - 1], items[i], u - knots[i], knots[i + p] - knots[i]);
  }
  for (std::size_t j = knot_total; j > s + 1; --j) knots[j] = knots[j - 1];
  knots[s + 1] = u;
}

/// curve(u) by knot span for BSpline and Nurbs: find_span(u), then point_in_span.
/// EmptyControlPolygon, NotFinite, ParameterOutOfRange.
template <class Curve, Scalar S>
[[nodiscard]] constexpr auto evaluate_in_span(const Curve& curve, S u) -> Result<decltype(curve.point_in_span(0, u))> {
  CURVESTEP_TRY(const std::size_t span, curve.find_span(u));
  return curve.point_in_span(span, u);
}

/// curve(u) by knot span; contract: u in the domain (the hot path).
template <class Curve, Scalar S>
[[nodiscard]] constexpr auto point_in_found_span(const Curve& curve, S u) {
  const auto span = curve.find_span(u);
  CURVESTEP_EXPECTS(span.has_value());
  return curve.point_in_span(span.value(), u);
}
}  // namespace detail

/// A B-spline curve of runtime degree 1..MaxDegree with up to MaxControlPoints control points in
/// Dim dimensions, parameter domain [u_p, u_{n+1}]. Satisfies ParametricCurve.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxControlPoints>
class BSpline {
  static_assert(MaxDegree >= 1 && MaxDegree <= 30, "a B-spline type allows degrees 1..30");
  static_assert(MaxControlPoints >= 2, "a B-spline needs room for at least two control points");

 public:
  using scalar_type = S;
  using Point = Vec<S, Dim>;
  static constexpr std::size_t dimension = Dim;
  static constexpr std::size_t max_degree = MaxDegree;
  static constexpr std::size_t capacity = MaxControlPoints;                     ///< control points
  static constexpr std::size_t knot_capacity = MaxControlPoints + MaxDegree + 1;  ///< knots

  /// An empty curve (no control points): every evaluation fails with EmptyControlPolygon.
  constexpr BSpline() = default;

  /// A curve from control points, knots and degree. Errors: EmptyControlPolygon, DegreeTooLow
  /// (degree 0), DegreeAboveCapacity (index = degree), CapacityExceeded (index = point count),
  /// TooFewPoints (fewer than degree+1 points), NotFinite (index = control point), then the
  /// knot errors of validate_knots (index = knot).
  [[nodiscard]] static constexpr Result<BSpline> create(std::span<const Point> control, std::span<const S> knots,
                                                        std::size_t degree) noexcept {
    CURVESTEP_CHECK(check_shape(control.size(), degree));
    for (std::size_t i = 0; i < control.size(); ++i) {
      for (std::size_t axis = 0; axis < Dim; ++axis) {
        if (!is_finite(control[i][axis])) return fail(Error::NotFinite, i);
      }
    }
    CURVESTEP_CHECK(validate_knots(knots, degree, control.size()));
    BSpline curve;
    for (std::size_t i = 0; i < control.size(); ++i) curve.points_[i] = control[i];
    for (std::size_t i = 0; i < knots.size(); ++i) curve.knots_[i] = knots[i];
    curve.count_ = control.size();
    curve.degree_ = degree;
    curve.layout_ = curve.clamped_layout() ? KnotLayout::Clamped : KnotLayout::Unclamped;
    return curve;
  }

  /// Convenience: create({p0, p1, ...}, {u0, u1, ...}, degree).
  [[nodiscard]] static constexpr Result<BSpline> create(std::initializer_list<Point> control,
                                                        std::initializer_list<S> knots, std::size_t degree) noexcept {
    return create(std::span<const Point>(control.begin(), control.size()), std::span<const S>(knots.begin(), knots.size()),
                  degree);
  }

  /// A clamped curve with uniform interior knots on [start, end] (default [0, 1]).
  /// Errors as create and uniform_clamped_knots.
  [[nodiscard]] static constexpr Result<BSpline> clamped(std::span<const Point> control, std::size_t degree,
                                                         S start = S{}, S end = from_int<S>(1)) noexcept {
    CURVESTEP_CHECK(check_shape(control.size(), degree));
    std::array<S, knot_capacity> knots{};
    CURVESTEP_TRY(const std::size_t count, uniform_clamped_knots(control.size(), degree, start, end, std::span<S>(knots)));
    return create(control, std::span<const S>(knots.data(), count), degree);
  }

  /// A closed (periodic) curve through the N distinct points `control`, uniform knot spacing,
  /// domain [start, start + N·spacing] (default [0, N]). Stores N + degree points (the first
  /// `degree` repeated). Errors as create (CapacityExceeded: index = N + degree) and
  /// uniform_periodic_knots.
  [[nodiscard]] static constexpr Result<BSpline> closed(std::span<const Point> control, std::size_t degree,
                                                        S start = S{}, S spacing = from_int<S>(1)) noexcept {
    std::array<S, knot_capacity> knots{};
    CURVESTEP_CHECK(check_closed_shape(control.size(), degree));
    CURVESTEP_TRY(const std::size_t count,
                  uniform_periodic_knots(control.size(), degree, start, spacing, std::span<S>(knots)));
    return wrap(control, std::span<const S>(knots.data(), count), degree);
  }

  /// A closed curve with non-uniform periodic knots: u_{j+1} − u_j = spacings[j mod N], N =
  /// control.size() = spacings.size() (seed 004 eq. 3.2). Errors as closed and periodic_knots;
  /// InvalidArgument (index = spacings.size()) if the counts differ.
  [[nodiscard]] static constexpr Result<BSpline> closed(std::span<const Point> control, std::size_t degree,
                                                        std::span<const S> spacings, S start = S{}) noexcept {
    if (spacings.size() != control.size()) return fail(Error::InvalidArgument, spacings.size());
    std::array<S, knot_capacity> knots{};
    CURVESTEP_CHECK(check_closed_shape(control.size(), degree));
    CURVESTEP_TRY(const std::size_t count, periodic_knots(spacings, degree, start, std::span<S>(knots)));
    return wrap(control, std::span<const S>(knots.data(), count), degree);
  }

  /// Degree p.
  [[nodiscard]] constexpr std::size_t degree() const noexcept { return degree_; }
  /// Number of stored control points n+1 (for a closed curve: N + degree).
  [[nodiscard]] constexpr std::size_t size() const noexcept { return count_; }
  /// The stored control points P_0..P_n.
  [[nodiscard]] constexpr std::span<const Point> control_points() const noexcept {
    return std::span<const Point>(points_.data(), count_);
  }
  /// The knot vector u_0..u_{n+p+1} (empty for an empty curve).
  [[nodiscard]] constexpr std::span<const S> knots() const noexcept {
    return std::span<const S>(knots_.data(), count_ == 0 ? 0 : knot_count(count_, degree_));
  }
  /// Clamped, unclamped or periodic.
  [[nodiscard]] constexpr KnotLayout layout() const noexcept { return layout_; }
  /// Start u_p and end u_{n+1} of the domain. Contract: not empty.
  [[nodiscard]] constexpr S domain_start() const {
    CURVESTEP_EXPECTS(count_ > 0);
    return knots_[degree_];
  }
  [[nodiscard]] constexpr S domain_end() const {
    CURVESTEP_EXPECTS(count_ > 0);
    return knots_[count_];
  }
  /// Number of non-empty knot spans in the domain (= number of Bézier pieces).
  [[nodiscard]] constexpr std::size_t span_count() const noexcept {
    std::size_t spans = 0;
    for (std::size_t s = degree_; s < count_; ++s) spans += knots_[s] < knots_[s + 1] ? 1U : 0U;
    return spans;
  }

  /// The stored control points P_{span−p}..P_span of knot span `span` (contract: degree <= span < size()).
  [[nodiscard]] constexpr std::array<Point, MaxDegree + 1> local_points(std::size_t span) const {
    CURVESTEP_EXPECTS(span >= degree_ && span < count_);
    std::array<Point, MaxDegree + 1> d{};
    for (std::size_t j = 0; j <= degree_; ++j) d[j] = points_[span - degree_ + j];
    return d;
  }

  /// The knot span s with u_s <= u < u_{s+1} (right end: the last non-empty span).
  /// EmptyControlPolygon, NotFinite, ParameterOutOfRange.
  [[nodiscard]] constexpr Result<std::size_t> find_span(S u) const noexcept {
    if (count_ == 0) return fail(Error::EmptyControlPolygon);
    return curvestep::find_span(knots(), degree_, u);
  }

  /// s(u) by de Boor. EmptyControlPolygon, NotFinite, ParameterOutOfRange.
  [[nodiscard]] constexpr Result<Point> evaluate(S u) const { return detail::evaluate_in_span(*this, u); }

  /// s(u); contract: u in the domain (the hot path).
  [[nodiscard]] constexpr Point point_at(S u) const { return detail::point_in_found_span(*this, u); }

  /// s(u) for u in knot span `span` (contract: u_span <= u <= u_{span+1}, span a non-empty
  /// span of the domain). Skips the span search when the caller already knows it.
  [[nodiscard]] constexpr Point point_in_span(std::size_t span, S u) const {
    CURVESTEP_EXPECTS(span >= degree_ && span < count_ && !(u < knots_[span]) && !(knots_[span + 1] < u));
    return detail::de_boor(local_points(span), degree_, knots(), span, [u](std::size_t) { return u; });
  }

  /// The blossom of the polynomial piece on knot span `span` at parameters[0..p−1]
  /// (contract: parameters.size() == degree(), each in [u_span, u_{span+1}]). Symmetric in its
  /// arguments; blossom(u,...,u) = s(u), blossom(u_{i+1},...,u_{i+p}) = P_i.
  [[nodiscard]] constexpr Point blossom(std::size_t span, std::span<const S> parameters) const {
    CURVESTEP_EXPECTS(parameters.size() == degree_ && span >= degree_ && span < count_);
    for (const S& t : parameters) CURVESTEP_EXPECTS(!(t < knots_[span]) && !(knots_[span + 1] < t));
    return detail::de_boor(local_points(span), degree_, knots(), span,
                           [parameters](std::size_t r) { return parameters[r - 1]; });
  }

  /// s^(order)(u) (order 0: the point). EmptyControlPolygon, NotFinite, ParameterOutOfRange,
  /// FixedOverflow/NotFinite if a derivative leaves the scalar's range.
  [[nodiscard]] constexpr Result<Point> derivative_at(S u, std::size_t order = 1) const {
    CURVESTEP_TRY(const std::size_t span, find_span(u));
    if (order > degree_) return Point{};
    return detail::derivative_in_span(local_points(span), degree_, knots(), span, u, order);
  }

  /// The same curve with ū inserted `times` more times (Boehm). Errors: EmptyControlPolygon,
  /// NotFinite, ParameterOutOfRange (ū outside the domain), KnotMultiplicityTooHigh (ū would be
  /// repeated more than degree times inside the domain, or degree+1 at its ends; index = the
  /// span of ū), CapacityExceeded (index = control points needed). The result's layout is
  /// Clamped or Unclamped (a closed curve stays closed but is no longer in periodic form).
  [[nodiscard]] constexpr Result<BSpline> insert_knot(S u, std::size_t times = 1) const {
    CURVESTEP_TRY(const std::size_t span, find_span(u));
    const std::size_t existing = knot_multiplicity(knots(), u);
    const bool interior = domain_start() < u && u < domain_end();
    const std::size_t limit = interior ? degree_ : degree_ + 1;
    if (existing + times > limit) return fail(Error::KnotMultiplicityTooHigh, span);
    if (count_ + times > MaxControlPoints) return fail(Error::CapacityExceeded, count_ + times);
    BSpline curve = *this;
    const auto combine = [](const Point& a, const Point& b, S numerator, S denominator) {
      return detail::ratio_lerp(a, b, numerator, denominator);
    };
    for (std::size_t k = 0; k < times; ++k) {
      detail::boehm_insert(std::span<Point>(curve.points_), curve.count_, std::span<S>(curve.knots_), degree_, u, combine);
      ++curve.count_;
    }
    curve.layout_ = curve.clamped_layout() ? KnotLayout::Clamped : KnotLayout::Unclamped;
    return curve;
  }

  /// The axis-aligned box of the control points; it contains the whole curve.
  [[nodiscard]] constexpr BoundingBox<S, Dim> bounding_box() const {
    return curvestep::bounding_box<S, Dim>(control_points());
  }

 private:
  [[nodiscard]] static constexpr Result<void> check_shape(std::size_t count, std::size_t degree) noexcept {
    if (count == 0) return fail(Error::EmptyControlPolygon);
    if (degree == 0) return fail(Error::DegreeTooLow);
    if (degree > MaxDegree) return fail(Error::DegreeAboveCapacity, degree);
    if (count > MaxControlPoints) return fail(Error::CapacityExceeded, count);
    if (count < degree + 1) return fail(Error::TooFewPoints, count);
    return ok();
  }

  [[nodiscard]] static constexpr Result<void> check_closed_shape(std::size_t count, std::size_t degree) noexcept {
    if (count == 0) return fail(Error::EmptyControlPolygon);
    if (degree == 0) return fail(Error::DegreeTooLow);
    if (degree > MaxDegree) return fail(Error::DegreeAboveCapacity, degree);
    if (count < 2) return fail(Error::TooFewPoints, count);
    if (count + degree > MaxControlPoints) return fail(Error::CapacityExceeded, count + degree);
    return ok();
  }

  /// The closed curve: the points followed by the first `degree` of them again.
  [[nodiscard]] static constexpr Result<BSpline> wrap(std::span<const Point> control, std::span<const S> knots,
                                                      std::size_t degree) noexcept {
    std::array<Point, MaxControlPoints> wrapped{};
    const std::size_t count = control.size() + degree;
    for (std::size_t i = 0; i < count; ++i) wrapped[i] = control[i % control.size()];
    CURVESTEP_TRY(BSpline curve, create(std::span<const Point>(wrapped.data(), count), knots, degree));
    curve.layout_ = KnotLayout::Periodic;
    return curve;
  }

  [[nodiscard]] constexpr bool clamped_layout() const noexcept {
    const std::size_t last = knot_count(count_, degree_) - 1;
    return knots_[0] == knots_[degree_] && knots_[count_] == knots_[last];
  }

  std::array<Point, MaxControlPoints> points_{};
  std::array<S, knot_capacity> knots_{};
  std::size_t count_ = 0;
  std::size_t degree_ = 1;
  KnotLayout layout_ = KnotLayout::Unclamped;
};

}  // namespace curvestep
