// SPDX-License-Identifier: MIT
// MotionController: segment queue + look-ahead planner + fixed-rate interpolator, with feed hold,
// resume and abort. The same code runs in the host simulator and in the firmware.
//
//   push segments ─► queue (Capacity) ─► plan: length, caps, junction speed (once, at push)
//                                     └► per segment start: exit speed by a backward pass over the
//                                        next Lookahead segments ─► S-curve profile ─► per tick:
//                                        t → s (profile) → u (arc-length table) → p(u) → setpoint
//
// Determinism: a segment's exit speed depends only on the segment and the Lookahead segments after
// it (or the end of the job), never on how many happened to be queued: the window ends with a
// stop, whether the job ends there or not. So a firmware whose queue is kept at least Lookahead
// deep produces exactly the simulator's setpoints; all planning arithmetic is +, −, ×, ÷ and sqrt
// in IEEE double, which rounds identically on every target, and positions are quantised to the
// position scalar (Q16.16 in fixed-point builds) only at the output.
// Time is tick / rate_hz; segment boundaries fall between ticks and the remainder carries over,
// so speed is continuous across segments. The last setpoint of a job is its end point exactly.
// Feed hold brakes along the path (possibly into later segments) within the limits; resume plans
// the rest of the segment from rest; abort stops at once and flushes the queue.
// Budget per tick: one profile evaluation (a cubic), a binary search in a 65-entry table, one
// curve evaluation (de Casteljau, degree <= 7) and the quantisation.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include <curvestep/core/container/ring_buffer.hpp>
#include <curvestep/core/motion/path_length_table.hpp>
#include <curvestep/core/motion/cusps.hpp>
#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/core/motion/path_segment.hpp>
#include <curvestep/core/motion/segment_plan.hpp>
#include <curvestep/core/motion/setpoint.hpp>
#include <curvestep/core/motion/velocity_profile.hpp>

namespace curvestep {

/// Progress states of a MotionController (never errors: those are Result values).
enum class ControllerState : std::uint8_t {
  Idle = 0,      ///< configured, not started
  Running = 1,   ///< following the path
  Holding = 2,   ///< braking for a feed hold
  Held = 3,      ///< stopped on the path by a feed hold; resume() continues
  Starved = 4,   ///< the queue ran out before the end of the job; stopped on the path
  Finished = 5,  ///< the last setpoint (the job's end point) has been produced
  Aborted = 6,   ///< stopped at once, queue flushed
  Fault = 7,     ///< an error stopped the controller (see fault())
};

/// Queue, planner and interpolator for one machine. S is the position scalar of the setpoints.
template <Scalar S, std::size_t QueueCapacity = 32, std::size_t Lookahead = 16, std::size_t TableIntervals = 64>
class MotionController {
  static_assert(Lookahead >= 1 && Lookahead < QueueCapacity, "the look-ahead window must fit in the queue");

 public:
  /// Number of segments the window looks ahead.
  static constexpr std::size_t lookahead = Lookahead;

  /// Sets the machine. InvalidLimit/InvalidRate from MachineLimits::validate; InvalidState while moving.
  [[nodiscard]] Result<void> configure(const MachineLimits& machine) noexcept {
    if (!stopped()) return fail(Error::InvalidState);
    CURVESTEP_CHECK(machine.validate());
    machine_ = machine;
    configured_ = true;
    return ok();
  }

