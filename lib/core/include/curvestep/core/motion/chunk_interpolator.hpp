// SPDX-License-Identifier: MIT
// ChunkInterpolator: the per-tick part of the MotionController (motion_controller.hpp). Given the
// segment being followed (SegmentMotion: curve, arc-length table, speed profile, clock), it
// evaluates the path exactly at a tick, or plans a chunk of ticks that are stepped from a quintic
// Hermite instead.
//
// Inside one profile phase of one segment the ticks are cut into chunks of N = 2^k <= max_ticks()
// ticks. At a chunk's end the path is evaluated exactly (position, velocity, acceleration); the
// ticks inside follow the quintic Hermite between the chunk's ends (hermite_chunk.hpp), stepped by
// 5 additions per axis. A chunk is used only if the Hermite is within chunk_error_bound(N)/4 of
// exact evaluations at its middle (and its quarters when it crosses a knot of the arc-length
// table); otherwise N is halved, down to the exact path. Every setpoint that is not stepped is the
// exact evaluation bit for bit. Budget: docs/motion.md, "Per-tick work".
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <curvestep/core/motion/hermite_chunk.hpp>
#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/core/motion/path_length_table.hpp>
#include <curvestep/core/motion/path_segment.hpp>
#include <curvestep/core/motion/velocity_profile.hpp>

namespace curvestep {

/// Work of the interpolator so far (for tests and benchmarks).
struct InterpolatorStats {
  std::uint64_t exact_evaluations = 0;  ///< exact path evaluations (exact ticks, chunk ends and checks)
  std::uint64_t stepped_ticks = 0;      ///< setpoints produced by forward differencing
  std::uint64_t chunks = 0;             ///< chunks of >= 2 ticks accepted
  std::uint64_t rejected_chunks = 0;    ///< chunk halvings because the midpoint check failed
};

/// The segment being followed, as the interpolator sees it: tick → segment time τ → distance s
/// (profile, from `offset_mm` on) → parameter u (arc-length table) → point p(u).
template <std::size_t TableIntervals>
struct SegmentMotion {
  const PathSegment& segment;
  const PathLengthTable<TableIntervals>& table;
  const VelocityProfile& profile;
  double offset_mm;            ///< arc length at which the profile starts
  double origin_s;             ///< the profiles' clock when it started
  std::uint64_t rested_ticks;  ///< ticks that do not advance the clock (rests at joints)
  double rate_hz;

  /// Segment time at `tick`.
  [[nodiscard]] double tau_at(std::uint64_t tick) const noexcept {
    return static_cast<double>(tick - rested_ticks) / rate_hz - origin_s;
  }
};

/// Exact evaluation and chunked stepping of the path, with the chunk length adapted to the path.
template <std::size_t TableIntervals>
class ChunkInterpolator {
 public:
  using Motion = SegmentMotion<TableIntervals>;

  /// Longest chunk in ticks (a power of two, 1..HermiteChunk::max_ticks; the caller checks).
  void set_max_ticks(std::uint32_t ticks) noexcept {
    max_ticks_ = ticks;
    preferred_ticks_ = ticks;
  }
  [[nodiscard]] std::uint32_t max_ticks() const noexcept { return max_ticks_; }

  /// A new job: the adaptation of the chunk length starts afresh.
  void restart_adaptation() noexcept {
    preferred_ticks_ = max_ticks_;
    retry_tick_ = 0;
    backoff_ticks_ = 1;
  }

  /// Back to no chunk, nothing cached, no work counted (the controller's reset()).
  void reset() noexcept {
    drop();
    begin_tick_ = no_chunk;
    retry_tick_ = 0;
    backoff_ticks_ = 1;
    stats_ = InterpolatorStats{};
  }

  /// The plan changed (a new profile or a stop): the chunk and the cached states no longer hold.
  void drop() noexcept {
    end_tick_ = no_chunk;
    for (auto& c : cache_) c.tick = no_chunk;
  }

