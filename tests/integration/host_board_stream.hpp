// SPDX-License-Identifier: MIT
// Streams a job to the host board's firmware running in a thread of the test process (run_device,
// fast mode) on a fresh pseudo-terminal: the outputs stay in the test's hands.
#pragma once

#include <atomic>
#include <thread>

#include <curvestep/boards/host/device.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/link/streamer.hpp>
#include <curvestep/host/link/transport.hpp>

namespace curvestep::test {

/// Streams `job` with `machine` to run_device(`output`, `options` in fast mode); the device
/// stops when the stream has ended (or thrown).
template <class Output>
host::link::StreamResult stream_to_host_board(const host::Job& job, const MachineLimits& machine, Output& output,
                                              boards::host::DeviceOptions options = {}) {
  host::link::PseudoTerminal pty;
  std::atomic<bool> stop{false};
  options.fast = true;
  std::thread device([&] { boards::host::run_device(pty.master_fd(), output, options, stop, nullptr); });
  host::link::StreamResult result;
  try {
    auto port = host::link::open_terminal(pty.slave_path(), 115200);
    result = host::link::stream_job(*port, job, machine);
  } catch (...) {
    stop = true;
    device.join();
    throw;
  }
  stop = true;
  device.join();
  return result;
}

}  // namespace curvestep::test
