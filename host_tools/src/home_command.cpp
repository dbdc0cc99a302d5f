// SPDX-License-Identifier: MIT
// `curvestep home --port P --machine MACHINE.json [--axes xyz]`: the homing cycle of the machine
// file's "homing" section, one axis at a time in its order. Per axis, each move planned on the host
// like a jog (jog_move.hpp) and sent as a one-line job:
//   0. standing on the switch already: pull off first (motion away from a closed switch is allowed);
//   1. seek toward the switch at the seek speed for up to "distance" (SeekSwitch: the controller
//      ends the move where the switch closes and reports that position, SwitchReport);
//   2. pull off by "pull_off" (the switch must open again);
//   3. locate: toward the switch at the locate speed for up to twice the pull-off (SeekSwitch);
//   4. pull off again, and SetPosition: the axis is at "position".
// No soft limits apply while homing (the position is not known yet); hard limits do.
#include <array>
#include <cctype>
#include <cstdint>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/host/csv.hpp>
#include <curvestep/host/job_pipeline.hpp>
#include <curvestep/host/link/host_link.hpp>
#include <curvestep/host/link/status_query.hpp>
#include <curvestep/host/link/streamer.hpp>
#include <curvestep/host/link/transport.hpp>

#include "command_registry.hpp"
#include "jog_move.hpp"
#include "machine_for_link.hpp"

namespace curvestep::host {
namespace {

struct HomeCommandOptions {
  std::string machine;
  std::string port;
  int baud = 115200;
  std::string axes;  ///< "xy", "z", ...; empty: every axis of the "homing" section
  unsigned link_timeout_ms = 3000;
};

/// Exit status: the controller or the link failed, or a switch did not behave.
constexpr int exit_device_error = 4;

constexpr std::array<const char*, 3> axis_names{"x", "y", "z"};

/// Homing moves on one controller: where it stands, each move from there.
class HomingMoves {
 public:
  HomingMoves(link::Transport& transport, const MachineLimits& machine, unsigned link_timeout_ms)
      : transport_(transport), machine_(machine) {
    options_.link.link_timeout_ms = link_timeout_ms;
    refresh();
  }

  /// Moves `axis` by `distance_mm` at `feed_mm_per_s`; with `seek`, the move ends where that
  /// switch closes: the SwitchReport, or none if it ran its whole length.
  std::optional<protocol::SwitchReport> move(std::size_t axis, double distance_mm, double feed_mm_per_s,
                                             std::optional<std::uint8_t> seek) {
    std::array<double, 3> delta{};
    delta[axis] = distance_mm;
    options_.seek_switch = seek;
    const link::StreamResult result = link::stream_job(transport_, jog_job(position_, delta, feed_mm_per_s), machine_, options_);
    refresh();
    return result.switch_closed;
  }

  /// Tells the controller that `axis` stands at `position_mm` (SetPosition).
  void set(std::size_t axis, double position_mm) {
    protocol::SetPosition m;
    m.axes = static_cast<std::uint8_t>(1u << axis);
    const std::int32_t raw = Q16_16::from_double(position_mm).value().raw();
    (axis == 0 ? m.x : axis == 1 ? m.y : m.z) = raw;
    absorb(link::set_position(transport_, options_.link, m));
  }

  /// True if `limit_switch` is closed now.
  [[nodiscard]] bool closed(std::uint8_t limit_switch) const noexcept { return (switches_ & (1u << limit_switch)) != 0; }
  /// Where the controller stands, mm.
  [[nodiscard]] const std::array<double, 3>& position() const noexcept { return position_; }

 private:
  void refresh() { absorb(link::read_status(transport_, options_.link)); }
  void absorb(const protocol::StatusReport& status) {
    for (std::size_t a = 0; a < 3; ++a) position_[a] = static_cast<double>(status.position[a]) / 65536.0;
    switches_ = status.limit_switches;
  }

