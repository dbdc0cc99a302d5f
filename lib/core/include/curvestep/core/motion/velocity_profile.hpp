// SPDX-License-Identifier: MIT
// VelocityProfile: speed along one segment, from an entry to an exit speed, within a, j and v caps.
//
// A jerk-limited (S-curve) change of speed from v0 to v1 with acceleration at most a and jerk at
// most j, starting and ending at zero acceleration, takes
//     Δv >= a²/j:  T = Δv/a + a/j,   phases: jerk +j for a/j, constant a, jerk -j for a/j
//     Δv <  a²/j:  T = 2 sqrt(Δv/j), peak acceleration sqrt(Δv j)
// and covers the distance D = (v0 + v1)/2 · T. A segment profile is accelerate → cruise →
// decelerate: the peak speed vp is the largest speed <= cap with D(v0,vp) + D(vp,v1) <= L, found
// by bisection (60 halvings: deterministic, exact to double rounding). The trapezoidal profile is
// the limit j → ∞ (T = Δv/a). Acceleration is zero at both ends of every segment, so joining
// profiles never jumps the acceleration. s(t) within a phase of constant jerk is the cubic
// s0 + v0 τ + a0 τ²/2 + j τ³/6; the last phase ends at s = L exactly (the end is clamped).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

#include <curvestep/core/contract.hpp>
#include <curvestep/core/result.hpp>

namespace curvestep {

/// Kinematic state at one instant along a segment.
struct MotionState {
  double distance_mm = 0;           ///< s from the start of the segment
  double speed_mm_per_s = 0;        ///< v = ds/dt
  double acceleration_mm_per_s2 = 0;  ///< a = dv/dt
};

/// Limits used for one profile.
struct ProfileLimits {
  double speed_cap_mm_per_s = 0;  ///< cruise speed cap (feed, machine, curvature)
  double acceleration_mm_per_s2 = 0;  ///< tangential acceleration cap
  double jerk_mm_per_s3 = 0;      ///< tangential jerk cap (used when jerk_limited)
  bool jerk_limited = true;       ///< S-curve (true) or trapezoid (false)
};

/// Time needed to change speed by `delta_v` >= 0 from rest acceleration to rest acceleration.
[[nodiscard]] inline double speed_change_time(double delta_v, const ProfileLimits& limits) noexcept {
  if (!(delta_v > 0)) return 0;
  const double a = limits.acceleration_mm_per_s2;
  if (!limits.jerk_limited) return delta_v / a;
  const double j = limits.jerk_mm_per_s3;
  if (delta_v >= a * a / j) return delta_v / a + a / j;
  return 2 * std::sqrt(delta_v / j);
}

/// Distance covered while changing speed between v0 and v1 (either order).
[[nodiscard]] inline double speed_change_distance(double v0, double v1, const ProfileLimits& limits) noexcept {
  const double dv = v1 > v0 ? v1 - v0 : v0 - v1;
  return (v0 + v1) / 2 * speed_change_time(dv, limits);
}

namespace detail {
/// The two ends of a bisection.
struct Bracket {
  double low;
  double high;
};
/// Bisection of [low, high] by 60 halvings (deterministic, exact to double rounding): `low_side`
/// of a middle says whether the boundary lies above it (the middle becomes `low`) or not.
template <class LowSide>
[[nodiscard]] Bracket bisect(double low, double high, const LowSide& low_side) noexcept {
  for (int i = 0; i < 60; ++i) {
    const double middle = (low + high) / 2;
    if (low_side(middle)) {
      low = middle;
    } else {
      high = middle;
    }
  }
  return Bracket{low, high};
}
}  // namespace detail

/// The largest v1 <= cap reachable from v0 within `distance` (accelerating; by symmetry also the
/// largest v0 from which v1 can be reached decelerating).
[[nodiscard]] inline double reachable_speed(double v0, double distance, double cap, const ProfileLimits& limits) noexcept {
  if (cap <= v0) return cap;
  if (speed_change_distance(v0, cap, limits) <= distance) return cap;
  return detail::bisect(v0, cap, [&](double v) { return speed_change_distance(v0, v, limits) <= distance; }).low;
}

/// The largest speed <= v1 that a slow-down from v0 (acceleration 0 at both ends) reaches within
/// `distance`, or -1 if not even a stop fits. D(v, v0) is not monotone in v: it rises from a stop
/// to a peak and falls again towards v0 (a small speed change is short, a stop is long, a change of
/// about two thirds of v0 is longest), so when v1 is out of reach a lower speed, down to a stop,
/// may still be reachable: the largest such one.
[[nodiscard]] inline double highest_reachable_slower(double v0, double v1, double distance, const ProfileLimits& limits) noexcept {
  if (speed_change_distance(0, v0, limits) > distance) return -1;
  if (speed_change_distance(v1, v0, limits) <= distance) return v1;
  return detail::bisect(0, v1, [&](double v) { return speed_change_distance(v, v0, limits) <= distance; }).low;
}

/// The speed profile of one segment: up to 7 phases of constant jerk.
class VelocityProfile {
 public:
  /// One phase: constant jerk for `duration_s`, starting from `start`.
  struct Phase {
    double duration_s = 0;
    double jerk_mm_per_s3 = 0;
    MotionState start{};
  };

