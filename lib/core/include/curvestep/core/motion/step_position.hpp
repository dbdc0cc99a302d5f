// SPDX-License-Identifier: MIT
// StepScale and position_in_steps: millimetres to motor steps with one exact, documented rounding.
//
// Why this file exists
// --------------------
// "After any job the step count on each axis equals the end position in steps" only means
// something if "the position in steps" has one definition that the host simulator, every board
// and the tests share. It is
//
//     steps(p) = round_half_away_from_zero(p_mm * steps_per_mm)
//
// computed as follows.
//
// * steps_per_mm is quantised ONCE, when the machine is configured, to an unsigned 32.32 integer
//   (StepScale::raw() = round(steps_per_mm * 2^32)). Values with at most 32 binary fraction digits
//   (80, 200, 78.125, 0.5 ...) are exact; others, such as 2000/25.4, carry an error below 2^-33
//   steps per millimetre, i.e. below 4e-6 steps over the whole 32 m range of Q16.16. The scale is
//   limited to 2^20 steps/mm so that it is also exact as a double.
//
// * Fixed-point positions (Q16.16 and any Fixed with 16..31 fraction bits) are converted with
//   integers only: |raw| * scale is a 63 x 52 bit product that the code forms from two 32 x 32
//   multiplications (one UMULL each on Cortex-M), so it is EXACT. The result is the exact rational
//   raw * scale / 2^(F+32) rounded half away from zero: bit-identical on every target.
//   Example: 80 steps/mm and a Q16.16 position give round(raw * 80 / 65536) exactly.
//
// * float and double positions are widened to double, multiplied once by the quantised scale
//   (one IEEE rounding, the same on x86-64 SSE2 and on soft/hard-float Cortex-M) and then rounded
//   half away from zero. The count is therefore exact unless p * steps_per_mm lies within one
//   double ulp (2^-52 relative) of a half step.
//
// Fine positions. The step generator also needs where a position lies BETWEEN two steps, to place
// the step edges inside a tick (see step_generator.hpp). The conversion therefore first produces a
// fine position u in 1/65536 step, truncated toward zero in magnitude, and the count is
// round_half_away(u / 65536). Truncating the magnitude keeps the rounding exact: for any x and
// F >= 1, |x| >= k + 1/2 exactly when floor(|x| * 2^F) >= (k + 1/2) * 2^F, so the double rounding
// x -> u -> count gives the same count as rounding x directly.
//
// Range. Counts are int32 on every target. |count| <= 2^31 - 1; a position further out is
// StepCountOverflow, never a wrapped count. NaN or infinity is NotFinite.
//
// Cost (Cortex-M3, 72 MHz): a Q16.16 conversion is two UMULL, one add and a few shifts, about 15
// cycles; a float conversion is one software double multiply, about 80 to 120 cycles.
#pragma once

#include <cstddef>
#include <cstdint>

#include <curvestep/core/result.hpp>
#include <curvestep/core/scalar.hpp>

namespace curvestep {

/// Largest steps_per_mm a StepScale accepts (2^20): the quantised scale stays exact as a double.
inline constexpr double max_steps_per_mm = 1048576.0;

/// Largest magnitude of a step count (2^31 - 1): counts are int32 on every target.
inline constexpr std::int32_t max_step_count = 2147483647;

/// Fraction bits of a fine step position (fine positions count 1/65536 step).
inline constexpr int fine_step_bits = 16;

/// One step in fine-position units (2^16).
inline constexpr std::int64_t fine_steps_per_step = std::int64_t{1} << fine_step_bits;

/// Steps per millimetre of one axis, quantised once to an unsigned 32.32 integer.
/// A default StepScale is zero: the axis is not driven by steps and never moves.
class StepScale {
 public:
  /// Zero steps per millimetre.
  constexpr StepScale() noexcept = default;

  /// round(steps_per_mm * 2^32), half away from zero. InvalidLimit for a negative, non-finite or
  /// larger than max_steps_per_mm value.
  [[nodiscard]] static constexpr Result<StepScale> create(double steps_per_mm) noexcept {
    if (!(steps_per_mm >= 0.0) || !(steps_per_mm <= max_steps_per_mm)) return fail(Error::InvalidLimit);
    const double scaled = steps_per_mm * 4294967296.0;  // exact: a power of two
    StepScale scale;
    scale.raw_ = static_cast<std::uint64_t>(scaled + 0.5);  // < 2^52 + 1/2, so the sum is exact
    return scale;
  }

