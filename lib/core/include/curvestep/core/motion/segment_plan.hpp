// SPDX-License-Identifier: MIT
// SegmentPlan: what the planner needs to know of one segment — its length, the speed, acceleration
// and jerk caps along it, and its end tangents and curvature vectors for the junctions.
//
// Limits are sufficient conditions on the whole acceleration and jerk vectors, not just their
// tangential parts. With T, N the unit tangent and normal, κ the curvature and a_t, j_t the
// tangential acceleration and jerk, a moving point has
//     a = a_t T + v²κ N                     j = (j_t − v³κ²) T + (3 v a_t κ + v³ dκ/ds) N.
// So |a| <= a_max holds if v²κ <= ½ a_max and |a_t| <= √(a_max² − (v_cap²κ)²), and |j| <= j_max
// holds if (j_t + v³κ²)² + (3 v |a_t| κ + v³ρ)² <= j_max², ρ >= |d(κN)/ds|: the speed cap is taken
// with j_t = ½ j_max (curvature_jerk_speed_cap), the profile then takes what is left at the fastest
// speed, up to ¾ j_max (curve_profile_jerk), and a joint's curvature jump what is left there
// (junction_speed).
// With the trapezoid profile (no jerk limit) the jerk terms cap nothing: v²κ <= ½ a_max and the
// acceleration bounds remain. A straight segment keeps the full a_max and j_max. Per-axis velocity
// limits cap v |T_axis|;
// an axis sees |a_t| |T_axis| + v²κ |N_axis| of acceleration, so each axis limit caps the speed
// (v²κ max|N_axis| <= ½ a_axis) and then the tangential acceleration by what the centripetal part at
// that speed leaves: a_t <= (a_axis − v_cap² κ max|N_axis|) / max|T_axis| (an XY move is not slowed
// by a slow Z axis, and a gently curved Z profile keeps most of a_max along the path). The chord
// between two setpoints must stay within the tolerance: its sagitta κ (v Δt)² / 8 <= tolerance.
// κ and dκ/ds are sampled at 129 points (dκ/ds by differences of κ over arc length, with a 25%
// margin); the planning is a pure function of the segment and the machine (deterministic).
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>

#include <curvestep/core/detail/golden_section.hpp>
#include <curvestep/core/motion/feed_override.hpp>
#include <curvestep/core/motion/path_length_table.hpp>
#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/core/motion/path_segment.hpp>
#include <curvestep/core/motion/velocity_profile.hpp>

namespace curvestep {

/// Planning data of one segment.
struct SegmentPlan {
  double length_mm = 0;                 ///< arc length
  ProfileLimits limits{};               ///< caps for the segment's speed profile
  MachinePoint start_tangent{};         ///< unit tangent at u = 0
  MachinePoint end_tangent{};           ///< unit tangent at u = 1
  MachinePoint start_curvature{};       ///< curvature vector κN at u = 0
  MachinePoint end_curvature{};         ///< curvature vector κN at u = 1
  double max_curvature_per_mm = 0;      ///< largest κ along the segment
  double max_curvature_rate_per_mm2 = 0;  ///< largest |d(κN)/ds| along it (sampled, with its margin)
  OverridableCaps caps{};               ///< what a feed or rapid override scales (limits: at 100 %)

