// SPDX-License-Identifier: MIT
// Board hooks for machine events (QueueEvent, docs/porting.md "Machine event hooks"): every hook
// is optional; a board implements those its hardware has, and App calls them when the motion
// reaches the event's point, with the index of the setpoint it happened at:
//
//   void spindle(bool on, bool counter_clockwise, std::uint32_t rpm, std::uint32_t setpoint);
//   void coolant(bool mist, bool flood, std::uint32_t setpoint);       // the state after M7/M8/M9
//   void digital_output(std::uint32_t number, bool on, std::uint32_t setpoint);
//   void pen(bool down, std::uint32_t pulse_us, std::uint32_t setpoint);  // servo pulse width, 0: none given
//   void tool_change(std::uint32_t tool, std::uint32_t setpoint);
//   void machine_event(const protocol::QueueEvent& event, std::uint32_t setpoint);  // every event (logs)
//
// Hooks run in on_tick(), inside the control period: they must return at once (set a pin, load a
// timer compare register), never wait.
#pragma once

#include <cstdint>

#include <curvestep/protocol/messages.hpp>

namespace curvestep::firmware {

/// The coolant outputs' state, changed by M7 (mist on), M8 (flood on), M9 (both off).
struct CoolantState {
  bool mist = false;
  bool flood = false;
};

/// The spindle's state, changed by SpindleOn / SpindleOff / SpindleSpeed.
struct SpindleState {
  bool on = false;
  bool counter_clockwise = false;
  std::uint32_t rpm = 0;
};

/// Calls the hooks `board` has for `event` at setpoint `setpoint`, updating the spindle and
/// coolant state (a hook gets the whole state, so a board needs no memory of its own).
template <class B>
void apply_machine_event(B& board, const protocol::QueueEvent& event, std::uint32_t setpoint, SpindleState& spindle,
                         CoolantState& coolant) noexcept {
  using protocol::MachineEventKind;
  if constexpr (requires { board.machine_event(event, setpoint); }) board.machine_event(event, setpoint);
  switch (event.kind) {
    case MachineEventKind::SpindleOn: spindle = SpindleState{true, event.flag, event.value}; break;
    case MachineEventKind::SpindleOff: spindle.on = false; break;
    case MachineEventKind::SpindleSpeed: spindle.rpm = event.value; break;
    case MachineEventKind::CoolantMist: coolant.mist = true; break;
    case MachineEventKind::CoolantFlood: coolant.flood = true; break;
    case MachineEventKind::CoolantOff: coolant = CoolantState{}; break;
    default: break;
  }
  switch (event.kind) {
    case MachineEventKind::SpindleOn:
    case MachineEventKind::SpindleOff:
    case MachineEventKind::SpindleSpeed:
      if constexpr (requires { board.spindle(true, true, std::uint32_t{}, setpoint); }) {
        board.spindle(spindle.on, spindle.counter_clockwise, spindle.rpm, setpoint);
      }
      return;
    case MachineEventKind::CoolantMist:
    case MachineEventKind::CoolantFlood:
    case MachineEventKind::CoolantOff:
      if constexpr (requires { board.coolant(true, true, setpoint); }) board.coolant(coolant.mist, coolant.flood, setpoint);
      return;
    case MachineEventKind::DigitalOutput:
      if constexpr (requires { board.digital_output(std::uint32_t{}, true, setpoint); }) {
        board.digital_output(event.value, event.flag, setpoint);
      }
      return;
    case MachineEventKind::PenUp:
    case MachineEventKind::PenDown:
      if constexpr (requires { board.pen(true, std::uint32_t{}, setpoint); }) {
        board.pen(event.kind == MachineEventKind::PenDown, event.value, setpoint);
      }
      return;
    case MachineEventKind::ToolChange:
      if constexpr (requires { board.tool_change(std::uint32_t{}, setpoint); }) board.tool_change(event.value, setpoint);
      return;
    default: return;
  }
}

}  // namespace curvestep::firmware