  constexpr VelocityProfile() = default;

  /// Plans L mm from v0 to v1. InvalidLimit for non-positive caps, InvalidArgument if v1 cannot
  /// be reached from v0 within L (the planner prevents that; a small shortfall from rounding is
  /// absorbed by lowering the exit speed).
  [[nodiscard]] static Result<VelocityProfile> plan(double length_mm, double v0, double v1, const ProfileLimits& limits) noexcept {
    if (!(limits.acceleration_mm_per_s2 > 0) || !(limits.speed_cap_mm_per_s > 0) ||
        (limits.jerk_limited && !(limits.jerk_mm_per_s3 > 0))) {
      return fail(Error::InvalidLimit);
    }
    if (!(length_mm > 0) || !(v0 >= 0) || !(v1 >= 0)) return fail(Error::InvalidArgument);
    const double cap = limits.speed_cap_mm_per_s;
    if (v0 > cap) v0 = cap;
    if (v1 > cap) v1 = cap;
    // Unreachable exit speed: lower it to what the length allows (or raise the request to v0's reach).
    if (v1 > v0) {
      v1 = std::fmin(v1, reachable_speed(v0, length_mm, cap, limits));
    } else if (v0 > v1) {
      const double needed = speed_change_distance(v1, v0, limits);
      if (needed > length_mm * (1 + 1e-9) + 1e-12) return fail(Error::InvalidArgument);
    }
    // Peak speed: the largest vp with D(v0,vp) + D(vp,v1) <= L.
    const double floor_speed = v0 > v1 ? v0 : v1;
    auto total = [&](double vp) { return speed_change_distance(v0, vp, limits) + speed_change_distance(vp, v1, limits); };
    double vp = cap;
    if (total(cap) > length_mm) vp = detail::bisect(floor_speed, cap, [&](double v) { return total(v) <= length_mm; }).low;
    return assemble(length_mm, v0, vp, v1, limits);
  }

  /// Plans L mm entered at v0 faster than plan() allows (after a lowered feed override: above the
  /// speed cap, or too fast to reach v1 within L): only slowing down. If v1 is reachable, slow down
  /// to the largest vp <= min(cap, v0) from which v1 still is, cruise, and slow down to v1 (vp is
  /// the cap if that fits); otherwise slow down over all of L as far as it goes (exit_speed() then
  /// lies above v1: the next segment goes on slowing down). Never faster than v0. InvalidLimit for
  /// non-positive caps, InvalidArgument for a non-positive length or negative speeds.
  [[nodiscard]] static Result<VelocityProfile> slow_down(double length_mm, double v0, double v1, const ProfileLimits& limits) noexcept {
    if (!(limits.acceleration_mm_per_s2 > 0) || !(limits.speed_cap_mm_per_s > 0) ||
        (limits.jerk_limited && !(limits.jerk_mm_per_s3 > 0))) {
      return fail(Error::InvalidLimit);
    }
    if (!(length_mm > 0) || !(v0 >= 0) || !(v1 >= 0)) return fail(Error::InvalidArgument);
    const double top = std::fmin(limits.speed_cap_mm_per_s, v0);
    if (v1 > top) v1 = top;
    double vp = top;
    if (speed_change_distance(v1, v0, limits) > length_mm) {
      // v1 out of reach: the lowest speed reachable within L above v1 (D(v, v0) falls as v rises from
      // its peak near v0 / 3 to v0; below the peak a lower speed may be reachable too: the controller
      // looks there when it must, highest_reachable_slower).
      v1 = detail::bisect(v1, v0, [&](double v) { return speed_change_distance(v, v0, limits) > length_mm; }).high;
      vp = v1;
    } else {
      auto total = [&](double v) { return speed_change_distance(v0, v, limits) + speed_change_distance(v, v1, limits); };
      // total(v1) = D(v0, v1) <= L
      if (total(top) > length_mm) vp = detail::bisect(v1, top, [&](double v) { return total(v) <= length_mm; }).low;
    }
    return assemble(length_mm, v0, vp, v1, limits);
  }

