// SPDX-License-Identifier: MIT
// `curvestep sample JOB --tolerance MM`: the job flattened into a polyline within the tolerance.
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include <curvestep/host/csv.hpp>
#include <curvestep/host/flatten.hpp>
#include <curvestep/host/job.hpp>

#include "command_registry.hpp"

namespace curvestep::host {
namespace {

struct SampleOptions {
  std::string job;
  double tolerance_mm = 0;
  std::string out;
};

void run_sample(const SampleOptions& options) {
  if (!(options.tolerance_mm >= 1e-6)) throw std::invalid_argument("--tolerance must be at least 1e-6 mm");
  const Job job = load_job(options.job);
  const auto points = flatten_path(job.segments, options.tolerance_mm);
  if (options.out.empty()) {
    write_points_csv(std::cout, points);
    return;
  }
  std::ofstream file(options.out);
  if (!file) throw std::runtime_error(options.out + ": cannot open for writing");
  write_points_csv(file, points);
  if (!file) throw std::runtime_error(options.out + ": write failed");
}

}  // namespace

namespace {

void add_sample_command(CLI::App& app) {
  auto options = std::make_shared<SampleOptions>();
  auto* sample = app.add_subcommand("sample", "Flatten a job into a polyline within a tolerance (CSV x,y,z)");
  sample->add_option("job", options->job, "Job file (JSON, see docs/job_format.md)")->required();
  sample->add_option("--tolerance", options->tolerance_mm, "Largest distance from the true path, mm")->required();
  sample->add_option("-o,--output", options->out, "Output CSV file (default: standard output)");
  sample->callback([options] { run_sample(*options); });
}

const RegisterCommand registered{30, add_sample_command};

}  // namespace

}  // namespace curvestep::host
