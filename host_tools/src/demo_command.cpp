// SPDX-License-Identifier: MIT
// `curvestep demo`: the whole product end to end with nothing attached. For a bundled drawing (SVG)
// and a bundled CNC program (G-code) it starts the firmware as a virtual device on a pseudo-terminal,
// streams the job over the real protocol, captures the device's setpoints, checks them bit for bit
// against the simulator, and writes plots, the setpoints and an HTML report.
//
// The simulator is given what the device receives: the job and the machine after a round trip
// through the wire format and the firmware's own conversions, so a value the wire rounds (a weight,
// a tolerance) cannot make the comparison fail, and a real difference still does.
//
// The job-shaping options of sim, plot and stream (job_pipeline_options.hpp: --page, --fit, --layers,
// ...) shape the drawing (--drawing, else the bundled one); the G-code program gets the ones that are
// not for drawings only (--blend-tolerance, --strict-step-rate). The drawing's subpaths are always
// ordered (--optimize is the default here).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <curvestep/boards/host/board.hpp>
#include <curvestep/host/csv.hpp>
#include <curvestep/host/job_file.hpp>
#include <curvestep/host/link/streamer.hpp>
#include <curvestep/host/link/transport.hpp>
#include <curvestep/host/link/wire.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/job_pipeline.hpp>
#include <curvestep/host/report.hpp>
#include <curvestep/host/simulator.hpp>

#include "board_thread.hpp"
#include "command_registry.hpp"
#include "job_pipeline_options.hpp"

