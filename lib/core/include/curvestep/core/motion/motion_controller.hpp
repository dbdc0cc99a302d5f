// SPDX-License-Identifier: MIT
// MotionController: segment queue + look-ahead planner + fixed-rate interpolator, with feed hold,
// resume and abort. The same code runs in the host simulator and in the firmware.
//
//   push segments ─► queue (Capacity) ─► plan: length, caps, junction speed (once, at push)
//                                     └► per segment start: exit speed by a backward pass over the
//                                        next lookahead_window() segments ─► S-curve profile ─► per tick:
//                                        t → s (profile) → u (arc-length table) → p(u) → setpoint
//                                        (exactly at chunk ends, forward-differenced in between)
//
// Determinism: a segment's exit speed depends only on the segment and the W segments after it (or
// the end of the job), never on how many happened to be queued: the window ends with a stop,
// whether the job ends there or not. W is the run-time window (set_lookahead, 1..Lookahead,
// default Lookahead), so the setpoints are a function of the job, the machine and W alone: a
// controller with set_lookahead(W) gives exactly those of any controller with window W (e.g. a
// smaller queue with Lookahead = W), and a firmware whose queue is kept at least W deep produces
// exactly the simulator's setpoints with the same W; all planning arithmetic is +, −, ×, ÷ and sqrt
// in IEEE double, which rounds identically on every target, and positions are quantised to the
// position scalar (Q16.16 in fixed-point builds) only at the output.
// Time is tick / rate_hz; segment boundaries fall between ticks and the remainder carries over,
// so speed is continuous across segments. The last setpoint of a job is its end point exactly.
// Feed hold brakes along the path (possibly into later segments) within the limits; resume plans
// the rest of the segment from rest; abort stops at once and flushes the queue.
// A segment pushed with a JointStop (joint_stop.hpp) is entered from rest: the junction speed into
// it is 0, and with rest_ticks the setpoints stay at the joint for that many ticks, labelled with
// the segment, while the clock that drives the profiles stands still (time_now() counts motion
// ticks only), so the motion after a rest is bit for bit the motion without it, later by rest_ticks.
//
// Feed and rapid override (set_override, feed_override.hpp): scales the programmed speeds, never a
// machine or geometric cap. A new override takes effect at once while stopped, on start and resume,
// and while moving at the first tick not inside a chunk whose profile acceleration is 0 (a cruise,
// or a segment's start) where the rest of the segment can be re-planned from that state with it:
// slowing down to a lower cap must fit in the rest of the segment, and the exit speed the window
// gives must be reachable. Until then the plan follows the override in effect. The rule is a pure
// function of the ticks at which overrides are set, so `sim --override-at` replays a device.
//
// Per-tick work (docs/motion.md, "Per-tick work"): ticks are stepped in chunks from a quintic
// Hermite between exact evaluations, or evaluated exactly (chunk_interpolator.hpp).
// Budget per tick: a stepped tick is 15 additions, the profile's speed (a quadratic) and the
// quantisation; a chunk end costs a plan: 2 to 4 exact evaluations (profile, table search, de
// Casteljau) and 2 derivatives, plus up to 3 evaluations and 2 derivatives per halving (at most
// ~25 evaluations, ~40 000 host instructions, from 256 down to 2). The tick that starts a segment
// (its arc-length table, ~200 000) stays the worst case.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include <curvestep/core/container/ring_buffer.hpp>
#include <curvestep/core/motion/chunk_interpolator.hpp>
#include <curvestep/core/motion/hermite_chunk.hpp>
#include <curvestep/core/motion/path_length_table.hpp>
#include <curvestep/core/motion/controller_state.hpp>
#include <curvestep/core/motion/cusps.hpp>
#include <curvestep/core/motion/feed_override.hpp>
#include <curvestep/core/motion/joint_stop.hpp>
#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/core/motion/path_segment.hpp>
#include <curvestep/core/motion/segment_plan.hpp>
#include <curvestep/core/motion/setpoint.hpp>
#include <curvestep/core/motion/velocity_profile.hpp>

namespace curvestep {

/// Queue, planner and interpolator for one machine. S is the position scalar of the setpoints.
template <Scalar S, std::size_t QueueCapacity = 32, std::size_t Lookahead = 16, std::size_t TableIntervals = 64>
class MotionController {
  static_assert(Lookahead >= 1 && Lookahead < QueueCapacity, "the look-ahead window must fit in the queue");

 public:
  /// The largest look-ahead window (segments); the window in use is lookahead_window().
  static constexpr std::size_t lookahead = Lookahead;

  /// Sets the look-ahead window: the number of queued segments after the current one that its exit
  /// speed (and a feed hold's limits) consider, 1..Lookahead (default Lookahead). The setpoints
  /// depend on the window, not on the queue's capacity. InvalidArgument outside 1..Lookahead;
  /// InvalidState while moving. Kept by reset().
  [[nodiscard]] Result<void> set_lookahead(std::size_t window) noexcept {
    if (!stopped()) return fail(Error::InvalidState);
    if (window < 1 || window > Lookahead) return fail(Error::InvalidArgument);
    lookahead_ = window;
    return ok();
  }
  [[nodiscard]] std::size_t lookahead_window() const noexcept { return lookahead_; }

