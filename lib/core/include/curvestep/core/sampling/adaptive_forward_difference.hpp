// SPDX-License-Identifier: MIT
// AdaptiveForwardDifference: forward differencing whose step halves or doubles in place to hold the chord in a band.
//
// Why. A fixed parameter step gives chords whose length follows the parametric speed, which
// can vary several-fold along one Bézier. Adaptive forward differencing (Lien, Shantz and
// Pratt 1987) changes the step by transforming the difference table, not by restarting: with
// E = 1 + Δ the shift operator, E_{h/2} = E_h^{1/2} and E_{2h} = E_h², so
//     Δ_{h/2}^j = ((1+Δ)^{1/2} - 1)^j = Σ_k H_jk Δ^k,    Δ_{2h}^j = (2Δ + Δ²)^j = Σ_k D_jk Δ^k,
// both truncated at k = n because Δ^{n+1} = 0. H has dyadic entries (denominators <= 256:
// row 1 is 1/2, -1/8, 1/16, -5/128, 7/256), D small integers (row 1: 2, 1). The parameter
// stays dyadic, t = k 2^-L, so a doubling is allowed when k is even and the walk lands on
// t = 1 exactly.
//
// Error control. Instead of a fixed re-seed interval the stepper carries a proven bound e_j
// of the error of every table entry and updates it with the table:
//   * seed: e_0 = 0, e_j = rounding of the seed (fixed: (n-j+1)/2 units of 2^-G raw; float:
//     u |Δ^j|), plus the sub-curve error of the exact seed (see forward_difference.hpp);
//   * step: e_j += e_{j+1} (fixed: the additions are exact; float: + u |new Δ^j|);
//   * halve / double: e'_j = Σ_k |H_jk| e_k (+ one rounding) or Σ_k |D_jk| e_k.
// Before a step would push the position's bound past the budget (2^-budget_bits of the
// output resolution, as in ForwardDifference) the table is re-seeded exactly at the new
// point. So error_bound() is a proof, not an estimate, whatever sequence of halvings and
// doublings the caller makes. Fixed point keeps G = 53 - bits(max|b|) fraction bits so that
// the transforms' products (|H_jk| 256 <= 128) cannot overflow (checked all the same: an
// overflow falls back to an exact re-seed). Levels run from L_min (h <= 1/(4n), so
// |Δ^k| <= |p| 2^-k) to 30.
//
// ISR budget: a step is n additions per axis plus n bound updates; a halving or doubling
// about n²/2 multiply-adds per axis; step_within() adds one chord length (a square root).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include <curvestep/core/contract.hpp>
#include <curvestep/core/curve/bezier.hpp>
#include <curvestep/core/result.hpp>
#include <curvestep/core/sampling/detail/difference_seed.hpp>

namespace curvestep {

namespace detail {
/// 256 × H_jk (halving transform), rows j = 1..5, columns k = 0..5.
inline constexpr std::array<std::array<std::int64_t, 6>, 6> halving_numerators{{
    {0, 0, 0, 0, 0, 0},
    {0, 128, -32, 16, -10, 7},
    {0, 0, 64, -32, 20, -14},
    {0, 0, 0, 32, -24, 18},
    {0, 0, 0, 0, 16, -16},
    {0, 0, 0, 0, 0, 8},
}};
/// D_jk (doubling transform), rows j = 1..5.
inline constexpr std::array<std::array<std::int64_t, 6>, 6> doubling_coefficients{{
    {0, 0, 0, 0, 0, 0},
    {0, 2, 1, 0, 0, 0},
    {0, 0, 4, 4, 1, 0},
    {0, 0, 0, 8, 12, 6},
    {0, 0, 0, 0, 16, 32},
    {0, 0, 0, 0, 0, 32},
}};
}  // namespace detail

/// Forward differencing of a Bézier of degree 1..MaxDegree on dyadic parameters t = k 2^-level,
/// with in-place step halving and doubling and a carried, proven error bound.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree = 5>
class AdaptiveForwardDifference {
  static_assert(MaxDegree >= 1 && MaxDegree <= 5, "forward differencing supports degrees 1 to 5");