  /// True while a chunk (or a kept exact state of the next tick) is pending.
  [[nodiscard]] bool pending() const noexcept { return end_tick_ != no_chunk; }
  /// True if `tick` lies inside the pending chunk (stepped), false at its end.
  [[nodiscard]] bool steps(std::uint64_t tick) const noexcept { return tick < end_tick_; }

  /// The next stepped position, and the profile's speed at segment time tau (in the chunk's phase).
  [[nodiscard]] MachinePoint step() noexcept {
    ++stats_.stepped_ticks;
    last_ticks_ = ticks_;
    return chunk_.next();
  }
  [[nodiscard]] double stepped_speed(const VelocityProfile& profile, double tau) const noexcept {
    return profile.state_in(span_, tau).speed_mm_per_s;
  }

  /// The pending chunk's end, evaluated exactly when it was planned; no chunk is pending after.
  [[nodiscard]] PathTickState finish() noexcept {
    end_tick_ = no_chunk;
    return end_state_;
  }

  /// Marks the next setpoint as not stepped (last_ticks() = 1 until a step).
  void note_exact() noexcept { last_ticks_ = 1; }

  /// The exact path at segment time tau: profile → arc-length table → curve (the position is what
  /// the per-tick exact evaluation gives, bit for bit); velocity and acceleration are added by
  /// add_derivatives() when a chunk needs them.
  [[nodiscard]] PathTickState exact_state(const Motion& motion, double tau) noexcept {
    ++stats_.exact_evaluations;
    const MotionState m = motion.profile.at(tau);
    const auto located = motion.table.locate(motion.offset_mm + m.distance_mm);
    PathTickState state;
    state.position = motion.segment.point(located.u);
    state.speed_mm_per_s = m.speed_mm_per_s;
    state.tau_s = tau;
    state.u = located.u;
    state.ds_du = located.ds_du;
    state.d2s_du2 = located.d2s_du2;
    return state;
  }