  /// Queues a segment, planning its length, caps and the junction speed from the previous one. A
  /// Bézier with cusps is queued as its pieces between the cusps (each needs a queue slot).
  /// QueueFull when there is no room (retry after setpoints drain it), ConfigurationMissing before
  /// configure, InvalidState after end_of_job or abort, DegenerateCurve/InvalidLimit from the analysis.
  [[nodiscard]] Result<void> try_push(const PathSegment& segment, std::uint32_t job_index) noexcept {
    if (!configured_) return fail(Error::ConfigurationMissing);
    if (end_of_job_ || state_ == ControllerState::Aborted || state_ == ControllerState::Fault) return fail(Error::InvalidState);
    const auto cusps = find_cusps(segment);
    if (queue_.available() < cusps.count + 1) return fail(Error::QueueFull);
    // Split in place, piece by piece (no array of pieces on the stack). With cusps, a first pass
    // plans every piece without queueing, so that an error leaves the queue as it was; the
    // second pass computes the same pieces and plans again (deterministic) and queues them.
    if (cusps.count > 0) CURVESTEP_CHECK(push_pieces(segment, cusps, job_index, false));
    CURVESTEP_CHECK(push_pieces(segment, cusps, job_index, true));
    if (state_ == ControllerState::Finished) state_ = ControllerState::Idle;
    return ok();
  }

  /// No more segments will come: the last queued one ends the job with a stop.
  void end_of_job() noexcept { end_of_job_ = true; }

  /// Starts moving from the first queued segment. NothingQueued, ConfigurationMissing, InvalidState.
  [[nodiscard]] Result<void> start() noexcept {
    if (!configured_) return fail(Error::ConfigurationMissing);
    if (state_ != ControllerState::Idle) return fail(Error::InvalidState);
    if (queue_.empty()) return fail(Error::NothingQueued);
    CURVESTEP_CHECK(begin_segment(0, 0, 0));
    state_ = ControllerState::Running;
    return ok();
  }

  /// Feed hold: brake to a stop along the path within the limits. Ignored unless running.
  void hold() noexcept {
    if (state_ != ControllerState::Running) return;
    const auto now = profile_.at(time_now() - origin_s_);
    ProfileLimits limits = front().plan.limits;
    for (std::size_t i = 1; i < queue_.size() && i <= Lookahead; ++i) {
      limits.acceleration_mm_per_s2 = std::fmin(limits.acceleration_mm_per_s2, queue_[i].plan.limits.acceleration_mm_per_s2);
      limits.jerk_mm_per_s3 = std::fmin(limits.jerk_mm_per_s3, queue_[i].plan.limits.jerk_mm_per_s3);
    }
    hold_profile_ = VelocityProfile::stop(now.speed_mm_per_s, now.acceleration_mm_per_s2, limits);
    hold_base_mm_ = offset_mm_ + now.distance_mm;
    origin_s_ = time_now();
    state_ = ControllerState::Holding;
  }

  /// Continues after a hold or a starved queue: the rest of the segment is planned from rest.
  [[nodiscard]] Result<void> resume() noexcept {
    if (state_ != ControllerState::Held && state_ != ControllerState::Starved) return fail(Error::InvalidState);
    if (queue_.empty()) return fail(Error::NothingQueued);
    if (state_ == ControllerState::Starved) {
      if (queue_.size() < 2) return fail(Error::NothingQueued);
      queue_.pop_front();
      CURVESTEP_CHECK(begin_segment(0, 0, time_now()));
    } else {
      CURVESTEP_CHECK(begin_segment(hold_base_mm_, 0, time_now()));
    }
    state_ = ControllerState::Running;
    return ok();
  }

  /// Stops at once (no braking) and flushes the queue.
  void abort() noexcept {
    queue_.clear();
    state_ = ControllerState::Aborted;
  }

  /// Back to Idle after Finished or Aborted, keeping the configuration (a new job).
  void reset() noexcept {
    queue_.clear();
    state_ = ControllerState::Idle;
    end_of_job_ = false;
    has_previous_ = false;
    tick_ = 0;
  }

  /// The next setpoint (one tick). InvalidState when idle, finished, aborted or faulted.
  /// Holding, Held and Starved produce setpoints that stay on the path (speed 0 once stopped).
  [[nodiscard]] Result<Setpoint<S>> next_setpoint() noexcept {
    switch (state_) {
      case ControllerState::Running: return running_tick();
      case ControllerState::Holding: return holding_tick();
      case ControllerState::Held:
      case ControllerState::Starved: return emit(last_position_, 0, last_segment_);
      default: return fail(Error::InvalidState);
    }
  }

