// SPDX-License-Identifier: MIT
// ForwardDifference: steps a Bézier segment of degree 1..5 at h = 1/N with additions only, within a proven bound.
//
// Why. A polynomial of degree n sampled at t_k = k h has an (n+1)-entry difference table
// (p, Δp, Δ²p, ..., Δⁿp) with Δⁿp constant, so the next sample costs n additions per axis:
//     p += Δ¹;  Δ¹ += Δ²;  ...;  Δⁿ⁻¹ += Δⁿ.
// Done naively in the output format the roundings of the seed and of every addition pile up
// (a rounding of Δʲ grows like C(k,j) after k steps). Here the error is bounded by design:
//
// Chunks and re-seeding. The N steps are cut into chunks of K = 2^r steps (the re-seed interval,
// smaller near the end so that chunks never pass t = 1). At each chunk start k0 the table is
// re-seeded from an exact de Casteljau computation: the sub-curve on [k0/N, (k0+K)/N] (two
// splits, integer ratios k/N) and its power coefficients a_i; in the sub-curve's own parameter
// the step is 2^-r, so Δʲ(0) = Σ_{i>=j} a_i j! S(i,j) 2^{-r i} needs only shifts (see
// detail/difference_seed.hpp).
//
// Fixed point (Fixed<int32, F>, e.g. Q16.16). All arithmetic is on int64 integers:
//   * control points carry E extra fraction bits (E = min(20, 50 - bits(max|b|) - n));
//     each of the 2n lerp levels of the split rounds by <= 2^-E-1 raw, and lerps with t in
//     [0,1] do not amplify earlier errors: the sub-curve is within n 2^-E raw of the true one;
//   * the table holds every order in units of 2^-G raw, G = min(48, 62 - bits(max|b|)), so the
//     additions in step() are exact integer additions. The seed rounds each of the n-j+1 terms
//     of Δʲ once: |ε_j| <= (n-j+1)/2 units; Δ⁰ = c_0 is exact;
//   * the stepped table is the exact difference table of the rounded seed, so after k steps
//     the position is off by Σ_j C(k,j) ε_j <= 2^-G-1 Σ_{j>=1} (n-j+1) C(K,j) raw;
//   * K is the largest power of two (<= 2^20 and <= N) for which that sum is <= 1/16 raw;
//   * point() rounds the accumulator to nearest: <= 1/2 raw.
//   Total: |point() - p(k/N)| <= 1/2 + n 2^-E + 1/16 raw  (< 0.6 raw: 9 nm in Q16.16), at
//   every step, for any N < 2^32. Only the position must fit in int64 (|p| 2^G < 2^62): the
//   higher differences may wrap during the last steps of a chunk (they sample beyond it) and
//   the additions are done modulo 2^64 on purpose, which keeps the position exact.
//   Exactness: when N is a power of two and the samples are representable (TV-10 of
//   seeds_000_002_003.md, TV-08 of seed_001.md) every seed term is exact and so is every point.
//
// Floating point (float, double). The seed is computed in double; the position is kept as
// origin + offset (origin = the chunk's first point rounded to S, offset accumulates the
// steps), so the additions round relative to the small offset, not to the coordinates. With
// u = epsilon(S)/2, D_j >= |Δʲ| over a chunk (from the hodographs' control points) and
// D_0 = K D_1 the offset's size, the accumulated error after k <= K steps is at most
//     u [ Σ_{j>=1} C(K,j) D_j   (seed roundings)  +  Σ_{j<n} C(K,j+1) D_j   (additions) ]
// and K is the largest power of two for which this is <= 1/2 ulp of the largest coordinate
// (the same policy as fixed point: stepping error <= 2^-budget_bits of the output resolution;
// the default budget is 1/2 for floats, 1/16 for fixed point). The output origin + offset adds
// one rounding u|p|, the double seed 3^n 4n u_double max|b|: in all about 1 ulp.
//
// ISR budget. step() is n additions per axis plus one compare; point() one rounding shift per
// axis (for G >= 32, i.e. coordinates within ±2^30 raw, a 64-bit addition and a 32-bit shift of
// the high word: high_rounded()); a re-seed (every K steps) about 4n² multiply-divides per axis. A 3-axis cubic in
// Q16.16 on a Cortex-M3 at 72 MHz: 9 64-bit additions and 3 shifts, estimated at ~40 cycles
// per step plus ~1 cycle of amortised re-seed, far inside a 100 kHz tick (720 cycles). On the
// host it is 68 instructions per 3-axis point against 703 for Q16.16 de Casteljau (callgrind,
// benchmarks/run_callgrind.sh; figures in docs/forward_differencing.md).
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