 public:
  using scalar_type = S;                                 ///< coordinate type
  using Point = Vec<S, Dim>;                             ///< a point of the curve
  static constexpr std::size_t capacity = MaxDegree + 1; ///< difference-table entries per axis
  /// Finest level: h = 2^-30.
  static constexpr int max_level = 30;
  /// Default error budget, as ForwardDifference::default_budget_bits.
  static constexpr int default_budget_bits = FixedPoint<S> ? 4 : 1;

  /// An empty stepper.
  constexpr AdaptiveForwardDifference() = default;

  /// Starts at p(0) with step 2^-level (raised to the minimum level h <= 1/(4n) if smaller).
  /// DegreeTooLow, DegreeAboveCapacity, InvalidStep (level > 30), FixedOverflow.
  template <std::size_t CurveMaxDegree>
  [[nodiscard]] static Result<AdaptiveForwardDifference> create(const Bezier<S, Dim, CurveMaxDegree>& curve, int level,
                                                                int budget_bits = default_budget_bits) noexcept {
    const std::size_t n = curve.degree();
    if (n == 0) return fail(Error::DegreeTooLow, 0);
    if (n > MaxDegree) return fail(Error::DegreeAboveCapacity, n);
    if (level < 0 || level > max_level) return fail(Error::InvalidStep);
    if (budget_bits < 0 || budget_bits > 24) return fail(Error::InvalidArgument);
    AdaptiveForwardDifference stepper;
    stepper.degree_ = n;
    stepper.minimum_level_ = detail::bit_width(4 * n - 1);  // 2^L >= 4n
    stepper.level_ = level < stepper.minimum_level_ ? stepper.minimum_level_ : level;
    double largest = 0;
    if constexpr (FixedPoint<S>) {
      std::uint64_t magnitude = 1;
      for (std::size_t i = 0; i <= n; ++i) {
        for (std::size_t axis = 0; axis < Dim; ++axis) {
          const auto raw = static_cast<std::int64_t>(curve[i][axis].raw());
          const auto m = static_cast<std::uint64_t>(raw < 0 ? -raw : raw);
          if (m > magnitude) magnitude = m;
        }
      }
      const int bits = detail::bit_width(magnitude);
      stepper.extra_bits_ = 50 - bits - static_cast<int>(n) > 20 ? 20 : 50 - bits - static_cast<int>(n);
      stepper.fraction_bits_ = 53 - bits > 48 ? 48 : 53 - bits;
      if (stepper.extra_bits_ < 0 || stepper.fraction_bits_ < 8) return fail(Error::FixedOverflow);
      for (std::size_t i = 0; i <= n; ++i) {
        for (std::size_t axis = 0; axis < Dim; ++axis) {
          stepper.control_[axis][i] = static_cast<std::int64_t>(curve[i][axis].raw()) * (std::int64_t{1} << stepper.extra_bits_);
        }
      }
      stepper.budget_ = std::ldexp(1.0, stepper.fraction_bits_ - budget_bits);  // in units of 2^-G raw
    } else {
      for (std::size_t i = 0; i <= n; ++i) {
        for (std::size_t axis = 0; axis < Dim; ++axis) {
          stepper.control_[axis][i] = static_cast<double>(curve[i][axis]);
          largest = std::fmax(largest, std::fabs(stepper.control_[axis][i]));
        }
      }
      const double u = static_cast<double>(std::numeric_limits<S>::epsilon()) / 2;
      stepper.largest_ = largest;
      stepper.budget_ = std::ldexp(2 * u * (largest > 0 ? largest : 1.0), -budget_bits);  // curve units
    }
    stepper.reseed();
    return stepper;
  }

  /// The current point p(parameter()), within error_bound().
  [[nodiscard]] constexpr Point point() const noexcept {
    Point p;
    for (std::size_t axis = 0; axis < Dim; ++axis) {
      if constexpr (FixedPoint<S>) {
        p[axis] = S::from_raw(static_cast<typename S::rep>(detail::round_shift_right(table_[axis][0], fraction_bits_)));
      } else {
        p[axis] = origin_[axis] + table_[axis][0];
      }
    }
    return p;
  }