  /// Extends the window by distance: past lookahead_window() segments, more queued segments (up to
  /// Lookahead) join it until their lengths add up to `distance_mm`, so short segments never hide
  /// the braking distance. 0 (the default) turns it off; the setpoints then depend on the count
  /// window alone, as a firmware's do. With it on, they depend on the job, the machine, the window
  /// and the distance (a pure function of the queued segments' lengths, bit for bit everywhere).
  /// InvalidArgument for a negative or non-finite distance; InvalidState while moving.
  [[nodiscard]] Result<void> set_lookahead_distance(double distance_mm) noexcept {
    if (!stopped()) return fail(Error::InvalidState);
    if (!(distance_mm >= 0) || !(distance_mm < 1e300)) return fail(Error::InvalidArgument);
    lookahead_distance_mm_ = distance_mm;
    return ok();
  }
  [[nodiscard]] double lookahead_distance_mm() const noexcept { return lookahead_distance_mm_; }

  /// Sets the feed and rapid override (percent of the programmed speeds). While stopped it takes
  /// effect at once; while moving it is requested and takes effect at the first tick where the
  /// rest of the segment can be re-planned with it (see the top of this file), at the latest on the
  /// next resume. InvalidArgument outside FeedOverride's ranges. Kept by reset().
  [[nodiscard]] Result<void> set_override(FeedOverride requested) noexcept {
    if (!requested.valid()) return fail(Error::InvalidArgument);
    requested_override_ = requested;
    if (stopped()) take_override();
    return ok();
  }
  /// The override the plan follows now.
  [[nodiscard]] FeedOverride override_in_effect() const noexcept { return override_; }
  /// The override last set (in effect, or waiting for a point where it can take effect).
  [[nodiscard]] FeedOverride requested_override() const noexcept { return requested_override_; }
  /// The tick of the first setpoint planned with the override in effect.
  [[nodiscard]] std::uint64_t override_tick() const noexcept { return override_tick_; }

  /// Sets the machine. InvalidLimit/InvalidRate from MachineLimits::validate; InvalidState while moving.
  [[nodiscard]] Result<void> configure(const MachineLimits& machine) noexcept {
    if (!stopped()) return fail(Error::InvalidState);
    CURVESTEP_CHECK(machine.validate());
    machine_ = machine;
    configured_ = true;
    return ok();
  }

  /// Queues a segment, planning its length, caps and the junction speed from the previous one
  /// (0 with an exact stop in `entry`, whose rest_ticks then come before the segment). A
  /// Bézier with cusps is queued as its pieces between the cusps (each needs a queue slot).
  /// QueueFull when there is no room (retry after setpoints drain it), ConfigurationMissing before
  /// configure, InvalidState after end_of_job or abort, DegenerateCurve/InvalidLimit from the analysis.
  [[nodiscard]] Result<void> try_push(const PathSegment& segment, std::uint32_t job_index, JointStop entry = {}) noexcept {
    if (!configured_) return fail(Error::ConfigurationMissing);
    if (end_of_job_ || state_ == ControllerState::Aborted || state_ == ControllerState::Fault) return fail(Error::InvalidState);
    const auto cusps = find_cusps(segment);
    if (queue_.available() < cusps.count + 1) return fail(Error::QueueFull);
    // Split in place, piece by piece (no array of pieces on the stack). With cusps, a first pass
    // plans every piece without queueing, so that an error leaves the queue as it was; the
    // second pass computes the same pieces and plans again (deterministic) and queues them.
    if (cusps.count > 0) CURVESTEP_CHECK(push_pieces(segment, cusps, job_index, entry, false));
    CURVESTEP_CHECK(push_pieces(segment, cusps, job_index, entry, true));
    if (state_ == ControllerState::Finished) state_ = ControllerState::Idle;
    return ok();
  }

  /// No more segments will come: the last queued one ends the job with a stop, then the machine
  /// rests `final_rest_ticks` ticks at its end (a G4 dwell after the job's last move): setpoints at
  /// the end point, speed 0, labelled with the last segment's job index + 1 (the joint "after" it).
  void end_of_job(std::uint32_t final_rest_ticks = 0) noexcept {
    end_of_job_ = true;
    final_rest_ticks_ = final_rest_ticks;
  }

  /// Starts moving from the first queued segment. NothingQueued, ConfigurationMissing, InvalidState.
  [[nodiscard]] Result<void> start() noexcept {
    if (!configured_) return fail(Error::ConfigurationMissing);
    if (state_ != ControllerState::Idle) return fail(Error::InvalidState);
    if (queue_.empty()) return fail(Error::NothingQueued);
    CURVESTEP_CHECK(begin_segment(0, 0, 0));
    rest_left_ = queue_.front().rest_ticks;
    rest_position_ = front().segment.start();
    // A job's setpoints depend only on the job: the chunk adaptation starts afresh.
    chunks_.restart_adaptation();
    state_ = ControllerState::Running;
    return ok();
  }