/// Fixed-step evaluator of one Bézier segment of degree 1..MaxDegree (<= 5) in Dim dimensions:
/// point() is p(index()/steps()) within error_bound(), step() advances by h = 1/steps().
template <Scalar S, std::size_t Dim, std::size_t MaxDegree = 5>
class ForwardDifference {
  static_assert(MaxDegree >= 1 && MaxDegree <= 5, "forward differencing supports degrees 1 to 5");

 public:
  using scalar_type = S;                                 ///< coordinate type
  using Point = Vec<S, Dim>;                             ///< a point of the curve
  static constexpr std::size_t dimension = Dim;          ///< coordinates per point
  static constexpr std::size_t max_degree = MaxDegree;   ///< highest degree accepted (<= 5)
  static constexpr std::size_t capacity = MaxDegree + 1; ///< difference-table entries per axis
  /// Upper limit of the re-seed interval (steps between exact re-seeds).
  static constexpr std::uint32_t max_reseed_interval = std::uint32_t{1} << 20;
  /// The stepping error budget is 2^-budget_bits of the output resolution (one raw unit in
  /// fixed point, one ulp of the largest coordinate in floating point). Default 1/16 raw for
  /// fixed point (its re-seeds are nearly free) and 1/2 ulp for floating point (where a
  /// re-seed costs about 40 steps' work, so a tighter budget would cost ~10% speed).
  static constexpr int default_budget_bits = FixedPoint<S> ? 4 : 1;

  /// An empty stepper (finished, at the origin).
  constexpr ForwardDifference() = default;

  /// Steps `curve` in `steps` equal parameter steps (h = 1/steps), starting at p(0).
  /// DegreeTooLow (degree 0), DegreeAboveCapacity, InvalidStep (steps == 0).
  /// `budget_bits` sets the stepping budget (see default_budget_bits); InvalidArgument outside 0..24.
  template <std::size_t CurveMaxDegree>
  [[nodiscard]] static Result<ForwardDifference> create(const Bezier<S, Dim, CurveMaxDegree>& curve,
                                                                  std::uint32_t steps,
                                                                  int budget_bits = default_budget_bits) noexcept {
    const std::size_t n = curve.degree();
    if (n == 0) return fail(Error::DegreeTooLow, 0);
    if (n > MaxDegree) return fail(Error::DegreeAboveCapacity, n);
    if (steps == 0) return fail(Error::InvalidStep);
    if (budget_bits < 0 || budget_bits > 24) return fail(Error::InvalidArgument);
    ForwardDifference stepper;
    stepper.degree_ = n;
    stepper.steps_ = steps;
    if constexpr (FixedPoint<S>) {
      std::uint64_t largest = 1;
      for (std::size_t i = 0; i <= n; ++i) {
        for (std::size_t axis = 0; axis < Dim; ++axis) {
          const auto raw = static_cast<std::int64_t>(curve[i][axis].raw());
          const auto magnitude = static_cast<std::uint64_t>(raw < 0 ? -raw : raw);
          if (magnitude > largest) largest = magnitude;
        }
      }
      const int magnitude_bits = detail::bit_width(largest);
      int extra = 50 - magnitude_bits - static_cast<int>(n);
      if (extra > 20) extra = 20;
      if (extra < 0) return fail(Error::FixedOverflow);
      int fraction = 62 - magnitude_bits;
      if (fraction > 48) fraction = 48;
      stepper.extra_bits_ = extra;
      stepper.fraction_bits_ = fraction;
      stepper.half_ = fraction >= 1 ? std::int64_t{1} << (fraction - 1) : 0;
      for (std::size_t i = 0; i <= n; ++i) {
        for (std::size_t axis = 0; axis < Dim; ++axis) {
          stepper.control_[axis][i] = static_cast<std::int64_t>(curve[i][axis].raw()) * (std::int64_t{1} << extra);
        }
      }
      // Largest K = 2^r with 2^-G-1 Σ_{j>=1} (n-j+1) C(K,j) <= 2^-budget raw.
      const std::uint64_t limit = fraction - budget_bits + 1 >= 63
                                      ? std::numeric_limits<std::uint64_t>::max()
                                      : (fraction - budget_bits + 1 <= 0 ? 0 : std::uint64_t{1} << (fraction - budget_bits + 1));
      std::uint32_t interval = 1;
      while (interval < max_reseed_interval && interval < steps &&
             fixed_stepping_sum(2 * static_cast<std::uint64_t>(interval), n) <= limit) {
        interval *= 2;
      }
      stepper.reseed_interval_ = interval;
      stepper.bound_ = (0.5 + static_cast<double>(n) * std::ldexp(1.0, -extra) +
                        static_cast<double>(fixed_stepping_sum(interval, n)) * std::ldexp(1.0, -fraction - 1)) *
                       to_double(resolution<S>());
    } else {
      for (std::size_t i = 0; i <= n; ++i) {
        for (std::size_t axis = 0; axis < Dim; ++axis) stepper.control_[axis][i] = static_cast<double>(curve[i][axis]);
      }
      stepper.choose_floating_interval(budget_bits);
    }
    stepper.reseed(0);
    return stepper;
  }

