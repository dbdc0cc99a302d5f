// SPDX-License-Identifier: MIT
// The job pipeline: step-rate-aware limits (hand-computed), the smoothed job, and the same options
// on every command that moves a machine.
#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/host/job_pipeline.hpp>
#include <curvestep/host/simulator.hpp>

using namespace curvestep;
using namespace curvestep::host;

namespace {

const std::filesystem::path source_dir(CURVESTEP_SOURCE_DIR);

MachineLimits slow_drivers() {
  MachineLimits m = load_machine_file(source_dir / "examples/jobs/machine.json").limits;
  m.max_step_rate_hz = 8000;  // x, y: 80 steps/mm -> 100 mm/s; z: 400 steps/mm -> 20 mm/s
  return m;
}

std::string help_of(const std::string& command) {
  const std::string line = std::string(CURVESTEP_BINARY) + " " + command + " --help 2>&1";
  std::FILE* pipe = popen(line.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::string text;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), pipe) != nullptr) text += buffer.data();
  pclose(pipe);
  return text;
}

}  // namespace

TEST_CASE("pipeline: an axis whose drivers cannot step v_max is planned slower, by hand", "[host][pipeline]") {
  std::vector<std::string> notes;
  const MachineLimits m = step_rate_aware(slow_drivers(), &notes);
  // 0.99 · 8000 / 80 = 99 mm/s for x and y (machine v_max 200); z: 0.99 · 8000 / 400 = 19.8 < its 20.
  CHECK(m.axes[0].v_max_mm_per_s == Approx(99.0));
  CHECK(m.axes[1].v_max_mm_per_s == Approx(99.0));
  CHECK(m.axes[2].v_max_mm_per_s == Approx(19.8));
  CHECK(notes.size() == 3);
  // Fast drivers: nothing changes.
  const MachineLimits fast = load_machine_file(source_dir / "examples/jobs/machine.json").limits;
  const MachineLimits same = step_rate_aware(fast);
  for (std::size_t a = 0; a < motion_axes; ++a) CHECK(same.axes[a].v_max_mm_per_s == fast.axes[a].v_max_mm_per_s);
}

TEST_CASE("pipeline: a job too fast for the drivers runs within max_step_rate, and --strict-step-rate refuses it", "[host][pipeline]") {
  const auto job = source_dir / "examples/jobs/every_type.json";
  const MachineLimits machine = slow_drivers();
  const PreparedJob planned_slower = prepare_job(job, machine, 0.01, JobPipelineOptions{});
  const auto slower = simulate(planned_slower.job, planned_slower.machine).summary;
  CHECK(slower.violations.empty());
  for (std::size_t a = 0; a < motion_axes; ++a) CHECK(slower.peak_step_rate_hz[a] <= 8000);
  JobPipelineOptions strict;
  strict.strict_step_rate = true;
  const PreparedJob as_programmed = prepare_job(job, machine, 0.01, strict);
  const auto refused = simulate(as_programmed.job, as_programmed.machine).summary;
  REQUIRE_FALSE(refused.violations.empty());
  CHECK(refused.violations.front().find("max_step_rate") != std::string::npos);
}

TEST_CASE("pipeline: the job is smoothed with the machine file's tolerance unless the command line says otherwise", "[host][pipeline]") {
  const auto job = source_dir / "examples/jobs/polyline.json";
  const MachineLimits machine = load_machine_file(source_dir / "examples/jobs/machine.json").limits;
  const PreparedJob from_file = prepare_job(job, machine, 0.01, JobPipelineOptions{});
  CHECK(from_file.smoothing.tolerance_mm == 0.01);
  CHECK(from_file.smoothing.runs_fitted == 1);
  JobPipelineOptions off;
  off.blend_tolerance_mm = 0;
  const PreparedJob as_programmed = prepare_job(job, machine, 0.01, off);
  CHECK(as_programmed.job.segments.size() == 95);
  CHECK(from_file.job.segments.size() < as_programmed.job.segments.size());
}

TEST_CASE("pipeline: sim, plot, stream and gpio accept the same job options", "[host][pipeline]") {
  for (const char* command : {"sim", "plot", "stream", "gpio"}) {
    INFO(command);
    const std::string help = help_of(command);
    CHECK(help.find("--optimize") != std::string::npos);
    CHECK(help.find("--blend-tolerance") != std::string::npos);
    CHECK(help.find("--strict-step-rate") != std::string::npos);
  }
}
