// SPDX-License-Identifier: MIT
// The firmware side of the sim-versus-App tests (feed hold, overrides): `curvestep device`'s App on
// a FakeBoard, a job streamed to it with the test's commands between ticks, and the comparisons of
// its setpoints with a simulation's.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/firmware/app.hpp>
#include <curvestep/protocol/messages.hpp>

#include "fake_board.hpp"  // tests/firmware/app

namespace curvestep::sim_testing {

using DeviceApp = firmware::App<firmware::testing::FakeBoard, Q16_16, 32, 16>;  // `curvestep device`'s App: look-ahead 16
using DeviceHost = firmware::testing::Host<DeviceApp>;

/// Streams `job` to a DeviceApp configured with `machine` until it has run to its end;
/// `between_ticks(app, host)` may send commands before each tick (firmware::testing::stream_job).
/// No error report may arrive. Returns the streamed setpoints by index.
template <class BetweenTicks>
std::map<std::uint32_t, protocol::WirePoint> stream_to_device_app(const std::vector<protocol::QueueSegment>& job,
                                                                  const protocol::MachineConfiguration& machine,
                                                                  BetweenTicks between_ticks) {
  firmware::testing::FakeBoard board;
  DeviceApp app(board);
  DeviceHost host(board, app);
  REQUIRE(host.connect());
  REQUIRE(host.send(protocol::Message(machine)));
  firmware::testing::stream_job(host, app, board, job, 400000, between_ticks);
  for (const auto& e : host.received.errors) {
    UNSCOPED_INFO("error " << static_cast<int>(e.code) << " index " << e.index << " sequence " << int(e.sequence));
  }
  REQUIRE(host.received.errors.empty());
  std::map<std::uint32_t, protocol::WirePoint> out;
  for (const auto& [index, point] : host.setpoints()) out[index] = point;
  return out;
}

/// The setpoints of `device` that `simulated` does not have at the same index.
inline std::size_t mismatches(const std::map<std::uint32_t, protocol::WirePoint>& device,
                              const std::map<std::uint32_t, protocol::WirePoint>& simulated) {
  std::size_t count = 0;
  for (const auto& [index, point] : device) {
    const auto found = simulated.find(index);
    if (found == simulated.end() || found->second != point) ++count;
  }
  return count;
}

/// Checks that `run()` is refused with a one-line std::runtime_error containing `part`.
template <class Run>
void check_refused_in_one_line(Run run, const std::string& part) {
  try {
    run();
    FAIL("accepted");
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    CHECK_THAT(what, Catch::Contains(part));
    CHECK(what.find('\n') == std::string::npos);
  }
}

}  // namespace curvestep::sim_testing