  /// The quantised scale as an unsigned 32.32 integer (steps per millimetre * 2^32).
  [[nodiscard]] constexpr std::uint64_t raw() const noexcept { return raw_; }

  /// The quantised scale in steps per millimetre (exact: raw() < 2^53).
  [[nodiscard]] constexpr double steps_per_mm() const noexcept {
    return static_cast<double>(raw_) / 4294967296.0;
  }

  /// True if the axis is not driven by steps.
  [[nodiscard]] constexpr bool is_zero() const noexcept { return raw_ == 0; }

  /// Same quantised scale.
  friend constexpr bool operator==(StepScale, StepScale) noexcept = default;

 private:
  std::uint64_t raw_ = 0;
};

/// A position in 1/65536 step, truncated toward zero in magnitude (see the essay above).
/// StepCountOverflow if the step count would exceed max_step_count, NotFinite for NaN/inf.
template <Scalar S>
[[nodiscard]] constexpr Result<std::int64_t> fine_step_position(S position_mm, StepScale scale) noexcept {
  // |count| <= 2^31 - 1  <=>  |u| < (2^31 - 1/2) * 2^16.
  constexpr std::uint64_t limit = (std::uint64_t{1} << 47) - (std::uint64_t{1} << 15);
  bool negative = false;
  std::uint64_t magnitude_fine = 0;
  if constexpr (FixedPoint<S>) {
    static_assert(S::fraction_bits >= fine_step_bits && S::fraction_bits <= 31 && sizeof(typename S::rep) <= 4,
                  "fine_step_position needs a Fixed with 16..31 fraction bits in at most 32 bits");
    const auto raw = static_cast<std::int64_t>(position_mm.raw());
    negative = raw < 0;
    const auto magnitude = static_cast<std::uint64_t>(negative ? -raw : raw);  // <= 2^31
    const std::uint64_t high = scale.raw() >> 32;           // < 2^21
    const std::uint64_t low = scale.raw() & 0xFFFFFFFFu;    // < 2^32
    // floor(|raw| * scale / 2^32), exactly: magnitude * high < 2^52, magnitude * low < 2^63.
    const std::uint64_t product = magnitude * high + ((magnitude * low) >> 32);
    magnitude_fine = product >> (S::fraction_bits - fine_step_bits);
  } else {
    const double value = static_cast<double>(position_mm);
    if (!is_finite(value)) return fail(Error::NotFinite);
    // One multiplication by steps_per_mm * 2^16: the same double as round(value * steps_per_mm)
    // * 2^16, because scaling by a power of two is exact. The one rounding of the float path.
    const double fine = value * (static_cast<double>(scale.raw()) / 65536.0);
    negative = fine < 0.0;
    const double magnitude = negative ? -fine : fine;
    if (!(magnitude < static_cast<double>(limit))) return fail(Error::StepCountOverflow);
    magnitude_fine = static_cast<std::uint64_t>(magnitude);  // truncates toward zero
  }
  if (magnitude_fine >= limit) return fail(Error::StepCountOverflow);
  const auto signed_fine = static_cast<std::int64_t>(magnitude_fine);
  return negative ? -signed_fine : signed_fine;
}

/// The step count of a fine position: round(u / 65536), half away from zero. |u| must be below
/// 2^47 - 2^15 (every fine_step_position result is).
[[nodiscard]] constexpr std::int32_t steps_of_fine_position(std::int64_t fine) noexcept {
  const bool negative = fine < 0;
  const auto magnitude = static_cast<std::uint64_t>(negative ? -fine : fine);
  const auto count = static_cast<std::int32_t>((magnitude + (std::uint64_t{1} << (fine_step_bits - 1))) >> fine_step_bits);
  return negative ? -count : count;
}

/// The position in whole steps: round(position_mm * steps_per_mm), half away from zero.
/// StepCountOverflow beyond max_step_count, NotFinite for NaN/inf.
template <Scalar S>
[[nodiscard]] constexpr Result<std::int32_t> position_in_steps(S position_mm, StepScale scale) noexcept {
  CURVESTEP_TRY(const std::int64_t fine, fine_step_position(position_mm, scale));
  return steps_of_fine_position(fine);
}

}  // namespace curvestep
