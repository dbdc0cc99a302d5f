// SPDX-License-Identifier: MIT
// RationalBezier: r(t) = Σ w_i b_i B^n_i(t) / Σ w_i B^n_i(t), with positive weights.
//
// Evaluated by de Casteljau in homogeneous coordinates (w b, w) and one division, which keeps
// every step a convex combination. The homogeneous points are taken relative to the first control
// point, (w (b - b_0), w), and b_0 is added back after the division: the weight coordinate carries
// a relative rounding error (2^-17 per level in Q16.16) that the division multiplies by the
// projected value, so this keeps the error proportional to the curve's extent instead of its
// distance from the origin (a 1 mm arc at x = 10 m would otherwise be off by ~0.1 mm). For Fixed,
// point_at and split also multiply all weights by the largest power of two that keeps w and
// w |b - b_0| at most 2^13: the projection is unchanged and the weight coordinate gains those
// bits, so a 200 mm curve with weights in [0.5, 2] is within ~30 units of Q16.16 instead of ~400.
// Derivatives come from the homogeneous curve A(t) = (w r)(t) and its weight w(t) by the Leibniz
// rule: w r^(k) = A^(k) - Σ_{i=1..k} C(k,i) w^(i) r^(k-i).
// Positive weights keep the curve inside the convex hull of its control points.
#pragma once

#include <array>
#include <cstddef>
#include <initializer_list>
#include <optional>
#include <span>

#include <curvestep/core/curve/bezier.hpp>
#include <curvestep/core/detail/binomial.hpp>
#include <curvestep/core/detail/checked.hpp>

namespace curvestep {

/// A rational Bézier curve of runtime degree up to MaxDegree with positive weights, on [0,1].
template <Scalar S, std::size_t Dim, std::size_t MaxDegree = 7>
class RationalBezier {
 public:
  using scalar_type = S;
  using Point = Vec<S, Dim>;
  using Homogeneous = Bezier<S, Dim + 1, MaxDegree>;  ///< the curve (w b, w) in one more dimension
  using HomogeneousPoint = Vec<S, Dim + 1>;           ///< (w b, w)
  static constexpr std::size_t dimension = Dim;
  static constexpr std::size_t max_degree = MaxDegree;
  static constexpr std::size_t capacity = MaxDegree + 1;

  constexpr RationalBezier() = default;

  /// From control points and their weights (same count). NonPositiveWeight (index = weight),
  /// EmptyControlPolygon, DegreeAboveCapacity, InvalidArgument (counts differ), FixedOverflow if
  /// w_i b_i does not fit.
  [[nodiscard]] static constexpr Result<RationalBezier> create(std::span<const Point> control,
                                                               std::span<const S> weights) noexcept {
    Result<RationalBezier> out(std::in_place);  // filled in place and returned by name: no copy
    if (const auto made = create_into(out.value(), control, weights); !made) out = made.failure();
    return out;
  }

  /// create(control, weights) written into `out` (for callers that hold the curve inside a larger
  /// object: no Result<RationalBezier> copy on the stack). The same errors; on an error `out`
  /// holds unspecified values.
  [[nodiscard]] static constexpr Result<void> create_into(RationalBezier& out, std::span<const Point> control,
                                                          std::span<const S> weights) noexcept {
    if (control.empty()) return fail(Error::EmptyControlPolygon);
    if (control.size() > capacity) return fail(Error::DegreeAboveCapacity, control.size() - 1);
    if (weights.size() != control.size()) return fail(Error::InvalidArgument, weights.size());
    auto& homogeneous = out.homogeneous_.points_;
    for (std::size_t i = 0; i < capacity; ++i) {
      homogeneous[i] = Vec<S, Dim + 1>{};
      out.points_[i] = Point{};
    }
    for (std::size_t i = 0; i < control.size(); ++i) {
      if (!is_finite(weights[i])) return fail(Error::NotFinite, i);
      if (!(S{} < weights[i])) return fail(Error::NonPositiveWeight, i);
      for (std::size_t axis = 0; axis < Dim; ++axis) {
        if (!is_finite(control[i][axis])) return fail(Error::NotFinite, i);
        const auto c = checked_mul(control[i][axis], weights[i]);
        if (!c) return fail(c.error(), i);
        homogeneous[i][axis] = c.value();
      }
      homogeneous[i][Dim] = weights[i];
      out.points_[i] = control[i];
    }
    // (Homogeneous::create would accept these points: finite products and weights, count checked.)
    out.homogeneous_.degree_ = control.size() - 1;
    return ok();
  }