  /// A curve (some curvature along it), not a straight line.
  [[nodiscard]] bool curved() const noexcept { return max_curvature_per_mm > 0; }
};

namespace detail {
/// Cube root by Newton's method (deterministic, unlike libm's cbrt across C libraries).
[[nodiscard]] inline double cube_root(double x) noexcept {
  if (!(x > 0)) return 0;
  double r = x > 1 ? x / 3 : 1;
  for (int i = 0; i < 100; ++i) {
    const double next = r - (r * r * r - x) / (3 * r * r);
    if (next == r) break;
    r = next;
  }
  return r;
}

/// The largest x in [low, high] for which `fits(x)` holds, by 48 halvings (deterministic: the same
/// doubles on host and firmware); `fits` must hold at `low` and be monotone (true, then false).
template <class Fits>
[[nodiscard]] double largest_fitting(double low, double high, const Fits& fits) noexcept {
  for (int i = 0; i < 48; ++i) {
    const double mid = (low + high) / 2;
    (fits(mid) ? low : high) = mid;
  }
  return low;
}

/// Unit tangent and curvature vector from the first two derivatives.
inline void tangent_and_curvature(const MachinePoint& d1, const MachinePoint& d2, MachinePoint& tangent,
                                  MachinePoint& curvature) noexcept {
  const double s2 = dot(d1, d1);
  tangent = MachinePoint{};
  curvature = MachinePoint{};
  if (!(s2 > 0)) return;
  const double speed = std::sqrt(s2);
  tangent = d1 / speed;
  const double d12 = dot(d1, d2);
  // κN = (r'' |r'|² − r' (r'·r'')) / |r'|^4
  curvature = (d2 * s2 - d1 * d12) / (s2 * s2);
}
}  // namespace detail

/// The speed at which the plain sum of a curve's jerk terms reaches the budget the profile leaves:
/// v³(κ² + ρ) <= ¼ j_max, ρ >= |d(κN)/ds| (see curvature_jerk_speed_cap).
[[nodiscard]] inline double curvature_jerk_sum_speed(double j_max, double max_kappa, double curvature_rate) noexcept {
  return detail::cube_root(0.25 * j_max / (max_kappa * max_kappa + curvature_rate));
}

/// The fastest speed at which a curve's own jerk keeps the whole jerk vector within j_max beside the
/// profile's. With D = d(κN)/ds = −κ² T + κ' N + κτ B and ρ >= |D|, the jerk
/// j = j_t T + 3 v a_t κ N + v³ D has a part along the path of at most ½ j + v³κ² (|j_t| <= ½ j)
/// and one across it of at most 3 v a_t κ + v³ρ. The two are orthogonal, so |j| <= j_max while
/// (½ j + v³κ²)² + (3 v a_t κ + v³ρ)² <= j². The tangential acceleration keeps what it had at the
/// speed v₀ where the plain sum reaches the budget (v₀³(κ² + ρ) = ¼ j, 3 v₀ a_t κ = ¼ j: a_t =
/// j / (12 v₀ κ)), so with u = v/v₀, p = v₀³κ²/j and q = v₀³ρ/j (p + q = ¼) the speed is the
/// largest u with (½ + p u³)² + (¼ u + q u³)² <= 1, found by bisection on [1, 4] (at u = 1 the
/// left side is at most 10/16). A tolerance-sized blend (ρ >> κ²) gets u = 1.29, an arc 1.32.
/// `v0` is curvature_jerk_sum_speed(j_max, max_kappa, curvature_rate), when the caller has it.
[[nodiscard]] inline double curvature_jerk_speed_cap(double j_max, double max_kappa, double curvature_rate, double v0) noexcept {
  if (!(v0 > 0)) return v0;
  const double p = v0 * v0 * v0 * max_kappa * max_kappa / j_max;
  const double q = v0 * v0 * v0 * curvature_rate / j_max;
  return v0 * detail::largest_fitting(1, 4, [&](double u) {
           const double u3 = u * u * u;
           const double along = 0.5 + p * u3;
           const double across = 0.25 * u + q * u3;
           return along * along + across * across <= 1;
         });
}
[[nodiscard]] inline double curvature_jerk_speed_cap(double j_max, double max_kappa, double curvature_rate) noexcept {
  return curvature_jerk_speed_cap(j_max, max_kappa, curvature_rate, curvature_jerk_sum_speed(j_max, max_kappa, curvature_rate));
}

/// The tangential jerk a curve's profile may use: the largest j_t with
/// (j_t + v³κ²)² + (3 v a_t κ + v³ρ)² <= j² at every speed the segment runs, between ½ j (which
/// curvature_jerk_speed_cap guarantees up to the cap) and ¾ j. `v_high` is the segment's fastest
/// speed (its cap under the largest feed override) and `across_high` a bound of 3 v a_t κ over its
/// speeds. The upper end is for joints: a setpoint's third difference weighs the jerk on both sides
/// of a joint and the step a curvature jump makes there by a quadratic B-spline over three ticks, and
/// beside a line's full j and a jump of ½ j (junction_speed) that mix stays within j while the
/// curve's j_t <= 0.79 j (√3/2 j measured 1.018 j on a random job). A gently curved segment (a
/// fitted raster row, a large arc) so changes speed nearly as fast as a line.
[[nodiscard]] inline double curve_profile_jerk(double j_max, double max_kappa, double curvature_rate, double v_high,
                                               double across_high) noexcept {
  const double v3 = v_high * v_high * v_high;
  const double across = across_high + v3 * curvature_rate;
  const double room = across < j_max ? std::sqrt(j_max * j_max - across * across) - v3 * max_kappa * max_kappa : 0.0;
  return std::fmax(0.5 * j_max, std::fmin(0.75 * j_max, room));
}

/// Analyses a segment for the machine: length, caps, end tangents and curvatures.
template <std::size_t Intervals = 64>
[[nodiscard]] Result<SegmentPlan> plan_segment(const PathSegment& segment, const PathLengthTable<Intervals>& table,
                                               const MachineLimits& machine) {
  Result<SegmentPlan> out(std::in_place);  // filled in place and returned by name (no copy)
  SegmentPlan& plan = out.value();
  plan.length_mm = table.length();
  double a_max = machine.a_max_mm_per_s2;
  // The programmed speed (what an override scales) and every other cap apart: the cap is their
  // minimum, the same value as taking them in turn (fmin is exact).
  const double programmed = segment.rapid() ? (machine.rapid_mm_per_s > 0 ? machine.rapid_mm_per_s : machine.v_max_mm_per_s)
                                            : (segment.feed_mm_per_s() > 0 ? segment.feed_mm_per_s() : machine.feed_mm_per_s);
  double speed_cap = machine.v_max_mm_per_s;

  constexpr std::size_t samples = 128;
  // The speeds are not kept (129 doubles, 1 KiB of a microcontroller's stack): the scan from a
  // vanishing end evaluates them again, the same pure function of u, so the same bits.
  const auto speed = [&segment](std::size_t k) { return norm(segment.derivative(static_cast<double>(k) / samples, 1)); };
  double largest_speed = 0;
  double start_speed = 0;
  double end_speed = 0;
  for (std::size_t k = 0; k <= samples; ++k) {
    const double v = speed(k);
    if (k == 0) start_speed = v;
    if (k == samples) end_speed = v;
    largest_speed = std::fmax(largest_speed, v);
  }
  // An end where the velocity vanishes is a cusp the controller split at: the curvature is unbounded
  // next to it, but the speed goes to zero there (the junction is a reversal), v²κ ~ s^(5/6) -> 0.
  // Its neighbourhood (speed below 5% of the largest) is left out of the curvature caps.
  std::size_t first = 0;
  std::size_t last = samples;
  if (start_speed <= 1e-7 * largest_speed) {
    while (first < samples && speed(first) < 0.05 * largest_speed) ++first;
  }
  if (end_speed <= 1e-7 * largest_speed) {
    while (last > first && speed(last) < 0.05 * largest_speed) --last;
  }
  double max_kappa = 0;
  double max_kappa_rate = 0;  // |dκ/ds|
  double previous_s = 0;
  double peak_u = 0;
  MachinePoint previous_curvature{};
  std::array<double, motion_axes> max_tangent_component{};
  std::array<double, motion_axes> max_normal_component{};
  auto kappa_at = [&](double u) {
    MachinePoint tangent;
    MachinePoint curvature;
    detail::tangent_and_curvature(segment.derivative(u, 1), segment.derivative(u, 2), tangent, curvature);
    return norm(curvature);
  };
  for (std::size_t k = 0; k <= samples; ++k) {
    const double u = static_cast<double>(k) / samples;
    MachinePoint tangent;
    MachinePoint curvature;
    detail::tangent_and_curvature(segment.derivative(u, 1), segment.derivative(u, 2), tangent, curvature);
    if (k == 0) {
      plan.start_tangent = tangent;
      plan.start_curvature = curvature;
    }
    if (k == samples) {
      plan.end_tangent = tangent;
      plan.end_curvature = curvature;
    }
    const double kappa = norm(curvature);
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      max_tangent_component[axis] = std::fmax(max_tangent_component[axis], std::fabs(tangent[axis]));
      if (kappa > 0) max_normal_component[axis] = std::fmax(max_normal_component[axis], std::fabs(curvature[axis]) / kappa);
    }
    if (k < first || k > last) continue;
    const double s = table.length_at(segment, u);
    if (k > first && s > previous_s) {
      max_kappa_rate = std::fmax(max_kappa_rate, norm(curvature - previous_curvature) / (s - previous_s));
    }
    if (kappa > max_kappa) {
      max_kappa = kappa;
      peak_u = u;
    }
    previous_s = s;
    previous_curvature = curvature;
  }
  // Refine the largest curvature between the neighbouring samples (golden-section search).
  if (max_kappa > 0) {
    const double low = std::fmax(static_cast<double>(first) / samples, peak_u - 1.0 / samples);
    const double high = std::fmin(static_cast<double>(last) / samples, peak_u + 1.0 / samples);
    const auto peak = detail::golden_section_minimum([&](double u) { return -kappa_at(u); }, low, high, 40);
    max_kappa = std::fmax(max_kappa, -peak.value);
  }
  if (!std::isfinite(max_kappa) || !std::isfinite(max_kappa_rate)) {
    out = fail(Error::DegenerateCurve);
    return out;
  }
  max_kappa_rate *= 1.25;
  plan.max_curvature_per_mm = max_kappa;
  plan.max_curvature_rate_per_mm2 = max_kappa_rate;

