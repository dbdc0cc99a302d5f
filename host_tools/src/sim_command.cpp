// SPDX-License-Identifier: MIT
// `curvestep sim JOB --machine MACHINE.json [--rate HZ] [--lookahead N] [-o setpoints.csv] [--report report.html]`:
// replays a job through the firmware's motion code and prints what the machine would do.
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <unistd.h>

#include <curvestep/host/job_file.hpp>
#include <curvestep/host/csv.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/report.hpp>
#include <curvestep/host/simulator.hpp>

#include "command_registry.hpp"
#include "rate_option.hpp"

namespace curvestep::host {
namespace {

struct SimOptions {
  std::string job;
  std::string machine;
  double rate_hz = 0;
  long long lookahead = static_cast<long long>(SimulationOptions::max_lookahead);
  std::string output;
  std::string report;
  bool double_precision = false;
};

/// Exit status for a job the machine cannot run within its limits.
constexpr int exit_limits_exceeded = 3;

int run_sim(const SimOptions& o) {
  if (o.lookahead < 1 || o.lookahead > static_cast<long long>(SimulationOptions::max_lookahead)) {
    throw std::runtime_error("--lookahead: must be between 1 and " + std::to_string(SimulationOptions::max_lookahead) + " segments");
  }
  const Job job = load_job_file(o.job);
  MachineLimits machine = load_machine(o.machine);
  if (o.rate_hz > 0) {
    machine.rate_hz = o.rate_hz;
    if (auto valid = machine.validate(); !valid) throw std::runtime_error("--rate: must be between 100 and 100000 Hz");
  }
  SimulationOptions options;
  options.lookahead = static_cast<std::size_t>(o.lookahead);
  options.fixed_point = !o.double_precision;
  options.progress = make_terminal_progress();  // a bar with ETA on a terminal, quiet otherwise
  const SimulationResult result = simulate(job, machine, options);
  finish_terminal_progress();
  if (!o.output.empty()) write_output(o.output, [&](std::ostream& out) { write_setpoints_csv(out, result.setpoints); });
  if (!o.report.empty()) {
    ReportInput report;
    report.job = &job;
    report.machine = &machine;
    report.result = &result;
    report.fixed_point = !o.double_precision;
    report.title = o.job;
    write_html_report(o.report, report);
  }
  std::cout << "curvestep sim " << o.job << " (" << (o.double_precision ? "double" : "Q16.16");
  if (options.lookahead != SimulationOptions::max_lookahead) std::cout << ", look-ahead " << options.lookahead;
  std::cout << ")\n"
            << format_summary(result.summary, machine);
  if (!o.output.empty()) std::cout << "  wrote " << o.output << "\n";
  if (!o.report.empty()) std::cout << "  wrote " << o.report << "\n";
  return result.summary.violations.empty() ? 0 : exit_limits_exceeded;
}

}  // namespace

namespace {

void add_sim_command(CLI::App& app) {
  auto options = std::make_shared<SimOptions>();
  auto* sim = app.add_subcommand("sim", "Replay a job exactly as the firmware would run it and report the motion");
  sim->add_option("job", options->job, "Job file: .json, G-code (.ngc .nc .gcode .tap) or .svg")->required()->check(CLI::ExistingFile);
  sim->add_option("--machine,-m", options->machine, "Machine file (.json)")->required()->check(CLI::ExistingFile);
  sim->add_option("--rate", options->rate_hz, "Setpoint rate in Hz (100..100000), overriding the machine file")
      ->check(rate_hz_check());
  sim->add_option("--lookahead", options->lookahead,
                  "Look-ahead window in segments (1..16, default 16). The setpoints depend on it: give a device's "
                  "window to reproduce its stream bit for bit (docs/motion.md, \"Look-ahead and determinism\")");
  sim->add_option("-o,--output", options->output, "Write the setpoints as CSV (t,x,y,z,v)");
  sim->add_option("--report", options->report, "Write a self-contained HTML report (path, speed/acceleration/jerk, summary)");
  sim->add_flag("--double", options->double_precision, "Write double-precision setpoints instead of Q16.16");
  sim->callback([options] {
    const int status = run_sim(*options);
    if (status != 0) throw CLI::RuntimeError(status);
  });
}

const RegisterCommand registered{40, add_sim_command};

}  // namespace

}  // namespace curvestep::host
