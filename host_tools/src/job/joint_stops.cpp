// SPDX-License-Identifier: MIT
#include <curvestep/host/joint_stops.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

#include <curvestep/host/csv.hpp>

namespace curvestep::host {

bool needs_rest(JobEventKind kind) noexcept {
  switch (kind) {
    case JobEventKind::Dwell:
    case JobEventKind::ProgramPause:
    case JobEventKind::ToolChange:
    case JobEventKind::LayerChange: return true;
    default: return false;
  }
}

std::uint32_t dwell_ticks(double seconds, double rate_hz) {
  if (!(seconds >= 0) || !std::isfinite(seconds)) {
    throw std::invalid_argument("dwell of " + format_number(seconds) + " s: must be a finite time >= 0");
  }
  const double ticks = std::floor(seconds * rate_hz + 0.5);
  if (!(ticks <= static_cast<double>(std::numeric_limits<std::uint32_t>::max()))) {
    throw std::invalid_argument("dwell of " + format_number(seconds) + " s is longer than 2^32 - 1 ticks at " +
                                format_number(rate_hz) + " Hz");
  }
  return static_cast<std::uint32_t>(ticks);
}

JointStop JointStops::operator[](std::size_t joint) const {
  const auto found = stops_.find(std::min(joint, segments_));
  return found == stops_.end() ? JointStop{} : found->second;
}

JointStop& JointStops::edit(std::size_t joint) { return stops_[std::min(joint, segments_)]; }

JointStops joint_stops(const std::vector<JobEvent>& events, std::size_t segments, const std::string& name, double rate_hz) {
  JointStops stops(segments);
  std::map<std::size_t, std::size_t> machine_events;  // per joint with events
  for (const JobEvent& event : events) {
    if (event.kind == JobEventKind::Dwell || event.kind == JobEventKind::Message) continue;
    const std::size_t joint = std::min(event.before_segment, segments);
    if (++machine_events[joint] > max_events_passed_at_speed) stops.edit(joint).stop = true;
  }
  for (const JobEvent& event : events) {
    if (!needs_rest(event.kind)) continue;
    JointStop& stop = stops.edit(event.before_segment);
    stop.stop = true;
    if (event.kind != JobEventKind::Dwell) continue;
    const std::string where = name + (event.line > 0 ? ":" + std::to_string(event.line) : std::string{}) + ": ";
    try {
      const std::uint64_t total = std::uint64_t{stop.rest_ticks} + dwell_ticks(event.value, rate_hz);
      if (total > std::numeric_limits<std::uint32_t>::max()) throw std::invalid_argument("the dwells here add up to more than 2^32 - 1 ticks");
      stop.rest_ticks = static_cast<std::uint32_t>(total);
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(where + e.what());
    }
  }
  return stops;
}

JointStops joint_stops(const Job& job, double rate_hz) {
  return joint_stops(job.events, job.segments.size(), job.name, rate_hz);
}

}  // namespace curvestep::host
