// SPDX-License-Identifier: MIT
// `curvestep plot JOB -o out.svg [--machine MACHINE.json]`: the path as an SVG drawing, feed moves
// coloured by planned speed (with a machine, from a simulation) or by segment (without). The
// simulation's setpoints are drawn as they come (memory independent of the job's length).
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include <curvestep/host/job.hpp>
#include <curvestep/host/job_file.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/report.hpp>
#include <curvestep/host/job_pipeline.hpp>
#include <curvestep/host/streamed_job.hpp>
#include <curvestep/host/simulator.hpp>

#include "command_registry.hpp"
#include "job_pipeline_options.hpp"

namespace curvestep::host {
namespace {

struct PlotOptions {
  std::string job;
  std::string machine;
  std::string output;
  JobPipelineOptions pipeline;
};

void run_plot(const PlotOptions& o) {
  PathPlotOptions plot;
  if (o.machine.empty()) {
    // Without a machine: the programmed path (nothing to smooth for).
    const Job job = load_job_file(o.job, job_file_options(o.pipeline));
    plot.title = job.name;
    write_path_plot(o.output, job, nullptr, plot);
  } else {
    // With a machine: the path the machine runs (the job pipeline of sim, stream and gpio).
    const MachineFile machine_file = load_machine_file(o.machine);
    // A streamed job is not held: each of the two passes below reads the file again, as sim does.
    const StreamedJobPlan plan = plan_job(o.job, machine_file, machine_file.limits, o.pipeline);
    const Job& job = plan.prepared.job;
    const MachineLimits& machine = plan.prepared.machine;
    plot.title = job.name;
    // The setpoints are drawn as they are made, twice over (extent, then strokes): none is kept.
    const auto progress = make_terminal_progress();
    int pass = 0;
    SimulationOptions options;
    options.lookahead_distance_mm = lookahead_distance_for(machine);
    options.progress = [&](double fraction) {
      if (progress) progress((pass + fraction) / 2);
    };
    const SetpointReplay replay = [&](const SetpointSink& sink) {
      (void)simulate_streamed_job(plan, o.job, machine_file, machine_file.limits, o.pipeline, options, sink);
      ++pass;
    };
    if (plan.streamed) {
      if (plan.segments == 0) throw std::invalid_argument(job.name + ": the job has no segments");
      write_path_plot_streamed(o.output, PlottedJob{job.name, [&plan](std::size_t source) { return plan.rapid_source(source); }}, replay,
                               plot);
    } else {
      write_path_plot_streamed(o.output, job, replay, plot);
    }
    finish_terminal_progress();
  }
  std::cout << "  wrote " << o.output << "\n";
}

void add_plot_command(CLI::App& app) {
  auto options = std::make_shared<PlotOptions>();
  auto* plot = app.add_subcommand("plot", "Draw a job's path as SVG (coloured by planned speed with --machine, else by segment)");
  plot->add_option("job", options->job, "Job file (.json, G-code or .svg)")->required()->check(CLI::ExistingFile);
  plot->add_option("-o,--output", options->output, "SVG file to write")->required();
  plot->add_option("--machine,-m", options->machine, "Machine file (.json): simulate and colour by planned speed")
      ->check(CLI::ExistingFile);
  add_job_pipeline_options(plot, options->pipeline);
  plot->callback([options] { run_plot(*options); });
}

const RegisterCommand registered{45, add_plot_command};

}  // namespace
}  // namespace curvestep::host
