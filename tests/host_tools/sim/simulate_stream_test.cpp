// SPDX-License-Identifier: MIT
// simulate_stream (issue 19.7): the setpoints reach the sink as they are made, in order, and none
// is kept; the records and the summary equal simulate()'s, and `curvestep sim -o` writes the same
// CSV as write_setpoints_csv of the kept setpoints. A ReadableJob is simulated from one new read.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/host/job.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/readable_job.hpp>
#include <curvestep/host/segment_source.hpp>
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

TEST_CASE("simulate_stream: a ReadableJob runs from one new read as the job held whole, its progress from its approximate length",
          "[host_tools][sim][stream]") {
  // One 100 mm line at 1 mm/s: about 100 000 setpoints at 1 kHz, progress reported every 20 000.
  const Job job = parse_job(R"({"version": 1, "segments": [{"type": "line", "points": [[0, 0], [100, 0]], "feed": 1}]})", "slow.json");
  const MachineLimits machine = load_machine(source("examples/jobs/machine.json"));
  const SimulationResult kept = simulate(job, machine);
  ReadableJob readable_job = readable(job);
  readable_job.approximate_length_mm = 100;  // the line's length, by hand
  std::size_t reads = 0;
  readable_job.read = [&job, &reads] {
    ++reads;
    return std::make_unique<JobSegments>(job);
  };
  std::vector<double> fractions;
  SimulationOptions options;
  options.progress = [&](double f) { fractions.push_back(f); };
  std::size_t count = 0;
  std::size_t differing = 0;
  const SimulationSummary streamed = simulate_stream(readable_job, machine, options, [&](const SetpointRecord& r) {
    if (count >= kept.setpoints.size() || r.raw_q16 != kept.setpoints[count].raw_q16 || r.index != kept.setpoints[count].index) ++differing;
    ++count;
  });
  CHECK(reads == 1);
  CHECK(count == kept.setpoints.size());
  CHECK(differing == 0);
  CHECK(streamed.setpoints == kept.summary.setpoints);
  CHECK(streamed.duration_s == kept.summary.duration_s);
  CHECK(streamed.peak_jerk_mm_per_s3 == kept.summary.peak_jerk_mm_per_s3);
  REQUIRE(fractions.size() == 6);  // at 20 000, 40 000, ..., 100 000 setpoints, then 1.0 at the end
  for (std::size_t i = 0; i + 1 < fractions.size(); ++i) {
    INFO("report " << i);
    CHECK(fractions[i] == Approx(0.2 * static_cast<double>(i + 1)).margin(0.01));  // 20·(i+1) mm of 100
  }
  CHECK(fractions.back() == 1.0);
}