  /// Feed hold: brake to a stop along the path within the limits. Ignored unless running.
  void hold() noexcept {
    if (state_ != ControllerState::Running) return;
    if (rest_left_ > 0 || final_rest_left_ > 0) return hold_at_rest();
    state_ = ControllerState::Holding;
    begin_stop();
  }

  /// Continues after a hold or a starved queue: the rest of the segment is planned from rest.
  [[nodiscard]] Result<void> resume() noexcept {
    if (state_ != ControllerState::Held && state_ != ControllerState::Starved) return fail(Error::InvalidState);
    if (queue_.empty()) return fail(Error::NothingQueued);
    if (state_ == ControllerState::Starved) {
      if (queue_.size() < 2) return fail(Error::NothingQueued);
      queue_.pop_front();
      CURVESTEP_CHECK(begin_segment(0, 0, time_now()));
      rest_left_ = queue_.front().rest_ticks;
      rest_position_ = last_position_;
    } else {
      CURVESTEP_CHECK(begin_segment(hold_base_mm_, 0, time_now()));
    }
    state_ = ControllerState::Running;
    return ok();
  }

  /// Stops at once (no braking) and flushes the queue.
  void abort() noexcept {
    queue_.clear();
    rest_left_ = 0;
    final_rest_left_ = 0;
    hold_deferred_ = false;
    state_ = ControllerState::Aborted;
  }

  /// Back to Idle after Finished or Aborted, keeping the configuration (a new job).
  void reset() noexcept {
    queue_.clear();
    state_ = ControllerState::Idle;
    hold_deferred_ = false;
    end_of_job_ = false;
    final_rest_ticks_ = 0;
    final_rest_left_ = 0;
    has_previous_ = false;
    tick_ = 0;
    override_ = requested_override_;
    override_tick_ = 0;
    rested_ticks_ = 0;
    rest_left_ = 0;
    chunks_.reset();
  }

  /// The next setpoint (one tick). InvalidState when idle, finished, aborted or faulted.
  /// Holding, Held and Starved produce setpoints that stay on the path (speed 0 once stopped).
  [[nodiscard]] Result<Setpoint<S>> next_setpoint() noexcept {
    chunks_.note_exact();
    switch (state_) {
      case ControllerState::Running: return running_tick();
      case ControllerState::Holding: return holding_tick();
      case ControllerState::Held:
      case ControllerState::Starved: return emit(last_position_, 0, last_segment_);
      default: return fail(Error::InvalidState);
    }
  }

  [[nodiscard]] ControllerState state() const noexcept { return state_; }
  /// True if the next setpoint would be the last of everything queued before the job's end is
  /// known (it would leave the controller Starved): a caller with more to queue for that joint (the
  /// App's machine events, firmware/app.hpp) may wait instead of ticking, at the setpoint before the
  /// end, where the plan (whose window ends at rest) is already at rest or within a tick of it;
  /// queueing the next segment then continues exactly as if it had been there all along.
  [[nodiscard]] bool next_tick_ends_queue() const noexcept {
    return state_ == ControllerState::Running && !end_of_job_ && queue_.size() == 1 && rest_left_ == 0 &&
           !chunks_.pending() && time_now() - origin_s_ >= profile_.duration_s();
  }
  [[nodiscard]] bool finished() const noexcept { return state_ == ControllerState::Finished; }
  /// The error that put the controller into Fault.
  [[nodiscard]] Failure fault() const noexcept { return fault_; }
  [[nodiscard]] std::size_t queued() const noexcept { return queue_.size(); }
  [[nodiscard]] static constexpr std::size_t queue_capacity() noexcept { return QueueCapacity; }
  [[nodiscard]] bool queue_full() const noexcept { return queue_.full(); }
  [[nodiscard]] std::uint64_t tick() const noexcept { return tick_; }
  /// True if the last setpoint was a tick of a rest at a joint (JointStop::rest_ticks).
  [[nodiscard]] bool resting() const noexcept { return last_was_rest_; }
  /// Ticks of rest so far in this job (the clock of the profiles is tick() minus these).
  [[nodiscard]] std::uint64_t rested_ticks() const noexcept { return rested_ticks_; }
  [[nodiscard]] const MachineLimits& machine() const noexcept { return machine_; }
  /// The profile of the segment being followed (for reports and tests).
  [[nodiscard]] const VelocityProfile& current_profile() const noexcept { return profile_; }

  /// Work of the interpolator so far (for tests and benchmarks; reset() clears it).
  using InterpolatorStats = curvestep::InterpolatorStats;
  [[nodiscard]] const InterpolatorStats& interpolator_stats() const noexcept { return chunks_.stats(); }
  /// The length in ticks of the chunk the last setpoint was stepped in, 1 if it was evaluated
  /// exactly (tests check each stepped setpoint against chunk_error_bound of its chunk).
  [[nodiscard]] std::uint32_t last_chunk_ticks() const noexcept { return chunks_.last_ticks(); }

