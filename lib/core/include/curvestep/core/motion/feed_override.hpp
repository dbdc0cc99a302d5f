// SPDX-License-Identifier: MIT
// FeedOverride: the operator's scaling of the programmed feed (10..200 %) and of rapids (10..100 %),
// and OverridableCaps, the part of a segment's caps it scales.
//
// The override scales only what the job asks for (a move's feed, the rapid speed), never a cap the
// machine or the geometry sets (v_max, the axes, curvature, chord, jerk): with c the segment's caps
// at 100 %, the speed cap at p % is min(programmed · p/100, geometric). The tangential acceleration
// cap of a curved segment depends on its speed cap (the centripetal part at the cap, and 3 v a κ <=
// j/4 up to the speed where the plain sum of the jerk terms binds), so the plan keeps two: the one
// at 100 % (valid up to the speed cap at 100 %) and the one at the largest feed override (valid up
// to that speed); acceleration_for(v) picks the one valid at v.
// At 100 % every value is the plan's own, bit for bit (fmin is exact and p/100 = 1).
#pragma once

#include <cmath>
#include <cstdint>

#include <curvestep/core/motion/velocity_profile.hpp>

namespace curvestep {

/// Feed and rapid override in percent of the programmed speeds.
struct FeedOverride {
  static constexpr std::uint16_t min_feed_percent = 10;    ///< slowest feed override
  static constexpr std::uint16_t max_feed_percent = 200;   ///< fastest feed override
  static constexpr std::uint16_t min_rapid_percent = 10;   ///< slowest rapid override
  static constexpr std::uint16_t max_rapid_percent = 100;  ///< rapids never run above their speed

  std::uint16_t feed_percent = 100;   ///< scales the feed of feed moves, 10..200
  std::uint16_t rapid_percent = 100;  ///< scales the speed of rapids, 10..100

  /// True if both percentages lie in their ranges.
  [[nodiscard]] constexpr bool valid() const noexcept {
    return feed_percent >= min_feed_percent && feed_percent <= max_feed_percent && rapid_percent >= min_rapid_percent &&
           rapid_percent <= max_rapid_percent;
  }
  friend constexpr bool operator==(const FeedOverride&, const FeedOverride&) = default;
};

/// The caps of one segment that an override changes, next to the plan's limits at 100 %.
struct OverridableCaps {
  double programmed_mm_per_s = 0;     ///< the speed the job asks for: the move's feed, or the rapid speed
  double geometric_cap_mm_per_s = 0;  ///< every other speed cap (machine, axes, curvature, chord)
  double acceleration_at_max_override_mm_per_s2 = 0;  ///< tangential acceleration cap valid up to the
                                                      ///< speed cap at FeedOverride::max_feed_percent
  bool rapid = false;                 ///< scaled by the rapid override (else by the feed override)

  /// The speed cap under `o` (mm/s).
  [[nodiscard]] double speed_cap(FeedOverride o) const noexcept {
    const double percent = rapid ? o.rapid_percent : o.feed_percent;
    return std::fmin(programmed_mm_per_s * (percent / 100.0), geometric_cap_mm_per_s);
  }

  /// The tangential acceleration cap valid for every speed up to `speed` (`at_full`: the plan's
  /// limits at 100 %, valid up to their speed cap).
  [[nodiscard]] double acceleration_for(double speed, const ProfileLimits& at_full) const noexcept {
    return speed > at_full.speed_cap_mm_per_s ? acceleration_at_max_override_mm_per_s2 : at_full.acceleration_mm_per_s2;
  }

  /// The profile limits under `o`; with `entry_mm_per_s` above the new cap, the acceleration is
  /// the one valid at that entry speed (the profile slows down from it).
  [[nodiscard]] ProfileLimits limits(const ProfileLimits& at_full, FeedOverride o, double entry_mm_per_s = 0) const noexcept {
    ProfileLimits l = at_full;
    l.speed_cap_mm_per_s = speed_cap(o);
    l.acceleration_mm_per_s2 = acceleration_for(std::fmax(l.speed_cap_mm_per_s, entry_mm_per_s), at_full);
    return l;
  }
};

}  // namespace curvestep
