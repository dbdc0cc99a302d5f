// SPDX-License-Identifier: MIT
// Finite differences of sampled positions: the one implementation behind the simulator's summary
// (peak speed, acceleration, jerk, chord deviation, distance, axis speeds) and the report's
// acceleration and jerk curves (report.hpp, motion_profile).
//
// For positions p_i sampled dt apart and a stride k, the backward differences are
//   Δ¹_i = p_i − p_{i−k}, Δ²_i = p_i − 2p_{i−k} + p_{i−2k}, Δ³_i = p_i − 3p_{i−k} + 3p_{i−2k} − p_{i−3k},
// so |Δ¹|/h, |Δ²|/h² and |Δ³|/h³ with h = k·dt estimate speed, acceleration and jerk; |Δ²|/8 is
// the sagitta of the chord between neighbouring samples (k = 1).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace curvestep::host {

/// The differences at one sample: Euclidean norms of Δ¹, Δ² and Δ³ (0 where a difference reaches
/// before the first sample) and |Δ¹| of each axis.
struct SampleDifferences {
  double first = 0;
  double second = 0;
  double third = 0;
  std::array<double, 3> axis_first{};
};

/// The differences at sample i (i >= stride k >= 1), `position(j)` returning sample j.
template <class PositionAt>
[[nodiscard]] SampleDifferences differences_at(std::size_t i, PositionAt&& position, std::size_t k) {
  SampleDifferences d;
  double v2 = 0, a2 = 0, j2 = 0;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const auto p = [&](std::size_t back) { return position(i - back * k)[axis]; };
    const double d1 = p(0) - p(1);
    v2 += d1 * d1;
    d.axis_first[axis] = std::fabs(d1);
    if (i >= 2 * k) {
      const double d2 = p(0) - 2 * p(1) + p(2);
      a2 += d2 * d2;
    }
    if (i >= 3 * k) {
      const double d3 = p(0) - 3 * p(1) + 3 * p(2) - p(3);
      j2 += d3 * d3;
    }
  }
  d.first = std::sqrt(v2);
  d.second = std::sqrt(a2);
  d.third = std::sqrt(j2);
  return d;
}

/// Differences of samples as they come, `stride` (>= 1) samples apart, keeping the last 3·stride + 1:
/// memory independent of the number of samples. push() returns the differences at the new sample,
/// those of position_differences (all 0 before the stride's first sample).
class RunningDifferences {
 public:
  explicit RunningDifferences(std::size_t stride = 1) : stride_(stride == 0 ? 1 : stride), last_(3 * stride_ + 1) {}
  SampleDifferences push(const std::array<double, 3>& point) {
    last_[count_ % last_.size()] = point;
    ++count_;
    if (count_ - 1 < stride_) return {};
    return differences_at(count_ - 1, [this](std::size_t j) -> const std::array<double, 3>& { return last_[j % last_.size()]; }, stride_);
  }
  [[nodiscard]] std::size_t count() const noexcept { return count_; }

 private:
  std::size_t stride_;
  std::vector<std::array<double, 3>> last_;
  std::size_t count_ = 0;
};

/// Euclidean norms of the backward differences of every sample (0 where a difference reaches
/// before the first sample), and the largest |Δ¹| of each axis.
struct PositionDifferences {
  std::vector<double> first;   ///< |Δ¹_i|, 0 for i < k
  std::vector<double> second;  ///< |Δ²_i|, 0 for i < 2k
  std::vector<double> third;   ///< |Δ³_i|, 0 for i < 3k
  std::array<double, 3> peak_axis_first{};  ///< max over i of |Δ¹_i| on each axis
};

/// The differences of `count` positions, `position(i)` returning sample i as three coordinates
/// (x, y, z in mm), taken `stride` (>= 1) samples apart.
template <class PositionAt>
[[nodiscard]] PositionDifferences position_differences(std::size_t count, PositionAt position, std::size_t stride) {
  const std::size_t k = stride == 0 ? 1 : stride;
  PositionDifferences d;
  d.first.assign(count, 0.0);
  d.second.assign(count, 0.0);
  d.third.assign(count, 0.0);
  for (std::size_t i = k; i < count; ++i) {
    const SampleDifferences at = differences_at(i, position, k);
    d.first[i] = at.first;
    d.second[i] = at.second;
    d.third[i] = at.third;
    for (std::size_t axis = 0; axis < 3; ++axis) d.peak_axis_first[axis] = std::fmax(d.peak_axis_first[axis], at.axis_first[axis]);
  }
  return d;
}

}  // namespace curvestep::host