  // What a PieceRecorder (piece_recorder.hpp) needs to hand the stream to a PieceExecutor:
  /// The unrounded position (mm) of the last setpoint.
  [[nodiscard]] const MachinePoint& last_unrounded_position() const noexcept { return last_position_; }
  /// True if a chunk begins at the last setpoint: its next chunk_ticks() setpoints are the chunk's
  /// (chunk_ticks() - 1 stepped from chunk_controls(), relative to the last setpoint, then
  /// chunk_end_position() exactly).
  [[nodiscard]] bool chunk_begins_at_last_setpoint() const noexcept { return chunks_.began_before(tick_); }
  [[nodiscard]] std::uint32_t chunk_ticks() const noexcept { return chunks_.ticks(); }
  [[nodiscard]] const HermiteChunk::Controls& chunk_controls() const noexcept { return chunks_.controls(); }
  [[nodiscard]] const MachinePoint& chunk_end_position() const noexcept { return chunks_.end_position(); }

  /// Longest chunk in ticks (a power of two, 1..HermiteChunk::max_ticks, the default). 1 evaluates
  /// the path exactly at every tick (the reference the stepped stream is tested against).
  /// InvalidArgument otherwise; InvalidState while moving.
  [[nodiscard]] Result<void> set_max_chunk_ticks(std::uint32_t ticks) noexcept {
    if (!stopped()) return fail(Error::InvalidState);
    if (ticks == 0 || ticks > HermiteChunk::max_ticks || (ticks & (ticks - 1)) != 0) return fail(Error::InvalidArgument);
    chunks_.set_max_ticks(ticks);
    return ok();
  }
  [[nodiscard]] std::uint32_t max_chunk_ticks() const noexcept { return chunks_.max_ticks(); }

 private:
  /// What the queue keeps of a SegmentPlan (the end tangents and curvatures are needed only for
  /// the junction with the next pushed segment: previous_plan_).
  struct QueuedPlan {
    double length_mm = 0;    ///< arc length
    ProfileLimits limits{};  ///< caps for the segment's speed profile at 100 % override
    OverridableCaps caps{};  ///< what an override scales (limits_under)
  };

  /// A queue slot: the segment in compact form (PathSegment::compact; front() expands it).
  struct Entry {
    CompactSegment segment{};
    QueuedPlan plan{};
    double junction_apart = 0;    ///< speed cap at the joint into this segment, apart from the segments' caps
    std::uint32_t job_index = 0;  ///< the segment's index in the job
    std::uint32_t serial = 0;     ///< push count, identifies the slot's content for front()
    std::uint32_t rest_ticks = 0; ///< ticks of rest at the joint into this segment (JointStop)
  };

  /// The front entry, its segment expanded to a PathSegment (once per entry, cached in current_).
  struct Front {
    const PathSegment& segment;
    const QueuedPlan& plan;
    std::uint32_t job_index;
  };

  /// Plans the pieces of `segment` between its cusps (split in place) and, if `commit`, queues
  /// them. The pieces and plans are those of splitting at each cusp in turn.
  template <class Cusps>
  [[nodiscard]] Result<void> push_pieces(const PathSegment& segment, const Cusps& cusps, std::uint32_t job_index,
                                         JointStop entry, bool commit) noexcept {
    SegmentPlan previous = previous_plan_;
    bool has_previous = has_previous_;
    if (cusps.count == 0) {
      CURVESTEP_CHECK(push_piece(segment, job_index, entry, previous, has_previous, commit));
    } else {
      PathSegment rest = segment;
      PathSegment piece;
      double consumed = 0;  // the parameter of `rest`'s start on the original segment
      for (std::size_t i = 0; i < cusps.count; ++i) {
        CURVESTEP_CHECK(rest.split_off((cusps.parameters[i] - consumed) / (1 - consumed), piece));
        CURVESTEP_CHECK(push_piece(piece, job_index, i == 0 ? entry : JointStop{}, previous, has_previous, commit));
        consumed = cusps.parameters[i];
      }
      CURVESTEP_CHECK(push_piece(rest, job_index, JointStop{}, previous, has_previous, commit));
    }
    if (commit) {
      previous_plan_ = previous;
      has_previous_ = true;
    }
    return ok();
  }

  /// Plans one piece after `previous` (updated) and, if `commit`, queues it (room checked by try_push).
  [[nodiscard]] Result<void> push_piece(const PathSegment& piece, std::uint32_t job_index, JointStop entry, SegmentPlan& previous,
                                        bool& has_previous, bool commit) noexcept {
    CURVESTEP_TRY(const SegmentPlan plan, plan_piece(piece, job_index));
    const bool passed_moving = has_previous && !entry.at_rest();
    if (commit) enqueue(piece, plan, passed_moving ? junction_speed_caps_apart(previous, plan, machine_) : 0, job_index, entry.rest_ticks);
    previous = plan;
    has_previous = true;
    return ok();
  }