  for (std::size_t axis = 0; axis < motion_axes; ++axis) {
    const double limit = machine.axes[axis].v_max_mm_per_s;
    if (limit > 0 && max_tangent_component[axis] > 0) speed_cap = std::fmin(speed_cap, limit / max_tangent_component[axis]);
  }
  double jerk = machine.j_max_mm_per_s3;
  const bool jerk_of_curvature = machine.jerk_limited && max_kappa > 0;  // the trapezoid limits no jerk
  const double jerk_sum_speed = jerk_of_curvature ? curvature_jerk_sum_speed(jerk, max_kappa, max_kappa_rate) : 0.0;
  if (max_kappa > 0) {
    speed_cap = std::fmin(speed_cap, std::sqrt(0.5 * a_max / max_kappa));  // v²κ <= a/2
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {              // per axis: v²κ |N_axis| <= a_axis/2
      const double limit = machine.axes[axis].a_max_mm_per_s2;
      if (limit > 0 && max_normal_component[axis] > 0) {
        speed_cap = std::fmin(speed_cap, std::sqrt(0.5 * limit / (max_kappa * max_normal_component[axis])));
      }
    }
    // The trapezoid limits no jerk (its acceleration steps): nor does the curvature's jerk cap it.
    if (jerk_of_curvature) {
      speed_cap = std::fmin(speed_cap, curvature_jerk_speed_cap(jerk, max_kappa, max_kappa_rate, jerk_sum_speed));
    }
    const double dt = 1.0 / machine.rate_hz;
    speed_cap = std::fmin(speed_cap, std::sqrt(8 * machine.tolerance_mm / max_kappa) / dt);  // chord sagitta
  }
  const double geometric_cap = speed_cap;
  speed_cap = std::fmin(programmed, geometric_cap);
  // Tangential acceleration: what the centripetal part c = v_cap² κ (<= a_max/2) leaves of the whole
  // vector, √(a_max² − c²) (>= 0.866 a_max), and per axis a_t |T_axis| + v_cap² κ |N_axis| <= a_axis;
  // with curvature also 3 v a κ <= j/4 at v = min(v_cap, v0), v0 where the plain sum of the jerk
  // terms binds (curvature_jerk_speed_cap). A function of the speed cap: also taken at the cap of
  // the largest feed override (OverridableCaps).
  const auto acceleration_at = [&](double cap) {
    const double centripetal_max = cap * cap * max_kappa;
    double acceleration = std::sqrt(std::fmax(0.0, a_max * a_max - centripetal_max * centripetal_max));
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      const double limit = machine.axes[axis].a_max_mm_per_s2;
      if (!(limit > 0) || !(max_tangent_component[axis] > 0)) continue;
      const double centripetal = max_kappa > 0 ? cap * cap * max_kappa * max_normal_component[axis] : 0.0;
      acceleration = std::fmin(acceleration, (limit - centripetal) / max_tangent_component[axis]);
    }
    // 3 v a κ <= j/4 up to the speed where the sum of the jerk terms binds; above it (up to the cap
    // by orthogonal parts) the acceleration stays what it was there (curvature_jerk_speed_cap).
    if (jerk_of_curvature) {
      acceleration = std::fmin(acceleration, 0.25 * jerk / (3 * std::fmin(cap, jerk_sum_speed) * max_kappa));
    }
    return acceleration;
  };
  const double acceleration = acceleration_at(speed_cap);
  const double fastest_cap = segment.rapid() ? speed_cap
                                             : std::fmin(programmed * (FeedOverride::max_feed_percent / 100.0), geometric_cap);
  const double fastest_acceleration = fastest_cap > speed_cap ? acceleration_at(fastest_cap) : acceleration;
  plan.caps = OverridableCaps{programmed, geometric_cap, fastest_acceleration, segment.rapid()};
  if (jerk_of_curvature) {
    // Jerk: the profile keeps what the curvature's parts leave at the fastest speed, at least half
    // (curvature_jerk_speed_cap), at most ¾; at a joint a curvature jump takes what they leave
    // there within one tick (junction_speed, detail::joint_jerk_fits).
    const double across = 3 * max_kappa * std::fmax(speed_cap * acceleration, fastest_cap * fastest_acceleration);
    jerk = curve_profile_jerk(jerk, max_kappa, max_kappa_rate, fastest_cap, across);
  }
  if (!(speed_cap > 0) || !(acceleration > 0)) {
    out = fail(Error::InvalidLimit);
    return out;
  }
  plan.limits = ProfileLimits{speed_cap, acceleration, jerk, machine.jerk_limited};
  return out;
}

