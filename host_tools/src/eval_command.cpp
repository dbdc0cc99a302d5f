// SPDX-License-Identifier: MIT
// `curvestep eval JOB --segment I --u U1,U2,...`: exact positions of one segment of a job file.
#include <cstddef>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <curvestep/host/job_file.hpp>
#include <curvestep/host/csv.hpp>
#include <curvestep/host/job.hpp>

#include "command_registry.hpp"
#include "job_pipeline_options.hpp"

namespace curvestep::host {
namespace {

struct EvalOptions {
  std::string job;
  long long segment = 0;
  std::vector<double> parameters;
  std::string out;
  bool optimize = false;
  std::vector<std::string> subroutine_path;
};

void run_eval(const EvalOptions& options) {
  std::vector<std::string> notes;
  JobFileOptions file;
  file.optimize = options.optimize;
  file.gcode.subroutine_path.assign(options.subroutine_path.begin(), options.subroutine_path.end());
  const Job job = load_job_file(options.job, file, &notes);
  for (const auto& note : notes) std::cerr << "curvestep: " << note << "\n";
  std::vector<MachinePoint> points;
  for (const double u : options.parameters) points.push_back(evaluate_segment(job, static_cast<std::size_t>(options.segment), u));
  write_output(options.out, [&](std::ostream& out) { write_points_csv(out, points); });
}

}  // namespace

namespace {

void add_eval_command(CLI::App& app) {
  auto options = std::make_shared<EvalOptions>();
  auto* eval = app.add_subcommand("eval", "Write the exact points of one segment of a job at its own parameter values (CSV x,y,z)");
  eval->add_option("job", options->job, job_file_help())->required();
  eval->add_option("--segment", options->segment, "Segment index in the file, counted from 0")
      ->required()
      ->check(CLI::Range(0LL, 1000000000LL));
  eval->add_option("--u", options->parameters, "Parameter values, comma separated ([0,1], or the knot domain of a bspline/nurbs)")
      ->required()
      ->delimiter(',');
  eval->add_option("-o,--output", options->out, "Output CSV file (default: standard output)");
  eval->add_flag("--optimize", options->optimize, "SVG: order subpaths to shorten pen-up travel and report the saving");
  add_subroutine_path_option(eval, options->subroutine_path);
  eval->callback([options] { run_eval(*options); });
}

const RegisterCommand registered{20, add_eval_command};

}  // namespace

}  // namespace curvestep::host