  /// Queues a planned piece (its own frame: the entry is not on the stack while planning).
  [[gnu::noinline]] void enqueue(const PathSegment& piece, const SegmentPlan& plan, double junction, std::uint32_t job_index,
                                 std::uint32_t rest_ticks) noexcept {
    const Entry entry{piece.compact(), QueuedPlan{plan.length_mm, plan.limits, plan.caps}, junction, job_index, ++pushed_serial_, rest_ticks};
    [[maybe_unused]] const bool pushed = queue_.try_push(entry);
  }

  /// The plan of one piece; its path-length table (1 KiB) lives only while this runs, not while
  /// the queue entry is built.
  [[nodiscard]] Result<SegmentPlan> plan_piece(const PathSegment& piece, std::uint32_t job_index) const noexcept {
    const auto table = PathLengthTable<TableIntervals>::build(piece);
    if (!table) return table.failure();
    auto plan = plan_segment(piece, table.value(), machine_);
    if (!plan) return fail(plan.error(), job_index);
    return plan;
  }

  [[nodiscard]] bool stopped() const noexcept {
    return state_ == ControllerState::Idle || state_ == ControllerState::Finished || state_ == ControllerState::Aborted ||
           state_ == ControllerState::Fault;
  }
  [[nodiscard]] Front front() const {
    const Entry& e = queue_.front();
    if (e.serial != expanded_serial_) {
      current_ = PathSegment::expand(e.segment).value();  // compact() of a valid PathSegment: cannot fail
      expanded_serial_ = e.serial;
    }
    return Front{current_, e.plan, e.job_index};
  }
  /// The profiles' clock: motion ticks only (rests stop it), so a rest shifts what follows by whole ticks.
  [[nodiscard]] double time_now() const noexcept { return static_cast<double>(tick_ - rested_ticks_) / machine_.rate_hz; }

  /// The highest exit speed of the front segment when entered at v0: a backward pass over the
  /// next lookahead_ segments, whose window always ends at rest.
  /// The segments after the front that the window covers: lookahead_ of them (or all queued), and
  /// with a look-ahead distance as many more (up to Lookahead) as it takes to cover that distance.
  [[nodiscard]] std::size_t window_size() const noexcept {
    const std::size_t after = queue_.size() - 1;
    std::size_t window = after < lookahead_ ? after : lookahead_;
    if (lookahead_distance_mm_ > 0) {
      double covered = 0;
      for (std::size_t m = 1; m <= window; ++m) covered += queue_[m].plan.length_mm;
      while (covered < lookahead_distance_mm_ && window < after && window < Lookahead) covered += queue_[++window].plan.length_mm;
    }
    return window;
  }

  /// The limits of queued segment `e` under override `o` (entered at `entry_mm_per_s`).
  [[nodiscard]] static ProfileLimits limits_under(const Entry& e, FeedOverride o, double entry_mm_per_s = 0) noexcept {
    return e.plan.caps.limits(e.plan.limits, o, entry_mm_per_s);
  }

  /// The speed cap at the joint into queue_[m] (m >= 1) under override `o`.
  [[nodiscard]] double junction_into(std::size_t m, FeedOverride o) const noexcept {
    return std::fmin(std::fmin(queue_[m - 1].plan.caps.speed_cap(o), queue_[m].plan.caps.speed_cap(o)), queue_[m].junction_apart);
  }

  /// The highest exit speed of the front segment (limits `front_limits`) when entered at v0 under
  /// override `o`.
  [[nodiscard]] double exit_speed(FeedOverride o, double v0, double remaining_mm, const ProfileLimits& front_limits) const noexcept {
    const std::size_t window = window_size();
    if (window == 0) return 0;
    double v = 0;  // the largest entry speed of segment m from which a stop by the window's end works
    for (std::size_t m = window; m >= 1; --m) {
      const ProfileLimits limits = limits_under(queue_[m], o);
      v = std::fmin(junction_into(m, o), reachable_speed(v, queue_[m].plan.length_mm, limits.speed_cap_mm_per_s, limits));
    }
    return std::fmin(v, reachable_speed(v0, remaining_mm, front_limits.speed_cap_mm_per_s, front_limits));
  }

  /// Starts following the front segment from arc length `offset` at speed v0 at time `origin`.
  [[nodiscard]] Result<void> begin_segment(double offset, double v0, double origin) noexcept {
    CURVESTEP_TRY(table_, PathLengthTable<TableIntervals>::build(front().segment));
    if (requested_override_ != override_ && override_fits(v0, table_.length() - offset)) take_override();
    return plan_rest(offset, v0, origin);
  }

