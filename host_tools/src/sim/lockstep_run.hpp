// SPDX-License-Identifier: MIT
// LockstepRun: one or more MotionControllers run in lockstep over one job, with the feed holds and
// overrides of a simulation applied between ticks as the firmware takes them. Private to the
// simulator library: simulate() and PiecePlanner (plan_pieces) are its two users.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <curvestep/core/error_text.hpp>
#include <curvestep/core/motion/motion_controller.hpp>
#include <curvestep/host/joint_stops.hpp>
#include <curvestep/host/segment_source.hpp>
#include <curvestep/host/simulator.hpp>

namespace curvestep::host::detail {

/// Room for the largest window behind the segment in progress, and for cusp splits.
constexpr std::size_t queue_capacity = SimulationOptions::max_distance_window + 16;

// The controllers' largest window is the distance window's; set_lookahead() keeps the count window
// at options.lookahead (<= max_lookahead), which alone decides the setpoints without a distance.
using ExactController = MotionController<double, queue_capacity, SimulationOptions::max_distance_window>;
using FixedController = MotionController<Q16_16, queue_capacity, SimulationOptions::max_distance_window>;

/// Refuses what neither simulate() nor a PiecePlanner can run (std::runtime_error): an invalid
/// machine, a look-ahead window outside 1..max_lookahead, holds or overrides out of time order, an
/// override outside its ranges. A job without segments runs and makes no setpoints (LinuxCNC runs
/// a program without moves too).
void check_request(const MachineLimits& machine, const SimulationOptions& options);

/// "job: segment 3: <description> (<name>)".
inline std::string failure_text(const std::string& job_name, const Failure& f) {
  std::ostringstream s;
  s << job_name << ": ";
  if (f.index != no_index) s << "segment " << f.index << ": ";
  s << describe(f.code) << " (" << error_name(f.code) << ")";
  return s.str();
}

/// Runs one or more MotionControllers in lockstep over the same job: the same queue filling
/// (cusp splits wait for room), the same start, one setpoint of each per step. The first
/// controller decides when the queue is full; the others must take every segment it takes.
/// simulate() runs a double and a Q16.16 controller (two output scalars, one plan), PiecePlanner
/// the Q16.16 one alone. A run is begin(), then prepare() and tick() until finished(); run() does
/// all of it. Holds and overrides may be added while it runs, for ticks not yet prepared.
template <class... Controllers>
class LockstepRun {
 public:
  LockstepRun(const Job& job, const MachineLimits& machine, const SimulationOptions& options, std::vector<FeedHoldEvent> holds = {})
      : LockstepRun(job.name, job.segments.size(), joint_stops(job, machine.rate_hz), std::make_unique<JobSegments>(job), machine, options,
                    std::move(holds)) {}

  /// A job of `segments` segments pulled from `source` as the queues take them (a streamed job),
  /// with its joint stops `entries` (joint_stops).
  LockstepRun(std::string name, std::size_t segments, JointStops entries, std::unique_ptr<SegmentSource> source,
              const MachineLimits& machine, const SimulationOptions& options, std::vector<FeedHoldEvent> holds = {})
      : name_(std::move(name)), segments_(segments), source_(std::move(source)), entries_(std::move(entries)), holds_(std::move(holds)),
        overrides_(options.overrides) {
    std::apply([&](auto&... c) { (check(c.configure(machine), "machine"), ...); }, controllers_);
    std::apply([&](auto&... c) { (check(c.set_lookahead(options.lookahead), "lookahead"), ...); }, controllers_);
    std::apply([&](auto&... c) { (check(c.set_lookahead_distance(options.lookahead_distance_mm), "lookahead distance"), ...); },
               controllers_);
  }

  /// Fills the queues, starts, and calls on_tick with each step's setpoints (a tuple, one per
  /// controller) until the first controller has finished the job.
  template <class OnTick>
  void run(OnTick&& on_tick) {
    if (!begin()) return;
    while (!finished()) {
      prepare();
      on_tick(tick());
    }
  }

  /// Fills the queues and starts (an override at tick 0 is set before, as a device takes it while
  /// idle). False for a job without segments (modes, S, M words only): it makes no setpoints.
  bool begin() {
    if (segments_ == 0) return false;
    fill();
    apply_override();
    std::apply([&](auto&... c) { (check(c.start(), no_index), ...); }, controllers_);
    return true;
  }

  /// Between two ticks: refills the queues, then the holds, resumes and overrides due before the
  /// next setpoint.
  void prepare() {
    fill();
    apply_feed_hold();
    apply_override();
  }

  /// The next setpoint of every controller (a tuple, in their order).
  auto tick() {
    // A braced list evaluates left to right: the controllers tick in their order.
    return std::apply([&](auto&... c) { return std::tuple{next_of(c)...}; }, controllers_);
  }

  /// True once the first controller has finished the job.
  [[nodiscard]] bool finished() const { return lead().finished(); }

  /// The first controller (it decides when the queue is full and when the job is over).
  [[nodiscard]] const auto& lead() const { return std::get<0>(controllers_); }