  /// As create(curve, steps) with steps = 1/step; InvalidStep unless 1/step is an integer
  /// (within the scalar's resolution) between 1 and 2^32 - 1.
  template <std::size_t CurveMaxDegree>
  [[nodiscard]] static Result<ForwardDifference> create_with_step(const Bezier<S, Dim, CurveMaxDegree>& curve,
                                                                  S step) noexcept {
    if (!(S{} < step) || from_int<S>(1) < step) return fail(Error::InvalidStep);
    const double h = to_double(step);
    const double rounded = std::floor(1.0 / h + 0.5);
    if (rounded < 1.0 || rounded > 4294967295.0) return fail(Error::InvalidStep);
    // step must be 1/N as closely as S can hold it: half a raw unit (Fixed) or one ulp (float).
    const double allowed = FixedPoint<S> ? to_double(resolution<S>()) / 2 : to_double(resolution<S>()) * h;
    if (std::fabs(h - 1.0 / rounded) > allowed) return fail(Error::InvalidStep);
    return create(curve, static_cast<std::uint32_t>(rounded));
  }

  /// The current point p(index()/steps()), within error_bound() per coordinate.
  [[nodiscard, gnu::always_inline]] constexpr Point point() const noexcept {
    Point p;
    if constexpr (FixedPoint<S>) {
      if (fraction_bits_ >= 32) {  // every curve within ±2^30 raw (Q16.16: ±16384 mm): the cheap rounding
#pragma GCC unroll 4
        for (std::size_t axis = 0; axis < Dim; ++axis) p[axis] = S::from_raw(static_cast<typename S::rep>(high_rounded(axis)));
        return p;
      }
    }
#pragma GCC unroll 4
    for (std::size_t axis = 0; axis < Dim; ++axis) p[axis] = coordinate(axis);
    return p;
  }

  /// One coordinate of point().
  [[nodiscard]] constexpr S coordinate(std::size_t axis) const noexcept {
    if constexpr (FixedPoint<S>) {
      if (fraction_bits_ >= 32) return S::from_raw(static_cast<typename S::rep>(high_rounded(axis)));
      const auto wide = static_cast<std::int64_t>(table_[axis][0]);
      return S::from_raw(static_cast<typename S::rep>(detail::round_shift_right(wide, fraction_bits_)));
    } else {
      return origin_[axis] + table_[axis][0];
    }
  }

  /// Advances to the next point (t += h); re-seeds at chunk ends. Contract: !finished().
  void step() noexcept {
    CURVESTEP_EXPECTS(index_ < steps_);
    ++index_;
    if (index_ == chunk_end_) {
      reseed(index_);
      return;
    }
    if (degree_ == 3) {  // the fast path: three additions per axis
#pragma GCC unroll 4
      for (std::size_t axis = 0; axis < Dim; ++axis) {
        auto& d = table_[axis];
        d[0] += d[1];
        d[1] += d[2];
        d[2] += d[3];
      }
      return;
    }
    for (std::size_t axis = 0; axis < Dim; ++axis) {
      auto& d = table_[axis];
      for (std::size_t j = 0; j < degree_; ++j) d[j] += d[j + 1];
    }
  }

  /// True once point() is p(1).
  [[nodiscard]] constexpr bool finished() const noexcept { return index_ == steps_; }
  /// Steps taken so far (point() is p(index()/steps())).
  [[nodiscard]] constexpr std::uint32_t index() const noexcept { return index_; }
  /// N, the number of steps from p(0) to p(1).
  [[nodiscard]] constexpr std::uint32_t steps() const noexcept { return steps_; }
  /// The curve's degree.
  [[nodiscard]] constexpr std::size_t degree() const noexcept { return degree_; }
  /// Steps between exact re-seeds (a power of two; chosen from the documented bound).
  [[nodiscard]] constexpr std::uint32_t reseed_interval() const noexcept { return reseed_interval_; }
  /// Proven bound of |point() - p(index()/steps())| per coordinate, in curve units.
  [[nodiscard]] constexpr double error_bound() const noexcept { return bound_; }