  [[nodiscard]] ControllerState state() const noexcept { return state_; }
  [[nodiscard]] bool finished() const noexcept { return state_ == ControllerState::Finished; }
  /// The error that put the controller into Fault.
  [[nodiscard]] Failure fault() const noexcept { return fault_; }
  [[nodiscard]] std::size_t queued() const noexcept { return queue_.size(); }
  [[nodiscard]] static constexpr std::size_t queue_capacity() noexcept { return QueueCapacity; }
  [[nodiscard]] bool queue_full() const noexcept { return queue_.full(); }
  [[nodiscard]] std::uint64_t tick() const noexcept { return tick_; }
  [[nodiscard]] const MachineLimits& machine() const noexcept { return machine_; }
  /// The profile of the segment being followed (for reports and tests).
  [[nodiscard]] const VelocityProfile& current_profile() const noexcept { return profile_; }

 private:
  /// What the queue keeps of a SegmentPlan (the end tangents and curvatures are needed only for
  /// the junction with the next pushed segment: previous_plan_).
  struct QueuedPlan {
    double length_mm = 0;   ///< arc length
    ProfileLimits limits{};  ///< caps for the segment's speed profile
  };

  /// A queue slot: the segment in compact form (PathSegment::compact; front() expands it).
  struct Entry {
    CompactSegment segment{};
    QueuedPlan plan{};
    double junction_in = 0;       ///< speed cap at the joint into this segment
    std::uint32_t job_index = 0;  ///< the segment's index in the job
    std::uint32_t serial = 0;     ///< push count, identifies the slot's content for front()
  };

  /// The front entry, its segment expanded to a PathSegment (once per entry, cached in current_).
  struct Front {
    const PathSegment& segment;
    const QueuedPlan& plan;
    double junction_in;
    std::uint32_t job_index;
  };

  /// Plans the pieces of `segment` between its cusps (split in place) and, if `commit`, queues
  /// them. The pieces and plans are those of splitting at each cusp in turn.
  template <class Cusps>
  [[nodiscard]] Result<void> push_pieces(const PathSegment& segment, const Cusps& cusps, std::uint32_t job_index,
                                         bool commit) noexcept {
    SegmentPlan previous = previous_plan_;
    bool has_previous = has_previous_;
    if (cusps.count == 0) {
      CURVESTEP_CHECK(push_piece(segment, job_index, previous, has_previous, commit));
    } else {
      PathSegment rest = segment;
      PathSegment piece;
      double consumed = 0;  // the parameter of `rest`'s start on the original segment
      for (std::size_t i = 0; i < cusps.count; ++i) {
        CURVESTEP_CHECK(rest.split_off((cusps.parameters[i] - consumed) / (1 - consumed), piece));
        CURVESTEP_CHECK(push_piece(piece, job_index, previous, has_previous, commit));
        consumed = cusps.parameters[i];
      }
      CURVESTEP_CHECK(push_piece(rest, job_index, previous, has_previous, commit));
    }
    if (commit) {
      previous_plan_ = previous;
      has_previous_ = true;
    }
    return ok();
  }

  /// Plans one piece after `previous` (updated) and, if `commit`, queues it (room checked by try_push).
  [[nodiscard]] Result<void> push_piece(const PathSegment& piece, std::uint32_t job_index, SegmentPlan& previous,
                                        bool& has_previous, bool commit) noexcept {
    CURVESTEP_TRY(const SegmentPlan plan, plan_piece(piece, job_index));
    if (commit) enqueue(piece, plan, has_previous ? junction_speed(previous, plan, machine_) : 0, job_index);
    previous = plan;
    has_previous = true;
    return ok();
  }