  link::Transport& transport_;
  MachineLimits machine_;
  link::StreamOptions options_;
  std::array<double, 3> position_{};
  std::uint8_t switches_ = 0;
};

/// The coordinate of `axis` in a SwitchReport, mm.
double coordinate(const protocol::SwitchReport& r, std::size_t axis) {
  return static_cast<double>(axis == 0 ? r.x : axis == 1 ? r.y : r.z) / 65536.0;
}

/// Homes `axis`; prints where its switch closed. std::runtime_error if the switch misbehaves.
void home_axis(HomingMoves& moves, std::size_t axis, const HomingAxis& h) {
  const double toward = h.max_side ? 1.0 : -1.0;
  const auto bit = static_cast<std::uint8_t>(2 * axis + (h.max_side ? 1 : 0));
  const std::string name = std::string(axis_names[axis]) + (h.max_side ? " max" : " min") + " switch";
  if (moves.closed(bit)) (void)moves.move(axis, -toward * h.pull_off_mm, h.seek_mm_per_s, std::nullopt);
  const auto seek = moves.move(axis, toward * h.distance_mm, h.seek_mm_per_s, bit);
  if (!seek) {
    throw std::runtime_error("homing " + std::string(axis_names[axis]) + ": the " + name + " did not close within " +
                             format_number(h.distance_mm) + " mm (\"distance\")");
  }
  (void)moves.move(axis, -toward * h.pull_off_mm, h.seek_mm_per_s, std::nullopt);
  if (moves.closed(bit)) {
    throw std::runtime_error("homing " + std::string(axis_names[axis]) + ": the " + name + " is still closed after the pull-off of " +
                             format_number(h.pull_off_mm) + " mm (\"pull_off\")");
  }
  const auto locate = moves.move(axis, toward * 2 * h.pull_off_mm, h.locate_mm_per_s, bit);
  if (!locate) {
    throw std::runtime_error("homing " + std::string(axis_names[axis]) + ": the " + name + " did not close again within " +
                             format_number(2 * h.pull_off_mm) + " mm (twice \"pull_off\") at the locate speed");
  }
  (void)moves.move(axis, -toward * h.pull_off_mm, h.seek_mm_per_s, std::nullopt);
  moves.set(axis, h.position_mm);
  std::cout << "  " << axis_names[axis] << ": " << name << " closed at " << format_number(coordinate(*seek, axis)) << " mm (seek, setpoint "
            << seek->setpoint_index << ") and " << format_number(coordinate(*locate, axis)) << " mm (locate, setpoint "
            << locate->setpoint_index << "); now at " << format_number(moves.position()[axis]) << " mm\n";
}

int run_home(const HomeCommandOptions& o) {
  const MachineFile machine_file = load_machine_for_link(o.machine);
  if (!machine_file.homing) throw std::runtime_error(o.machine + ": no \"homing\" section (docs/job_format.md)");
  const HomingCycle& cycle = *machine_file.homing;
  std::array<bool, 3> wanted{o.axes.empty(), o.axes.empty(), o.axes.empty()};
  for (const char c : o.axes) {
    const auto axis = std::string("xyz").find(static_cast<char>(std::tolower(c)));
    if (axis == std::string::npos) throw std::runtime_error("--axes: \"" + std::string(1, c) + "\" is no axis (x, y, z)");
    if (!cycle.axes[axis]) throw std::runtime_error("--axes: axis " + std::string(axis_names[axis]) + " has no entry in \"homing\"");
    wanted[axis] = true;
  }
  std::vector<std::string> notes;
  const MachineLimits machine = step_rate_aware(machine_file.limits, &notes);
  for (const auto& note : notes) std::cerr << "curvestep home: note: " << note << "\n";
  auto transport = link::open_port(o.port, o.baud);
  std::cout << "curvestep home -> " << o.port << "\n";
  try {
    HomingMoves moves(*transport, machine, o.link_timeout_ms);
    for (const std::size_t axis : cycle.order) {
      if (wanted[axis]) home_axis(moves, axis, *cycle.axes[axis]);
    }
    std::cout << "  position:            ";
    for (std::size_t a = 0; a < 3; ++a) std::cout << (a == 0 ? "" : " ") << axis_names[a] << " " << format_number(moves.position()[a]);
    std::cout << " mm\n";
  } catch (const std::runtime_error& e) {  // StreamError, LinkError, TransportError, a switch that misbehaved
    std::cerr << "curvestep home: " << e.what() << "\n";
    return exit_device_error;
  }
  return 0;
}

void add_home_command(CLI::App& app) {
  auto options = std::make_shared<HomeCommandOptions>();
  auto* home = app.add_subcommand("home", "Home the axes on their limit switches (the machine file's \"homing\" section)");
  home->add_option("--machine,-m", options->machine, "Machine file (.json) with a \"homing\" section")->required()->check(CLI::ExistingFile);
  home->add_option("--port,-p", options->port, "Serial port or pseudo-terminal of the controller")->required();
  home->add_option("--baud", options->baud, "Baud rate (real ports)");
  home->add_option("--axes", options->axes, "Home only these axes (e.g. xy), in the section's order (default: all of it)");
  home->add_option("--link-timeout-ms", options->link_timeout_ms, "Give up after this long without a word from the controller");
  home->footer("Exit status: 0 homed; 4 the controller, the link or a switch failed (the message says which); 1 bad input.");
  home->callback([options] {
    const int status = run_home(*options);
    if (status != 0) throw CLI::RuntimeError(status);
  });
}

const RegisterCommand registered{53, add_home_command};

}  // namespace
}  // namespace curvestep::host