  /// Plans the rest of the front segment, from arc length `offset` at speed v0 (acceleration 0) at
  /// time `origin`, under the override in effect (from above its cap: slowing down first).
  [[nodiscard]] Result<void> plan_rest(double offset, double v0, double origin) noexcept {
    chunks_.drop();
    offset_mm_ = offset;
    origin_s_ = origin;
    const double remaining = table_.length() - offset;
    if (!(remaining > 1e-12)) {
      profile_ = VelocityProfile{};
      return ok();
    }
    const ProfileLimits limits = limits_under(queue_.front(), override_, v0);
    const double v1 = exit_speed(override_, v0, remaining, limits);
    // Entered faster than the override's caps or exit allow (it was lowered): only slow down.
    const bool too_fast = v0 > limits.speed_cap_mm_per_s ||
                          (v1 < v0 && speed_change_distance(v1, v0, limits) > remaining * (1 + 1e-9) + 1e-12);
    auto profile = too_fast ? VelocityProfile::slow_down(remaining, v0, v1, limits) : VelocityProfile::plan(remaining, v0, v1, limits);
    if (!profile) return fail(profile.error(), front().job_index);
    if (too_fast && v0 <= limits.speed_cap_mm_per_s) {
      // Slowing down "as far as it goes" must not pass the next joint faster than its cap (a corner,
      // or the window's end at rest): where v1 is out of reach only because a stop is shorter than a
      // partial slow-down (highest_reachable_slower), end slower than v1 instead.
      const double joint_cap = window_size() == 0 ? 0.0 : junction_into(1, override_);
      if (profile.value().exit_speed() > joint_cap) {
        const double slower = highest_reachable_slower(v0, std::fmin(v1, joint_cap), remaining * (1 + 1e-9) + 1e-12, limits);
        if (slower >= 0) {
          if (auto stop_first = VelocityProfile::plan(remaining, v0, slower, limits)) profile = stop_first;
        }
      }
    }
    profile_ = profile.value();
    return ok();
  }

  /// True if the requested override can take effect at speed v0 (acceleration 0) with `remaining`
  /// mm of the front segment left. Caps only: the plan so far stays within what the new caps
  /// allow, or slows down to them (plan_rest, VelocityProfile::slow_down) segment after segment,
  /// as fast as the plan so far could brake for its corners. Raising the feed above 100 % from at
  /// most 100 % also lowers the acceleration of curved segments (OverridableCaps): that must let
  /// the exit speed of the new window be reached within this segment.
  [[nodiscard]] bool override_fits(double v0, double remaining) const noexcept {
    const bool slower_braking = override_.feed_percent <= 100 && requested_override_.feed_percent > 100;
    if (!slower_braking || !(remaining > 1e-12)) return true;
    const ProfileLimits limits = limits_under(queue_.front(), requested_override_, v0);
    const double v1 = exit_speed(requested_override_, v0, remaining, limits);
    return v1 >= v0 || speed_change_distance(v1, v0, limits) <= remaining;
  }

  void take_override() noexcept {
    override_ = requested_override_;
    override_tick_ = tick_;
  }

  /// True if a requested override may take effect at segment time tau: following the plan (not
  /// braking for a hold), inside the profile, at zero acceleration.
  [[nodiscard]] bool override_due(double tau) const noexcept {
    return requested_override_ != override_ && !hold_deferred_ && profile_.phase_count() > 0 && tau < profile_.duration_s() &&
           profile_.at(tau).acceleration_mm_per_s2 == 0;
  }

  /// At segment time tau (override_due): re-plans the rest of the segment under the requested
  /// override from the present state if it fits there; the setpoint of this tick is unchanged.
  [[nodiscard]] Result<void> take_override_here(double tau) noexcept {
    const MotionState m = profile_.at(tau);
    const double offset = offset_mm_ + m.distance_mm;
    if (!override_fits(m.speed_mm_per_s, table_.length() - offset)) return ok();
    take_override();
    return plan_rest(offset, m.speed_mm_per_s, time_now());
  }

