// SPDX-License-Identifier: MIT
// stream_job against a firmware App in this process (in_process_device.hpp): the real upload loop,
// link and App, without a pseudo-terminal. The reference is the simulator: the captured setpoints
// equal simulate()'s raw Q16.16 stream with the device's window, bit for bit.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/firmware/app.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/link/streamer.hpp>
#include <curvestep/host/link/wire.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/simulator.hpp>

#include "in_process_device.hpp"

using namespace curvestep;
namespace hl = curvestep::host::link;

namespace {

const std::filesystem::path examples = CURVESTEP_EXAMPLE_JOBS;

/// Same number of setpoints, the same raw Q16.16 positions at the same index.
void require_same_setpoints(const std::vector<host::SetpointRecord>& got, const std::vector<host::SetpointRecord>& expected) {
  REQUIRE(got.size() == expected.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    const bool same = got[i].raw_q16 == expected[i].raw_q16 && got[i].time_s == expected[i].time_s;
    if (!same && differing++ == 0) {
      INFO("first difference at setpoint " << i);
      CHECK(same);
    }
  }
  CHECK(differing == 0);
}

}  // namespace

TEST_CASE("stream in process: a planning App with look-ahead 9 streams curvestep sim --lookahead 9 bit for bit",
          "[host_tools][stream]") {
  using WindowApp = firmware::App<firmware::testing::FakeBoard, Q16_16, 17, 9>;
  const auto machine = host::load_machine(examples / "machine.json");
  const auto job = host::load_job(examples / "seed_cubic.json");
  hl::testing::InProcessDevice<WindowApp, 9> device;
  std::vector<std::string> warnings;
  hl::StreamOptions options;
  options.warn = [&warnings](const std::string& text) { warnings.push_back(text); };
  const hl::StreamResult result = hl::stream_job(device, job, machine, options);
  CHECK(warnings.empty());
  CHECK(result.lookahead == 9);
  CHECK(result.pieces_sent == 0);
  CHECK(result.standing_ticks == 0);
  host::SimulationOptions nine;
  nine.lookahead = 9;
  const auto [device_job, device_machine] = hl::as_device_sees(job, machine);
  require_same_setpoints(result.setpoints, host::simulate(device_job, device_machine, nine).setpoints);
}
