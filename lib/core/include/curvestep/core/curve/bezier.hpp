// SPDX-License-Identifier: MIT
// Bezier<S, Dim, MaxDegree>: a polynomial curve segment given by its control points, no heap.
//
// Evaluation is de Casteljau's algorithm: b^r_i = (1-t) b^{r-1}_i + t b^{r-1}_{i+1}, b^n_0 = p(t).
// For t in [0,1] every step is a convex combination, so every intermediate point lies in the
// convex hull of the control points: with Fixed scalars nothing can overflow and the error is at
// most n roundings of half a unit per coordinate. The same triangle gives the split at t
// (upper diagonal: left half, lower diagonal: right half) and, run with a different parameter
// on each level, the blossom P(u_1..u_n) (the polar form; order-independent).
//
// Operations whose results may leave the control points' hull (derivatives, extrapolated
// blossoms, basis changes) use exact integer combinations and report FixedOverflow/NotFinite.
// The local parameter domain is [0,1]; CompositeBezier maps a global [a,b] onto it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>

#include <curvestep/core/contract.hpp>
#include <curvestep/core/detail/binomial.hpp>
#include <curvestep/core/detail/exact_combination.hpp>
#include <curvestep/core/geometry/bounding_box.hpp>
#include <curvestep/core/geometry/vec.hpp>
#include <curvestep/core/result.hpp>

namespace curvestep {

template <Scalar S, std::size_t Dim, std::size_t MaxDegree>
class Bezier;
template <Scalar S, std::size_t Dim, std::size_t MaxDegree>
class RationalBezier;

/// The two halves of a curve split at one parameter.
template <class Curve>
struct SplitCurves {
  Curve left;   ///< the curve on [0, t], reparametrised to [0, 1]
  Curve right;  ///< the curve on [t, 1], reparametrised to [0, 1]
};

/// The full de Casteljau triangle for one t: level r holds n+1-r points.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree>
struct DeCasteljauTriangle {
  std::array<std::array<Vec<S, Dim>, MaxDegree + 1>, MaxDegree + 1> levels{};  ///< levels[r][i] = b^r_i
  std::size_t degree = 0;                                                       ///< n
};

/// A Bézier curve of runtime degree 0..MaxDegree in Dim dimensions on the local domain [0,1].
template <Scalar S, std::size_t Dim, std::size_t MaxDegree = 7>
class Bezier {
  static_assert(MaxDegree >= 1, "a Bezier type must allow at least degree 1");
  static_assert(MaxDegree <= 30, "degrees above 30 lose all precision and overflow binomials");

 public:
  using scalar_type = S;
  using Point = Vec<S, Dim>;
  static constexpr std::size_t dimension = Dim;
  static constexpr std::size_t max_degree = MaxDegree;
  static constexpr std::size_t capacity = MaxDegree + 1;  ///< maximum number of control points

  /// A degree-0 curve at the origin.
  constexpr Bezier() = default;

  /// A curve from its control points. EmptyControlPolygon, DegreeAboveCapacity (index = the degree
  /// asked for, which is also the first control point that does not fit),
  /// NotFinite (index = control point) for NaN/inf coordinates.
  [[nodiscard]] static constexpr Result<Bezier> create(std::span<const Point> control) noexcept {
    Result<Bezier> out(std::in_place);  // filled in place and returned by name: no copy of the curve
    if (const auto made = create_into(out.value(), control); !made) out = made.failure();
    return out;
  }

  /// create(control) written into `out` (for callers that hold the curve inside a larger object:
  /// no Result<Bezier> copy on the stack). The same errors; on an error `out` is unchanged.
  [[nodiscard]] static constexpr Result<void> create_into(Bezier& out, std::span<const Point> control) noexcept {
    if (control.empty()) return fail(Error::EmptyControlPolygon);
    if (control.size() > capacity) return fail(Error::DegreeAboveCapacity, control.size() - 1);
    for (std::size_t i = 0; i < control.size(); ++i) {
      for (std::size_t axis = 0; axis < Dim; ++axis) {
        if (!is_finite(control[i][axis])) return fail(Error::NotFinite, i);
      }
    }
    for (std::size_t i = 0; i < capacity; ++i) out.points_[i] = i < control.size() ? control[i] : Point{};
    out.degree_ = control.size() - 1;
    return ok();
  }

  /// Convenience: create({p0, p1, ...}).
  [[nodiscard]] static constexpr Result<Bezier> create(std::initializer_list<Point> control) noexcept {
    return create(std::span<const Point>(control.begin(), control.size()));
  }

  /// Degree n (number of control points minus one).
  [[nodiscard]] constexpr std::size_t degree() const noexcept { return degree_; }
  /// The n+1 control points.
  [[nodiscard]] constexpr std::span<const Point> control_points() const noexcept {
    return std::span<const Point>(points_.data(), degree_ + 1);
  }
  /// Control point i; contract: i <= degree().
  [[nodiscard]] constexpr const Point& operator[](std::size_t i) const {
    CURVESTEP_EXPECTS(i <= degree_);
    return points_[i];
  }
  /// First and last control points (the curve's end points).
  [[nodiscard]] constexpr const Point& front() const noexcept { return points_[0]; }
  [[nodiscard]] constexpr const Point& back() const noexcept { return points_[degree_]; }