  /// The chord to the next point, p(t + h) - p(t) (the first difference).
  [[nodiscard]] constexpr Point next_chord() const noexcept {
    Point d;
    for (std::size_t axis = 0; axis < Dim; ++axis) {
      if constexpr (FixedPoint<S>) {
        d[axis] = S::from_raw(static_cast<typename S::rep>(detail::round_shift_right(table_[axis][1], fraction_bits_)));
      } else {
        d[axis] = table_[axis][1];
      }
    }
    return d;
  }

  /// Length of next_chord(), in double (no Fixed overflow of the squared norm).
  [[nodiscard]] double next_chord_length() const noexcept { return chord_length(1, 0); }

  /// Advances by the current step h. Contract: !finished().
  void step() noexcept {
    CURVESTEP_EXPECTS(!finished());
    ++index_;
    if (finished()) {
      land_on_end();
      return;
    }
    // The bound after this step; re-seed instead if it would leave the budget.
    std::array<double, capacity> next = error_;
    for (std::size_t j = 0; j < degree_; ++j) next[j] += error_[j + 1];
    if (next[0] > budget_) {
      reseed();
      return;
    }
    for (std::size_t axis = 0; axis < Dim; ++axis) {
      for (std::size_t j = 0; j < degree_; ++j) table_[axis][j] += table_[axis][j + 1];
    }
    if constexpr (!FixedPoint<S>) {
      const double u = static_cast<double>(std::numeric_limits<S>::epsilon()) / 2;
      for (std::size_t j = 0; j < degree_; ++j) next[j] += u * largest_difference(j);
    }
    error_ = next;
  }

  /// Halves the step in place (level + 1). False at max_level.
  bool halve() noexcept {
    if (level_ >= max_level) return false;
    ++level_;
    index_ *= 2;
    if (!transform(true)) reseed();
    return true;
  }

  /// Doubles the step in place (level - 1). False if the index is odd (not aligned with the
  /// coarser grid) or the level is already the minimum.
  bool double_step() noexcept {
    if (level_ <= minimum_level_ || index_ % 2 != 0) return false;
    --level_;
    index_ /= 2;
    if (!transform(false)) reseed();
    return true;
  }

  /// Halves while the next chord is longer than max_chord, doubles while it (and the doubled
  /// chord) allow, so that consecutive points stay max_chord apart at most and min_chord at
  /// least where the grid allows; then steps. Contract: !finished(), 0 <= min_chord <= max_chord.
  void step_within(double min_chord, double max_chord) noexcept {
    CURVESTEP_EXPECTS(!finished() && !(min_chord < 0) && !(max_chord < min_chord));
    double length = next_chord_length();
    while (length > max_chord && halve()) length = next_chord_length();
    while (length < min_chord && index_ % 2 == 0 && level_ > minimum_level_) {
      const double doubled = chord_length(2, 1);  // 2Δ¹ + Δ²
      if (doubled > max_chord) break;
      double_step();
      length = next_chord_length();
    }
    step();
  }

  /// True once point() is p(1).
  [[nodiscard]] constexpr bool finished() const noexcept { return index_ == (std::uint64_t{1} << level_); }
  /// The current parameter t = index 2^-level.
  [[nodiscard]] constexpr double parameter() const noexcept { return std::ldexp(static_cast<double>(index_), -level_); }
  /// The step level: h = 2^-level.
  [[nodiscard]] constexpr int level() const noexcept { return level_; }
  /// The coarsest level allowed (h <= 1/(4n)).
  [[nodiscard]] constexpr int minimum_level() const noexcept { return minimum_level_; }
  /// Steps from t = 0 at the current level (t = index 2^-level).
  [[nodiscard]] constexpr std::uint64_t index() const noexcept { return index_; }
  /// Exact re-seeds so far (the bound triggers them; also after an overflowing transform).
  [[nodiscard]] constexpr std::uint32_t reseeds() const noexcept { return reseeds_; }
  /// Proven bound of |point() - p(parameter())| per coordinate, in curve units.
  [[nodiscard]] double error_bound() const noexcept {
    if constexpr (FixedPoint<S>) {
      return (0.5 + static_cast<double>(degree_) * std::ldexp(1.0, -extra_bits_) + std::ldexp(error_[0], -fraction_bits_)) *
             to_double(resolution<S>());
    } else {
      const double u = static_cast<double>(std::numeric_limits<S>::epsilon()) / 2;
      const double double_u = std::numeric_limits<double>::epsilon() / 2;
      return error_[0] + 2 * u * largest_ + std::pow(3.0, static_cast<double>(degree_)) * 4.0 *
                                                static_cast<double>(degree_) * double_u * largest_;
    }
  }

