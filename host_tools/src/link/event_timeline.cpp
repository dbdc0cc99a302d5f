// SPDX-License-Identifier: MIT
#include <curvestep/host/link/event_timeline.hpp>

namespace curvestep::host::link {

void SimulatedEventTimeline::on_setpoint(const SetpointRecord& setpoint) {
  clock_.reached(setpoint.segment);
  while (at_.size() < events_.size() && clock_.due(events_[at_.size()])) at_.push_back(setpoint.index);
}

void SimulatedEventTimeline::finish(std::uint64_t last_index) {
  while (at_.size() < events_.size()) at_.push_back(last_index);
}

std::string event_line(const protocol::QueueEvent& event, std::uint64_t setpoint) {
  return std::string("event ") + protocol::machine_event_name(event.kind) + " value " + std::to_string(event.value) + " flag " +
         (event.flag ? "1" : "0") + " at setpoint " + std::to_string(setpoint);
}

}  // namespace curvestep::host::link