  /// Queues a planned piece (its own frame: the entry is not on the stack while planning).
  [[gnu::noinline]] void enqueue(const PathSegment& piece, const SegmentPlan& plan, double junction, std::uint32_t job_index) noexcept {
    const Entry entry{piece.compact(), QueuedPlan{plan.length_mm, plan.limits}, junction, job_index, ++pushed_serial_};
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
    return Front{current_, e.plan, e.junction_in, e.job_index};
  }
  [[nodiscard]] double time_now() const noexcept { return static_cast<double>(tick_) / machine_.rate_hz; }

  /// The highest exit speed of the front segment when entered at v0: a backward pass over the
  /// next Lookahead segments, whose window always ends at rest.
  [[nodiscard]] double exit_speed(double v0, double remaining_mm) const noexcept {
    const std::size_t after = queue_.size() - 1;
    const std::size_t window = after < Lookahead ? after : Lookahead;
    if (window == 0) return 0;
    double v = 0;  // the largest entry speed of segment m from which a stop by the window's end works
    for (std::size_t m = window; m >= 1; --m) {
      const Entry& e = queue_[m];
      v = std::fmin(e.junction_in, reachable_speed(v, e.plan.length_mm, e.plan.limits.speed_cap_mm_per_s, e.plan.limits));
    }
    const auto& limits = front().plan.limits;
    return std::fmin(v, reachable_speed(v0, remaining_mm, limits.speed_cap_mm_per_s, limits));
  }

  /// Starts following the front segment from arc length `offset` at speed v0 at time `origin`.
  [[nodiscard]] Result<void> begin_segment(double offset, double v0, double origin) noexcept {
    CURVESTEP_TRY(table_, PathLengthTable<TableIntervals>::build(front().segment));
    offset_mm_ = offset;
    origin_s_ = origin;
    const double remaining = table_.length() - offset;
    if (!(remaining > 1e-12)) {
      profile_ = VelocityProfile{};
      return ok();
    }
    const double v1 = exit_speed(v0, remaining);
    auto profile = VelocityProfile::plan(remaining, v0, v1, front().plan.limits);
    if (!profile) return fail(profile.error(), front().job_index);
    profile_ = profile.value();
    return ok();
  }

  [[nodiscard]] Result<Setpoint<S>> running_tick() noexcept {
    const double t = time_now();
    double tau = t - origin_s_;
    while (tau >= profile_.duration_s()) {
      if (queue_.size() > 1) {
        const double exit = profile_.exit_speed();
        origin_s_ += profile_.duration_s();
        queue_.pop_front();
        if (auto started = begin_segment(0, exit, origin_s_); !started) return fault(started.failure());
        tau = t - origin_s_;
        continue;
      }
      // Last queued segment done: the job's end (exactly) or a starved queue.
      const MachinePoint end = front().segment.end();
      last_segment_ = front().job_index;
      if (end_of_job_) {
        queue_.pop_front();
        state_ = ControllerState::Finished;
      } else {
        hold_base_mm_ = table_.length();
        state_ = ControllerState::Starved;
      }
      return emit(end, 0, last_segment_);
    }
    const MotionState m = profile_.at(tau);
    const double u = table_.parameter_at(offset_mm_ + m.distance_mm);
    return emit(front().segment.point(u), m.speed_mm_per_s, front().job_index);
  }

  [[nodiscard]] Result<Setpoint<S>> holding_tick() noexcept {
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

  [[nodiscard]] Result<Setpoint<S>> emit(const MachinePoint& p, double speed, std::uint32_t segment) noexcept {
    Setpoint<S> sp;
    sp.tick = tick_;
    sp.speed_mm_per_s = speed;
    sp.segment = segment;
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      auto c = from_double<S>(p[axis]);
      if (!c) return fault(fail(c.error(), segment));
      sp.position[axis] = c.value();
    }
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
  std::uint64_t tick_ = 0;
  MachinePoint last_position_{};
  std::uint32_t last_segment_ = 0;
};

}  // namespace curvestep
