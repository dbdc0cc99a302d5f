// SPDX-License-Identifier: MIT
// `curvestep sample JOB --tolerance MM`: the job flattened into a polyline within the tolerance.
#include <vector>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include <curvestep/host/job_file.hpp>
#include <curvestep/host/csv.hpp>
#include <curvestep/host/flatten.hpp>
#include <curvestep/host/job.hpp>

#include "command_registry.hpp"
#include "job_pipeline_options.hpp"

namespace curvestep::host {
namespace {

struct SampleOptions {
  std::string job;
  double tolerance_mm = 0;
  std::string out;
  bool optimize = false;
  std::vector<std::string> subroutine_path;
};

void run_sample(const SampleOptions& options) {
  if (!(options.tolerance_mm >= 1e-6)) throw std::invalid_argument("--tolerance must be at least 1e-6 mm");
  std::vector<std::string> notes;
  JobFileOptions file;
  file.optimize = options.optimize;
  file.gcode.subroutine_path.assign(options.subroutine_path.begin(), options.subroutine_path.end());
  const Job job = load_job_file(options.job, file, &notes);
  for (const auto& note : notes) std::cerr << "curvestep: " << note << "\n";
  const auto points = flatten_path(job.segments, options.tolerance_mm);
  write_output(options.out, [&](std::ostream& out) { write_points_csv(out, points); });
}

}  // namespace

namespace {

void add_sample_command(CLI::App& app) {
  auto options = std::make_shared<SampleOptions>();
  auto* sample = app.add_subcommand("sample", "Flatten a job into a polyline within a tolerance (CSV x,y,z)");
  sample->add_option("job", options->job, job_file_help())->required();
  sample->add_option("--tolerance", options->tolerance_mm, "Largest distance from the true path, mm")->required();
  sample->add_option("-o,--output", options->out, "Output CSV file (default: standard output)");
  sample->add_flag("--optimize", options->optimize, "SVG: order subpaths to shorten pen-up travel and report the saving");
  add_subroutine_path_option(sample, options->subroutine_path);
  sample->callback([options] { run_sample(*options); });
}

const RegisterCommand registered{30, add_sample_command};

}  // namespace

}  // namespace curvestep::host
