// SPDX-License-Identifier: MIT
// EventTimeline: the machine events of a job (QueueEvent) waiting for the motion to reach them.
//
// Each event is keyed by the job segment it precedes and a number of ticks into the rest at that
// joint. The App shows it every setpoint's segment number (reached()); an event is due at the
// setpoint that is the `after_rest_ticks`-th (from 0) of its segment, or as soon as a later
// segment's setpoint comes; finish() makes every remaining event due (the job's end, where the
// events after its last move belong). Due events leave in the order they were queued. A fixed
// ring of Capacity events: no heap; push() refuses a full ring (QueueFull), and the App offers
// credit for no more than fit (docs/protocol.md, "Credit"). Capacity 0: no events at all.
#pragma once

#include <cstddef>
#include <cstdint>

#include <curvestep/core/container/ring_buffer.hpp>
#include <curvestep/core/result.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::firmware {

/// Where the motion is, in the events' terms: the segment number of the last setpoint and how
/// many setpoints of that segment came before it (the ticks into a rest at its joint).
class EventClock {
 public:
  /// The motion produced a setpoint of `segment`.
  void reached(std::uint32_t segment) noexcept {
    if (!started_ || segment != segment_) {
      started_ = true;
      segment_ = segment;
      ticks_ = 0;
    } else {
      ++ticks_;
    }
  }
  /// True if `event` is due at the last setpoint: its segment is behind, or it is this segment's
  /// and its ticks into the rest have come.
  [[nodiscard]] bool due(const protocol::QueueEvent& event) const noexcept {
    return started_ && (event.segment < segment_ || (event.segment == segment_ && event.after_rest_ticks <= ticks_));
  }
  /// True if the motion is past segment numbers below `segment`.
  [[nodiscard]] bool past(std::uint32_t segment) const noexcept { return started_ && segment < segment_; }
  /// A new job.
  void restart() noexcept { started_ = false; }

 private:
  std::uint32_t segment_ = 0;  ///< segment of the last setpoint
  std::uint32_t ticks_ = 0;    ///< setpoints of that segment before the last one
  bool started_ = false;       ///< a setpoint of this job has been seen
};

template <std::size_t Capacity = 16>
class EventTimeline {
 public:
  /// Queues an event. QueueFull when the ring is full; InvalidArgument (index = byte offset of
  /// `segment`, 0) for an event before the segment the motion is already past.
  [[nodiscard]] Result<void> push(const protocol::QueueEvent& event) noexcept {
    if (clock_.past(event.segment)) return fail(Error::InvalidArgument, 0);
    if (!events_.try_push(event)) return fail(Error::QueueFull);
    return ok();
  }

  /// The motion produced a setpoint of `segment`: calls `act(event)` for every event now due.
  template <class Act>
  void reached(std::uint32_t segment, Act&& act) {
    clock_.reached(segment);
    while (!events_.empty() && clock_.due(events_.front())) {
      act(events_.front());
      events_.pop_front();
    }
  }

  /// True if the first waiting event precedes segment `next_segment` or a later one: the segment
  /// not yet queued (the count of segments taken) that the motion, at the end of what is queued,
  /// needs next. The App then waits there rather than running the queue dry (at_joint()).
  [[nodiscard]] bool waiting_for(std::uint32_t next_segment) const noexcept {
    return !events_.empty() && events_.front().segment >= next_segment;
  }

  /// The motion waits at the joint before segment `next_segment`, not yet queued: calls
  /// `act(event)` for the events due right at that joint (keyed to it, no rest before them), in
  /// order, so that their room takes more events, and the segment, from the host. Events after a
  /// rest at that joint wait for it (the rest comes with the segment).
  template <class Act>
  void at_joint(std::uint32_t next_segment, Act&& act) {
    while (!events_.empty() && events_.front().segment == next_segment && events_.front().after_rest_ticks == 0) {
      act(events_.front());
      events_.pop_front();
    }
  }

  /// The job ended: calls `act(event)` for every event left, in order.
  template <class Act>
  void finish(Act&& act) {
    while (!events_.empty()) {
      act(events_.front());
      events_.pop_front();
    }
    clock_.restart();
  }

  /// Forgets every event (abort, a new session or configuration).
  void clear() noexcept {
    events_.clear();
    clock_.restart();
  }

  [[nodiscard]] std::size_t size() const noexcept { return events_.size(); }
  [[nodiscard]] std::size_t free() const noexcept { return Capacity - events_.size(); }
  [[nodiscard]] static constexpr std::size_t capacity() noexcept { return Capacity; }

 private:
  RingBuffer<protocol::QueueEvent, Capacity> events_{};
  EventClock clock_{};
};

/// No room for machine events (a controller short of RAM, such as the 8 KiB STM32F1 executor
/// image): QueueEvent is refused (NotSupported) and takes no room from the credit.
template <>
class EventTimeline<0> {
 public:
  [[nodiscard]] Result<void> push(const protocol::QueueEvent&) noexcept { return fail(Error::NotSupported); }
  template <class Act>
  void reached(std::uint32_t, Act&&) {}
  template <class Act>
  void finish(Act&&) {}
  [[nodiscard]] bool waiting_for(std::uint32_t) const noexcept { return false; }
  template <class Act>
  void at_joint(std::uint32_t, Act&&) {}
  void clear() noexcept {}
  [[nodiscard]] std::size_t size() const noexcept { return 0; }
  [[nodiscard]] std::size_t free() const noexcept { return ~std::size_t{0}; }
  [[nodiscard]] static constexpr std::size_t capacity() noexcept { return 0; }
};

}  // namespace curvestep::firmware
