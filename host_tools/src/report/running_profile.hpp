// SPDX-License-Identifier: MIT
// The report's speed, acceleration and jerk of setpoints as they come (report.hpp, MotionProfile):
// motion_profile() and the streamed report compute them here, so both give the same numbers.
#pragma once

#include <cstddef>

#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/host/position_differences.hpp>
#include <curvestep/host/simulator.hpp>

namespace curvestep::host::report_detail {

/// The profile at one setpoint.
struct ProfileSample {
  double time_s = 0;
  double speed_mm_per_s = 0;
  double acceleration_mm_per_s2 = 0;  ///< 0 before 2·stride setpoints
  double jerk_mm_per_s3 = 0;          ///< 0 before 3·stride setpoints
};

/// Differences `stride` setpoints apart (report.hpp explains the stride), keeping 3·stride + 1.
class RunningProfile {
 public:
  RunningProfile(const MachineLimits& machine, bool quantised);
  [[nodiscard]] ProfileSample push(const SetpointRecord& r);
  [[nodiscard]] std::size_t stride() const noexcept { return stride_; }

 private:
  std::size_t stride_ = 1;
  double h_ = 0;  ///< stride · dt
  RunningDifferences differences_;
};

}  // namespace curvestep::host::report_detail
