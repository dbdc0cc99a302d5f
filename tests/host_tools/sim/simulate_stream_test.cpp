// SPDX-License-Identifier: MIT
// simulate_stream (issue 19.7): the setpoints reach the sink as they are made, in order, and none
// is kept; the records and the summary equal simulate()'s, and `curvestep sim -o` writes the same
// CSV as write_setpoints_csv of the kept setpoints.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/host/job.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/simulator.hpp>

using namespace curvestep;
using namespace curvestep::host;

namespace {

std::string source(const std::string& relative) { return std::string(CURVESTEP_SOURCE_DIR) + "/" + relative; }

}  // namespace

TEST_CASE("simulate_stream: the sink sees simulate()'s setpoints in order, and the same summary", "[host_tools][sim][stream]") {
  const Job job = load_job(source("examples/jobs/every_type.json"));
  const MachineLimits machine = load_machine(source("examples/jobs/machine.json"));
  const SimulationResult kept = simulate(job, machine);
  std::size_t count = 0;
  std::size_t differing = 0;
  const SimulationSummary streamed = simulate_stream(job, machine, {}, [&](const SetpointRecord& r) {
    if (count >= kept.setpoints.size() || r.raw_q16 != kept.setpoints[count].raw_q16 || r.index != kept.setpoints[count].index ||
        r.time_s != kept.setpoints[count].time_s) {
      ++differing;
    }
    ++count;
  });
  CHECK(count == kept.setpoints.size());
  CHECK(differing == 0);
  CHECK(streamed.setpoints == kept.summary.setpoints);
  CHECK(streamed.duration_s == kept.summary.duration_s);
  CHECK(streamed.distance_mm == kept.summary.distance_mm);
  CHECK(streamed.peak_speed_mm_per_s == kept.summary.peak_speed_mm_per_s);
  CHECK(streamed.peak_acceleration_mm_per_s2 == kept.summary.peak_acceleration_mm_per_s2);
  CHECK(streamed.peak_jerk_mm_per_s3 == kept.summary.peak_jerk_mm_per_s3);
  CHECK(streamed.max_quantisation_mm == kept.summary.max_quantisation_mm);
  CHECK(streamed.peak_step_rate_hz == kept.summary.peak_step_rate_hz);
  CHECK(streamed.violations == kept.summary.violations);
}

TEST_CASE("simulate_stream: sim -o writes the CSV of the kept setpoints", "[host_tools][sim][stream]") {
  const std::string csv = "/tmp/curvestep_simulate_stream_test_" + std::to_string(::getpid()) + ".csv";
  const std::string command = std::string(CURVESTEP_BINARY) + " sim " + source("examples/jobs/seed_cubic.json") + " --machine " +
                              source("examples/jobs/machine.json") + " --lookahead 16 -o " + csv + " > /dev/null 2>&1";
  REQUIRE(std::system(command.c_str()) == 0);
  std::ifstream in(csv);
  std::stringstream written;
  written << in.rdbuf();
  SimulationOptions options;
  options.lookahead = 16;
  const SimulationResult kept = simulate(load_job(source("examples/jobs/seed_cubic.json")), load_machine(source("examples/jobs/machine.json")), options);
  std::ostringstream expected;
  write_setpoints_csv(expected, kept.setpoints);
  CHECK(written.str() == expected.str());
  std::remove(csv.c_str());
}