  /// The shortest stop from speed v and acceleration a within the limits (feed hold): first bring
  /// the acceleration to zero with jerk ∓j, then an S-curve (or trapezoid) down to rest. Its
  /// length_mm() is the distance needed.
  [[nodiscard]] static VelocityProfile stop(double v, double a, const ProfileLimits& limits) noexcept {
    VelocityProfile p;
    p.trapezoid_ = !limits.jerk_limited;
    p.entry_ = v;
    p.exit_ = 0;
    p.peak_ = v;
    double speed = v;
    if (limits.jerk_limited && a != 0) {
      const double j = limits.jerk_mm_per_s3;
      const double duration = std::fabs(a) / j;
      p.phases_[p.count_++] = Phase{duration, a > 0 ? -j : j, MotionState{0, v, a}};
      speed = v + a * duration / 2;  // v + a²/(2j) (a > 0) or v − a²/(2j) (a < 0)
      if (speed < 0) speed = 0;
      if (speed > p.peak_) p.peak_ = speed;
    }
    p.add_speed_change(speed, 0, limits);
    if (p.count_ > 0) {
      const Phase& last = p.phases_[p.count_ - 1];
      p.length_ = advance(last.start, last.jerk_mm_per_s3, last.duration_s).distance_mm;
    }
    for (std::size_t i = 0; i < p.count_; ++i) p.duration_ += p.phases_[i].duration_s;
    return p;
  }

  /// Total time (s).
  [[nodiscard]] constexpr double duration_s() const noexcept { return duration_; }
  [[nodiscard]] constexpr double length_mm() const noexcept { return length_; }
  [[nodiscard]] constexpr double entry_speed() const noexcept { return entry_; }
  [[nodiscard]] constexpr double exit_speed() const noexcept { return exit_; }
  [[nodiscard]] constexpr double peak_speed() const noexcept { return peak_; }
  [[nodiscard]] constexpr std::size_t phase_count() const noexcept { return count_; }
  [[nodiscard]] constexpr const Phase& phase(std::size_t i) const noexcept { return phases_[i]; }

  /// The phase that at(t) uses for t, and its time span [begin_s, end_s) computed exactly as at()
  /// computes it (the last phase runs to duration_s()). Inside one span s(t) is one cubic.
  struct PhaseSpan {
    std::size_t index = 0;  ///< phase number
    double begin_s = 0;     ///< first time of the phase (at() subtracts it)
    double end_s = 0;       ///< first time past the phase
  };

  /// The span of the phase containing t (t <= 0: the first phase). Contract: phase_count() > 0.
  [[nodiscard]] PhaseSpan phase_span(double t) const noexcept {
    CURVESTEP_EXPECTS(count_ > 0);
    double elapsed = 0;
    for (std::size_t i = 0; i + 1 < count_; ++i) {
      const double end = elapsed + phases_[i].duration_s;
      if (t < end) return PhaseSpan{i, elapsed, end};
      elapsed = end;
    }
    return PhaseSpan{count_ - 1, elapsed, duration_};
  }

  /// The state at t inside `span` (t in [span.begin_s, span.end_s)), with at()'s clamps: equal to
  /// at(t) bit for bit for 0 < t < duration_s(). At t = span.begin_s it is the phase's own start
  /// (a trapezoid's acceleration after its jump, where at(0) reports 0).
  [[nodiscard]] MotionState state_in(const PhaseSpan& span, double t) const noexcept {
    const Phase& ph = phases_[span.index];
    MotionState m = advance(ph.start, ph.jerk_mm_per_s3, t - span.begin_s);
    if (m.distance_mm > length_) m.distance_mm = length_;
    if (m.speed_mm_per_s < 0) m.speed_mm_per_s = 0;
    return m;
  }

