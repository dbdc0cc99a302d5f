// SPDX-License-Identifier: MIT
// A job of wire segments as the simulator loads it: the firmware's own conversion of each one, so
// that a simulation and an App fed the same QueueSegments plan the same path.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/firmware/conversions.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/simulator.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::sim_testing {

inline host::Job to_host_job(const std::vector<protocol::QueueSegment>& wire) {
  host::Job job;
  job.name = "wire";
  for (const auto& s : wire) {
    const auto segment = firmware::to_path_segment(s);
    REQUIRE(segment.has_value());
    job.segments.push_back(segment.value());
  }
  return job;
}

/// The simulation options of `curvestep device`'s window (App<_, _, 32, 16>: look-ahead 16).
inline host::SimulationOptions device_window() {
  host::SimulationOptions options;
  options.lookahead = 16;
  return options;
}

/// index -> Q16.16 setpoint of host::simulate() of `wire` on `machine` with `options`.
inline std::map<std::uint32_t, protocol::WirePoint> simulated_setpoints(const std::vector<protocol::QueueSegment>& wire,
                                                                        const protocol::MachineConfiguration& machine,
                                                                        const host::SimulationOptions& options) {
  const auto limits = firmware::to_machine_limits(machine);
  REQUIRE(limits.has_value());
  const auto result = host::simulate(to_host_job(wire), limits.value(), options);
  std::map<std::uint32_t, protocol::WirePoint> out;
  for (const auto& r : result.setpoints) out[static_cast<std::uint32_t>(r.index)] = protocol::WirePoint{r.raw_q16[0], r.raw_q16[1], r.raw_q16[2]};
  return out;
}

}  // namespace curvestep::sim_testing
