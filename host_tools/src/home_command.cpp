// SPDX-License-Identifier: MIT
// `curvestep home --port P --machine MACHINE.json [--axes xyz]`: the homing cycle of the machine
// file's "homing" section (homing_cycle.hpp), one axis at a time in its order. Ctrl-C, SIGTERM,
// Esc and Ctrl-X abort it: a running move stops at once (Abort), the command waits until the
// controller stands and exits with status 6 naming where it stands.
#include <array>
#include <cctype>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <curvestep/host/job_pipeline.hpp>
#include <curvestep/host/link/transport.hpp>

#include "command_registry.hpp"
#include "controller_moves.hpp"
#include "homing_cycle.hpp"
#include "link_options.hpp"
#include "machine_for_link.hpp"
#include "operator_session.hpp"

namespace curvestep::host {
namespace {

struct HomeCommandOptions {
  std::string machine;
  ControllerLinkOptions link;
  std::string axes;  ///< "xy", "z", ...; empty: every axis of the "homing" section
  bool keys = false;
};

/// Exit status: the controller or the link failed, or a switch did not behave.
constexpr int exit_device_error = 4;

/// The axes `--axes` names (all of the cycle's if empty). std::runtime_error for one that is no
/// axis or does not home.
std::array<bool, 3> wanted_axes(const std::string& axes, const HomingCycle& cycle) {
  std::array<bool, 3> wanted{axes.empty(), axes.empty(), axes.empty()};
  for (const char c : axes) {
    const auto axis = std::string("xyz").find(static_cast<char>(std::tolower(c)));
    if (axis == std::string::npos) throw std::runtime_error("--axes: \"" + std::string(1, c) + "\" is no axis (x, y, z)");
    if (!cycle.axes[axis]) throw std::runtime_error("--axes: axis " + std::string(1, "xyz"[axis]) + " has no entry in \"homing\"");
    wanted[axis] = true;
  }
  return wanted;
}

int run_home(const HomeCommandOptions& o) {
  const MachineFile machine_file = load_machine_for_link(o.machine);
  if (!machine_file.homing) throw std::runtime_error(o.machine + ": no \"homing\" section (docs/job_format.md)");
  const std::array<bool, 3> wanted = wanted_axes(o.axes, *machine_file.homing);
  std::vector<std::string> notes;
  const MachineLimits machine = step_rate_aware(machine_file.limits, &notes);
  for (const auto& note : notes) std::cerr << "curvestep home: note: " << note << "\n";
  auto transport = link::open_port(o.link.port, o.link.baud);
  OperatorSession session("curvestep home", o.keys);
  const link::StreamOptions options = session.abortable_moves(o.link.link_timeout_ms);
  std::cout << "curvestep home -> " << o.link.port << std::endl;
  try {
    ControllerMoves moves(*transport, machine_file, machine, options);
    run_homing_cycle(moves, *machine_file.homing, wanted, std::cout);
    std::cout << "  position:            " << format_position(moves.position_mm()) << " mm\n";
  } catch (const HomingAborted& e) {
    session.end_line();
    std::cerr << "curvestep home: " << e.what() << "\n";
    return exit_aborted;
  } catch (const std::runtime_error& e) {  // StreamError, LinkError, TransportError, a switch that misbehaved
    session.end_line();
    std::cerr << "curvestep home: " << e.what() << "\n";
    return exit_device_error;
  }
  return 0;
}

void add_home_command(CLI::App& app) {
  auto options = std::make_shared<HomeCommandOptions>();
  auto* home = app.add_subcommand("home", "Home the axes on their limit switches (the machine file's \"homing\" section)");
  home->add_option("--machine,-m", options->machine, "Machine file (.json) with a \"homing\" section")->required()->check(CLI::ExistingFile);
  add_controller_link_options(*home, options->link);
  home->add_option("--axes", options->axes, "Home only these axes (e.g. xy), in the section's order (default: all of it)");
  add_keys_option(*home, options->keys, "Esc / Ctrl-X abort, ? status");
  home->footer(
      "Ctrl-C, Esc or Ctrl-X abort the homing (the controller stops at once), as does SIGTERM.\n"
      "Exit status: 0 homed; 4 the controller, the link or a switch failed (the message says which); 6 aborted by the\n"
      "operator; 1 bad input.");
  home->callback([options] {
    const int status = run_home(*options);
    if (status != 0) throw CLI::RuntimeError(status);
  });
}

const RegisterCommand registered{53, add_home_command};

}  // namespace
}  // namespace curvestep::host