  [[nodiscard]] static constexpr Result<RationalBezier> create(std::initializer_list<Point> control,
                                                               std::initializer_list<S> weights) noexcept {
    return create(std::span<const Point>(control.begin(), control.size()), std::span<const S>(weights.begin(), weights.size()));
  }

  /// A polynomial Bézier as a rational one (all weights 1).
  [[nodiscard]] static constexpr Result<RationalBezier> from_polynomial(const Bezier<S, Dim, MaxDegree>& curve) noexcept {
    std::array<S, capacity> ones{};
    for (auto& w : ones) w = from_int<S>(1);
    return create(curve.control_points(), std::span<const S>(ones.data(), curve.degree() + 1));
  }

  [[nodiscard]] constexpr std::size_t degree() const noexcept { return homogeneous_.degree(); }
  [[nodiscard]] constexpr std::span<const Point> control_points() const noexcept {
    return std::span<const Point>(points_.data(), degree() + 1);
  }
  /// Weight i; contract: i <= degree().
  [[nodiscard]] constexpr S weight(std::size_t i) const { return homogeneous_[i][Dim]; }
  /// The homogeneous polynomial curve (w b, w).
  [[nodiscard]] constexpr const Homogeneous& homogeneous() const noexcept { return homogeneous_; }
  [[nodiscard]] constexpr const Point& front() const noexcept { return points_[0]; }
  [[nodiscard]] constexpr const Point& back() const noexcept { return points_[degree()]; }

  /// r(t) for t in [0,1]; ParameterOutOfRange otherwise.
  [[nodiscard]] constexpr Result<Point> evaluate(S t) const {
    if (!(S{} <= t && t <= from_int<S>(1))) return fail(Error::ParameterOutOfRange);  // NaN too
    return point_at(t);
  }

  /// r(t), contract t in [0,1]. The end points are returned exactly.
  [[nodiscard]] constexpr Point point_at(S t) const {
    if (t == S{}) return points_[0];
    if (t == from_int<S>(1)) return points_[degree()];
    // De Casteljau in place: the numbers of Homogeneous::point_at on the local curve, or on the
    // curve itself where the control points are too far apart for (b - b_0).
    std::array<HomogeneousPoint, capacity> h{};
    const bool local = local_homogeneous(h, true);
    if (!local) h = homogeneous_.points_;
    for (std::size_t r = 1; r <= degree(); ++r) {
      for (std::size_t i = 0; i + r <= degree(); ++i) h[i] = lerp(h[i], h[i + 1], t);
    }
    return local ? points_[0] + project(h[0]) : project(h[0]);
  }

  /// r^(order)(t) for t in [0,1] (order 0: the point).
  [[nodiscard]] constexpr Result<Point> derivative_at(S t, std::size_t order = 1) const {
    if (!(S{} <= t && t <= from_int<S>(1))) return fail(Error::ParameterOutOfRange);  // NaN too
    if (order > MaxDegree + 4) return fail(Error::InvalidArgument);
    if (order == 0) return point_at(t);
    return higher_derivative_at<MaxDegree + 4>(t, order);
  }

  /// derivative_at(t, order) for orders up to MaxOrder only (InvalidArgument above), with its
  /// working arrays sized for MaxOrder: the same numbers on less stack (a motion planner needs
  /// orders 1..3, the general form up to MaxDegree + 4).
  template <std::size_t MaxOrder>
  [[nodiscard]] constexpr Result<Point> derivative_at_most(S t, std::size_t order) const {
    static_assert(MaxOrder <= MaxDegree + 4, "derivative_at supports orders up to MaxDegree + 4");
    if (!(S{} <= t && t <= from_int<S>(1))) return fail(Error::ParameterOutOfRange);  // NaN too
    if (order > MaxOrder) return fail(Error::InvalidArgument);
    if (order == 0) return point_at(t);
    return higher_derivative_at<MaxOrder>(t, order);
  }

