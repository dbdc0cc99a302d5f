// SPDX-License-Identifier: MIT
// BoardThread: the firmware on the Linux host board, serving a fresh pseudo-terminal in a thread of
// this process until it goes out of scope (curvestep demo and curvestep gpio).
#pragma once

#include <atomic>
#include <string>
#include <thread>

#include <curvestep/boards/host/device.hpp>
#include <curvestep/host/link/transport.hpp>

namespace curvestep::host {

/// Runs boards::host::run_device with `output` on one end of a new pty; port() is the other end.
template <class Output>
class BoardThread {
 public:
  /// `fast`: flow-controlled by the link instead of the wall clock (the same setpoints);
  /// `machine_outputs`: the board's spindle, coolant, output and pen lines (null: events only logged).
  BoardThread(Output& output, bool fast, boards::host::MachineOutputHooks* machine_outputs = nullptr)
      : output_(output), fast_(fast), machine_outputs_(machine_outputs), thread_([this] { serve(); }) {}
  BoardThread(const BoardThread&) = delete;
  BoardThread& operator=(const BoardThread&) = delete;
  /// Stops the device and waits for its thread.
  ~BoardThread() {
    stop_.store(true);
    thread_.join();
  }
  /// The pseudo-terminal to open as the device's serial port.
  [[nodiscard]] std::string port() const { return pty_.slave_path(); }

 private:
  void serve() {
    boards::host::DeviceOptions options;
    options.fast = fast_;
    options.machine_outputs = machine_outputs_;
    (void)boards::host::run_device(pty_.master_fd(), output_, options, stop_, nullptr);
  }

  link::PseudoTerminal pty_;
  Output& output_;
  bool fast_;
  boards::host::MachineOutputHooks* machine_outputs_;
  std::atomic<bool> stop_{false};
  std::thread thread_;  // last: started once every other member exists
};

}  // namespace curvestep::host
