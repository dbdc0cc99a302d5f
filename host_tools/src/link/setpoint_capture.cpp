// SPDX-License-Identifier: MIT
#include <curvestep/host/link/setpoint_capture.hpp>

#include <cmath>

namespace curvestep::host::link {

void SetpointCapture::receive(std::uint32_t index, const protocol::WirePoint& point) {
  if (received_ > 0 && index <= last_index_) {
    ++duplicates_;
    return;
  }
  const double dt = 1.0 / rate_hz_;
  const bool consecutive = received_ > 0 && index == last_index_ + 1;
  if (received_ > 0 && !consecutive) {
    skipped_ += index - last_index_ - 1;
    gaps_.push_back(Gap{last_index_, index - last_index_ - 1});
    gap_seen_ = true;
  }
  SetpointRecord r;
  r.time_s = static_cast<double>(index) * dt;
  r.index = index;
  double d2 = 0;
  for (std::size_t a = 0; a < 3; ++a) {
    r.raw_q16[a] = point[a];
    r.position_mm[a] = static_cast<double>(point[a]) / 65536.0;
    if (consecutive) {
      const double d = static_cast<double>(point[a] - previous_[a]) / 65536.0;
      d2 += d * d;
    }
  }
  r.speed_mm_per_s = std::sqrt(d2) / dt;
  previous_ = point;
  last_index_ = index;
  if (!gap_seen_) first_run_end_ = index;
  ++received_;
  if (sink_) {
    sink_(r);
  } else {
    records_.push_back(r);
  }
}

std::size_t SetpointCapture::standing_ticks(std::uint32_t end_index) const noexcept {
  const std::uint32_t expected = received_ == 0 ? 0 : last_index_ + 1;
  return skipped_ + (end_index > expected ? end_index - expected : 0);
}

std::uint64_t SetpointCapture::first_gap_between(std::uint64_t from, std::uint64_t until) const noexcept {
  for (const Gap& gap : gaps_) {
    if (gap.after < from) continue;
    return std::uint64_t{gap.after} + gap.length + 1 <= until ? gap.length : 0;
  }
  return 0;
}

}  // namespace curvestep::host::link