  [[nodiscard]] Result<Setpoint<S>> running_tick() noexcept {
    if (chunks_.pending()) {
      // Inside a chunk: no segment or phase boundary until its end (ChunkInterpolator::plan made sure).
      const double tau = time_now() - origin_s_;
      if (chunks_.steps(tick_)) {
        const MachinePoint stepped = chunks_.step();
        return emit(stepped, chunks_.stepped_speed(profile_, tau), front().job_index);
      }
      PathTickState end = chunks_.finish();  // evaluated exactly when the chunk was planned
      if (!override_due(tau)) {
        chunks_.plan(motion(), tick_, tau, end, machine_);
        return emit(end.position, end.speed_mm_per_s, front().job_index);
      }
      // An override may take effect here: the exact path below evaluates this tick again (the same bits).
    }
    if (final_rest_left_ > 0) return final_rest_tick();
    if (rest_left_ > 0) return rest_tick();
    const double t = time_now();
    double tau = t - origin_s_;
    while (tau >= profile_.duration_s()) {
      if (queue_.size() > 1) {
        const double exit = profile_.exit_speed();
        origin_s_ += profile_.duration_s();
        const MachinePoint joint = front().segment.end();
        queue_.pop_front();
        if (auto started = begin_segment(0, exit, origin_s_); !started) return fault(started.failure());
        if (queue_.front().rest_ticks > 0) {  // the rest begins at the first tick past the joint
          rest_left_ = queue_.front().rest_ticks;
          rest_position_ = joint;
          return rest_tick();
        }
        tau = t - origin_s_;
        continue;
      }
      // Last queued segment done: the job's end (exactly) or a starved queue.
      const MachinePoint end = front().segment.end();
      last_segment_ = front().job_index;
      if (end_of_job_ && final_rest_ticks_ > 0) {  // the rest follows at the end point, then Finished
        final_rest_left_ = final_rest_ticks_;
        final_rest_ticks_ = 0;
        rest_position_ = end;
        final_rest_label_ = last_segment_ + 1;
      } else if (end_of_job_) {
        queue_.pop_front();
        state_ = ControllerState::Finished;
      } else {
        hold_base_mm_ = table_.length();
        state_ = ControllerState::Starved;
      }
      return emit(end, 0, last_segment_);
    }
    if (override_due(tau)) {
      if (auto taken = take_override_here(tau); !taken) return fault(taken.failure());
      tau = t - origin_s_;
    }
    const SegmentMotion<TableIntervals> front_motion = motion();
    PathTickState now = chunks_.exact_state(front_motion, tau);
    chunks_.plan(front_motion, tick_, tau, now, machine_);
    return emit(now.position, now.speed_mm_per_s, front().job_index);
  }

  /// The front segment as the interpolator follows it.
  [[nodiscard]] SegmentMotion<TableIntervals> motion() const noexcept {
    return SegmentMotion<TableIntervals>{front().segment, table_, profile_, offset_mm_, origin_s_, rested_ticks_, machine_.rate_hz};
  }

  /// Held during a rest at a joint: the machine stands already; resume serves the rest of the rest first.
  void hold_at_rest() noexcept {
    hold_deferred_ = false;
    hold_base_mm_ = 0;
    state_ = ControllerState::Held;
  }

  /// Brakes from the present state of the plan, or, if that stop would pass a joint faster than its
  /// junction speed (a stop begun while the plan slows for a corner needs more room than the plan
  /// leaves), keeps following the plan (hold_deferred_) and tries again where the next segment begins.
  void begin_stop() noexcept {
    const auto now = profile_.at(time_now() - origin_s_);
    ProfileLimits limits = limits_under(queue_.front(), override_, now.speed_mm_per_s);
    const std::size_t window = window_size();
    for (std::size_t i = 1; i <= window; ++i) {
      const ProfileLimits next = limits_under(queue_[i], override_);
      limits.acceleration_mm_per_s2 = std::fmin(limits.acceleration_mm_per_s2, next.acceleration_mm_per_s2);
      limits.jerk_mm_per_s3 = std::fmin(limits.jerk_mm_per_s3, next.jerk_mm_per_s3);
    }
    const VelocityProfile stop = VelocityProfile::stop(now.speed_mm_per_s, now.acceleration_mm_per_s2, limits);
    hold_deferred_ = !stop_respects_joints(stop, profile_.length_mm() - now.distance_mm);
    if (hold_deferred_) return;
    hold_profile_ = stop;
    hold_base_mm_ = offset_mm_ + now.distance_mm;
    origin_s_ = time_now();
    chunks_.drop();
  }

  /// True if `stop`, begun `to_joint_mm` before the front segment's end, passes every queued joint
  /// no faster than its junction speed and comes to rest on the queued path.
  [[nodiscard]] bool stop_respects_joints(const VelocityProfile& stop, double to_joint_mm) const noexcept {
    double joint = to_joint_mm;
    for (std::size_t m = 1; m < queue_.size(); ++m) {
      if (joint >= stop.length_mm()) return true;  // at rest before this joint
      if (speed_at_distance(stop, joint) > junction_into(m, override_) * (1 + 1e-9) + 1e-9) return false;
      joint += queue_[m].plan.length_mm;
    }
    return joint >= stop.length_mm();
  }

  /// The speed of `profile` where it has covered `distance_mm` (bisection on time: the distance grows
  /// monotonically).
  [[nodiscard]] static double speed_at_distance(const VelocityProfile& profile, double distance_mm) noexcept {
    double low = 0;
    double high = profile.duration_s();
    for (int i = 0; i < 64; ++i) {
      const double middle = (low + high) / 2;
      if (profile.at(middle).distance_mm < distance_mm) {
        low = middle;
      } else {
        high = middle;
      }
    }
    return profile.at(high).speed_mm_per_s;
  }

  /// A hold that could not brake yet (begin_stop): the plan's own tick, and at the start of the next
  /// segment a new try; a rest at a joint holds there.
  [[nodiscard]] Result<Setpoint<S>> deferred_holding_tick() noexcept {
    const std::uint32_t serial = queue_.front().serial;
    state_ = ControllerState::Running;
    auto setpoint = running_tick();
    if (state_ != ControllerState::Running) {  // finished, starved or faulted on the way
      hold_deferred_ = false;
      return setpoint;
    }
    state_ = ControllerState::Holding;
    if (rest_left_ > 0 || final_rest_left_ > 0) {  // reached a rest: held there, as hold() at rest
      hold_at_rest();
    } else if (queue_.front().serial != serial) {
      begin_stop();
    }
    return setpoint;
  }

