// SPDX-License-Identifier: MIT
// `curvestep stream JOB --machine MACHINE.json --port PORT [--baud N] [--capture setpoints.csv] [--lookahead N]`:
// uploads a job to a controller with flow control, shows progress on a terminal, captures the
// controller's setpoint stream (the CSV of `curvestep sim -o`) and reports its errors. A
// controller without a planner (look-ahead 0) gets the job planned here with --lookahead N
// (default 16) as pieces: its stream is then `curvestep sim --lookahead N`'s.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <poll.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <curvestep/host/job.hpp>
#include <curvestep/host/job_file.hpp>
#include <curvestep/host/link/host_link.hpp>
#include <curvestep/host/link/streamer.hpp>
#include <curvestep/host/link/transport.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/job_pipeline.hpp>
#include <curvestep/host/simulator.hpp>

#include "command_registry.hpp"
#include "job_pipeline_options.hpp"

namespace curvestep::host {
namespace {

/// Program pauses (M0/M1, M6, a pen change): say what for on standard output and go on when the
/// operator presses Enter (a line on standard input), or at once with --resume-pauses.
void set_pause_handling(link::StreamOptions& options, bool at_once) {
  options.paused = [at_once](const std::string& what) {
    std::cout << "curvestep stream: " << what << (at_once ? " (--resume-pauses: going on)" : "; press Enter to go on") << std::endl;
  };
  if (at_once) return;  // resume_now empty: at once
  options.resume_now = [] {
    pollfd in{STDIN_FILENO, POLLIN, 0};
    if (::poll(&in, 1, 0) <= 0) return false;
    std::string line;
    std::getline(std::cin, line);  // a whole line is there (Enter) or the input ended
    return true;
  };
}

struct StreamCommandOptions {
  std::string job;
  std::string machine;
  std::string port;
  int baud = 115200;
  std::string capture;
  unsigned link_timeout_ms = 3000;
  std::size_t lookahead = SimulationOptions::max_lookahead;  ///< planning window for a controller without a planner
  bool resume_pauses = false;  ///< --resume-pauses: go on at once after M0/M1, M6 and pen changes
  JobPipelineOptions pipeline;
  bool lookahead_given = false;    ///< --lookahead given: plan with that count window alone
};

/// Exit status when the controller or the link failed.
constexpr int exit_device_error = 4;

/// The machine file without its "gpio" section (the device's wiring, not planning data).
MachineFile load_machine_for_stream(const std::string& path) {
  const std::string text = read_text_file(path);
  const auto root = nlohmann::json::parse(text, nullptr, false, true);
  if (root.is_object() && root.contains("gpio")) {
    auto planning = root;
    planning.erase("gpio");
    return parse_machine_file(planning.dump(2), path);
  }
  return load_machine_file(path);
}

std::string format_seconds(double s) {
  if (s < 0) return "--:--";
  const long total = static_cast<long>(s + 0.5);
  char text[32];
  std::snprintf(text, sizeof text, "%ld:%02ld", total / 60, total % 60);
  return text;
}

/// Which mode ran: the device planned with its own window, or it replayed pieces planned here.
std::string look_ahead_text(const link::StreamResult& result, bool by_distance) {
  if (result.lookahead == 0) {
    if (by_distance) return "none (it replays pieces planned here with the distance window: curvestep sim gives the same setpoints)";
    const std::string n = std::to_string(result.planned_lookahead);
    return "none (it replays pieces planned here with --lookahead " + n + ": curvestep sim --lookahead " + n +
           " gives the same setpoints)";
  }
  return std::to_string(result.lookahead) + " segments (" +
         (result.lookahead <= SimulationOptions::max_lookahead
              ? "curvestep sim --lookahead " + std::to_string(result.lookahead) + " plans the same setpoints"
              : "above curvestep sim's largest window, " + std::to_string(SimulationOptions::max_lookahead) +
                    ": no simulation replays it") +
         ")";
}

int run_stream(const StreamCommandOptions& o) {
  const MachineFile machine_file = load_machine_for_stream(o.machine);
  const PreparedJob prepared = prepare_job(o.job, machine_file, machine_file.limits, o.pipeline);
  const Job& job = prepared.job;
  const MachineLimits& machine = prepared.machine;
  for (const auto& note : prepared.notes) std::cerr << "curvestep stream: note: " << note << "\n";
  auto transport = link::open_port(o.port, o.baud);
  link::StreamOptions options;
  options.travel = machine_file.travel;
  options.link.link_timeout_ms = o.link_timeout_ms;
  options.lookahead = o.lookahead;
  if (!o.lookahead_given) options.lookahead_distance_mm = lookahead_distance_for(machine);
  options.warn = [](const std::string& text) { std::cerr << "curvestep stream: warning: " << text << "\n"; };
  set_pause_handling(options, o.resume_pauses);
  const bool terminal = isatty(STDERR_FILENO) != 0;
  if (terminal) {
    options.progress = [](const link::StreamProgress& p) {
      std::cerr << "\r  " << p.unit << " " << p.sent << "/" << p.total << "  setpoints " << p.setpoints_received
                << "  elapsed " << format_seconds(p.elapsed_s) << "  ETA " << format_seconds(p.eta_s) << "   " << std::flush;
    };
  }
  link::StreamResult result;
  try {
    result = link::stream_job(*transport, job, machine, options);
  } catch (const link::StreamError& e) {
    if (terminal) std::cerr << "\n";
    std::cerr << "curvestep stream: " << e.what() << "\n";
    return exit_device_error;
  } catch (const link::TransportError& e) {
    if (terminal) std::cerr << "\n";
    std::cerr << "curvestep stream: " << e.what() << "\n";
    return exit_device_error;
  }
  if (terminal) std::cerr << "\n";
  if (!o.capture.empty()) {
    std::ofstream out(o.capture);
    if (!out) throw std::runtime_error("cannot write " + o.capture);
    write_setpoints_csv(out, result.setpoints);
    if (!out) throw std::runtime_error("error writing " + o.capture);
  }
  std::cout << "curvestep stream " << o.job << " -> " << o.port << "\n"
            << "  setpoints received:  " << result.setpoints.size() << "\n"
            << "  ticks standing:      " << result.standing_ticks << " (held or starved, not reported)\n"
            << "  setpoints duplicated: " << result.duplicate_setpoints << "\n"
            << "  batches resent:      " << result.batches_repeated << "\n"
            << "  damaged frames:      " << result.frames_rejected << "\n"
            << "  device queue peak:   " << result.max_queue_depth << " of " << result.queue_capacity
            << (result.lookahead == 0 ? " pieces\n" : " segments\n")
            << "  device look-ahead:   " << look_ahead_text(result, !o.lookahead_given) << "\n";
  if (result.lookahead == 0) std::cout << "  pieces sent:         " << result.pieces_sent << "\n";
  std::cout << "  bytes sent:          " << result.bytes_sent << "\n" << smoothing::format_smoothing(prepared.smoothing);
  if (!o.capture.empty()) std::cout << "  wrote " << o.capture << "\n";
  if (result.duplicate_setpoints != 0) {
    std::cerr << "curvestep stream: the setpoint stream is broken: " << result.duplicate_setpoints << " duplicated\n";
    return exit_device_error;
  }
  return 0;
}

void add_stream_command(CLI::App& app) {
  auto options = std::make_shared<StreamCommandOptions>();
  auto* stream = app.add_subcommand("stream", "Upload a job to a controller and capture its setpoint stream");
  stream->add_option("job", options->job, "Job file (.json)")->required()->check(CLI::ExistingFile);
  stream->add_option("--machine,-m", options->machine, "Machine file (.json), sent to the controller at connect")
      ->required()
      ->check(CLI::ExistingFile);
  stream->add_option("--port,-p", options->port, "Serial port or pseudo-terminal (/dev/ttyUSB0, /dev/pts/3)")->required();
  stream->add_option("--baud", options->baud, "Baud rate (real ports)");
  stream->add_option("--capture", options->capture, "Write the controller's setpoints as CSV (t,x,y,z,v,index), as curvestep sim -o");
  auto* lookahead_option = stream->add_option("--lookahead", options->lookahead,
                     "Look-ahead window (segments) to plan with here for a controller without a planner, which replays "
                     "the planned pieces (as curvestep sim --lookahead); a controller with a planner uses its own")
      ->check(CLI::Range(std::size_t{1}, SimulationOptions::max_lookahead));
  add_job_pipeline_options(stream, options->pipeline);
  stream->add_option("--link-timeout-ms", options->link_timeout_ms, "Give up after this long without a word from the controller");
  stream->add_flag("--resume-pauses", options->resume_pauses,
                   "Go on at once after program pauses (M0/M1), tool changes (M6) and pen changes (scripts, tests)");
  stream->callback([options, lookahead_option] {
    options->lookahead_given = lookahead_option->count() > 0;
    const int status = run_stream(*options);
    if (status != 0) throw CLI::RuntimeError(status);
  });
}

const RegisterCommand registered{50, add_stream_command};

}  // namespace
}  // namespace curvestep::host
