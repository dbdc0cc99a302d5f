// SPDX-License-Identifier: MIT
// `curvestep device [--port PATH] [--machine MACHINE.json [--gpio] [--switch x-:POS ...]] [--fast] [--executor]`: runs the
// firmware as a Linux process (boards/host); --executor without a planner (it replays pieces the
// host planned, as the STM32F1 executor image does). Without --port it creates a pseudo-terminal and prints its path as
// the first line on standard output, then serves until stopped (SIGINT, SIGTERM).
#include <atomic>
#include <csignal>
#include <cstdio>
#include <fcntl.h>
#include <iostream>
#include <memory>
#include <optional>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include <curvestep/boards/host/device.hpp>
#include <curvestep/boards/host/gpio_output.hpp>
#include <curvestep/boards/host/gpiod_machine_outputs.hpp>
#include <curvestep/boards/host/simulated_switches.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/link/transport.hpp>
#include <curvestep/host/machine_file.hpp>

#include "command_registry.hpp"
#include "gpio_wiring.hpp"

namespace curvestep::host {
namespace {

std::atomic<bool> stop_requested{false};

extern "C" void on_stop_signal(int) { stop_requested.store(true); }

struct DeviceCommandOptions {
  std::string port;
  int baud = 115200;
  std::string machine;
  bool gpio = false;
  bool fast = false;
  bool executor = false;
  std::vector<std::string> switches;  ///< --switch x-:POS ...: simulated limit switches
  unsigned link_timeout_ms = 1000;
  unsigned retransmit_timeout_ms = 100;
};

/// A --switch value: "x-:POS" (the min switch of x at POS mm) or "y+:POS" (a max switch).
boards::host::SimulatedSwitch parse_switch(const std::string& text) {
  static const std::regex form("([xyzXYZ])([+-]):([+-]?[0-9]*\\.?[0-9]+([eE][+-]?[0-9]+)?)");
  std::smatch m;
  if (!std::regex_match(text, m, form)) {
    throw std::runtime_error("--switch \"" + text + "\": write an axis, - (min) or + (max), a colon and mm, e.g. x-:-2.5 or y+:180");
  }
  boards::host::SimulatedSwitch s;
  s.axis = static_cast<std::uint8_t>(std::string("xyz").find(static_cast<char>(std::tolower(m[1].str()[0]))));
  s.max_side = m[2].str() == "+";
  s.position_mm = std::stod(m[3].str());
  return s;
}

/// The simulated switches of --switch, in steps of `machine`'s axes.
boards::host::SwitchThresholds simulated_switches(const DeviceCommandOptions& o, const MachineFile& machine) {
  std::vector<boards::host::SimulatedSwitch> switches;
  for (const auto& text : o.switches) switches.push_back(parse_switch(text));
  std::array<double, 3> steps_per_mm{};
  for (std::size_t a = 0; a < 3; ++a) steps_per_mm[a] = machine.limits.axes[a].steps_per_mm;
  return boards::host::switch_thresholds(switches.data(), switches.size(), steps_per_mm);
}

/// What the --machine file gives the device, read once: with --switch the whole file (its axes'
/// steps_per_mm place the switches; its wiring serves --gpio), else for --gpio only its wiring
/// (the limits come from the host).
struct DeviceMachine {
  MachineWiring wiring;
  std::optional<boards::host::SwitchThresholds> switches;
};

DeviceMachine load_device_machine(const DeviceCommandOptions& o) {
  DeviceMachine device;
  if (!o.switches.empty()) {
    if (o.machine.empty()) throw std::runtime_error("--switch needs --machine (the axes' steps_per_mm place the switches)");
    const MachineFile machine = load_machine_file(o.machine);
    device.wiring = MachineWiring{machine.gpio, machine.pen};
    device.switches = simulated_switches(o, machine);
  } else if (o.gpio && !o.machine.empty()) {
    device.wiring = load_machine_wiring(o.machine);
  }
  return device;
}

template <class Output>
int serve(int fd, Output& output, const DeviceCommandOptions& o, boards::host::MachineOutputHooks* machine_outputs) {
  boards::host::DeviceOptions options;
  options.machine_outputs = machine_outputs;
  options.fast = o.fast;
  options.app.link_timeout_ms = o.link_timeout_ms;
  options.app.retransmit_timeout_ms = o.retransmit_timeout_ms;
  if (o.executor) return boards::host::run_device<Output, 0>(fd, output, options, stop_requested, stderr);
  return boards::host::run_device(fd, output, options, stop_requested, stderr);
}

int run_device_command(const DeviceCommandOptions& o) {
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
  std::signal(SIGPIPE, SIG_IGN);
  const DeviceMachine machine = load_device_machine(o);  // refused before the port opens
  const std::optional<boards::host::SwitchThresholds>& switches = machine.switches;
  std::unique_ptr<boards::host::GpiodStepOutput> gpio;
  std::unique_ptr<boards::host::GpiodMachineOutputs> outputs;  // spindle, coolant, digital outputs, servo pen
  if (o.gpio) {
    if (o.machine.empty()) throw std::runtime_error("--gpio needs --machine with a \"gpio\" section");
    const MachineWiring& wiring = machine.wiring;
    if (!wiring.gpio) throw std::runtime_error(o.machine + ": no \"gpio\" section (chip and line names) for --gpio");
    gpio = std::make_unique<boards::host::GpiodStepOutput>(step_lines(*wiring.gpio), boards::host::SystemClock::step_timer_hz);
    const auto lines = output_lines(*wiring.gpio, wiring.pen);
    if (lines.any()) outputs = std::make_unique<boards::host::GpiodMachineOutputs>(lines);
  }
  boards::host::MachineOutputHooks* hooks = outputs ? &outputs->hooks() : nullptr;
  std::unique_ptr<link::PseudoTerminal> pty;
  std::unique_ptr<link::FdTransport> line;
  int fd = -1;
  if (o.port.empty()) {
    pty = std::make_unique<link::PseudoTerminal>();
    fd = pty->master_fd();
    std::cout << pty->slave_path() << std::endl;  // first line: where to connect
  } else {
    line = link::open_terminal(o.port, o.baud);
    fd = line->fd();
    std::cout << o.port << std::endl;
  }
  boards::host::CountingStepOutput counting;
  if (switches) {
    if (gpio) {
      boards::host::SimulatedSwitches<boards::host::GpiodStepOutput> switched(*gpio, *switches);
      return serve(fd, switched, o, hooks);
    }
    boards::host::SimulatedSwitches<boards::host::CountingStepOutput> switched(counting, *switches);
    return serve(fd, switched, o, hooks);
  }
  if (gpio) return serve(fd, *gpio, o, hooks);
  return serve(fd, counting, o, hooks);
}

void add_device_command(CLI::App& app) {
  auto options = std::make_shared<DeviceCommandOptions>();
  auto* device = app.add_subcommand("device", "Run the controller firmware as a Linux process on a pseudo-terminal or a serial port");
  device->add_option("--port", options->port, "Serve on this tty instead of creating a pseudo-terminal");
  device->add_option("--baud", options->baud, "Baud rate of --port");
  device->add_option("--machine,-m", options->machine, "Machine file with a \"gpio\" section (for --gpio)")->check(CLI::ExistingFile);
  device->add_flag("--gpio", options->gpio,
                   "Drive step/dir lines, and the spindle, coolant, digital-output and servo-pen lines it names, through "
                   "libgpiod (chip and line names from --machine)");
  device->add_option("--switch", options->switches,
                     "Simulate a limit switch: x-:POS closes at or below POS mm on x, y+:POS at or above POS on y "
                     "(needs --machine for steps_per_mm; repeatable)");
  device->add_flag("--fast", options->fast,
                   "Tests: run ticks as fast as the link allows (flow-controlled), not in real time");
  device->add_flag("--executor", options->executor,
                   "No planner on the device: it replays motion planned by the host (curvestep stream plans it)");
  device->add_option("--link-timeout-ms", options->link_timeout_ms, "Feed hold after this long without a frame (0: never)");
  device
      ->add_option("--retransmit-timeout-ms", options->retransmit_timeout_ms,
                   "Resend unacknowledged setpoints after this silence; 255 timeouts without progress end the stream "
                   "(RetransmitLimit)")
      ->check(CLI::Range(1u, 60000u));
  device->callback([options] {
    const int status = run_device_command(*options);
    if (status != 0) throw CLI::RuntimeError(status);
  });
}

const RegisterCommand registered{60, add_device_command};

}  // namespace
}  // namespace curvestep::host