  /// Fixed point: the position accumulator of `axis` in units of 2^-wide_fraction_bits() raw.
  [[nodiscard]] constexpr std::int64_t wide_coordinate(std::size_t axis) const noexcept
    requires FixedPoint<S>
  {
    return static_cast<std::int64_t>(table_[axis][0]);
  }
  /// Fixed point: fraction bits of the accumulators beyond the raw unit (G).
  [[nodiscard]] constexpr int wide_fraction_bits() const noexcept
    requires FixedPoint<S>
  {
    return fraction_bits_;
  }

 private:
  using Accumulator = std::conditional_t<FixedPoint<S>, std::uint64_t, S>;
  using Control = std::conditional_t<FixedPoint<S>, std::int64_t, double>;

  /// round_shift_right(accumulator, G) for G >= 32, with one 64-bit addition and a 32-bit shift
  /// instead of a 64-bit shift by a run-time amount (about 20 Thumb-2 instructions per axis on a
  /// Cortex-M3). With v the accumulator, c = 2^(G-1) (v >= 0) or 2^(G-1) - 1 (v < 0) and s = G - 32:
  /// floor((v + c) / 2^G) = floor(floor((v + c) / 2^32) / 2^s), the same value; |v + c| < 2^62 + 2^47
  /// (the accumulator bound of create()), so the high word fits 32 bits.
  [[nodiscard, gnu::always_inline]] constexpr std::int32_t high_rounded(std::size_t axis) const noexcept
    requires FixedPoint<S>
  {
    const auto wide = static_cast<std::int64_t>(table_[axis][0]);
    const std::int64_t rounded = wide + (half_ + (wide >> 63));  // wide >> 63: -1 if negative, else 0
    return static_cast<std::int32_t>(rounded >> 32) >> (fraction_bits_ - 32);
  }

  /// Σ_{j=1..n} (n-j+1) C(K,j), saturating at 2^64-1.
  static constexpr std::uint64_t fixed_stepping_sum(std::uint64_t interval, std::size_t n) noexcept {
    constexpr std::uint64_t saturated = std::numeric_limits<std::uint64_t>::max();
    std::uint64_t sum = 0;
    std::uint64_t c = 1;  // C(K, j)
    for (std::size_t j = 1; j <= n; ++j) {
      if (interval < j) break;
      const std::uint64_t factor = interval - j + 1;
      if (c > saturated / factor) return saturated;
      c = c * factor / j;  // exact: C(K,j-1)(K-j+1) is divisible by j
      const std::uint64_t weight = n - j + 1;
      if (c > (saturated - sum) / weight) return saturated;
      sum += weight * c;
    }
    return sum;
  }

  /// Floating point: choose K from the bound in the essay; also sets bound_.
  void choose_floating_interval(int budget_bits) noexcept {
    const std::size_t n = degree_;
    const double u = static_cast<double>(std::numeric_limits<S>::epsilon()) / 2;
    const double h = 1.0 / static_cast<double>(steps_);
    double largest = 0;
    for (std::size_t axis = 0; axis < Dim; ++axis) {
      for (std::size_t i = 0; i <= n; ++i) largest = std::fmax(largest, std::fabs(control_[axis][i]));
    }
    // D_j = (1 + 2n h)^n h^j n!/(n-j)! max|Δʲ b_i|: bounds |Δʲ| also for samples just past t = 1.
    const double growth = std::pow(1.0 + 2.0 * static_cast<double>(n) * h, static_cast<double>(n));
    std::array<double, capacity + 1> bound_of_difference{};
    for (std::size_t j = 1; j <= n; ++j) {
      double m = 0;
      for (std::size_t axis = 0; axis < Dim; ++axis) {
        std::array<double, capacity> d{};
        for (std::size_t i = 0; i <= n; ++i) d[i] = control_[axis][i];
        for (std::size_t level = 1; level <= j; ++level) {
          for (std::size_t i = 0; i + level <= n; ++i) d[i] = d[i + 1] - d[i];
        }
        for (std::size_t i = 0; i + j <= n; ++i) m = std::fmax(m, std::fabs(d[i]));
      }
      double falling = 1;
      for (std::size_t k = 0; k < j; ++k) falling *= static_cast<double>(n - k);
      bound_of_difference[j] = 1.0001 * growth * std::pow(h, static_cast<double>(j)) * falling * m;
    }
    const double output_ulp = 2 * u * (largest > 0 ? largest * growth : 1.0);
    const auto stepping = [&](double interval) {
      double total = 0;
      double c = 1;  // C(K, j)
      const double offset = interval * bound_of_difference[1];
      for (std::size_t j = 0; j <= n; ++j) {
        if (j > 0) c = c * (interval - static_cast<double>(j) + 1) / static_cast<double>(j);
        const double next = c * (interval - static_cast<double>(j)) / static_cast<double>(j + 1);  // C(K, j+1)
        if (j >= 1) total += c * bound_of_difference[j];
        if (j < n) total += next * (j == 0 ? offset : bound_of_difference[j]);
      }
      return u * total;
    };
    std::uint32_t interval = 1;
    while (interval < max_reseed_interval && interval < steps_ &&
           stepping(2.0 * static_cast<double>(interval)) <= std::ldexp(output_ulp, -budget_bits)) {
      interval *= 2;
    }
    reseed_interval_ = interval;
    const double double_u = std::numeric_limits<double>::epsilon() / 2;
    bound_ = output_ulp / 2 + stepping(static_cast<double>(interval)) +
             std::pow(3.0, static_cast<double>(n)) * 4.0 * static_cast<double>(n) * double_u * largest;
  }

