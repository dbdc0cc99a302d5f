// SPDX-License-Identifier: MIT
// `curvestep console --port P --machine MACHINE.json [--feed F] [--keys]`: an idle interactive
// session on a controller, as a grbl sender's jog panel or a bCNC pendant: arrow keys and Page Up
// / Page Down jog by a step the operator cycles (0.1 / 1 / 10 mm), `h` homes, `?` shows the
// status, Esc / Ctrl-X abort a running jog or homing, `q` quits (console_session.hpp).
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <curvestep/host/job_pipeline.hpp>
#include <curvestep/host/link/console_keys.hpp>
#include <curvestep/host/link/transport.hpp>

#include "command_registry.hpp"
#include "console_session.hpp"
#include "controller_moves.hpp"
#include "link_options.hpp"
#include "machine_for_link.hpp"
#include "operator_session.hpp"

namespace curvestep::host {
namespace {

struct ConsoleCommandOptions {
  std::string machine;
  ControllerLinkOptions link;
  double feed_mm_per_s = 0;  ///< the jogs' feed; 0: the machine file's feed
  bool keys = false;
};

/// Exit status: the controller or the link failed.
constexpr int exit_device_error = 4;

int run_console(const ConsoleCommandOptions& o) {
  const MachineFile machine_file = load_machine_for_link(o.machine);
  std::vector<std::string> notes;
  const MachineLimits machine = step_rate_aware(machine_file.limits, &notes);
  for (const auto& note : notes) std::cerr << "curvestep console: note: " << note << "\n";
  auto transport = link::open_port(o.link.port, o.link.baud);
  OperatorSession session("curvestep console", o.keys);
  if (!session.console().reads_keys()) {
    throw std::runtime_error("no keys to read: standard input is no terminal (use --keys to read it anyway)");
  }
  const link::StreamOptions options = session.abortable_moves(o.link.link_timeout_ms);
  std::cout << "curvestep console -> " << o.link.port << "\n  " << link::ConsoleKeyDecoder::key_help() << std::endl;
  try {
    ControllerMoves moves(*transport, machine_file, machine, options);
    ConsoleSession console(moves, machine_file, session, o.feed_mm_per_s, std::cout);
    return console.run();
  } catch (const std::runtime_error& e) {  // LinkError, TransportError: the controller stopped answering
    session.end_line();
    std::cerr << "curvestep console: " << e.what() << "\n";
    return exit_device_error;
  }
}

void add_console_command(CLI::App& app) {
  auto options = std::make_shared<ConsoleCommandOptions>();
  auto* console = app.add_subcommand("console", "An interactive session on a controller: jog with the arrow keys, home, status");
  console->add_option("--machine,-m", options->machine, "Machine file (.json): limits, travel and homing")->required()->check(CLI::ExistingFile);
  add_controller_link_options(*console, options->link);
  console->add_option("--feed", options->feed_mm_per_s, "Jog feed in mm/s (default: the machine file's feed)")->check(CLI::PositiveNumber);
  add_keys_option(*console, options->keys, "the console keys below");
  console->footer(
      "Keys: arrow keys jog Y+ (up), Y- (down), X+ (right), X- (left); Page Up / Page Down jog Z+ / Z-; on a terminal\n"
      "without them d / a X+ / X-, w / s Y+ / Y-, r / f Z+ / Z-. t or Tab: jog step 0.1 -> 1 -> 10 mm (1 mm at start).\n"
      "h homes the machine file's \"homing\" axes; ? prints <State|MPos:x,y,z|Setpoint:n|Switches:...|Step:mm>;\n"
      "Esc or Ctrl-X abort a running jog or homing (the controller stops at once); q or Ctrl-D quit.\n"
      "A jog that would leave the machine's travel is refused before anything moves. Ctrl-C or SIGTERM during a move\n"
      "abort it and end the session (exit 6); at rest they end it.\n"
      "Exit status: 0 done; 4 the controller or link failed; 6 a move aborted by a signal; 1 bad input.");
  console->callback([options] {
    const int status = run_console(*options);
    if (status != 0) throw CLI::RuntimeError(status);
  });
}

const RegisterCommand registered{54, add_console_command};

}  // namespace
}  // namespace curvestep::host
