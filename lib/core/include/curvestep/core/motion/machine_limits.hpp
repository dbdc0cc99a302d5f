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

  /// Checks every field: InvalidLimit (index = LimitField) for non-positive or non-finite values
  /// (rapid, junction deviation and the axis fields may be 0),
  /// InvalidRate for a rate outside 100 Hz .. 100 kHz.
  [[nodiscard]] constexpr Result<void> validate() const noexcept {
    auto positive = [](double v) { return std::isfinite(v) && v > 0; };
    auto non_negative = [](double v) { return std::isfinite(v) && v >= 0; };
    if (!positive(v_max_mm_per_s)) return fail(Error::InvalidLimit, static_cast<std::size_t>(LimitField::VMax));
    if (!positive(a_max_mm_per_s2)) return fail(Error::InvalidLimit, static_cast<std::size_t>(LimitField::AMax));
    if (!positive(j_max_mm_per_s3)) return fail(Error::InvalidLimit, static_cast<std::size_t>(LimitField::JMax));
    if (!positive(feed_mm_per_s)) return fail(Error::InvalidLimit, static_cast<std::size_t>(LimitField::Feed));
    if (!positive(tolerance_mm)) return fail(Error::InvalidLimit, static_cast<std::size_t>(LimitField::Tolerance));
    if (!std::isfinite(rate_hz) || rate_hz < 100 || rate_hz > 100000) {
      return fail(Error::InvalidRate, static_cast<std::size_t>(LimitField::RateHz));
    }
    if (!non_negative(junction_deviation_mm)) {
      return fail(Error::InvalidLimit, static_cast<std::size_t>(LimitField::JunctionDeviation));
    }
    if (!non_negative(rapid_mm_per_s)) return fail(Error::InvalidLimit, static_cast<std::size_t>(LimitField::Rapid));
    if (!positive(max_step_rate_hz)) return fail(Error::InvalidLimit, static_cast<std::size_t>(LimitField::MaxStepRate));
    for (std::size_t i = 0; i < motion_axes; ++i) {
      if (!non_negative(axes[i].steps_per_mm)) {
        return fail(Error::InvalidLimit, static_cast<std::size_t>(LimitField::AxisStepsPerMm) + i);
      }
      if (!non_negative(axes[i].v_max_mm_per_s)) return fail(Error::InvalidLimit, static_cast<std::size_t>(LimitField::AxisVMax) + i);
      if (!non_negative(axes[i].a_max_mm_per_s2)) return fail(Error::InvalidLimit, static_cast<std::size_t>(LimitField::AxisAMax) + i);
    }
    return ok();
  }
};

}  // namespace curvestep