  /// p(t) for t in [0,1]; ParameterOutOfRange otherwise.
  [[nodiscard]] constexpr Result<Point> evaluate(S t) const {
    if (!(S{} <= t && t <= from_int<S>(1))) return fail(Error::ParameterOutOfRange);  // NaN too
    return point_at(t);
  }

  /// p(t) by de Casteljau; contract: t in [0,1] (the hot path: no Result, no checks beyond that).
  [[nodiscard]] constexpr Point point_at(S t) const {
    CURVESTEP_EXPECTS(S{} <= t && t <= from_int<S>(1));
    std::array<Point, capacity> work = points_;
    for (std::size_t r = 1; r <= degree_; ++r) {
      for (std::size_t i = 0; i + r <= degree_; ++i) work[i] = lerp(work[i], work[i + 1], t);
    }
    return work[0];
  }

  /// The whole de Casteljau triangle at t in [0,1].
  [[nodiscard]] constexpr Result<DeCasteljauTriangle<S, Dim, MaxDegree>> triangle(S t) const {
    if (!(S{} <= t && t <= from_int<S>(1))) return fail(Error::ParameterOutOfRange);  // NaN too
    DeCasteljauTriangle<S, Dim, MaxDegree> tri;
    tri.degree = degree_;
    tri.levels[0] = points_;
    for (std::size_t r = 1; r <= degree_; ++r) {
      for (std::size_t i = 0; i + r <= degree_; ++i) {
        tri.levels[r][i] = lerp(tri.levels[r - 1][i], tri.levels[r - 1][i + 1], t);
      }
    }
    return tri;
  }

  /// Splits at t in [0,1] into the curves on [0,t] and [t,1] (each reparametrised to [0,1]).
  [[nodiscard]] constexpr Result<SplitCurves<Bezier>> split(S t) const {
    Result<SplitCurves<Bezier>> out(std::in_place);  // filled in place: no copy of the halves
    if (const auto cut = split(t, out.value().left, out.value().right); !cut) out = cut.failure();
    return out;
  }

  /// split(t) into `left` and `right` (either may be this curve). ParameterOutOfRange leaves
  /// both unchanged.
  [[nodiscard]] constexpr Result<void> split(S t, Bezier& left, Bezier& right) const {
    if (!(S{} <= t && t <= from_int<S>(1))) return fail(Error::ParameterOutOfRange);  // NaN too
    const std::size_t n = degree_;
    std::array<Point, capacity> work = points_;  // read before left or right (may be *this) is written
    for (std::size_t i = n + 1; i < capacity; ++i) left.points_[i] = right.points_[i] = Point{};
    left.degree_ = right.degree_ = n;
    left.points_[0] = work[0];
    right.points_[n] = work[n];
    for (std::size_t r = 1; r <= n; ++r) {
      for (std::size_t i = 0; i + r <= n; ++i) work[i] = lerp(work[i], work[i + 1], t);
      left.points_[r] = work[0];
      right.points_[n - r] = work[n - r];
    }
    return ok();
  }

  /// The curve restricted to [t0, t1] within [0,1], reparametrised to [0,1].
  [[nodiscard]] constexpr Result<Bezier> segment(S t0, S t1) const {
    if (!(S{} <= t0 && t0 <= t1 && t1 <= from_int<S>(1))) return fail(Error::ParameterOutOfRange);
    std::array<S, MaxDegree> params{};
    std::array<Point, capacity> result{};
    for (std::size_t i = 0; i <= degree_; ++i) {
      for (std::size_t k = 0; k < degree_; ++k) params[k] = k < degree_ - i ? t0 : t1;
      auto p = blossom(std::span<const S>(params.data(), degree_));
      if (!p) return p.failure();
      result[i] = p.value();
    }
    return create(std::span<const Point>(result.data(), degree_ + 1));
  }

  /// The hodograph p'(t) as a curve of degree n-1: control points n (b_{i+1} - b_i).
  /// A degree-0 curve's derivative is the zero curve of degree 0. FixedOverflow/NotFinite.
  [[nodiscard]] constexpr Result<Bezier> derivative() const noexcept {
    // (hodograph_in_place below repeats these steps on a working array; keep the two alike)
    Bezier d;
    if (degree_ == 0) return d;
    d.degree_ = degree_ - 1;
    const auto n = static_cast<std::int64_t>(degree_);
    const std::array<std::int64_t, 2> weights{-n, n};
    for (std::size_t i = 0; i < degree_; ++i) {
      auto p = detail::exact_combination<S, Dim>(std::span<const Point>(&points_[i], 2), weights, 1);
      if (!p) return fail(p.error(), i);
      d.points_[i] = p.value();
    }
    return d;
  }

