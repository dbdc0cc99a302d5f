// SPDX-License-Identifier: MIT
// MachineLimits: what the machine can do (velocity, acceleration, jerk, rate, tolerance, axes).
//
// Limits are planning data, held in double on every target: the planner uses only +, -, *, / and
// sqrt, which IEEE 754 rounds identically on x86-64 (SSE2) and on Cortex-M (soft or hard float),
// so a plan is bit-identical wherever it is computed (-ffp-contract=off keeps FMA out).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <curvestep/core/result.hpp>

namespace curvestep {

/// Number of machine axes the motion layer handles (x, y, z); 2-axis jobs leave z at 0.
inline constexpr std::size_t motion_axes = 3;

/// Limits of one axis. Zero means "not limited beyond the path limits".
struct AxisLimits {
  double steps_per_mm = 0;      ///< step/dir resolution (0: axis not driven by steps)
  double v_max_mm_per_s = 0;    ///< axis velocity limit (0: none)
  double a_max_mm_per_s2 = 0;   ///< axis acceleration limit (0: none)
};

/// Which MachineLimits field an InvalidLimit error names (the error's index).
enum class LimitField : std::uint8_t {
  VMax = 0, AMax = 1, JMax = 2, Feed = 3, Tolerance = 4, RateHz = 5, JunctionDeviation = 6, Rapid = 7,
  AxisStepsPerMm = 10, AxisVMax = 13, AxisAMax = 16,  ///< + axis index (0 x, 1 y, 2 z)
  MaxStepRate = 19,
};

/// The range a field must lie in (inclusive; `low` 0 also admits 0 for the fields that may be 0).
/// Beyond these no machine exists, and the arithmetic of planning stops being meaningful: a
/// v_max of 5e-324 mm/s would stream setpoints at the start point for ever, 1e308 squares to
/// infinity (issues 19.8, 21, 24).
struct LimitRange {
  double low;
  double high;
};
[[nodiscard]] constexpr LimitRange limit_range(LimitField field) noexcept {
  switch (field) {
    case LimitField::VMax: case LimitField::Feed: case LimitField::Rapid: case LimitField::AxisVMax: return {1e-3, 1e6};
    case LimitField::AMax: case LimitField::AxisAMax: return {1e-3, 1e9};
    case LimitField::JMax: return {1e-3, 1e12};
    case LimitField::Tolerance: return {1e-6, 100};
    case LimitField::JunctionDeviation: return {0, 100};
    case LimitField::MaxStepRate: return {1, 1e8};
    case LimitField::AxisStepsPerMm: return {0, 1e6};
    case LimitField::RateHz: return {100, 100000};
  }
  return {0, 0};
}

/// Machine configuration used by the planner, interpolator and step generator.
struct MachineLimits {
  double v_max_mm_per_s = 100;          ///< path speed limit
  double a_max_mm_per_s2 = 1000;        ///< acceleration limit (tangential and centripetal together)
  double j_max_mm_per_s3 = 10000;       ///< jerk limit along the path
  double feed_mm_per_s = 50;            ///< default feed for segments without their own
  double rapid_mm_per_s = 0;            ///< speed of rapid moves (0: v_max)
  double tolerance_mm = 0.01;           ///< chord / path tolerance
  double rate_hz = 1000;                ///< setpoint rate, 100 Hz .. 100 kHz
  double junction_deviation_mm = 0.05;  ///< corner rounding allowance (grbl's junction deviation)
  double max_step_rate_hz = 100000;     ///< fastest step pulse train an axis driver can follow
  bool jerk_limited = true;             ///< S-curve (true) or trapezoidal (false) speed profiles
  std::array<AxisLimits, motion_axes> axes{};  ///< x, y, z

  /// Checks every field: InvalidLimit (index = LimitField, + axis for the axis fields) for a
  /// non-finite value or one outside limit_range() (rapid, junction deviation and the axis fields
  /// may also be 0: not limited), InvalidRate for a rate outside 100 Hz .. 100 kHz.
  [[nodiscard]] constexpr Result<void> validate() const noexcept {
    const auto in_range = [](double v, LimitField field, bool zero_allowed) {
      const LimitRange r = limit_range(field);
      return std::isfinite(v) && ((zero_allowed && v == 0) || (v >= r.low && v <= r.high));
    };
    const auto check = [&](double v, LimitField field, bool zero_allowed, std::size_t offset = 0) -> Result<void> {
      if (!in_range(v, field, zero_allowed)) return fail(Error::InvalidLimit, static_cast<std::size_t>(field) + offset);
      return ok();
    };
    CURVESTEP_CHECK(check(v_max_mm_per_s, LimitField::VMax, false));
    CURVESTEP_CHECK(check(a_max_mm_per_s2, LimitField::AMax, false));
    CURVESTEP_CHECK(check(j_max_mm_per_s3, LimitField::JMax, false));
    CURVESTEP_CHECK(check(feed_mm_per_s, LimitField::Feed, false));
    CURVESTEP_CHECK(check(tolerance_mm, LimitField::Tolerance, false));
    if (!std::isfinite(rate_hz) || rate_hz < 100 || rate_hz > 100000) {
      return fail(Error::InvalidRate, static_cast<std::size_t>(LimitField::RateHz));
    }
    CURVESTEP_CHECK(check(junction_deviation_mm, LimitField::JunctionDeviation, true));
    CURVESTEP_CHECK(check(rapid_mm_per_s, LimitField::Rapid, true));
    CURVESTEP_CHECK(check(max_step_rate_hz, LimitField::MaxStepRate, false));
    for (std::size_t i = 0; i < motion_axes; ++i) {
      CURVESTEP_CHECK(check(axes[i].steps_per_mm, LimitField::AxisStepsPerMm, true, i));
      CURVESTEP_CHECK(check(axes[i].v_max_mm_per_s, LimitField::AxisVMax, true, i));
      CURVESTEP_CHECK(check(axes[i].a_max_mm_per_s2, LimitField::AxisAMax, true, i));
    }
    return ok();
  }
};

}  // namespace curvestep