  [[nodiscard]] Result<Setpoint<S>> holding_tick() noexcept {
    if (hold_deferred_) return deferred_holding_tick();
    const double tau = time_now() - origin_s_;
    const MotionState m = hold_profile_.at(tau);
    double s = hold_base_mm_ + m.distance_mm;
    // The stop may run past the end of the segment: walk on along the queued path.
    while (s > table_.length() && queue_.size() > 1) {
      s -= table_.length();
      hold_base_mm_ -= table_.length();
      queue_.pop_front();
      CURVESTEP_TRY(table_, PathLengthTable<TableIntervals>::build(front().segment));
    }
    if (s > table_.length()) s = table_.length();
    if (tau >= hold_profile_.duration_s()) {
      hold_base_mm_ = s;
      state_ = ControllerState::Held;
    }
    return emit(front().segment.point(table_.parameter_at(s)), m.speed_mm_per_s, front().job_index);
  }

  /// One tick of a rest at a joint: the joint, speed 0, the segment after it; the clock stands still.
  [[nodiscard]] Result<Setpoint<S>> rest_tick() noexcept {
    --rest_left_;
    ++rested_ticks_;
    auto sp = emit(rest_position_, 0, front().job_index);
    last_was_rest_ = true;
    return sp;
  }

  /// One tick of the rest after the job's last move: its end point, speed 0; Finished after the last.
  [[nodiscard]] Result<Setpoint<S>> final_rest_tick() noexcept {
    --final_rest_left_;
    ++rested_ticks_;
    auto sp = emit(rest_position_, 0, final_rest_label_);
    last_was_rest_ = true;
    if (final_rest_left_ == 0) {
      queue_.pop_front();
      state_ = ControllerState::Finished;
    }
    return sp;
  }

  [[nodiscard]] Result<Setpoint<S>> emit(const MachinePoint& p, double speed, std::uint32_t segment) noexcept {
    last_was_rest_ = false;
    auto sp = make_setpoint<S>(p, tick_, speed, segment);
    if (!sp) return fault(sp.failure());
    last_position_ = p;
    last_segment_ = segment;
    ++tick_;
    return sp;
  }

  [[nodiscard]] Failure fault(Failure f) noexcept {
    fault_ = f;
    state_ = ControllerState::Fault;
    return f;
  }

  MachineLimits machine_{};
  bool configured_ = false;
  bool end_of_job_ = false;
  std::size_t lookahead_ = Lookahead;  ///< the look-ahead window in use (set_lookahead)
  double lookahead_distance_mm_ = 0;   ///< extends the window by distance (set_lookahead_distance), 0: off
  FeedOverride override_{};            ///< the override the plan follows
  FeedOverride requested_override_{};  ///< the override last set (set_override)
  std::uint64_t override_tick_ = 0;    ///< the first tick planned with override_
  ControllerState state_ = ControllerState::Idle;
  Failure fault_{Error::InvalidState, no_index};
  RingBuffer<Entry, QueueCapacity> queue_{};
  std::uint32_t pushed_serial_ = 0;          ///< serial of the last queued entry
  mutable std::uint32_t expanded_serial_ = 0;  ///< serial of the entry expanded in current_ (0: none)
  mutable PathSegment current_{};            ///< the front entry's segment, expanded
  SegmentPlan previous_plan_{};
  bool has_previous_ = false;
  PathLengthTable<TableIntervals> table_{};
  VelocityProfile profile_{};
  VelocityProfile hold_profile_{};
  double offset_mm_ = 0;
  double origin_s_ = 0;
  double hold_base_mm_ = 0;
  bool hold_deferred_ = false;      ///< holding, but following the plan to the next joint (begin_stop)
  std::uint64_t tick_ = 0;
  std::uint64_t rested_ticks_ = 0;  ///< ticks spent resting at joints (time_now() leaves them out)
  std::uint32_t rest_left_ = 0;     ///< ticks of the current rest still to come
  std::uint32_t final_rest_ticks_ = 0;  ///< the rest after the job's last move (end_of_job), not begun
  std::uint32_t final_rest_left_ = 0;   ///< ticks of that rest still to come once begun
  std::uint32_t final_rest_label_ = 0;  ///< the segment label of its setpoints (last job index + 1)
  MachinePoint rest_position_{};    ///< the joint of the current rest
  bool last_was_rest_ = false;      ///< the last setpoint was a rest tick (resting())
  MachinePoint last_position_{};
  std::uint32_t last_segment_ = 0;
  ChunkInterpolator<TableIntervals> chunks_{};  ///< exact evaluation and chunked stepping of the front segment
};

}  // namespace curvestep
