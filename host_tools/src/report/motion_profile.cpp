// SPDX-License-Identifier: MIT
#include <algorithm>
#include <cmath>

#include <curvestep/host/position_differences.hpp>
#include <curvestep/host/report.hpp>

namespace curvestep::host {

MotionProfile motion_profile(const std::vector<SetpointRecord>& setpoints, const MachineLimits& machine, bool quantised) {
  const double dt = 1.0 / machine.rate_hz;
  MotionProfile profile;
  if (quantised) {
    // Rounding error of a Q16.16 point: at most half an LSB per coordinate.
    const double e = std::sqrt(3.0) * std::ldexp(1.0, -17);
    constexpr std::size_t max_stride = 64;
    while (profile.stride < max_stride) {
      const double h = static_cast<double>(profile.stride) * dt;
      const bool acceleration_quiet = 4 * e / (h * h) <= 0.01 * machine.a_max_mm_per_s2;
      const bool jerk_quiet = !machine.jerk_limited || 8 * e / (h * h * h) <= 0.01 * machine.j_max_mm_per_s3;
      if (acceleration_quiet && jerk_quiet) break;
      ++profile.stride;
    }
  }
  const std::size_t k = profile.stride;
  const double h = static_cast<double>(k) * dt;
  const std::size_t n = setpoints.size();
  const PositionDifferences d = position_differences(n, [&](std::size_t i) { return setpoints[i].position_mm; }, k);
  profile.time_s.resize(n);
  profile.speed_mm_per_s.resize(n);
  profile.acceleration_mm_per_s2.resize(n);
  profile.jerk_mm_per_s3.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    profile.time_s[i] = setpoints[i].time_s;
    profile.speed_mm_per_s[i] = setpoints[i].speed_mm_per_s;
    profile.acceleration_mm_per_s2[i] = d.second[i] / (h * h);
    profile.jerk_mm_per_s3[i] = d.third[i] / (h * h * h);
  }
  return profile;
}

}  // namespace curvestep::host
