// SPDX-License-Identifier: MIT
// MachineEvents: the machine-event side of the App's job (QueueEvent, docs/firmware.md "Messages").
//
// Owns what the events leave behind: the queued events (EventTimeline, event_timeline.hpp), the
// spindle and coolant as the events last set them (the board hooks get the whole state,
// board_hooks.hpp), the pause in force (PauseReport) and the wait at a joint whose segment has not
// arrived (wait_at_joint). The App decides what a pause does to the motion and the phase; this
// class acts on the events and keeps their state. Capacity 0: no events at all (QueueEvent is
// NotSupported); the spindle, coolant and pause state stay (Abort and faults switch nothing off).
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>

#include <curvestep/core/result.hpp>
#include <curvestep/firmware/board_hooks.hpp>
#include <curvestep/firmware/event_timeline.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::firmware {

/// The job's machine events for the motion to reach, and the machine state they left.
template <std::size_t Events>
class MachineEvents {
 public:
  /// Queues an event (EventTimeline::push: QueueFull, InvalidArgument behind the motion).
  [[nodiscard]] Result<void> push(const protocol::QueueEvent& event) noexcept { return timeline_.push(event); }
  /// Events queued and not yet reached by the motion.
  [[nodiscard]] std::size_t size() const noexcept { return timeline_.size(); }
  /// Room for more events (a credit may be one).
  [[nodiscard]] std::size_t free() const noexcept { return timeline_.free(); }
  /// Forgets the queued events and any wait at a joint (the job was stopped).
  void clear() noexcept {
    timeline_.clear();
    waiting_at_joint_ = false;
  }

  /// The motion made a setpoint of `segment`: `act(event)` for every event now due.
  template <class Act>
  void reached(std::uint32_t segment, Act&& act) {
    timeline_.reached(segment, std::forward<Act>(act));
  }
  /// The job's last setpoint: `act(event)` for every event left (after the last move).
  template <class Act>
  void finish(Act&& act) {
    timeline_.finish(std::forward<Act>(act));
  }

  /// A due event at setpoint `at`: calls the board's hooks and keeps the spindle and coolant state.
  /// True if the event holds the job for the operator (pauses()).
  template <class B>
  [[nodiscard]] bool act_on(B& board, const protocol::QueueEvent& event, std::uint32_t at) noexcept {
    apply_machine_event(board, event, at, spindle_, coolant_);
    return pauses(event.kind);
  }
  /// The pause `event` (due at setpoint `at`) now holds the job; pause() reports it.
  void hold_for(const protocol::QueueEvent& event, std::uint32_t at) noexcept {
    pause_ = protocol::PauseReport{at, event.kind, event.value};
  }
  /// The pause last in force (PauseReport: the setpoint and the event that caused it).
  [[nodiscard]] const protocol::PauseReport& pause() const noexcept { return pause_; }

  /// Abort and faults: a running spindle and coolant are switched off through the same hooks (as
  /// M5 and M9 would) at setpoint `at`, so a stopped job never leaves a cutter turning.
  template <class B>
  void switch_off_spindle_and_coolant(B& board, std::uint32_t at) noexcept {
    protocol::QueueEvent off{};
    if (spindle_.on) {
      off.kind = protocol::MachineEventKind::SpindleOff;
      apply_machine_event(board, off, at, spindle_, coolant_);
    }
    if (coolant_.mist || coolant_.flood) {
      off.kind = protocol::MachineEventKind::CoolantOff;
      apply_machine_event(board, off, at, spindle_, coolant_);
    }
  }

  /// Machine events for the segment after everything queued (more of them than the ring holds,
  /// docs/protocol.md "Credit"): rather than run the queue dry, the motion waits at the setpoint
  /// before the queue's end (`at_end`: at rest or within a tick of it, the plan's window ends at
  /// rest there) and acts on the events due at that joint (`act(event)`), so that their room brings
  /// the rest of them and segment `next_segment` (the count of segments taken). Once that came, the
  /// motion goes on when `window_ready()` (the look-ahead window as full as after an underrun): the
  /// setpoints are those it would have made without waiting. True while waiting (no setpoint).
  /// Call only while the job runs and the controller moves; else stop_waiting().
  template <class WindowReady, class Act>
  [[nodiscard]] bool wait_at_joint(bool at_end, std::uint32_t next_segment, WindowReady&& window_ready, Act&& act) {
    if (!waiting_at_joint_ && !(at_end && timeline_.waiting_for(next_segment))) return false;
    if (!at_end && window_ready()) {
      waiting_at_joint_ = false;
      return false;
    }
    waiting_at_joint_ = true;
    timeline_.at_joint(next_segment, std::forward<Act>(act));
    return true;
  }
  /// The job does not run (or the controller does not move): no wait at a joint.
  void stop_waiting() noexcept { waiting_at_joint_ = false; }

  /// Events that hold the job for the operator (the joint is an exact stop: the machine stands).
  [[nodiscard]] static constexpr bool pauses(protocol::MachineEventKind kind) noexcept {
    using protocol::MachineEventKind;
    return kind == MachineEventKind::ProgramPause || kind == MachineEventKind::ToolChange || kind == MachineEventKind::LayerChange;
  }

 private:
  [[no_unique_address]] EventTimeline<Events> timeline_{};  ///< QueueEvents for the motion to reach (Events 0: no room)
  protocol::PauseReport pause_{};     ///< the pause in force (JobMotion::Paused), reported once
  SpindleState spindle_{};            ///< the spindle as the events left it (board hooks)
  CoolantState coolant_{};            ///< the coolant as the events left it (board hooks)
  bool waiting_at_joint_ = false;     ///< the motion waits for the segment its events precede
};

}  // namespace curvestep::firmware