 private:
  /// derivative_at() for 1 <= order <= MaxOrder (its own frame: the point's is not stacked on top of it).
  template <std::size_t MaxOrder>
  [[nodiscard, gnu::noinline]] constexpr Result<Point> higher_derivative_at(S t, std::size_t order) const {
    // Derivatives of order >= 1 do not change under translation: work relative to b_0.
    // A^(k)(t) = base.derivative_at(t, k) for k = 0..order is computed in one working array (the
    // k-th hodograph from the (k-1)-th, the same steps as Bezier::derivative) instead of copies
    // of the homogeneous curve, and the Leibniz step k follows at once: the same numbers. Errors
    // as before: any hodograph's first, else the first Leibniz step's (kept until the hodographs
    // are all checked).
    std::array<HomogeneousPoint, capacity> hodograph{};
    if (!local_homogeneous(hodograph, false)) hodograph = homogeneous_.points_;
    std::size_t n = degree();
    std::array<S, MaxOrder + 1> weight_derivatives{};  // w^(k)(t)
    std::array<Point, MaxOrder + 1> r{};
    std::optional<Failure> leibniz_failure;
    for (std::size_t k = 0; k <= order; ++k) {
      if (k > 0) {
        if (const auto failed = Homogeneous::hodograph_in_place(hodograph, n)) return *failed;
      }
      if (leibniz_failure) continue;
      HomogeneousPoint derivative;  // A^(k)(t): de Casteljau one coordinate at a time (it is component-wise)
      for (std::size_t c = 0; c <= Dim; ++c) {
        std::array<S, capacity> work{};
        for (std::size_t i = 0; i <= n; ++i) work[i] = hodograph[i][c];
        for (std::size_t level = 1; level <= n; ++level) {
          for (std::size_t i = 0; i + level <= n; ++i) work[i] = lerp(work[i], work[i + 1], t);
        }
        derivative[c] = work[0];
      }
      weight_derivatives[k] = derivative[Dim];
      const S w = weight_derivatives[0];
      for (std::size_t axis = 0; axis < Dim && !leibniz_failure; ++axis) {
        detail::Checked<S> numerator(derivative[axis]);
        for (std::size_t i = 1; i <= k; ++i) {
          const auto c = static_cast<int>(detail::binomial(k, i));
          numerator = numerator - detail::Checked<S>(from_int<S>(c)) * detail::Checked<S>(weight_derivatives[i]) *
                                      detail::Checked<S>(r[k - i][axis]);
        }
        const auto quotient = (numerator / detail::Checked<S>(w)).result();
        if (quotient) {
          r[k][axis] = quotient.value();
        } else {
          leibniz_failure = quotient.failure();
        }
      }
    }
    if (leibniz_failure) return *leibniz_failure;
    return r[order];
  }

 public:

  /// Splits at t in [0,1]; both halves are rational curves of the same degree.
  [[nodiscard]] constexpr Result<SplitCurves<RationalBezier>> split(S t) const {
    Result<SplitCurves<RationalBezier>> out(std::in_place);  // filled in place: no copy of the halves
    if (const auto cut = split(t, out.value().left, out.value().right); !cut) out = cut.failure();
    return out;
  }

  /// split(t) into `left` and `right` (either may be this curve; no copies of the halves).
  /// ParameterOutOfRange leaves both unchanged.
  [[nodiscard]] constexpr Result<void> split(S t, RationalBezier& left, RationalBezier& right) const {
    if (!(S{} <= t && t <= from_int<S>(1))) return fail(Error::ParameterOutOfRange);  // NaN too
    // Everything read from this curve is read before left or right is written.
    const std::size_t n = degree();
    const Point first = points_[0];
    const Point last = points_[n];
    std::array<HomogeneousPoint, capacity> local{};
    const bool has_local = local_homogeneous(local, true);
    // The homogeneous halves, and their control points projected (from_homogeneous)...
    (void)homogeneous_.split(t, left.homogeneous_, right.homogeneous_);  // t is in range
    for (std::size_t i = 0; i < capacity; ++i) {
      if (i > n) {
        left.points_[i] = right.points_[i] = Point{};
        continue;
      }
      CURVESTEP_EXPECTS(S{} < left.homogeneous_[i][Dim] && S{} < right.homogeneous_[i][Dim]);
      left.points_[i] = project(left.homogeneous_[i]);
      right.points_[i] = project(right.homogeneous_[i]);
    }
    // ... or, better, projected from the curve relative to b_0 (same weights, smaller errors),
    // by the de Casteljau triangle of Homogeneous::split in place; the outer end points are kept
    // exactly, as point_at returns them.
    if (has_local) {
      for (std::size_t r = 1; r <= n; ++r) {
        for (std::size_t i = 0; i + r <= n; ++i) local[i] = lerp(local[i], local[i + 1], t);
        left.points_[r] = first + project(local[0]);
        right.points_[n - r] = first + project(local[n - r]);
      }
    }
    left.points_[0] = first;
    right.points_[n] = last;
    return ok();
  }

