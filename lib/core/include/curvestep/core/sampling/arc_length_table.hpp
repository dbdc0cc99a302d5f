// SPDX-License-Identifier: MIT
// ArcLengthTable: arc length at a parameter and the parameter at an arc length, to a tolerance.
//
// Why. A planner moves at a set speed along the curve, so it needs t(s), the inverse of
// s(t) = ∫_0^t |r'(τ)| dτ; the curve parameter itself runs at a varying speed (several-fold
// along a typical Bézier). The table is built once (host or planner time) and queried per tick.
//
// Building. [t0, t1] is cut adaptively: an interval is accepted when the 5-point
// Gauss–Legendre value on it and the sum over its two halves differ by at most its share
// tolerance (b-a)/(t1-t0) of the requested tolerance; otherwise both halves are examined. The
// accepted intervals arrive in parameter order (depth first, left half first) and are stored as
// breakpoints t_i with cumulative lengths L_i (the refined values), at most Capacity of them
// (CapacityExceeded otherwise: raise Capacity or the tolerance). The error of the standard
// estimate is far below the difference it is tested on for smooth speeds, so |L_i - s(t_i)|
// stays within the tolerance; Fixed adds at most one raw unit of rounding per interval.
//
// Queries. length_at(t) = L_i + GL5(t_i, t) on the interval holding t (a sub-interval of an
// accepted one, so at least as accurate). parameter_at(s) finds the interval by binary search
// and solves L_i + GL5(t_i, t) = s by Newton's method (derivative |r'(t)|) kept inside the
// interval's bracket by bisection; it stops when |s(t) - s| <= tolerance or the bracket is one
// resolution step wide (Fixed: t has 2^-F resolution, so |Δs| <= speed * 2^-F).
#pragma once

#include <array>
#include <cstddef>

#include <curvestep/core/curve/arc_length.hpp>
#include <curvestep/core/curve/curve_concept.hpp>
#include <curvestep/core/result.hpp>

namespace curvestep {

/// Arc-length parametrisation of a copy of `Curve` with up to Capacity quadrature intervals.
template <ParametricCurve Curve, std::size_t Capacity = 64>
class ArcLengthTable {
  static_assert(Capacity >= 1, "an arc-length table needs at least one interval");

 public:
  using scalar_type = typename Curve::scalar_type;   ///< parameter and length type
  using S = scalar_type;                             ///< shorthand
  static constexpr std::size_t capacity = Capacity;  ///< most quadrature intervals

  /// An empty table (length 0).
  constexpr ArcLengthTable() = default;

  /// Tabulates `curve` on [t0, t1] (default [0, 1]) to within `tolerance` (arc-length units).
  /// InvalidTolerance, InvalidInterval (t1 <= t0), CapacityExceeded, IterationLimit, and the
  /// curve's own derivative errors.
  [[nodiscard]] static constexpr Result<ArcLengthTable> create(const Curve& curve, S tolerance, S t0 = S{},
                                                               S t1 = from_int<S>(1)) {
    if (!(S{} < tolerance) || !is_finite(tolerance)) return fail(Error::InvalidTolerance);
    if (!(t0 < t1)) return fail(Error::InvalidInterval);
    ArcLengthTable table;
    table.curve_ = curve;
    table.tolerance_ = tolerance;
    table.parameters_[0] = t0;
    table.lengths_[0] = S{};
    struct Interval {
      S a, b, whole;
    };
    constexpr std::size_t stack_capacity = 64;
    std::array<Interval, stack_capacity> stack{};
    std::size_t depth = 0;
    CURVESTEP_TRY(const S whole, detail::gauss_legendre_speed(curve, t0, t1));
    stack[depth++] = Interval{t0, t1, whole};
    const S span = t1 - t0;
    S total{};
    while (depth > 0) {
      const Interval iv = stack[--depth];
      const S middle = iv.a + (iv.b - iv.a) / from_int<S>(2);
      CURVESTEP_TRY(const S left, detail::gauss_legendre_speed(curve, iv.a, middle));
      CURVESTEP_TRY(const S right, detail::gauss_legendre_speed(curve, middle, iv.b));
      const S refined = left + right;
      const S share = tolerance * ((iv.b - iv.a) / span);
      const bool resolution_reached = !(iv.a < middle) || !(middle < iv.b);
      if (abs(refined - iv.whole) <= share || resolution_reached) {
        if (table.count_ == Capacity) return fail(Error::CapacityExceeded, Capacity);
        total = total + refined;
        ++table.count_;
        table.parameters_[table.count_] = iv.b;
        table.lengths_[table.count_] = total;
        continue;
      }
      if (depth + 2 > stack_capacity) return fail(Error::IterationLimit);
      stack[depth++] = Interval{middle, iv.b, right};
      stack[depth++] = Interval{iv.a, middle, left};
    }
    return table;
  }