  /// At `tick` (segment time tau, exact state `start`, its velocity and acceleration added here if
  /// not yet known): plans the chunk of ticks tick+1 .. tick+N. N is the largest power of two
  /// <= the preferred length whose last tick is still in the profile phase of `tick` (so chunks
  /// never straddle a phase or segment boundary). The Hermite to the exact end state is compared
  /// with exact evaluations at N/2, N/4 and 3N/4 and N is halved (the middle becoming the end)
  /// until all are within chunk_error_bound(N)/4; with N = 2 failing, the exact state of the
  /// next tick is kept (a chunk of one tick). Exact states computed for a rejected chunk are
  /// cached for the next one. N never goes below the shortest chunk whose check is above the
  /// rounding of the exact evaluation (rounding_floor); when no chunk passes, the next attempt
  /// waits a back-off of 1, 2, 4, ... ticks (exact ticks meanwhile).
  void plan(const Motion& motion, std::uint64_t tick, double tau, PathTickState& start, const MachineLimits& machine) noexcept {
    if (max_ticks_ < 2 || motion.profile.phase_count() == 0 || tick < retry_tick_) return;
    const auto span = motion.profile.phase_span(tau);
    const std::uint64_t k0 = tick;
    std::uint32_t n = preferred_ticks_;
    while (n >= 2 && !(motion.tau_at(k0 + n) < span.end_s)) n /= 2;
    const double floor = rounding_floor(start.position);
    std::uint32_t shortest = 2;
    while (shortest < n && chunk_error_bound(shortest, machine) / 4 < floor) shortest *= 2;
    if (n < 2 || chunk_error_bound(n, machine) / 4 < floor) return;
    const bool limited = n < preferred_ticks_;
    if (!start.smooth) add_derivatives(motion, start, span);
    bool rejected = false;
    while (start.smooth) {
      const PathTickState end = state_at(motion, k0 + n, span, true);
      if (!end.smooth) break;
      const auto q = HermiteChunk::controls(start, end, static_cast<double>(n) / machine.rate_hz);
      const double allowed = chunk_error_bound(n, machine) / 4;
      // σ = 1/2 first (where a smooth path's error peaks), then 1/4 and 3/4.
      bool passed = deviation(HermiteChunk::at_half(q), state_at(motion, k0 + n / 2, span, false), start) <= allowed;
      // Inside one piece of the arc-length table the exact path is smooth and the Hermite's error
      // peaks at σ = 1/2 (a line's is a cubic in t, reproduced up to rounding). The table is only
      // C1 at its knots, so a chunk that crosses one is also checked at σ = 1/4 and 3/4.
      if (passed && n >= 4 && motion.segment.kind() != SegmentKind::Line && crosses_knot(start.u, end.u)) {
        passed = deviation(HermiteChunk::at_quarter(q), state_at(motion, k0 + n / 4, span, false), start) <= allowed &&
                 deviation(HermiteChunk::at_three_quarters(q), state_at(motion, k0 + 3 * (n / 4), span, false), start) <= allowed;
      }
      if (passed && chunk_.start(start.position, q, n)) {
        ++stats_.chunks;
        ticks_ = n;
        begin_tick_ = k0;
        controls_ = q;
        end_tick_ = k0 + n;
        end_state_ = end;
        span_ = span;
        backoff_ticks_ = 1;
        if (rejected) {
          preferred_ticks_ = n;
        } else if (!limited && n < max_ticks_) {
          preferred_ticks_ = 2 * n;
        }
        return;
      }
      ++stats_.rejected_chunks;
      rejected = true;
      if (n == 2) {
        // The exact state of the next tick is known: keep it (a chunk of one tick, nothing stepped).
        end_tick_ = k0 + 1;
        begin_tick_ = no_chunk;  // nothing stepped: no chunk begins here
        end_state_ = state_at(motion, k0 + 1, span, false);
        span_ = span;
        break;
      }
      if (n / 2 < shortest) break;
      n /= 2;
    }
    // No chunk passed: exact ticks for a while, then try again from the shortest chunk.
    preferred_ticks_ = shortest;
    retry_tick_ = k0 + backoff_ticks_;
    if (backoff_ticks_ < HermiteChunk::max_ticks) backoff_ticks_ *= 2;
  }

  [[nodiscard]] const InterpolatorStats& stats() const noexcept { return stats_; }
  /// The length in ticks of the chunk the last setpoint was stepped in, 1 if it was exact.
  [[nodiscard]] std::uint32_t last_ticks() const noexcept { return last_ticks_; }
  /// True if a chunk that steps its ticks began at the tick before `tick`.
  [[nodiscard]] bool began_before(std::uint64_t tick) const noexcept { return end_tick_ != no_chunk && begin_tick_ + 1 == tick; }
  /// N, the control points and the exact end of the chunk being stepped.
  [[nodiscard]] std::uint32_t ticks() const noexcept { return ticks_; }
  [[nodiscard]] const HermiteChunk::Controls& controls() const noexcept { return controls_; }
  [[nodiscard]] const MachinePoint& end_position() const noexcept { return end_state_.position; }

 private:
  static constexpr std::uint64_t no_chunk = ~std::uint64_t{0};

  /// Velocity and acceleration of the exact path for a state from exact_state(), by the
  /// chain rule through the profile (ṡ, s̈ of the phase `span`) and the table's s(u):
  /// u̇ = ṡ / S'(u), ü = (s̈ - S''(u) u̇²) / S'(u), ẋ = p' u̇, ẍ = p'' u̇² + p' ü.
  static void add_derivatives(const Motion& motion, PathTickState& state, const VelocityProfile::PhaseSpan& span) noexcept {
    state.smooth = false;
    if (!(state.ds_du > 0)) return;  // a cusp end: |p'| = 0
    const MotionState m = motion.profile.state_in(span, state.tau_s);
    const double du = m.speed_mm_per_s / state.ds_du;
    const double ddu = (m.acceleration_mm_per_s2 - state.d2s_du2 * du * du) / state.ds_du;
    const MachinePoint d1 = motion.segment.derivative(state.u, 1);
    const MachinePoint d2 = motion.segment.derivative(state.u, 2);
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      state.velocity[axis] = d1[axis] * du;
      state.acceleration[axis] = d2[axis] * (du * du) + d1[axis] * ddu;
      if (!std::isfinite(state.velocity[axis]) || !std::isfinite(state.acceleration[axis])) return;
    }
    state.smooth = true;
  }