  /// Seeds the table for the chunk starting at step k0.
  void reseed(std::uint32_t k0) noexcept {
    const std::size_t n = degree_;
    if (k0 == steps_) {
      chunk_end_ = steps_;
      for (std::size_t axis = 0; axis < Dim; ++axis) {
        table_[axis] = {};
        if constexpr (FixedPoint<S>) {
          table_[axis][0] = detail::shift_left_modular(control_[axis][n], fraction_bits_ - extra_bits_);
        } else {
          origin_[axis] = static_cast<S>(control_[axis][n]);
          table_[axis][0] = static_cast<S>(control_[axis][n] - static_cast<double>(origin_[axis]));
        }
      }
      return;
    }
    std::uint32_t remaining = steps_ - k0;
    if (remaining > reseed_interval_) remaining = reseed_interval_;
    const int r = detail::floor_log2(remaining);
    const std::uint32_t chunk = std::uint32_t{1} << r;
    chunk_end_ = k0 + chunk;
    for (std::size_t axis = 0; axis < Dim; ++axis) {
      if constexpr (FixedPoint<S>) {
        const auto sub = detail::integer_sub_curve(control_[axis], n, k0, chunk_end_, steps_);
        const auto a = detail::power_coefficients(sub, n);
        for (std::size_t j = 0; j <= n; ++j) {
          std::uint64_t sum = 0;
          for (std::size_t i = j; i <= n; ++i) {
            const std::int64_t term = a[i] * detail::stirling_difference_weights[i][j];
            const int shift = extra_bits_ + r * static_cast<int>(i) - fraction_bits_;
            sum += shift > 0 ? static_cast<std::uint64_t>(detail::round_shift_right(term, shift))
                             : detail::shift_left_modular(term, -shift);
          }
          table_[axis][j] = sum;
        }
      } else {
        const auto sub = detail::floating_sub_curve(control_[axis], n, k0, chunk_end_, steps_);
        const auto a = detail::power_coefficients(sub, n);
        origin_[axis] = static_cast<S>(sub[0]);
        table_[axis][0] = static_cast<S>(sub[0] - static_cast<double>(origin_[axis]));  // origin's rounding
        std::array<double, capacity> scaled{};  // a_i / K^i: exact, K is a power of two
        double step_power = 1;
        const double step = 1.0 / static_cast<double>(chunk);
        for (std::size_t i = 1; i <= n; ++i) {
          step_power *= step;
          scaled[i] = a[i] * step_power;
        }
        for (std::size_t j = 1; j <= n; ++j) {
          double sum = 0;
          for (std::size_t i = j; i <= n; ++i) sum += scaled[i] * static_cast<double>(detail::stirling_difference_weights[i][j]);
          table_[axis][j] = static_cast<S>(sum);
        }
      }
    }
  }

  std::array<std::array<Accumulator, capacity>, Dim> table_{};  ///< per axis: Δ⁰..Δⁿ
  std::array<std::array<Control, capacity>, Dim> control_{};    ///< control points (scaled ints or doubles)
  Point origin_{};                                              ///< floating point: chunk origin
  std::uint32_t steps_ = 0;
  std::uint32_t index_ = 0;
  std::uint32_t chunk_end_ = 0;
  std::uint32_t reseed_interval_ = 1;
  std::size_t degree_ = 0;
  int extra_bits_ = 0;     ///< E
  int fraction_bits_ = 0;  ///< G
  std::int64_t half_ = 0;  ///< fixed point: 2^(G-1), the rounding addend of point()
  double bound_ = 0;
};

}  // namespace curvestep
