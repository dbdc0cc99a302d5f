// SPDX-License-Identifier: MIT
// A job's events as QueueEvents (host::link::to_wire_events) keyed by the one label rule,
// ReadableJob::event_labels (readable() of a job held whole): the file segment after each joint
// with events, after the last move the last one's + 1. Expected labels are written by hand from
// the job's source_index.
#include <cstddef>
#include <map>
#include <stdexcept>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/host/job.hpp>
#include <curvestep/host/link/wire.hpp>
#include <curvestep/host/readable_job.hpp>
#include <curvestep/protocol/messages.hpp>

using namespace curvestep;
using namespace curvestep::host;

namespace {

/// Three lines along x; smoothing made the first two of file segment 4 and the third of file segment 7.
/// Events: M3 S1000 before the second, G4 P0.5 and M64 P3 before the third, M5 after the last.
Job smoothed_job(bool with_source_index) {
  Job job;
  job.name = "labels.ngc";
  for (int k = 0; k < 3; ++k) {
    job.segments.push_back(PathSegment::make_line(MachinePoint{{10.0 * k, 0, 0}}, MachinePoint{{10.0 * (k + 1), 0, 0}}).value());
  }
  if (with_source_index) job.source_index = {4, 4, 7};
  job.events.push_back(JobEvent{JobEventKind::SpindleOn, 1, 1000, false, 0, {}});
  job.events.push_back(JobEvent{JobEventKind::Dwell, 2, 0.5, false, 0, {}});
  job.events.push_back(JobEvent{JobEventKind::DigitalOutput, 2, 3, true, 0, {}});
  job.events.push_back(JobEvent{JobEventKind::SpindleOff, 3, 0, false, 0, {}});
  return job;
}

}  // namespace

TEST_CASE("wire events: a job held whole is keyed by the file segment after each joint, after its last move the last one's + 1",
          "[host_tools][link][events]") {
  const Job job = smoothed_job(true);
  const ReadableJob readable_job = readable(job);
  CHECK(readable_job.segments == 3);
  CHECK(readable_job.file_segments == 8);  // file segment 7 is the last
  CHECK(readable_job.event_labels == std::map<std::size_t, std::size_t>{{1, 4}, {2, 7}, {3, 8}});

  const auto events = link::to_wire_events(job, 1000, readable_job.event_labels);
  REQUIRE(events.size() == 3);  // the dwell is motion (a JointStop), not an event
  CHECK(events[0].kind == protocol::MachineEventKind::SpindleOn);
  CHECK(events[0].segment == 4);
  CHECK(events[0].value == 1000);
  CHECK(events[0].after_rest_ticks == 0);
  CHECK(events[1].kind == protocol::MachineEventKind::DigitalOutput);
  CHECK(events[1].segment == 7);
  CHECK(events[1].value == 3);
  CHECK(events[1].flag);
  CHECK(events[1].after_rest_ticks == 500);  // after the 0.5 s dwell at 1 kHz
  CHECK(events[2].kind == protocol::MachineEventKind::SpindleOff);
  CHECK(events[2].segment == 8);
}

TEST_CASE("wire events: without a source_index a job's labels are its segment numbers, after its last move their count",
          "[host_tools][link][events]") {
  const Job job = smoothed_job(false);
  const ReadableJob readable_job = readable(job);
  CHECK(readable_job.file_segments == 3);
  CHECK(readable_job.event_labels == std::map<std::size_t, std::size_t>{{1, 1}, {2, 2}, {3, 3}});
  const auto events = link::to_wire_events(job, 1000, readable_job.event_labels);
  REQUIRE(events.size() == 3);
  CHECK(events[0].segment == 1);
  CHECK(events[1].segment == 2);
  CHECK(events[2].segment == 3);
}

TEST_CASE("wire events: a joint without a label is a programming error", "[host_tools][link][events]") {
  const Job job = smoothed_job(true);
  CHECK_THROWS_AS(link::to_wire_events(job, 1000, std::map<std::size_t, std::size_t>{{1, 4}, {3, 8}}), std::logic_error);
}