  /// State at time t in [0, duration] (clamped); at t >= duration: (L, exit speed, 0) exactly.
  [[nodiscard]] MotionState at(double t) const noexcept {
    if (!(t > 0)) return MotionState{0, entry_, 0};
    if (t >= duration_ || count_ == 0) return MotionState{length_, exit_, 0};
    return state_in(phase_span(t), t);
  }

 private:
  static MotionState advance(const MotionState& s, double jerk, double tau) noexcept {
    const double tau2 = tau * tau;
    return MotionState{s.distance_mm + s.speed_mm_per_s * tau + s.acceleration_mm_per_s2 * tau2 / 2 + jerk * tau2 * tau / 6,
                       s.speed_mm_per_s + s.acceleration_mm_per_s2 * tau + jerk * tau2 / 2,
                       s.acceleration_mm_per_s2 + jerk * tau};
  }

  /// Where the next phase starts: the end of the last one (rounding leaves a tiny acceleration
  /// after an S-curve ramp, and a trapezoid ramp ends with a jump to 0: both become 0), or the
  /// entry speed at rest.
  [[nodiscard]] MotionState next_start() const noexcept {
    MotionState start{};
    if (count_ > 0) {
      const Phase& last = phases_[count_ - 1];
      start = advance(last.start, last.jerk_mm_per_s3, last.duration_s);
      if (trapezoid_ || std::fabs(start.acceleration_mm_per_s2) < 1e-9) start.acceleration_mm_per_s2 = 0;
    } else {
      start.speed_mm_per_s = entry_;
    }
    return start;
  }

  /// L mm from v0 through a cruise at vp to v1 (the cruise fills what the two speed changes leave).
  [[nodiscard]] static VelocityProfile assemble(double length_mm, double v0, double vp, double v1, const ProfileLimits& limits) noexcept {
    VelocityProfile p;
    p.trapezoid_ = !limits.jerk_limited;
    p.length_ = length_mm;
    p.entry_ = v0;
    p.exit_ = v1;
    p.peak_ = vp > v0 ? vp : v0;
    p.add_speed_change(v0, vp, limits);
    const double cruise = length_mm - (speed_change_distance(v0, vp, limits) + speed_change_distance(vp, v1, limits));
    if (cruise > 0 && vp > 0) p.add_phase(cruise / vp, 0);
    p.add_speed_change(vp, v1, limits);
    p.duration_ = 0;
    for (std::size_t i = 0; i < p.count_; ++i) p.duration_ += p.phases_[i].duration_s;
    return p;
  }

  void append(double duration, double jerk, const MotionState& start) noexcept {
    if (count_ < phases_.size()) phases_[count_++] = Phase{duration, jerk, start};
  }

  void add_phase(double duration, double jerk) noexcept {
    if (!(duration > 0) || count_ == phases_.size()) return;
    append(duration, jerk, next_start());
  }

  void add_speed_change(double from, double to, const ProfileLimits& limits) noexcept {
    const double dv = to > from ? to - from : from - to;
    if (!(dv > 0)) return;
    const double sign = to > from ? 1.0 : -1.0;
    const double a = limits.acceleration_mm_per_s2;
    if (!limits.jerk_limited) {
      // Trapezoid: constant acceleration, modelled as one phase of zero jerk with a jump in a.
      MotionState start = next_start();
      start.speed_mm_per_s = from;
      start.acceleration_mm_per_s2 = sign * a;
      append(dv / a, 0, start);
      return;
    }
    const double j = limits.jerk_mm_per_s3;
    if (dv >= a * a / j) {
      add_phase(a / j, sign * j);
      add_phase(dv / a - a / j, 0);
      add_phase(a / j, -sign * j);
    } else {
      const double t = std::sqrt(dv / j);
      add_phase(t, sign * j);
      add_phase(t, -sign * j);
    }
  }

  std::array<Phase, 7> phases_{};
  std::size_t count_ = 0;
  double duration_ = 0;
  double length_ = 0;
  double entry_ = 0;
  double exit_ = 0;
  double peak_ = 0;
  bool trapezoid_ = false;
};

}  // namespace curvestep