  /// The order-th derivative curve (order 0: the curve itself).
  [[nodiscard]] constexpr Result<Bezier> derivative(std::size_t order) const noexcept {
    Bezier d = *this;
    for (std::size_t k = 0; k < order; ++k) {
      auto next = d.derivative();
      if (!next) return next.failure();
      d = next.value();
    }
    return d;
  }

  /// p^(order)(t) for t in [0,1].
  /// The same numbers as derivative(order).value().point_at(t) (and its errors), computed in one
  /// working array instead of copies of the curve.
  [[nodiscard]] constexpr Result<Point> derivative_at(S t, std::size_t order = 1) const {
    if (!(S{} <= t && t <= from_int<S>(1))) return fail(Error::ParameterOutOfRange);  // NaN too
    std::array<Point, capacity> work = points_;
    std::size_t n = degree_;
    for (std::size_t k = 0; k < order; ++k) {
      if (const auto failed = hodograph_in_place(work, n)) return *failed;
    }
    for (std::size_t r = 1; r <= n; ++r) {
      for (std::size_t i = 0; i + r <= n; ++i) work[i] = lerp(work[i], work[i + 1], t);
    }
    return work[0];
  }

  /// The same curve with degree n+1: b'_i = (i b_{i-1} + (n+1-i) b_i) / (n+1).
  /// DegreeAboveCapacity if n+1 > MaxDegree.
  [[nodiscard]] constexpr Result<Bezier> elevated() const noexcept {
    if (degree_ + 1 > MaxDegree) return fail(Error::DegreeAboveCapacity, degree_ + 1);
    Bezier e;
    e.degree_ = degree_ + 1;
    const auto m = static_cast<std::int64_t>(degree_ + 1);
    e.points_[0] = points_[0];
    e.points_[degree_ + 1] = points_[degree_];
    for (std::size_t i = 1; i <= degree_; ++i) {
      const auto ii = static_cast<std::int64_t>(i);
      const std::array<std::int64_t, 2> weights{ii, m - ii};
      auto p = detail::exact_combination<S, Dim>(std::span<const Point>(&points_[i - 1], 2), weights, m);
      if (!p) return fail(p.error(), i);
      e.points_[i] = p.value();
    }
    return e;
  }

  /// The blossom (polar form) P(u_1, ..., u_n): de Casteljau with u_r on level r. Symmetric in
  /// its arguments; P(t,...,t) = p(t); P(0^{n-i}, 1^i) = b_i. Any u (extrapolation is checked).
  /// Contract: u.size() == degree().
  [[nodiscard]] constexpr Result<Point> blossom(std::span<const S> u) const noexcept {
    CURVESTEP_EXPECTS(u.size() == degree_);
    std::array<Point, capacity> work = points_;
    for (std::size_t r = 1; r <= degree_; ++r) {
      for (std::size_t i = 0; i + r <= degree_; ++i) {
        auto p = checked_lerp(work[i], work[i + 1], u[r - 1]);
        if (!p) return fail(p.error(), r - 1);
        work[i] = p.value();
      }
    }
    return work[0];
  }

  /// The axis-aligned box of the control points; it contains the whole curve on [0,1].
  [[nodiscard]] constexpr BoundingBox<S, Dim> bounding_box() const {
    return curvestep::bounding_box<S, Dim>(control_points());
  }

  /// The same curve traversed backwards: control points reversed.
  [[nodiscard]] constexpr Bezier reversed() const noexcept {
    Bezier r;
    r.degree_ = degree_;
    for (std::size_t i = 0; i <= degree_; ++i) r.points_[i] = points_[degree_ - i];
    return r;
  }

  friend constexpr bool operator==(const Bezier& a, const Bezier& b) noexcept {
    if (a.degree_ != b.degree_) return false;
    for (std::size_t i = 0; i <= a.degree_; ++i) {
      if (!(a.points_[i] == b.points_[i])) return false;
    }
    return true;
  }

 private:
  template <Scalar, std::size_t, std::size_t>
  friend class RationalBezier;

  /// derivative() on the first n + 1 points of `work` in place (n becomes the hodograph's degree,
  /// a degree-0 curve gives the zero point): the same numbers and errors as derivative().
  [[nodiscard, gnu::always_inline]] static constexpr std::optional<Failure> hodograph_in_place(std::array<Point, capacity>& work, std::size_t& n) noexcept {
    if (n == 0) {
      work[0] = Point{};
      return std::nullopt;
    }
    const auto m = static_cast<std::int64_t>(n);
    const std::array<std::int64_t, 2> weights{-m, m};
    for (std::size_t i = 0; i < n; ++i) {
      auto p = detail::exact_combination<S, Dim>(std::span<const Point>(&work[i], 2), weights, 1);
      if (!p) return fail(p.error(), i);
      work[i] = p.value();
    }
    --n;
    return std::nullopt;
  }

  std::array<Point, capacity> points_{};
  std::size_t degree_ = 0;
};

}  // namespace curvestep