  /// True if u0 < u1 lie in different pieces of the arc-length table.
  [[nodiscard]] static bool crosses_knot(double u0, double u1) noexcept {
    constexpr double intervals = static_cast<double>(TableIntervals);
    return std::floor(u0 * intervals) != std::floor(u1 * intervals);
  }

  /// Largest per-axis |(x0 + offset) - exact| with x0 = start's position.
  [[nodiscard]] static double deviation(const MachinePoint& offset, const PathTickState& exact, const PathTickState& start) noexcept {
    double worst = 0;
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      worst = std::fmax(worst, std::fabs(offset[axis] - (exact.position[axis] - start.position[axis])));
    }
    return worst;
  }

  /// The exact state at `tick` (in phase `span` of the current segment), from the cache of states
  /// evaluated while planning, or evaluated now and cached; with velocity and acceleration if asked.
  [[nodiscard]] PathTickState state_at(const Motion& motion, std::uint64_t tick, const VelocityProfile::PhaseSpan& span,
                                       bool derivatives) noexcept {
    CachedState* slot = nullptr;
    for (auto& c : cache_) {
      if (c.tick == tick) {
        slot = &c;
        break;
      }
    }
    if (slot == nullptr) {
      slot = &cache_[0];  // replace the oldest (the smallest tick, often already passed)
      for (auto& c : cache_) {
        if (c.tick == no_chunk || (slot->tick != no_chunk && c.tick < slot->tick)) slot = &c;
      }
      slot->tick = tick;
      slot->state = exact_state(motion, motion.tau_at(tick));
    }
    if (derivatives && !slot->state.smooth) add_derivatives(motion, slot->state, span);
    return slot->state;
  }

  /// The rounding level of an exact evaluation near `p` (2^-48 of its largest coordinate, at
  /// least 2^-48 mm): a chunk whose check would be tighter than that is not attempted.
  [[nodiscard]] static double rounding_floor(const MachinePoint& p) noexcept {
    double largest = 1;
    for (std::size_t axis = 0; axis < motion_axes; ++axis) largest = std::fmax(largest, std::fabs(p[axis]));
    return largest * 0x1p-48;
  }

  struct CachedState {
    std::uint64_t tick = no_chunk;  ///< no_chunk: empty
    PathTickState state{};
  };

  std::uint32_t max_ticks_ = HermiteChunk::max_ticks;
  std::uint32_t preferred_ticks_ = HermiteChunk::max_ticks;
  std::uint64_t end_tick_ = no_chunk;    ///< the pending chunk's last tick (no_chunk: none)
  std::uint32_t ticks_ = 1;              ///< N of the chunk being stepped
  std::uint64_t begin_tick_ = no_chunk;  ///< the tick the chunk being stepped began at
  HermiteChunk::Controls controls_{};    ///< its control points
  std::uint32_t last_ticks_ = 1;         ///< N of the chunk of the last setpoint (1: exact)
  std::uint64_t retry_tick_ = 0;         ///< no chunk is planned before this tick (back-off)
  std::uint32_t backoff_ticks_ = 1;      ///< the next back-off after a failed plan
  HermiteChunk chunk_{};
  std::array<CachedState, 2> cache_{};   ///< exact states of future ticks (plan)
  PathTickState end_state_{};
  VelocityProfile::PhaseSpan span_{};
  InterpolatorStats stats_{};
};

}  // namespace curvestep
