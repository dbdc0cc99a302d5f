// SPDX-License-Identifier: MIT
// The event timeline of a simulated job: at which setpoint each machine event happens, by the
// firmware's own rule (firmware::EventClock) applied to the simulator's setpoints, so `curvestep
// sim` shows where a device calls its board hooks. One line per event, in the device's log format.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <curvestep/firmware/event_timeline.hpp>
#include <curvestep/host/simulator.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::host::link {

class SimulatedEventTimeline {
 public:
  /// `events` keyed by the job file's segment numbers (to_wire_events with file labels), as the
  /// simulator labels its setpoints.
  explicit SimulatedEventTimeline(std::vector<protocol::QueueEvent> events) : events_(std::move(events)) {}

  /// The simulator produced `setpoint`.
  void on_setpoint(const SetpointRecord& setpoint);
  /// The job ended at setpoint `last_index`: the events left happen there.
  void finish(std::uint64_t last_index);

  /// The events and the setpoint index of each (those reached so far).
  [[nodiscard]] const std::vector<protocol::QueueEvent>& events() const noexcept { return events_; }
  [[nodiscard]] const std::vector<std::uint64_t>& setpoints() const noexcept { return at_; }

 private:
  std::vector<protocol::QueueEvent> events_;
  std::vector<std::uint64_t> at_;
  firmware::EventClock clock_{};
};

/// "event NAME value V flag F at setpoint N": the line `curvestep device` logs for an event.
[[nodiscard]] std::string event_line(const protocol::QueueEvent& event, std::uint64_t setpoint);

}  // namespace curvestep::host::link