namespace curvestep::host {
namespace {

struct DemoOptions {
  std::string out = "build/demo";
  std::string examples = CURVESTEP_EXAMPLES_DIR;
  std::string drawing;          ///< empty: the bundled examples/svg/curvestep_demo.svg
  JobPipelineOptions pipeline;  ///< for the drawing; the program gets without_drawing_options(pipeline)
  DemoOptions() { pipeline.optimize = true; }
};

/// What one demo job produced.
struct DemoRun {
  std::string name;
  double duration_s = 0;
  double distance_mm = 0;
  double max_deviation_mm = 0;
  std::size_t setpoints = 0;   ///< captured from the device
  std::size_t expected = 0;    ///< produced by the simulator
  std::size_t lost = 0;        ///< setpoints the simulator produced that never arrived (must be 0: the stream is reliable)
  bool identical = false;      ///< every captured setpoint equals the simulator's at the same tick
  std::string difference;  ///< where the streams first differ, if they do
  std::vector<std::string> notes;  ///< the job pipeline's (import warnings, page layout, optimised travel)
};

DemoRun run_one(const std::filesystem::path& file, const MachineFile& machine_file, const std::string& out,
                const JobPipelineOptions& pipeline) {
  DemoRun run;
  run.name = file.filename().string();
  const PreparedJob prepared = prepare_job(file, machine_file, machine_file.limits, pipeline);
  const Job& job = prepared.job;
  run.notes = prepared.notes;
  const MachineLimits& machine = prepared.machine;
  const auto [device_job, device_machine] = link::as_device_sees(job, machine);

  link::StreamResult streamed;
  {
    boards::host::CountingStepOutput output;
    BoardThread<boards::host::CountingStepOutput> device(output, true);  // fast: no wall-clock wait
    auto transport = link::open_port(device.port(), 115200);
    streamed = link::stream_job(*transport, job, machine);
  }
  SimulationOptions replay;  // the device's planning window, from its Capabilities
  const bool replayable = streamed.lookahead >= 1 && streamed.lookahead <= SimulationOptions::max_lookahead;
  if (replayable) replay.lookahead = streamed.lookahead;
  const SimulationResult sim = simulate(device_job, device_machine, replay);
  run.setpoints = streamed.setpoints.size();
  run.expected = sim.setpoints.size();
  run.lost = run.expected > run.setpoints ? run.expected - run.setpoints : 0;
  run.duration_s = sim.summary.duration_s;
  run.distance_mm = sim.summary.distance_mm;
  run.max_deviation_mm = sim.summary.max_quantisation_mm + sim.summary.max_chord_deviation_mm;
  run.identical = !streamed.setpoints.empty() && streamed.setpoints.size() == sim.setpoints.size();
  if (!run.identical) run.difference = "captured " + std::to_string(streamed.setpoints.size()) + " setpoints";
  for (const auto& got : streamed.setpoints) {
    const auto tick = static_cast<std::size_t>(std::llround(got.time_s * device_machine.rate_hz));
    if (tick >= sim.setpoints.size() || got.raw_q16 != sim.setpoints[tick].raw_q16) {
      run.identical = false;
      run.difference = "first difference at setpoint " + std::to_string(tick);
      break;
    }
  }
  if (run.identical && streamed.setpoints.back().raw_q16 != sim.setpoints.back().raw_q16) {
    run.identical = false;
    run.difference = "the device did not end where the simulator did";
  }
  if (!replayable) {
    run.identical = false;
    run.difference = "the device's look-ahead " + std::to_string(streamed.lookahead) + " is beyond the simulator's " +
                     std::to_string(SimulationOptions::max_lookahead);
  }

  const std::string stem = out + "/" + file.stem().string();
  write_output(stem + "_device.csv", [&](std::ostream& s) { write_setpoints_csv(s, streamed.setpoints); });
  write_output(stem + "_sim.csv", [&](std::ostream& s) { write_setpoints_csv(s, sim.setpoints); });
  write_path_plot(stem + "_path.svg", device_job, &sim.setpoints, PathPlotOptions{});
  ReportInput report;
  report.job = &device_job;
  report.machine = &device_machine;
  report.result = &sim;
  report.fixed_point = true;
  report.title = run.name;
  write_html_report(stem + "_report.html", report);
  return run;
}

void run_demo(const DemoOptions& options) {
  std::filesystem::create_directories(options.out);
  const std::filesystem::path examples(options.examples);
  const MachineFile machine = load_machine_file(examples / "jobs" / "machine.json");
  const std::filesystem::path drawing = options.drawing.empty() ? examples / "svg" / "curvestep_demo.svg" : std::filesystem::path(options.drawing);
  const std::vector<std::pair<std::filesystem::path, JobPipelineOptions>> jobs{
      {drawing, options.pipeline}, {examples / "gcode" / "cnc_pocket.ngc", without_drawing_options(options.pipeline)}};
  std::cout << "curvestep demo: virtual device on a pseudo-terminal, real protocol, simulator check\n";
  bool all_identical = true;
  for (const auto& [file, pipeline] : jobs) {
    const DemoRun run = run_one(file, machine, options.out, pipeline);
    all_identical = all_identical && run.identical;
    std::cout << "  " << run.name << "\n"
              << "    duration:             " << run.duration_s << " s\n"
              << "    distance:             " << run.distance_mm << " mm\n"
              << "    max deviation:        " << run.max_deviation_mm * 1000 << " um\n"
              << "    setpoints:            " << run.setpoints << " captured of " << run.expected << "\n"
              << "    setpoints identical:  " << (run.identical ? "yes" : "no (" + run.difference + ")") << "\n";
    for (const auto& note : run.notes) std::cout << "    note: " << note << "\n";
    if (run.lost > 0) {
      all_identical = false;
      std::cout << "    error:                " << run.lost << " setpoints never arrived\n";
    }
  }
  std::cout << "  outputs (plots, setpoints, reports) in " << options.out << "\n";
  if (!all_identical) throw std::runtime_error("the device's setpoints differ from the simulator's");
}

void add_demo_command(CLI::App& app) {
  auto options = std::make_shared<DemoOptions>();
  auto* demo = app.add_subcommand("demo", "Stream the bundled SVG and G-code examples to a virtual device and check them against the simulator");
  demo->add_option("--out", options->out, "Output folder")->capture_default_str();
  demo->add_option("--examples", options->examples, "Folder with the bundled examples")->capture_default_str();
  demo->add_option("--drawing", options->drawing, "SVG drawing to run instead of the bundled one (the G-code program stays)");
  add_job_pipeline_options(demo, options->pipeline);
  demo->callback([options] { run_demo(*options); });
}

const RegisterCommand registered{90, add_demo_command};

}  // namespace
}  // namespace curvestep::host