  /// Total arc length of [t0, t1].
  [[nodiscard]] constexpr S total_length() const noexcept { return lengths_[count_]; }
  /// Number of quadrature intervals used.
  [[nodiscard]] constexpr std::size_t size() const noexcept { return count_; }
  /// The parameter domain's ends.
  [[nodiscard]] constexpr S start() const noexcept { return parameters_[0]; }
  [[nodiscard]] constexpr S end() const noexcept { return parameters_[count_]; }
  /// The tabulated curve.
  [[nodiscard]] constexpr const Curve& curve() const noexcept { return curve_; }

  /// Arc length from start() to t; ParameterOutOfRange outside [start(), end()].
  [[nodiscard]] constexpr Result<S> length_at(S t) const {
    if (count_ == 0 || t < start() || end() < t) return fail(Error::ParameterOutOfRange);
    const std::size_t i = interval_of_parameter(t);
    if (t == parameters_[i]) return lengths_[i];
    CURVESTEP_TRY(const S part, detail::gauss_legendre_speed(curve_, parameters_[i], t));
    return lengths_[i] + part;
  }

  /// The parameter t at arc length s from start(); ParameterOutOfRange outside [0, total_length()].
  [[nodiscard]] constexpr Result<S> parameter_at(S s) const {
    if (count_ == 0 || s < S{} || total_length() < s) return fail(Error::ParameterOutOfRange);
    const std::size_t i = interval_of_length(s);
    S low = parameters_[i];
    S high = parameters_[i + 1];
    const S base = lengths_[i];
    const S width = lengths_[i + 1] - base;
    if (!(S{} < width)) return low;
    if (s == base) return low;
    if (s == lengths_[i + 1]) return high;
    S t = low + (high - low) * ((s - base) / width);  // linear first guess
    for (int iteration = 0; iteration < 40; ++iteration) {
      if (t < low || high < t) t = low + (high - low) / from_int<S>(2);
      CURVESTEP_TRY(const S part, detail::gauss_legendre_speed(curve_, parameters_[i], t));
      const S error = base + part - s;
      if (abs(error) <= tolerance_) return t;
      if (S{} < error) {
        high = t;
      } else {
        low = t;
      }
      const S middle = low + (high - low) / from_int<S>(2);
      if (!(low < middle) || !(middle < high)) return abs(error) <= tolerance_ ? t : middle;  // resolution reached
      CURVESTEP_TRY(const auto derivative, curve_.derivative_at(t, 1));
      const S speed = norm(derivative);
      S next = middle;
      if (S{} < speed) {
        const auto step = checked_div(error, speed);
        if (step) next = t - step.value();
      }
      t = (low < next && next < high) ? next : middle;
    }
    return t;
  }

 private:
  /// i with parameters_[i] <= t < parameters_[i+1] (the last interval for t == end()).
  [[nodiscard]] constexpr std::size_t interval_of_parameter(S t) const noexcept {
    std::size_t low = 0;
    std::size_t high = count_;  // parameters_[high] >= t
    while (high - low > 1) {
      const std::size_t middle = (low + high) / 2;
      if (t < parameters_[middle]) {
        high = middle;
      } else {
        low = middle;
      }
    }
    return low;
  }
  /// i with lengths_[i] <= s <= lengths_[i+1].
  [[nodiscard]] constexpr std::size_t interval_of_length(S s) const noexcept {
    std::size_t low = 0;
    std::size_t high = count_;
    while (high - low > 1) {
      const std::size_t middle = (low + high) / 2;
      if (s < lengths_[middle]) {
        high = middle;
      } else {
        low = middle;
      }
    }
    return low;
  }

  Curve curve_{};
  std::array<S, Capacity + 1> parameters_{};  ///< breakpoints t_0 < ... < t_count
  std::array<S, Capacity + 1> lengths_{};     ///< cumulative arc length at each breakpoint
  std::size_t count_ = 0;
  S tolerance_{};
};

}  // namespace curvestep