 private:
  using Accumulator = std::conditional_t<FixedPoint<S>, std::int64_t, S>;
  using Control = std::conditional_t<FixedPoint<S>, std::int64_t, double>;

  [[nodiscard]] double value_of(std::size_t axis, std::size_t j) const noexcept {
    if constexpr (FixedPoint<S>) {
      return std::ldexp(static_cast<double>(table_[axis][j]), -fraction_bits_) * to_double(resolution<S>());
    } else {
      return static_cast<double>(table_[axis][j]);
    }
  }

  /// |a Δ¹ + b Δ²| in curve units.
  [[nodiscard]] double chord_length(int a, int b) const noexcept {
    double sum = 0;
    for (std::size_t axis = 0; axis < Dim; ++axis) {
      const double second = degree_ >= 2 ? value_of(axis, 2) : 0.0;
      const double c = a * value_of(axis, 1) + b * second;
      sum += c * c;
    }
    return std::sqrt(sum);
  }

  [[nodiscard]] double largest_difference(std::size_t j) const noexcept {
    double m = 0;
    for (std::size_t axis = 0; axis < Dim; ++axis) m = std::fmax(m, std::fabs(static_cast<double>(table_[axis][j])));
    return m;
  }

  /// Applies the halving or doubling transform to orders 1..n; false on a Fixed overflow.
  bool transform(bool halving) noexcept {
    const std::size_t n = degree_;
    std::array<double, capacity> previous_difference{};
    for (std::size_t k = 0; k <= n; ++k) previous_difference[k] = largest_difference(k);
    std::array<std::array<Accumulator, capacity>, Dim> result = table_;
    for (std::size_t axis = 0; axis < Dim; ++axis) {
      for (std::size_t j = 1; j <= n; ++j) {
        if constexpr (FixedPoint<S>) {
          std::int64_t sum = 0;
          for (std::size_t k = j; k <= n; ++k) {
            const std::int64_t c = halving ? detail::halving_numerators[j][k] : detail::doubling_coefficients[j][k];
            std::int64_t term = 0;
            if (__builtin_mul_overflow(table_[axis][k], c, &term) || __builtin_add_overflow(sum, term, &sum)) return false;
          }
          result[axis][j] = halving ? detail::round_shift_right(sum, 8) : sum;
        } else {
          double sum = 0;
          for (std::size_t k = j; k <= n; ++k) {
            const double c = halving ? static_cast<double>(detail::halving_numerators[j][k]) / 256.0
                                     : static_cast<double>(detail::doubling_coefficients[j][k]);
            sum += c * static_cast<double>(table_[axis][k]);
          }
          result[axis][j] = static_cast<S>(sum);
        }
      }
    }
    table_ = result;
    std::array<double, capacity> next = error_;
    for (std::size_t j = 1; j <= n; ++j) {
      double e = 0;
      for (std::size_t k = j; k <= n; ++k) {
        const double c = halving ? std::fabs(static_cast<double>(detail::halving_numerators[j][k])) / 256.0
                                 : static_cast<double>(detail::doubling_coefficients[j][k]);
        e += c * error_[k];
      }
      if constexpr (FixedPoint<S>) {
        next[j] = e + (halving ? 0.5 : 0.0);
      } else {
        // The double sum's own error, then the rounding to S.
        const double u = static_cast<double>(std::numeric_limits<S>::epsilon()) / 2;
        const double double_u = std::numeric_limits<double>::epsilon() / 2;
        double magnitude = 0;
        for (std::size_t k = j; k <= n; ++k) {
          const double c = halving ? std::fabs(static_cast<double>(detail::halving_numerators[j][k])) / 256.0
                                   : static_cast<double>(detail::doubling_coefficients[j][k]);
          magnitude += c * (previous_difference[k] + error_[k]);
        }
        next[j] = e + static_cast<double>(n + 1) * double_u * magnitude + u * largest_difference(j);
      }
    }
    error_ = next;
    return true;
  }