/// grbl's junction-deviation speed (its documented formula, not its code): the circle tangent to
/// both directions whose closest point lies `deviation_mm` inside the corner has the radius
///     r = δ · sin(φ/2) / (1 − sin(φ/2)),
/// with φ the angle between the *reversed* incoming direction and the outgoing one (φ = 180°
/// straight on, φ → 0 a reversal), and the speed on it at acceleration a is v = √(a r). With
/// θ = 180° − φ the deflection (the angle between the two tangents, cos θ = T_in · T_out),
/// sin(φ/2) = cos(θ/2). +infinity straight on, 0 for a reversal.
[[nodiscard]] inline double junction_deviation_speed(double cos_deflection, double a_max_mm_per_s2,
                                                     double deviation_mm) noexcept {
  const double sin_half_phi = std::sqrt(std::fmax(0.0, (1 + cos_deflection) / 2));  // = cos(θ/2)
  if (sin_half_phi >= 1) return std::numeric_limits<double>::infinity();
  if (!(sin_half_phi > 0)) return 0;
  return std::sqrt(a_max_mm_per_s2 * deviation_mm * sin_half_phi / (1 - sin_half_phi));
}

namespace detail {
/// Share of a limit that a velocity jump at a corner may use, as a fraction k of the limit. The jump
/// Δv = v (T_out − T_in) of a corner of deflection θ happens within one tick: differentiated
/// numerically it adds Δv/Δt to the acceleration and Δv/Δt² to the jerk beside the profile's own
/// tangential part (up to the full limit L along T_out). Its direction D = (T_out − T_in)/|…| has
/// D · T_out = sin(θ/2) = s, so the measured vector is at most L √(1 + k² + 2 k s); k is chosen so
/// that this stays within (1 + corner_limit_excess) L: k = √(s² + ε) − s, ε = 2·excess + excess².
inline constexpr double corner_limit_excess = 0.0075;
[[nodiscard]] inline double corner_jump_share(double half_angle_sin) noexcept {
  constexpr double epsilon = 2 * corner_limit_excess + corner_limit_excess * corner_limit_excess;
  return std::sqrt(half_angle_sin * half_angle_sin + epsilon) - half_angle_sin;
}

/// A near-tangent kink (G-code rounded to 4 decimals leaves 10⁻⁵ rad at a "tangent" line–arc joint)
/// that also has a curvature jump adds its velocity jump, X = 2 v sin(θ/2)/Δt² of jerk, to the
/// jump's step, J = v²|Δ(κN)|/Δt, across the path within the same three ticks. A setpoint's third
/// difference weighs the jerk on both sides by the quadratic B-spline of the ticks (W), the step by
/// the spline (K <= ¾) and the velocity jump by its derivative (|L| <= 1):
///     |j| <= max over the joint's place in the ticks of hypot(W j_line + (1 − W) j_t, K J + |L| X).
/// Beside a line's full j and a curve whose profile takes ¾ j (curve_profile_jerk) this stays within
/// the corner's 0.75 % (corner_limit_excess) while X + 0.47 J <= 0.295 j (worked on a grid of the
/// joint's place: J = ½ j allows X = 0.061 j, J = 0 allows 0.298 j); with a profile of ½ j, J = ½ j
/// allowed X = 0.168 j, more than a corner's share ever gives (0.1225 j).
struct KinkBesideCurvatureJump {
  double jump_weight;  ///< w
  double room;         ///< c, in units of j
};
inline constexpr KinkBesideCurvatureJump kink_beside_curvature_jump{0.47, 0.295};

/// Whether one side of a joint is straight (its profile takes the whole j) and the other a curve
/// whose profile takes more than ½ j.
[[nodiscard]] inline bool line_beside_raised_curve(const SegmentPlan& a, const SegmentPlan& b, double j) noexcept {
  const auto raised = [j](const SegmentPlan& p) { return p.curved() && p.limits.jerk_mm_per_s3 > 0.5 * j; };
  return (!a.curved() && raised(b)) || (raised(a) && !b.curved());
}

/// Whether a joint passed at `speed`, whose curvature vector jumps by `jump_per_tick` × Δt within
/// one tick, keeps the jerk within j beside a neighbour's own parts there. A profile's acceleration
/// is 0 at a joint, so along the path a curved neighbour has at most its profile's jerk (½ j to
/// ¾ j, curve_profile_jerk) + v³κ², a straight one ½ j as before; across the path v³ρ
/// (curvature_jerk_speed_cap) and the jump's v²|Δ(κN)|/Δt. At low speed this holds whenever the
/// jump keeps to ½ j; near a curve's cap the jump gets less.
[[nodiscard]] inline bool joint_jerk_fits(double speed, const SegmentPlan& neighbour, double j, double jump_per_tick) noexcept {
  const double v3 = speed * speed * speed;
  const double profile = neighbour.curved() ? neighbour.limits.jerk_mm_per_s3 : 0.5 * j;
  const double along = profile + v3 * neighbour.max_curvature_per_mm * neighbour.max_curvature_per_mm;
  const double across = v3 * neighbour.max_curvature_rate_per_mm2 + speed * speed * jump_per_tick;
  return along * along + across * across <= j * j;
}
}  // namespace detail