  /// A hold before setpoint `hold.tick`, which must not come before the last hold's nor be prepared yet.
  void add_hold(const FeedHoldEvent& hold) { holds_.push_back(hold); }
  /// An override before setpoint `override_event.tick`, not before the last override's nor prepared yet.
  void add_override(const FeedOverrideEvent& override_event) { overrides_.push_back(override_event); }

  /// Throws if a feed hold or an override was asked for at a tick the job never reached (after its end).
  void check_holds_done() const {
    if (next_override_ < overrides_.size()) {
      throw std::runtime_error(name_ + ": --override-at: the job ended at setpoint " + std::to_string(lead().tick() - 1) +
                               ", before the override at setpoint " + std::to_string(overrides_[next_override_].tick));
    }
    if (next_hold_ < holds_.size()) {
      throw std::runtime_error(name_ + ": --hold-at: the job ended at setpoint " + std::to_string(lead().tick() - 1) +
                               ", before the hold at setpoint " + std::to_string(holds_[next_hold_].tick));
    }
  }

 private:
  /// Between two ticks, as the firmware takes FeedHold and Resume: hold() before the hold's tick,
  /// resume() once the controller has stood its standing ticks.
  void apply_feed_hold() {
    const bool held = lead().state() == ControllerState::Held;
    if (held && standing_ == holds_[next_hold_ - 1].standing_ticks) {
      std::apply([&](auto&... c) { (check(c.resume(), no_index), ...); }, controllers_);
      standing_ = 0;
    } else if (held) {
      ++standing_;
    }
    if (next_hold_ < holds_.size() && lead().tick() == holds_[next_hold_].tick) {
      if (lead().state() != ControllerState::Running) {
        throw std::runtime_error(name_ + ": --hold-at: the controller is not moving at setpoint " +
                                 std::to_string(holds_[next_hold_].tick) + " (still braking or standing from the hold before)");
      }
      std::apply([](auto&... c) { (c.hold(), ...); }, controllers_);
      ++next_hold_;
    }
  }

  /// Between two ticks, as the firmware takes FeedOverride: set_override() before the override's tick.
  void apply_override() {
    while (next_override_ < overrides_.size() && lead().tick() == overrides_[next_override_].tick) {
      const FeedOverride value = overrides_[next_override_].value;
      std::apply([&](auto&... c) { (check(c.set_override(value), "--override-at"), ...); }, controllers_);
      ++next_override_;
    }
  }

  void fill() {
    auto& head = std::get<0>(controllers_);
    while (next_ < segments_ && !queue_full()) {
      if (current_ == nullptr && (current_ = source_->next(current_source_)) == nullptr) {
        throw std::runtime_error(name_ + ": the job ended after " + std::to_string(next_) + " of its " + std::to_string(segments_) + " segments");
      }
      const auto index = static_cast<std::uint32_t>(current_source_);
      auto pushed = head.try_push(*current_, index, entries_[next_]);
      if (!pushed && pushed.error() == Error::QueueFull) return;  // a cusp split needs more room: later (current_ is kept)
      check(pushed, index);
      std::apply([&](auto&, auto&... others) { (check(others.try_push(*current_, index, entries_[next_]), index), ...); }, controllers_);
      current_ = nullptr;
      ++next_;
    }
    if (next_ == segments_) {
      const std::uint32_t final_rest = entries_.at_end().rest_ticks;  // the dwells after the last move
      std::apply([final_rest](auto&... c) { (c.end_of_job(final_rest), ...); }, controllers_);
    }
  }

  [[nodiscard]] bool queue_full() const {
    return std::apply([](const auto&... c) { return (c.queue_full() || ...); }, controllers_);
  }

  template <class Controller>
  auto next_of(Controller& controller) {
    auto setpoint = controller.next_setpoint();
    if (!setpoint) throw std::runtime_error(failure_text(name_, setpoint.failure()));
    return setpoint.value();
  }

  void check(const Result<void>& r, std::size_t index) const {
    if (!r) {
      Failure f = r.failure();
      if (f.index == no_index) f.index = static_cast<std::uint16_t>(index > no_index ? no_index : index);
      throw std::runtime_error(failure_text(name_, f));
    }
  }
  void check(const Result<void>& r, const char* what) const {
    if (!r) throw std::runtime_error(name_ + ": " + what + ": " + std::string(describe(r.error())));
  }

  std::string name_;                       ///< the job's, for messages
  std::size_t segments_ = 0;               ///< in the job
  std::unique_ptr<SegmentSource> source_;  ///< where they come from
  const PathSegment* current_ = nullptr;   ///< pulled from source_, not taken by the queues yet
  std::size_t current_source_ = 0;         ///< its Job::source_index entry
  JointStops entries_;  ///< the joints with job events: an exact stop and rest before a segment; the end's
  std::size_t next_ = 0;
  std::tuple<Controllers...> controllers_;
  std::vector<FeedHoldEvent> holds_;  // in tick order
  std::size_t next_hold_ = 0;         // the next hold to apply
  std::uint64_t standing_ = 0;        // ticks stood in the current hold
  std::vector<FeedOverrideEvent> overrides_;  // in tick order
  std::size_t next_override_ = 0;             // the next override to set
};

}  // namespace curvestep::host::detail
