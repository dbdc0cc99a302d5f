// SPDX-License-Identifier: MIT
// `curvestep jog --port P --machine MACHINE.json X+10 [Y-2.5 ...] [--feed F]`: a relative move of
// the named axes (several at once: one straight line), from where the controller stands (its
// StatusReport), planned with the machine file's limits (step-rate aware, as every job), checked
// against its travel (soft limits) before anything moves, and sent as a one-segment job through
// the normal link (ControllerMoves::jog). Ctrl-C, Esc or Ctrl-X abort it (Abort), SIGTERM too.
#include <array>
#include <cctype>
#include <iostream>
#include <memory>
#include <optional>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include <curvestep/host/job_pipeline.hpp>
#include <curvestep/host/link/streamer.hpp>
#include <curvestep/host/link/transport.hpp>
#include <curvestep/host/load_error.hpp>

#include "command_registry.hpp"
#include "controller_moves.hpp"
#include "link_options.hpp"
#include "machine_for_link.hpp"
#include "operator_session.hpp"

namespace curvestep::host {
namespace {

struct JogCommandOptions {
  std::vector<std::string> moves;  ///< X+10, y-2.5, ...
  std::string machine;
  ControllerLinkOptions link;
  double feed_mm_per_s = 0;  ///< 0: the machine file's feed
  bool keys = false;
};

/// Exit status: the jog would leave the machine's travel (nothing moved).
constexpr int exit_outside_travel = 3;
/// Exit status: the controller or the link failed.
constexpr int exit_device_error = 4;

/// The distance per axis of moves like "X+10" "y-2.5" (each axis at most once). std::runtime_error otherwise.
std::array<double, 3> parse_moves(const std::vector<std::string>& moves) {
  static const std::regex form("([XYZxyz])([+-][0-9]*\\.?[0-9]+([eE][+-]?[0-9]+)?)");
  std::array<double, 3> distance{};
  std::array<bool, 3> given{};
  for (const auto& move : moves) {
    std::smatch m;
    if (!std::regex_match(move, m, form)) {
      throw std::runtime_error("jog: \"" + move + "\" is no move: write an axis, a sign and mm, e.g. X+10 or Z-0.5");
    }
    const std::size_t axis = static_cast<std::size_t>(std::string("xyz").find(static_cast<char>(std::tolower(m[1].str()[0]))));
    if (given[axis]) throw std::runtime_error("jog: axis " + m[1].str() + " is given twice");
    given[axis] = true;
    distance[axis] = std::stod(m[2].str());
  }
  if (distance == std::array<double, 3>{}) throw std::runtime_error("jog: nothing to move (every distance is 0)");
  return distance;
}

int run_jog(const JogCommandOptions& o) {
  const std::array<double, 3> distance = parse_moves(o.moves);
  const MachineFile machine_file = load_machine_for_link(o.machine);
  std::vector<std::string> notes;
  const MachineLimits machine = step_rate_aware(machine_file.limits, &notes);
  auto transport = link::open_port(o.link.port, o.link.baud);
  OperatorSession session("curvestep jog", o.keys);
  const link::StreamOptions options = session.abortable_moves(o.link.link_timeout_ms);
  std::optional<ControllerMoves> moves;
  try {
    moves.emplace(*transport, machine_file, machine, options);
  } catch (const std::runtime_error& e) {  // LinkError, TransportError
    std::cerr << "curvestep jog: " << e.what() << "\n";
    return exit_device_error;
  }
  const std::array<double, 3> start = moves->position_mm();
  for (const auto& note : notes) std::cerr << "curvestep jog: note: " << note << "\n";
  link::StreamResult result;
  try {
    result = moves->jog(distance, o.feed_mm_per_s);
  } catch (const LoadError& e) {
    std::cerr << "curvestep jog: refused, nothing moved: " << e.what() << "\n";
    return exit_outside_travel;
  } catch (const std::runtime_error& e) {  // StreamError, LinkError, TransportError
    session.end_line();
    std::cerr << "curvestep jog: " << e.what() << "\n";
    return exit_device_error;
  }
  session.end_line();
  std::cout << "curvestep jog -> " << o.link.port << "\n  from:                " << format_position(start) << " mm\n  to:                  ";
  std::array<double, 3> end{};
  for (std::size_t a = 0; a < 3; ++a) end[a] = result.final_position_q16[a] / 65536.0;
  std::cout << format_position(end) << " mm (the controller's position)\n" << format_operator_summary(result, machine.rate_hz);
  session.warn_tick_overruns(result, machine.rate_hz);
  if (result.aborted) {
    std::cerr << "curvestep jog: aborted by the operator\n";
    return exit_aborted;
  }
  return 0;
}

void add_jog_command(CLI::App& app) {
  auto options = std::make_shared<JogCommandOptions>();
  auto* jog = app.add_subcommand("jog", "Move axes by a distance from where the controller stands (X+10 Y-5)");
  jog->add_option("moves", options->moves, "Axis, sign and mm: X+10 Y-2.5 Z+1 (several axes move together)")->required();
  jog->add_option("--machine,-m", options->machine, "Machine file (.json): limits and travel")->required()->check(CLI::ExistingFile);
  add_controller_link_options(*jog, options->link);
  jog->add_option("--feed", options->feed_mm_per_s, "Feed in mm/s (default: the machine file's feed)")->check(CLI::PositiveNumber);
  add_keys_option(*jog, options->keys, "Esc / Ctrl-X abort, ? status");
  jog->footer(
      "Ctrl-C, Esc or Ctrl-X abort the jog (the controller stops at once), as does SIGTERM.\n"
      "Exit status: 0 done; 3 the move would leave the machine's travel (nothing moved); 4 the controller or link\n"
      "failed; 6 aborted by the operator; 1 bad input.");
  jog->callback([options] {
    const int status = run_jog(*options);
    if (status != 0) throw CLI::RuntimeError(status);
  });
}

const RegisterCommand registered{52, add_jog_command};

}  // namespace
}  // namespace curvestep::host
