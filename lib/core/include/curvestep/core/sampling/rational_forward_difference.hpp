// SPDX-License-Identifier: MIT
// RationalForwardDifference: steps a rational Bézier (arcs, conics, NURBS pieces) at h = 1/N.
//
// Why. r(t) = X(t) / W(t) where (X, W) = Σ (w_i b_i, w_i) B_i(t) is a polynomial curve in one
// more dimension. The homogeneous curve is stepped by ForwardDifference (additions only, exact
// re-seeds) and each point costs one division per coordinate.
//
// Fixed point. The division uses the stepper's wide accumulators (2^-G raw units) directly,
// not their rounded values: x = X / W is computed by integer long division to F fraction bits
// and rounded once. With δ the accumulators' error (n 2^-E + 2^-16 raw: the homogeneous
// stepper runs with a 2^-16 stepping budget) and w_min the smallest weight,
//     |x - r(t)| <= 1/2 + δ (1 + max|x|) / w_min  raw units,
// e.g. 0.55 raw for a 1000 mm arc with weights >= 0.7. The homogeneous control points w_i b_i
// are those of RationalBezier (rounded once to S), which the bound measures against.
//
// Floating point. x = X / W in S: |x - r(t)| <= (e_X + max|x| e_W) / w_min + u |x|, with e_X the
// homogeneous stepper's bound and e_W that of the weight polynomial alone.
//
// ISR budget: the polynomial stepper's additions for Dim + 1 coordinates plus Dim divisions
// (Fixed: F + 2 shift-subtract rounds each, ~100 cycles per axis on a Cortex-M3).
#pragma once

#include <cstddef>
#include <cstdint>

#include <curvestep/core/curve/rational_bezier.hpp>
#include <curvestep/core/sampling/forward_difference.hpp>

namespace curvestep {

/// Fixed-step evaluator of a rational Bézier of degree 1..MaxDegree: point() is r(index()/steps()).
template <Scalar S, std::size_t Dim, std::size_t MaxDegree = 5>
class RationalForwardDifference {
 public:
  using scalar_type = S;      ///< coordinate type
  using Point = Vec<S, Dim>;  ///< a point of the curve
  using Homogeneous = ForwardDifference<S, Dim + 1, MaxDegree>;  ///< the stepper of (w b, w)
  static constexpr std::size_t dimension = Dim;  ///< coordinates per point

  /// An empty stepper.
  constexpr RationalForwardDifference() = default;

  /// Steps `curve` in `steps` equal parameter steps. Errors as ForwardDifference::create.
  template <std::size_t CurveMaxDegree>
  [[nodiscard]] static Result<RationalForwardDifference> create(const RationalBezier<S, Dim, CurveMaxDegree>& curve,
                                                                std::uint32_t steps) noexcept {
    RationalForwardDifference stepper;
    constexpr int budget = FixedPoint<S> ? 16 : 2;
    CURVESTEP_TRY(stepper.homogeneous_, Homogeneous::create(curve.homogeneous(), steps, budget));
    double smallest_weight = to_double(curve.weight(0));
    double largest = 0;
    for (std::size_t i = 0; i <= curve.degree(); ++i) {
      const double w = to_double(curve.weight(i));
      if (w < smallest_weight) smallest_weight = w;
      for (std::size_t axis = 0; axis < Dim; ++axis) {
        const double c = to_double(curve.control_points()[i][axis]);
        if ((c < 0 ? -c : c) > largest) largest = c < 0 ? -c : c;
      }
    }
    if constexpr (FixedPoint<S>) {
      // The homogeneous accumulators' error without the final rounding of the polynomial bound.
      const double unit = to_double(resolution<S>());
      const double accumulator_error = stepper.homogeneous_.error_bound() - 0.5 * unit;
      stepper.bound_ = 0.5 * unit + accumulator_error * (1 + largest) / smallest_weight;
    } else {
      // The weight's own bound is far smaller than the coordinates' (it is measured against
      // the weights' magnitude): get it from a stepper of W alone (construction only).
      std::array<Vec<S, 1>, CurveMaxDegree + 1> weight_points{};
      for (std::size_t i = 0; i <= curve.degree(); ++i) weight_points[i][0] = curve.weight(i);
      CURVESTEP_TRY(const auto weight_curve, (Bezier<S, 1, CurveMaxDegree>::create(
                                                 std::span<const Vec<S, 1>>(weight_points.data(), curve.degree() + 1))));
      CURVESTEP_TRY(const auto weight_stepper, (ForwardDifference<S, 1, MaxDegree>::create(weight_curve, steps, budget)));
      const double u = static_cast<double>(std::numeric_limits<S>::epsilon()) / 2;
      const double e = stepper.homogeneous_.error_bound();
      stepper.bound_ = (e + largest * weight_stepper.error_bound()) / smallest_weight + u * largest;
    }
    return stepper;
  }

  /// The current point r(index()/steps()), within error_bound() per coordinate.
  [[nodiscard]] constexpr Point point() const noexcept {
    Point p;
    if constexpr (FixedPoint<S>) {
      const std::int64_t weight = homogeneous_.wide_coordinate(Dim);
      for (std::size_t axis = 0; axis < Dim; ++axis) p[axis] = divide(homogeneous_.wide_coordinate(axis), weight);
    } else {
      const S weight = homogeneous_.coordinate(Dim);
      for (std::size_t axis = 0; axis < Dim; ++axis) p[axis] = homogeneous_.coordinate(axis) / weight;
    }
    return p;
  }

  /// Advances by h. Contract: !finished().
  void step() noexcept { homogeneous_.step(); }
  /// True once point() is r(1).
  [[nodiscard]] constexpr bool finished() const noexcept { return homogeneous_.finished(); }
  /// Steps taken so far.
  [[nodiscard]] constexpr std::uint32_t index() const noexcept { return homogeneous_.index(); }
  /// N, the number of steps from r(0) to r(1).
  [[nodiscard]] constexpr std::uint32_t steps() const noexcept { return homogeneous_.steps(); }
  /// Steps between exact re-seeds of the homogeneous stepper.
  [[nodiscard]] constexpr std::uint32_t reseed_interval() const noexcept { return homogeneous_.reseed_interval(); }
  /// Proven bound of |point() - r(index()/steps())| per coordinate, in curve units.
  [[nodiscard]] constexpr double error_bound() const noexcept { return bound_; }

 private:
  /// round(numerator / denominator * 2^F) for the wide accumulators (denominator > 0).
  static constexpr S divide(std::int64_t numerator, std::int64_t denominator) noexcept {
    const bool negative = numerator < 0;
    const auto divisor = static_cast<std::uint64_t>(denominator);
    const auto magnitude = static_cast<std::uint64_t>(negative ? -numerator : numerator);
    std::uint64_t quotient = magnitude / divisor;
    std::uint64_t remainder = magnitude % divisor;
    for (int bit = 0; bit < S::fraction_bits; ++bit) {  // remainder < divisor < 2^62: no overflow
      remainder <<= 1;
      quotient <<= 1;
      if (remainder >= divisor) {
        remainder -= divisor;
        quotient |= 1;
      }
    }
    if ((remainder << 1) >= divisor) ++quotient;  // ties away from zero
    const auto value = static_cast<std::int64_t>(quotient);
    return S::from_raw(static_cast<typename S::rep>(negative ? -value : value));
  }

  Homogeneous homogeneous_{};
  double bound_ = 0;
};

}  // namespace curvestep
