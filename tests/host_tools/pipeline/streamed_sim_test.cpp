// SPDX-License-Identifier: MIT
// `curvestep sim` of a job it does not hold (issue 19 item 7, streamed_job.hpp): the first pass
// finds what the whole-job pipeline finds (count, events, errors), and the run pulling the
// segments from a second read of the file makes the setpoints and summary of the job held whole,
// bit for bit. The expected side is the whole-job path (prepare_job + simulate_stream of the Job),
// which the streamed one does not use.
#include <array>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/host/job_pipeline.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/simulator.hpp>
#include <curvestep/host/streamed_job.hpp>

using namespace curvestep;
using namespace curvestep::host;

namespace {

const std::filesystem::path source_dir(CURVESTEP_SOURCE_DIR);

std::string scratch(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("streamed_sim_" + std::to_string(::getpid()) + "_" + name)).string();
}

struct Run {
  std::string csv;  ///< write_setpoint_csv_line of every setpoint
  std::vector<std::array<std::int32_t, 3>> raw;
  std::string summary;  ///< format_summary
  SimulationSummary figures;
};

SimulationOptions sim_options(const MachineLimits& machine) {
  SimulationOptions options;
  options.lookahead_distance_mm = lookahead_distance_for(machine);  // as `curvestep sim` without --lookahead
  return options;
}

Run collect(const std::function<SimulationSummary(const SetpointSink&)>& simulate_into, const MachineLimits& machine) {
  Run run;
  std::ostringstream csv;
  run.figures = simulate_into([&](const SetpointRecord& r) {
    write_setpoint_csv_line(csv, r);
    run.raw.push_back(r.raw_q16);
  });
  run.csv = csv.str();
  run.summary = format_summary(run.figures, machine);
  return run;
}

void check_same_as_whole(const std::filesystem::path& file, const JobPipelineOptions& options = {}) {
  INFO(file.string());
  const MachineFile machine_file = load_machine_file(source_dir / "examples/jobs/machine.json");
  const PreparedJob whole = prepare_job(file, machine_file, machine_file.limits, options);
  const Run expected = collect([&](const SetpointSink& sink) { return simulate_stream(whole.job, whole.machine, sim_options(whole.machine), sink); },
                               whole.machine);

  REQUIRE(is_streamed(file, machine_file));
  StreamedJobPlan plan = plan_streamed_job(file, machine_file, machine_file.limits, options);
  CHECK(plan.segments == whole.job.segments.size());
  CHECK(plan.prepared.job.segments.empty());
  CHECK(plan.prepared.job.source_index.empty());  // nothing per segment is kept
  REQUIRE(plan.prepared.job.events.size() == whole.job.events.size());
  const std::vector<std::size_t>& source_index = whole.job.source_index;
  for (std::size_t k = 0; k < whole.job.events.size(); ++k) {
    const std::size_t joint = whole.job.events[k].before_segment;
    CHECK(plan.prepared.job.events[k].before_segment == joint);
    CHECK(plan.prepared.job.events[k].text == whole.job.events[k].text);
    // The event timeline's label: the file segment after the joint, after the end the last one's + 1.
    const std::size_t label = joint < source_index.size() ? source_index[joint] : (source_index.empty() ? 0 : source_index.back() + 1);
    REQUIRE(plan.prepared.event_labels.count(joint) == 1);
    CHECK(plan.prepared.event_labels.at(joint) == label);
  }
  CHECK(plan.prepared.smoothing.segments_after == whole.smoothing.segments_after);
  CHECK(plan.prepared.notes == whole.notes);
  const Run streamed = collect(
      [&](const SetpointSink& sink) {
        StreamedJob job{&plan.prepared.job, plan.segments, plan.approximate_length_mm,
                        stream_segments(file, machine_file, machine_file.limits, options)};
        return simulate_stream(std::move(job), plan.prepared.machine, sim_options(plan.prepared.machine), sink);
      },
      plan.prepared.machine);
  CHECK(streamed.raw.size() == expected.raw.size());
  CHECK(streamed.raw == expected.raw);
  CHECK(streamed.csv == expected.csv);
  CHECK(streamed.summary == expected.summary);
  CHECK(streamed.figures.peak_jerk_mm_per_s3 == expected.figures.peak_jerk_mm_per_s3);
  CHECK(streamed.figures.max_quantisation_mm == expected.figures.max_quantisation_mm);
}

}  // namespace

TEST_CASE("streamed sim: every example G-code program simulates bit for bit as the job held whole", "[host_tools][pipeline][streamed]") {
  std::size_t programs = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(source_dir / "examples/gcode")) {
    const std::string extension = entry.path().extension().string();
    if (extension != ".ngc" && extension != ".nc" && extension != ".gcode" && extension != ".tap") continue;
    check_same_as_whole(entry.path());
    ++programs;
  }
  CHECK(programs >= 10);
}

