// SPDX-License-Identifier: MIT
// A firmware App<FakeBoard, ...> behind a host Transport, in this process: what stream_job writes
// goes to the App's serial input, what the App writes comes back from read(). The App ticks inside
// read() by the host board's fast-mode rule (boards/host/fast_mode.hpp, fast_tick_allowed), so a
// fast device never plans with less than a real-time one fed in time, nor underruns; held or
// starved, it waits for the host.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <thread>

#include <curvestep/boards/host/fast_mode.hpp>
#include <curvestep/firmware/app_settings.hpp>
#include <curvestep/host/link/transport.hpp>

#include "fake_board.hpp"  // tests/firmware/app

namespace curvestep::host::link::testing {

template <class AppType>
class InProcessDevice final : public Transport {
 public:
  InProcessDevice() : app_(std::make_unique<AppType>(board_)) {}
  /// A device whose App runs with `settings` (link timeout, stall timeout, ...).
  explicit InProcessDevice(const firmware::AppSettings& settings) : app_(std::make_unique<AppType>(board_, settings)) {}

  std::size_t read(std::span<std::byte> out, int /*timeout_ms*/) override {
    run();
    if (board_.outgoing.empty() && may_tick()) {
      app_->on_tick();
      run();
    }
    const std::size_t n = out.size() < board_.outgoing.size() ? out.size() : board_.outgoing.size();
    std::copy_n(board_.outgoing.begin(), n, out.begin());
    board_.outgoing.erase(board_.outgoing.begin(), board_.outgoing.begin() + static_cast<std::ptrdiff_t>(n));
    return n;  // 0 at once instead of waiting: the host's loop comes back
  }

  void write(std::span<const std::byte> bytes) override { board_.put_incoming(bytes); }

  [[nodiscard]] const std::string& name() const override { return name_; }

  /// Runs the App for `ms` of wall-clock time with no host reading: what it sends stays queued
  /// for the next host, as in a serial port's buffer.
  void run_unattended(std::chrono::milliseconds ms) {
    const auto end = std::chrono::steady_clock::now() + ms;
    while (std::chrono::steady_clock::now() < end) {
      run();
      if (may_tick()) app_->on_tick();
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    run();
  }

  /// The App (its statistics and state, after the job).
  [[nodiscard]] AppType& app() { return *app_; }

 private:
  void run() {
    // The App's clock is the wall clock, as on the host board: the link's timeouts and the
    // host's status requests run on the same time.
    board_.clock_ms = static_cast<std::uint32_t>(
        std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - epoch_).count());
    app_->poll();
  }

  [[nodiscard]] bool may_tick() const { return boards::host::fast_tick_allowed(*app_); }

  curvestep::firmware::testing::FakeBoard board_;
  std::unique_ptr<AppType> app_;
  std::chrono::steady_clock::time_point epoch_ = std::chrono::steady_clock::now();
  std::string name_ = "in-process App";
};

}  // namespace curvestep::host::link::testing
