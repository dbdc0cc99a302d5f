// SPDX-License-Identifier: MIT
// `curvestep proxy --device PORT [--drop R] [--corrupt R] [--duplicate R] [--delay R] ...`: a
// fault-injecting relay for link tests. It creates a pseudo-terminal for the host, prints its path
// as the first line on standard output, and relays to the device's port until stopped.
#include <atomic>
#include <csignal>
#include <iostream>
#include <memory>
#include <string>

#include <curvestep/host/link/fault_proxy.hpp>
#include <curvestep/host/link/transport.hpp>

#include "command_registry.hpp"

namespace curvestep::host {
namespace {

std::atomic<bool> proxy_stop{false};
extern "C" void on_proxy_signal(int) { proxy_stop.store(true); }

struct ProxyOptions {
  std::string device;
  int baud = 115200;
  link::FaultSettings faults;
  std::string direction = "both";
};

int run_proxy(const ProxyOptions& o) {
  std::signal(SIGINT, on_proxy_signal);
  std::signal(SIGTERM, on_proxy_signal);
  std::signal(SIGPIPE, SIG_IGN);
  link::FaultSettings faults = o.faults;
  faults.to_device = o.direction == "both" || o.direction == "to-device";
  faults.to_host = o.direction == "both" || o.direction == "to-host";
  auto device = link::open_port(o.device, o.baud);
  link::PseudoTerminal pty;
  auto host = pty.master_transport();
  std::cout << pty.slave_path() << std::endl;
  link::FaultCounters counters;
  link::run_fault_proxy(*host, *device, faults, proxy_stop, counters);
  std::cerr << "curvestep proxy: " << counters.bytes_to_device << " bytes to the device, " << counters.bytes_to_host
            << " to the host; dropped " << counters.dropped << ", corrupted " << counters.corrupted << ", duplicated "
            << counters.duplicated << ", delays " << counters.delayed << (counters.cut ? "; line cut" : "") << "\n";
  return 0;
}

void add_proxy_command(CLI::App& app) {
  auto o = std::make_shared<ProxyOptions>();
  auto* proxy = app.add_subcommand("proxy", "Relay between a host and a device, injecting faults (link tests)");
  proxy->add_option("--device", o->device, "The device's port or pseudo-terminal")->required();
  proxy->add_option("--baud", o->baud, "Baud rate of a real --device port");
  proxy->add_option("--drop", o->faults.drop, "Probability of dropping a byte")->check(CLI::Range(0.0, 1.0));
  proxy->add_option("--corrupt", o->faults.corrupt, "Probability of flipping one bit of a byte")->check(CLI::Range(0.0, 1.0));
  proxy->add_option("--duplicate", o->faults.duplicate, "Probability of sending a byte twice")->check(CLI::Range(0.0, 1.0));
  proxy->add_option("--delay", o->faults.delay, "Probability of delaying a byte (and what follows)")->check(CLI::Range(0.0, 1.0));
  proxy->add_option("--delay-ms", o->faults.delay_ms, "Length of one delay in ms");
  proxy->add_option("--seed", o->faults.seed, "Seed of the fault generator");
  proxy->add_option("--direction", o->direction, "Which bytes get faults: both, to-device, to-host")
      ->check(CLI::IsMember({"both", "to-device", "to-host"}));
  proxy->add_option("--cut-after-bytes", o->faults.cut_after_bytes,
                    "Stop relaying (both ways) after this many host-to-device bytes: the link dies");
  proxy->callback([o] { run_proxy(*o); });
}

const RegisterCommand registered{65, add_proxy_command};

}  // namespace
}  // namespace curvestep::host