TEST_CASE("streamed sim: programs with events simulate bit for bit as the job held whole with smoothing off", "[host_tools][pipeline][streamed]") {
  JobPipelineOptions off;
  off.blend_tolerance_mm = 0;  // the job as programmed: the stream numbers nothing
  for (const char* name : {"cam/freecad_style_profile.ngc", "cam/fusion_style_drill.nc", "cam/carbide_create_style.nc", "cnc_pocket.ngc"}) {
    check_same_as_whole(source_dir / "examples/gcode" / name, off);
  }
}

TEST_CASE("streamed sim: JSON jobs simulate bit for bit as the job held whole", "[host_tools][pipeline][streamed]") {
  for (const char* name : {"every_type.json", "helix.json", "inch_square.json", "polyline.json", "seed_cubic.json"}) {
    check_same_as_whole(source_dir / "examples/jobs" / name);
  }
}

TEST_CASE("streamed sim: the first pass refuses a move past the travel with the whole job's message", "[host_tools][pipeline][streamed]") {
  // The example machine with an x travel of 0 .. 50 mm.
  MachineFile machine_file = load_machine_file(source_dir / "examples/jobs/machine.json");
  REQUIRE_FALSE(machine_file.travel[0].has_value());
  machine_file.travel[0] = AxisTravel{0, 50};
  const std::string program = scratch("travel.ngc");
  std::ofstream(program) << "G21 G90 G17\nF600\nG1 X10\nG1 X20 Y5\nG1 X60 Y5\nG1 X0 Y0\n";
  std::string whole_message;
  try {
    (void)prepare_job(program, machine_file, machine_file.limits, JobPipelineOptions{});
  } catch (const std::exception& e) {
    whole_message = e.what();
  }
  REQUIRE(whole_message.find(":5") != std::string::npos);  // line 5 reaches x = 60 mm
  REQUIRE_THROWS_WITH(plan_streamed_job(program, machine_file, machine_file.limits, JobPipelineOptions{}), whole_message);
  std::remove(program.c_str());
}

TEST_CASE("streamed sim: an error of the second read is thrown by the run, and a source dropped early stops its thread",
          "[host_tools][pipeline][streamed]") {
  const MachineFile machine_file = load_machine_file(source_dir / "examples/jobs/machine.json");
  const std::string program = scratch("changed.ngc");
  std::string text = "G21 G90 G17\nF600\n";
  for (int i = 1; i <= 2000; ++i) text += "G1 X" + std::to_string(i % 2 == 0 ? 0 : 10) + " Y" + std::to_string(i) + "\n";
  std::ofstream(program) << text;
  StreamedJobPlan plan = plan_streamed_job(program, machine_file, machine_file.limits, JobPipelineOptions{});
  REQUIRE(plan.segments >= 2000);

  {  // dropped after one segment: the reader, blocked on the full queue, ends (no hang, no error)
    auto source = stream_segments(program, machine_file, machine_file.limits, JobPipelineOptions{});
    std::size_t index = 99;
    REQUIRE(source->next(index) != nullptr);
    CHECK(index == 0);
  }

  // The file changes between the passes: line 1500 no longer reads.
  std::ofstream(program) << text.substr(0, text.find("G1 X0 Y1500")) << "G1 X0 Y1500 Q\n";
  StreamedJob job{&plan.prepared.job, plan.segments, plan.approximate_length_mm,
                  stream_segments(program, machine_file, machine_file.limits, JobPipelineOptions{})};
  REQUIRE_THROWS_WITH(simulate_stream(std::move(job), plan.prepared.machine, sim_options(plan.prepared.machine), {}),
                      Catch::Contains(":1502"));
  std::remove(program.c_str());
}

TEST_CASE("streamed sim: a file changed after the first read ends the run with a message naming it", "[host_tools][pipeline][streamed]") {
  const MachineFile machine_file = load_machine_file(source_dir / "examples/jobs/machine.json");
  const std::string program = scratch("changed.ngc");
  std::ofstream(program) << "G21 G90 G17\nF600\nG1 X10\nG1 X10 Y10\nM2\n";
  const StreamedJobPlan plan = plan_streamed_job(program, machine_file, machine_file.limits, JobPipelineOptions{});
  REQUIRE(plan.segments >= 1);
  // The same file read again runs; rewritten (longer: another size) it is refused before a segment.
  SimulationOptions options;
  options.lookahead_distance_mm = lookahead_distance_for(plan.prepared.machine);
  CHECK(simulate_streamed_job(plan, program, machine_file, machine_file.limits, JobPipelineOptions{}, options, {}).setpoints > 0);
  std::ofstream(program) << "G21 G90 G17\nF600\nG1 X10\nG1 X10 Y10\nG1 X40 Y10\nM2\n";
  CHECK_THROWS_WITH(simulate_streamed_job(plan, program, machine_file, machine_file.limits, JobPipelineOptions{}, options, {}),
                    Catch::Contains(program) && Catch::Contains("the file changed while the job ran"));
  std::remove(program.c_str());
}
