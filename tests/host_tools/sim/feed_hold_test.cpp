// SPDX-License-Identifier: MIT
// `simulate` with a feed hold (SimulationOptions::holds, `curvestep sim --hold-at T:R`) against the
// firmware: an App<FakeBoard> (the real App over its serial link, as tests/firmware/app drive it)
// sent FeedHold between ticks H-1 and H, and Resume after it stood R ticks, streams exactly the
// simulation's setpoints; the R standing ticks are the simulation's only extra setpoints (a held
// App ticks without streaming). Also: the hold really changes the motion, and bad holds are refused.
#include <cstddef>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/firmware/app.hpp>
#include <curvestep/firmware/conversions.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/simulator.hpp>

#include "device_app_run.hpp"
#include "fake_board.hpp"  // tests/firmware/app
#include "wire_job.hpp"

using namespace curvestep;
using namespace curvestep::firmware;
using namespace curvestep::protocol;
using namespace curvestep::firmware::testing;
using curvestep::sim_testing::check_refused_in_one_line;
using curvestep::sim_testing::DeviceApp;
using curvestep::sim_testing::DeviceHost;
using curvestep::sim_testing::mismatches;
using curvestep::sim_testing::stream_to_device_app;
using curvestep::sim_testing::to_host_job;

namespace {

MachineConfiguration machine() { return curvestep::firmware::testing::machine(100); }

/// A zigzag of 30 lines of about 5 mm inside the test machine's ±100 mm travel, then an arc: long
/// enough to hold in the middle of a segment.
std::vector<QueueSegment> zigzag() {
  std::vector<QueueSegment> job;
  for (int k = 0; k < 30; ++k) job.push_back(line(p(3.0 * k - 45, (k % 2) * 4.0), p(3.0 * (k + 1) - 45, ((k + 1) % 2) * 4.0)));
  job.push_back(arc(p(45, 0), p(45, 8), p(45, 4), ArcDirection::CounterClockwise));
  job.back().end_of_job = true;
  return job;
}
/// index -> setpoint of simulate() with `holds`.
std::map<std::uint32_t, WirePoint> simulated(const std::vector<QueueSegment>& wire, const std::vector<host::FeedHoldEvent>& holds) {
  auto options = curvestep::sim_testing::device_window();
  options.holds = holds;
  return curvestep::sim_testing::simulated_setpoints(wire, machine(), options);
}

/// Streams the job to the App, sending FeedHold before tick `hold_tick` and Resume once the App's
/// controller has stood `standing` ticks; returns the streamed setpoints by index.
std::map<std::uint32_t, WirePoint> streamed_with_hold(const std::vector<QueueSegment>& job, std::uint64_t hold_tick,
                                                      std::uint64_t standing) {
  bool held_sent = false;
  bool resumed = false;
  std::uint64_t stood = 0;
  const auto hold_and_resume = [&](DeviceApp& app, DeviceHost& host) {
    if (!held_sent && app.moving() && app.controller().tick() == hold_tick) {
      REQUIRE(app.controller().state() == ControllerState::Running);
      REQUIRE(host.send(Message(FeedHold{})));
      host.pump();  // the App takes it before its next tick
      held_sent = true;
    }
    if (held_sent && !resumed && app.controller().state() == ControllerState::Held) {
      if (stood == standing) {
        REQUIRE(host.send(Message(Resume{})));
        host.pump();
        resumed = true;
      }
      ++stood;
    }
  };
  auto setpoints = stream_to_device_app(job, machine(), hold_and_resume);
  REQUIRE(resumed);
  return setpoints;
}

}  // namespace

TEST_CASE("sim feed hold: simulate with a hold at tick H standing R ticks equals the App held before H and resumed after R",
          "[host_tools][sim][hold]") {
  const auto job = zigzag();
  const auto unheld = simulated(job, {});
  for (const std::uint64_t standing : {std::uint64_t{0}, std::uint64_t{37}}) {
    for (const std::uint64_t hold_tick : {std::uint64_t{150}, std::uint64_t{1001}}) {
      INFO("hold before setpoint " << hold_tick << ", standing " << standing);
      REQUIRE(hold_tick < unheld.size());
      const auto device = streamed_with_hold(job, hold_tick, standing);
      const auto sim = simulated(job, {{hold_tick, standing}});
      // Every streamed setpoint is the simulation's at the same index ...
      CHECK(mismatches(device, sim) == 0);
      // ... and the simulation's others are exactly the R standing ticks, all at one point.
      std::vector<std::uint32_t> extra;
      for (const auto& [index, point] : sim) {
        if (device.count(index) == 0) extra.push_back(index);
      }
      REQUIRE(extra.size() == standing);
      for (std::size_t k = 0; k < extra.size(); ++k) {
        CHECK(extra[k] == extra[0] + k);
        CHECK(sim.at(extra[k]) == sim.at(extra[0] - 1));
      }
      // The hold matters: braking and starting again make the job longer, and the setpoints
      // before the hold are the unheld job's.
      CHECK(sim.size() > unheld.size() + standing);
      for (std::uint32_t i = 0; i < hold_tick; ++i) CHECK(sim.at(i) == unheld.at(i));
      CHECK(sim.rbegin()->second == unheld.rbegin()->second);
    }
  }
}

TEST_CASE("sim feed hold: a hold after the job's end or out of order is refused with one line", "[host_tools][sim][hold]") {
  const auto job = zigzag();
  const auto length = static_cast<std::uint64_t>(simulated(job, {}).size());
  const auto refused = [&](const std::vector<host::FeedHoldEvent>& holds, const std::string& part) {
    check_refused_in_one_line([&] { (void)simulated(job, holds); }, part);
  };
  refused({{length + 5, 0}}, "before the hold at setpoint " + std::to_string(length + 5));
  refused({{500, 0}, {400, 0}}, "in time order");
  refused({{500, 0}, {501, 0}}, "not moving at setpoint 501");
}