/// The largest speed at the joint from `previous` into `next` (both already planned), the smallest of:
///   the two segments' speed caps;
///   a corner of deflection θ (the angle between the tangents): grbl's junction deviation
///     (junction_deviation_speed) with the machine's δ, and the velocity jump 2 v sin(θ/2), which
///     happens within one tick, kept to a share k(θ) of both a_max Δt and j_max Δt² (k from
///     detail::corner_jump_share, so the measured acceleration and jerk stay within 0.75 % of the
///     limits even with the full tangential acceleration or jerk beside the corner). Trapezoid and
///     S-curve alike: a corner is passed at this speed, not at a stop. Both caps shrink as θ
///     grows, so a gentler corner is never slower than a sharper one. A reversal stops.
///   a jump Δ(κN) of the curvature vector changes the acceleration by v²|Δ(κN)| within one tick:
///     with the S-curve v² |Δ(κN)| <= ½ j_max Δt, and less where a neighbour runs above the speed
///     at which its plain sum of jerk terms binds (detail::joint_jerk_fits, by bisection).
/// Sharp corners remain slow: corner blending (host_tools smoothing) replaces them by curves of
/// continuous curvature, which this function then passes at their full speed.
/// junction_speed_caps_apart gives the same without the segments' caps (a feed override changes them).
[[nodiscard]] inline double junction_speed_caps_apart(const SegmentPlan& previous, const SegmentPlan& next,
                                                      const MachineLimits& machine) noexcept {
  double v = std::numeric_limits<double>::infinity();
  const double dt = 1.0 / machine.rate_hz;
  const double cos_theta = dot(previous.end_tangent, next.start_tangent);
  const double half_angle_sin = std::sqrt(std::fmax(0.0, (1 - cos_theta) / 2));  // sin(θ/2)
  constexpr double tangent_continuity = 1e-9;  // sin(θ/2) below this counts as a smooth join
  if (half_angle_sin > tangent_continuity) {
    if (half_angle_sin >= 1 - 1e-12) return 0;  // reversal
    v = std::fmin(v, junction_deviation_speed(cos_theta, machine.a_max_mm_per_s2, machine.junction_deviation_mm));
    const double share = detail::corner_jump_share(half_angle_sin);
    double jump = share * machine.a_max_mm_per_s2 * dt;  // the largest velocity jump
    if (machine.jerk_limited) jump = std::fmin(jump, share * machine.j_max_mm_per_s3 * dt * dt);
    v = std::fmin(v, jump / (2 * half_angle_sin));
  }
  const double curvature_jump = norm(previous.end_curvature - next.start_curvature);
  if (machine.jerk_limited && curvature_jump > 0) {
    const double j = machine.j_max_mm_per_s3;
    const double jump_per_tick = curvature_jump / dt;
    const auto fits = [&](double speed) {
      return detail::joint_jerk_fits(speed, previous, j, jump_per_tick) && detail::joint_jerk_fits(speed, next, j, jump_per_tick);
    };
    const double cap = std::sqrt(0.5 * j * dt / curvature_jump);
    v = std::fmin(v, fits(cap) ? cap : detail::largest_fitting(0, cap, fits));
    if (half_angle_sin > tangent_continuity && detail::line_beside_raised_curve(previous, next, j)) {
      // A kink beside the jump: X + w J <= c in units of j (detail::kink_beside_curvature_jump),
      // X = 2 v sin(θ/2)/Δt², J = v²|Δ(κN)|/Δt: the positive root of a v² + b v = c with
      // a = w |Δ(κN)|/(Δt j), b = 2 sin(θ/2)/(Δt² j).
      const double a = detail::kink_beside_curvature_jump.jump_weight * jump_per_tick / j;
      const double b = 2 * half_angle_sin / (j * dt * dt);
      const double c = detail::kink_beside_curvature_jump.room;
      v = std::fmin(v, 2 * c / (b + std::sqrt(b * b + 4 * a * c)));
    }
  }
  return v;
}

/// The junction speed of junction_speed_caps_apart capped by both segments' speed caps.
[[nodiscard]] inline double junction_speed(const SegmentPlan& previous, const SegmentPlan& next, const MachineLimits& machine) noexcept {
  return std::fmin(std::fmin(previous.limits.speed_cap_mm_per_s, next.limits.speed_cap_mm_per_s),
                   junction_speed_caps_apart(previous, next, machine));
}

}  // namespace curvestep