  /// The last step lands on t = 1: the end point exactly.
  void land_on_end() noexcept {
    const std::size_t n = degree_;
    for (std::size_t axis = 0; axis < Dim; ++axis) {
      table_[axis] = {};
      if constexpr (FixedPoint<S>) {
        table_[axis][0] = control_[axis][n] * (std::int64_t{1} << (fraction_bits_ - extra_bits_));
      } else {
        origin_[axis] = static_cast<S>(control_[axis][n]);
        table_[axis][0] = static_cast<S>(control_[axis][n] - static_cast<double>(origin_[axis]));
      }
    }
    error_ = {};
  }

  /// Seeds the table exactly at t = index 2^-level with step 2^-level.
  void reseed() noexcept {
    ++reseeds_;
    const std::size_t n = degree_;
    const std::uint64_t steps = std::uint64_t{1} << level_;
    std::uint64_t remaining = steps - index_;
    if (remaining > (std::uint64_t{1} << 16)) remaining = std::uint64_t{1} << 16;
    const int r = detail::floor_log2(remaining);
    const std::uint64_t chunk_end = index_ + (std::uint64_t{1} << r);
    error_ = {};
    for (std::size_t axis = 0; axis < Dim; ++axis) {
      if constexpr (FixedPoint<S>) {
        const auto sub = detail::integer_sub_curve(control_[axis], n, index_, chunk_end, steps);
        const auto a = detail::power_coefficients(sub, n);
        for (std::size_t j = 0; j <= n; ++j) {
          std::int64_t sum = 0;
          for (std::size_t i = j; i <= n; ++i) {
            const std::int64_t term = a[i] * detail::stirling_difference_weights[i][j];
            const int shift = extra_bits_ + r * static_cast<int>(i) - fraction_bits_;
            sum += shift > 0 ? detail::round_shift_right(term, shift) : static_cast<std::int64_t>(detail::shift_left_modular(term, -shift));
          }
          table_[axis][j] = sum;
          if (j > 0) error_[j] = 0.5 * static_cast<double>(n - j + 1);
        }
      } else {
        const auto sub = detail::floating_sub_curve(control_[axis], n, index_, chunk_end, steps);
        const auto a = detail::power_coefficients(sub, n);
        origin_[axis] = static_cast<S>(sub[0]);
        table_[axis][0] = static_cast<S>(sub[0] - static_cast<double>(origin_[axis]));
        const double step = std::ldexp(1.0, -r);
        for (std::size_t j = 1; j <= n; ++j) {
          double sum = 0;
          double power = 1;
          for (std::size_t i = 1; i <= n; ++i) {
            power *= step;
            if (i >= j) sum += a[i] * power * static_cast<double>(detail::stirling_difference_weights[i][j]);
          }
          table_[axis][j] = static_cast<S>(sum);
        }
      }
    }
    if constexpr (!FixedPoint<S>) {
      const double u = static_cast<double>(std::numeric_limits<S>::epsilon()) / 2;
      for (std::size_t j = 1; j <= n; ++j) error_[j] = u * largest_difference(j);
    }
  }

  std::array<std::array<Accumulator, capacity>, Dim> table_{};
  std::array<std::array<Control, capacity>, Dim> control_{};
  std::array<double, capacity> error_{};  ///< proven error of each table entry (fixed: units of 2^-G raw)
  Point origin_{};
  std::uint64_t index_ = 0;
  std::size_t degree_ = 0;
  int level_ = 0;
  int minimum_level_ = 0;
  int extra_bits_ = 0;
  int fraction_bits_ = 0;
  double budget_ = 0;
  double largest_ = 0;
  std::uint32_t reseeds_ = 0;
};

}  // namespace curvestep
