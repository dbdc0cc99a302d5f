// SPDX-License-Identifier: MIT
// A job of wire segments as the simulator loads it: the firmware's own conversion of each one, so
// that a simulation and an App fed the same QueueSegments plan the same path.
#pragma once

#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/firmware/conversions.hpp>
#include <curvestep/host/job.hpp>
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

}  // namespace curvestep::sim_testing
