// SPDX-License-Identifier: MIT
#include <algorithm>
#include <cmath>

#include <curvestep/host/position_differences.hpp>
#include <curvestep/host/report.hpp>

#include "running_profile.hpp"

namespace curvestep::host {
namespace report_detail {
namespace {

/// The smallest stride (at most 64) that keeps the Q16.16 rounding's share of acceleration and jerk
/// below 1% of the limits; 1 for exact positions.
std::size_t profile_stride(const MachineLimits& machine, bool quantised) {
  std::size_t stride = 1;
  if (!quantised) return stride;
  const double dt = 1.0 / machine.rate_hz;
  // Rounding error of a Q16.16 point: at most half an LSB per coordinate.
  const double e = std::sqrt(3.0) * std::ldexp(1.0, -17);
  constexpr std::size_t max_stride = 64;
  while (stride < max_stride) {
    const double h = static_cast<double>(stride) * dt;
    const bool acceleration_quiet = 4 * e / (h * h) <= 0.01 * machine.a_max_mm_per_s2;
    const bool jerk_quiet = !machine.jerk_limited || 8 * e / (h * h * h) <= 0.01 * machine.j_max_mm_per_s3;
    if (acceleration_quiet && jerk_quiet) break;
    ++stride;
  }
  return stride;
}

}  // namespace

RunningProfile::RunningProfile(const MachineLimits& machine, bool quantised)
    : stride_(profile_stride(machine, quantised)), h_(static_cast<double>(stride_) * (1.0 / machine.rate_hz)), differences_(stride_) {}

ProfileSample RunningProfile::push(const SetpointRecord& r) {
  const SampleDifferences d = differences_.push(r.position_mm);
  return ProfileSample{r.time_s, r.speed_mm_per_s, d.second / (h_ * h_), d.third / (h_ * h_ * h_)};
}

}  // namespace report_detail

MotionProfile motion_profile(const std::vector<SetpointRecord>& setpoints, const MachineLimits& machine, bool quantised) {
  report_detail::RunningProfile running(machine, quantised);
  MotionProfile profile;
  profile.stride = running.stride();
  const std::size_t n = setpoints.size();
  profile.time_s.resize(n);
  profile.speed_mm_per_s.resize(n);
  profile.acceleration_mm_per_s2.resize(n);
  profile.jerk_mm_per_s3.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const report_detail::ProfileSample p = running.push(setpoints[i]);
    profile.time_s[i] = p.time_s;
    profile.speed_mm_per_s[i] = p.speed_mm_per_s;
    profile.acceleration_mm_per_s2[i] = p.acceleration_mm_per_s2;
    profile.jerk_mm_per_s3[i] = p.jerk_mm_per_s3;
  }
  return profile;
}

}  // namespace curvestep::host
