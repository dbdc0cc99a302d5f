// SPDX-License-Identifier: MIT
// `curvestep stream JOB --machine MACHINE.json --port PORT [--baud N] [--capture setpoints.csv] [--lookahead N] [--keys]`:
// uploads a job to a controller with flow control, shows progress on a terminal, takes the
// operator's keys and signals (hold, resume, abort, status: operator_session.hpp), captures the
// controller's setpoint stream (the CSV of `curvestep sim -o`) and reports its errors. A
// controller without a planner (look-ahead 0) gets the job planned here with --lookahead N
// (default 16) as pieces: its stream is then `curvestep sim --lookahead N`'s.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include <curvestep/host/job.hpp>
#include <curvestep/host/job_file.hpp>
#include <curvestep/host/link/host_link.hpp>
#include <curvestep/host/link/streamer.hpp>
#include <curvestep/host/link/transport.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/job_pipeline.hpp>
#include <curvestep/host/simulator.hpp>
#include <curvestep/host/streamed_job.hpp>

#include "command_registry.hpp"
#include "job_pipeline_options.hpp"
#include "link_options.hpp"
#include "machine_for_link.hpp"
#include "operator_session.hpp"

namespace curvestep::host {
namespace {

/// Program pauses (M0/M1, M6, a pen change): with --resume-pauses say what for on standard output
/// and go on at once; else ask the operator (OperatorConsole::ask: Enter, r or ~ goes on, a or
/// Ctrl-X aborts) and wait for the answer, the link kept going.
void set_pause_handling(link::StreamOptions& options, bool at_once, link::OperatorConsole& console) {
  options.paused = [at_once, &console](const std::string& what) {
    if (at_once) {
      std::cout << "curvestep stream: " << what << " (--resume-pauses: going on)" << std::endl;
      return;
    }
    console.ask("curvestep stream: " + what +
                (console.reads_keys() ? "; go on: Enter, r or ~; abort: a, Ctrl-X or Esc"
                                      : "; no operator keys (standard input is no terminal): run with --keys or --resume-pauses"));
  };
  if (!at_once) options.resume_now = [] { return false; };  // the operator's Resume goes on (Streamer)
}

struct StreamCommandOptions {
  std::string job;
  std::string machine;
  ControllerLinkOptions link;
  std::string capture;
  unsigned retransmit_timeout_ms = 100;
  std::size_t lookahead = SimulationOptions::max_lookahead;  ///< planning window for a controller without a planner
  bool resume_pauses = false;  ///< --resume-pauses: go on at once after M0/M1, M6 and pen changes
  JobPipelineOptions pipeline;
  bool lookahead_given = false;    ///< --lookahead given: plan with that count window alone
  bool keys = false;               ///< --keys: read operator keys from stdin even if it is no terminal
  StartOverride start_override;    ///< --feed-override, --rapid-override
};

/// Exit status when the controller or the link failed.
constexpr int exit_device_error = 4;

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
  const MachineFile machine_file = load_machine_for_link(o.machine);
  // A streamed job is not held (streamed_job.hpp): the file is read for the plan, then again for
  // the wire's checks (or the host's planning) and for the upload. A pen drawing is prepared whole.
  const StreamedJobPlan plan = plan_job(o.job, machine_file, machine_file.limits, o.pipeline);
  const PreparedJob& prepared = plan.prepared;
  const MachineLimits& machine = prepared.machine;
  const ReadableJob readable_job = readable(plan, o.job, machine_file, machine_file.limits, o.pipeline);
  for (const auto& note : prepared.notes) std::cerr << "curvestep stream: note: " << note << "\n";
  auto transport = link::open_port(o.link.port, o.link.baud);
  link::StreamOptions options;
  options.travel = machine_file.travel;
  options.link.link_timeout_ms = o.link.link_timeout_ms;
  options.link.retransmit_timeout_ms = o.retransmit_timeout_ms;
  options.lookahead = o.lookahead;
  options.feed_override = o.start_override.value();
  if (!o.lookahead_given) options.lookahead_distance_mm = lookahead_distance_for(machine);
  options.warn = [](const std::string& text) { std::cerr << "curvestep stream: warning: " << text << "\n"; };
  OperatorSession session("curvestep stream", o.keys);
  session.attach(options);
  set_pause_handling(options, o.resume_pauses, session.console());
  // The setpoints go to the capture file as they arrive and are kept nowhere; a failed upload
  // leaves no capture behind (as before, when the file was written at the end).
  std::ofstream capture;
  if (!o.capture.empty()) {
    capture.open(o.capture);
    if (!capture) throw std::runtime_error("cannot write " + o.capture);
    write_setpoints_csv_header(capture);
  }
  options.setpoint_sink = [&](const SetpointRecord& r) {
    if (capture.is_open()) write_setpoint_csv_line(capture, r);
  };
  const auto drop_capture = [&] {
    if (!capture.is_open()) return;
    capture.close();
    std::error_code ignored;
    std::filesystem::remove(o.capture, ignored);
  };
  link::StreamResult result;
  try {
    result = link::stream_job(*transport, readable_job, machine, options);
  } catch (const link::StreamError& e) {
    drop_capture();
    session.end_line();
    std::cerr << "curvestep stream: " << e.what() << "\n";
    return exit_device_error;
  } catch (const link::TransportError& e) {
    drop_capture();
    session.end_line();
    std::cerr << "curvestep stream: " << e.what() << "\n";
    return exit_device_error;
  } catch (...) {
    drop_capture();
    throw;
  }
  session.end_line();
  if (capture.is_open()) {
    capture.close();
    if (!capture) throw std::runtime_error("error writing " + o.capture);
  }
  std::cout << "curvestep stream " << o.job << " -> " << o.link.port << "\n"
            << "  setpoints received:  " << result.setpoints_received << "\n"
            << "  ticks standing:      " << result.standing_ticks << " (held or starved, not reported)\n"
            << "  setpoints duplicated: " << result.duplicate_setpoints << "\n"
            << "  batches resent:      " << result.batches_repeated << "\n"
            << "  damaged frames:      " << result.frames_rejected << "\n"
            << "  device queue peak:   " << result.max_queue_depth << " of " << result.queue_capacity
            << (result.lookahead == 0 ? " pieces\n" : " segments\n")
            << "  device look-ahead:   " << look_ahead_text(result, !o.lookahead_given) << "\n";
  if (result.lookahead == 0) std::cout << "  pieces sent:         " << result.pieces_sent << "\n";
  std::cout << "  bytes sent:          " << result.bytes_sent << "\n" << smoothing::format_smoothing(prepared.smoothing);
  std::cout << format_operator_summary(result, machine.rate_hz);
  session.warn_tick_overruns(result, machine.rate_hz);
  if (!o.capture.empty()) std::cout << "  wrote " << o.capture << "\n";
  if (result.aborted) {
    std::cerr << "curvestep stream: aborted by the operator\n";
    return exit_aborted;
  }
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
  add_controller_link_options(*stream, options->link);
  stream->add_option("--capture", options->capture, "Write the controller's setpoints as CSV (t,x,y,z,v,index), as curvestep sim -o");
  auto* lookahead_option = stream->add_option("--lookahead", options->lookahead,
                     "Look-ahead window (segments) to plan with here for a controller without a planner, which replays "
                     "the planned pieces (as curvestep sim --lookahead); a controller with a planner uses its own")
      ->check(CLI::Range(std::size_t{1}, SimulationOptions::max_lookahead));
  add_job_pipeline_options(stream, options->pipeline);
  stream
      ->add_option("--retransmit-timeout-ms", options->retransmit_timeout_ms,
                   "Resend unacknowledged frames after this silence; 10 timeouts in a row without progress end the "
                   "upload (RetransmitLimit). Longer for a slow controller (an emulator starved of CPU)")
      ->check(CLI::Range(1u, 60000u));
  stream->add_flag("--resume-pauses", options->resume_pauses,
                   "Go on at once after program pauses (M0/M1), tool changes (M6) and pen changes (scripts, tests)");
  add_keys_option(*stream, options->keys, "! hold, ~ resume, Ctrl-X or Esc abort, ? status, ] [ } { = ( * ) overrides");
  add_start_override_options(*stream, options->start_override);
  stream->footer(
      std::string("While a job runs: ! feed hold, ~ resume, Ctrl-X or Esc abort, ? status line (keys from a terminal on stdin, or --keys);\n") +
      override_keys_footer +
      "Ctrl-C holds and asks (a second Ctrl-C aborts), SIGTERM aborts.\n"
      "Exit status: 0 done; 4 the controller or link failed; 6 aborted by the operator; 1 bad input.");
  stream->callback([options, lookahead_option] {
    options->lookahead_given = lookahead_option->count() > 0;
    const int status = run_stream(*options);
    if (status != 0) throw CLI::RuntimeError(status);
  });
}

const RegisterCommand registered{50, add_stream_command};

}  // namespace
}  // namespace curvestep::host