  /// The box of the control points; with positive weights it contains the curve.
  [[nodiscard]] constexpr BoundingBox<S, Dim> bounding_box() const {
    return curvestep::bounding_box<S, Dim>(control_points());
  }

  /// Builds the curve from a homogeneous one whose weights are known to be positive.
  [[nodiscard]] static constexpr RationalBezier from_homogeneous(const Homogeneous& h) {
    RationalBezier curve;
    curve.homogeneous_ = h;
    for (std::size_t i = 0; i <= h.degree(); ++i) {
      CURVESTEP_EXPECTS(S{} < h[i][Dim]);
      curve.points_[i] = project(h[i]);
    }
    return curve;
  }

 private:
  /// (w_i (b_i - b_0), w_i): the homogeneous curve relative to the first control point.
  /// `scaled` (Fixed, for points only): all weights multiplied by the largest power of two that
  /// keeps w and w |b - b_0| at most 2^13. The projection does not change, but the weight
  /// coordinate gains that many bits of relative precision, which is what limits the accuracy of
  /// the division (not used for derivatives, whose Leibniz products would grow by the same factor).
  /// Written into `h` (its first degree() + 1 points); false (h unspecified) if b_i - b_0 or its
  /// product with w_i leaves the range (FixedOverflow/NotFinite).
  [[nodiscard]] constexpr bool local_homogeneous(std::array<HomogeneousPoint, capacity>& h, bool scaled) const noexcept {
    int shift = 0;
    if constexpr (FixedPoint<S>) {
      if (scaled) {
        using W = typename S::wide;
        W largest_weight = 0;
        W extent = 0;
        for (std::size_t i = 0; i <= degree(); ++i) {
          const W w = homogeneous_[i][Dim].raw();
          if (w > largest_weight) largest_weight = w;
          for (std::size_t axis = 0; axis < Dim; ++axis) {
            W d = W{points_[i][axis].raw()} - W{points_[0][axis].raw()};
            if (d < 0) d = -d;
            if (d > extent) extent = d;
          }
        }
        // Keep the scaled weight and weight · extent at most 2^13 (in raw units 2^(F+13)): the
        // homogeneous de Casteljau forms convex combinations, so nothing grows beyond that.
        if (extent <= W{std::numeric_limits<typename S::rep>::max()}) {
          const W limit = W{1} << (S::fraction_bits + 13);
          const W product = S::round_shift(extent * largest_weight, S::fraction_bits);
          while (shift < S::fraction_bits && (largest_weight << (shift + 1)) <= limit && (product << (shift + 1)) <= limit) {
            ++shift;
          }
        }
      }
    }
    for (std::size_t i = 0; i <= degree(); ++i) {
      S w = homogeneous_[i][Dim];
      if constexpr (FixedPoint<S>) w = S::from_raw(static_cast<typename S::rep>(w.raw() << shift));
      for (std::size_t axis = 0; axis < Dim; ++axis) {
        const auto difference = checked_sub(points_[i][axis], points_[0][axis]);
        if (!difference) return false;
        const auto product = checked_mul(difference.value(), w);
        if (!product) return false;
        h[i][axis] = product.value();
      }
      h[i][Dim] = w;
    }
    // (Homogeneous::create would accept these: finite differences, products and weights.)
    return true;
  }

  static constexpr Point project(const Vec<S, Dim + 1>& h) {
    Point p;
    for (std::size_t axis = 0; axis < Dim; ++axis) p[axis] = h[axis] / h[Dim];
    return p;
  }

  Homogeneous homogeneous_{};
  std::array<Point, capacity> points_{};
};

}  // namespace curvestep
