// SPDX-License-Identifier: MIT
// `simulate` with overrides (SimulationOptions::overrides, `curvestep sim --override-at T:F:R`)
// against the firmware: an App<FakeBoard> (the real App over its serial link) sent FeedOverride
// between two ticks streams exactly the simulation's setpoints when the simulation sets the same
// overrides before the setpoint the App's StatusReport names (override_index). Also: the App
// refuses out-of-range values at their byte, a 50 % feed override makes a long line take the
// hand-computed time (about twice as long), and bad --override-at events are refused.
#include <cmath>
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

MachineConfiguration machine() { return curvestep::firmware::testing::machine(60); }  // v_max 100: room for 150 %

/// A zigzag of 6 lines of about 32 mm (long enough to cruise at every override), a rapid back,
/// then an arc.
std::vector<QueueSegment> zigzag() {
  std::vector<QueueSegment> job;
  for (int k = 0; k < 6; ++k) job.push_back(line(p(25.0 * k - 75, (k % 2) * 20.0), p(25.0 * (k + 1) - 75, ((k + 1) % 2) * 20.0)));
  job.push_back(line(p(75, 0), p(45, 0)));
  job.push_back(line(p(45, 0), p(0, 20)));
  job.back().rapid = true;
  job.push_back(line(p(0, 20), p(45, 0)));
  job.push_back(arc(p(45, 0), p(45, 8), p(45, 4), ArcDirection::CounterClockwise));
  job.back().end_of_job = true;
  return job;
}

/// index -> setpoint of simulate() with `overrides`.
std::map<std::uint32_t, WirePoint> simulated(const std::vector<QueueSegment>& wire, const std::vector<host::FeedOverrideEvent>& overrides) {
  auto options = curvestep::sim_testing::device_window();
  options.overrides = overrides;
  return curvestep::sim_testing::simulated_setpoints(wire, machine(), options);
}

struct DeviceRun {
  std::map<std::uint32_t, WirePoint> setpoints;
  std::vector<host::FeedOverrideEvent> reported;  ///< from the StatusReports that answered each FeedOverride
};

/// Streams the job to the App, sending each override when the App's controller is at `at_tick`
/// (before Start for tick 0); the replay events come from the App's StatusReports.
DeviceRun streamed_with_overrides(const std::vector<QueueSegment>& job, const std::vector<host::FeedOverrideEvent>& overrides) {
  std::size_t next = 0;
  DeviceRun run;
  const auto send_due = [&](DeviceApp& app, DeviceHost& host) {
    while (next < overrides.size() && (overrides[next].tick == 0 ? !app.moving() : app.moving() && app.controller().tick() == overrides[next].tick)) {
      const std::size_t statuses = host.received.status.size();
      REQUIRE(host.send(Message(protocol::FeedOverride{overrides[next].value.feed_percent, overrides[next].value.rapid_percent})));
      host.pump();  // the App takes it before its next tick and answers with a StatusReport
      REQUIRE(host.received.status.size() == statuses + 1);
      const StatusReport& s = host.received.status.back();
      run.reported.push_back({s.override_index, curvestep::FeedOverride{s.feed_override_percent, s.rapid_override_percent}});
      ++next;
    }
  };
  run.setpoints = stream_to_device_app(job, machine(), send_due);
  REQUIRE(next == overrides.size());
  return run;
}

}  // namespace

TEST_CASE("sim override: simulate with the overrides at the indices the App reported equals the App's stream bit for bit",
          "[host_tools][sim][override]") {
  const auto job = zigzag();
  const auto plain = simulated(job, {});
  const std::vector<host::FeedOverrideEvent> overrides = {
      {0, {150, 100}}, {400, {40, 50}}, {1201, {200, 25}}, {2003, {100, 100}}};
  REQUIRE(overrides.back().tick < plain.size());
  const DeviceRun device = streamed_with_overrides(job, overrides);
  REQUIRE(device.reported.size() == overrides.size());
  for (std::size_t k = 0; k < overrides.size(); ++k) {
    CHECK(device.reported[k].tick == overrides[k].tick);
    CHECK(device.reported[k].value == overrides[k].value);
  }
  const auto sim = simulated(job, device.reported);
  REQUIRE(device.setpoints.size() == sim.size());
  CHECK(mismatches(device.setpoints, sim) == 0);
  // The overrides matter: the stream differs from the plain job's, and ends at the same point.
  CHECK(sim.size() != plain.size());
  std::size_t changed = 0;
  for (const auto& [index, point] : sim) if (plain.count(index) == 0 || plain.at(index) != point) ++changed;
  CHECK(changed > sim.size() / 2);
  CHECK(sim.rbegin()->second == plain.rbegin()->second);
}

TEST_CASE("sim override: the App refuses a feed override outside 10..200 and a rapid override outside 10..100 at their byte",
          "[host_tools][sim][override]") {
  FakeBoard board;
  DeviceApp app(board);
  Host<DeviceApp> host(board, app);
  REQUIRE(host.connect());
  REQUIRE(host.send(Message(protocol::FeedOverride{9, 100})));
  REQUIRE(host.send(Message(protocol::FeedOverride{100, 101})));
  REQUIRE(host.send(Message(protocol::FeedOverride{10, 10})));
  host.pump();
  REQUIRE(host.received.errors.size() == 2);
  CHECK(host.received.errors[0].code == Error::InvalidArgument);
  CHECK(host.received.errors[0].index == 0);
  CHECK(host.received.errors[1].code == Error::InvalidArgument);
  CHECK(host.received.errors[1].index == 2);
  REQUIRE_FALSE(host.received.status.empty());
  CHECK(host.received.status.back().feed_override_percent == 10);
  CHECK(host.received.status.back().rapid_override_percent == 10);
}

TEST_CASE("sim override: a long line at 50 percent feed takes the hand-computed time, about twice the time at 100",
          "[host_tools][sim][override]") {
  host::Job job;
  job.name = "line";
  job.segments.push_back(PathSegment::make_line(MachinePoint{{0, 0, 0}}, MachinePoint{{200, 0, 0}}).value());
  MachineLimits m;
  m.v_max_mm_per_s = 200;
  m.a_max_mm_per_s2 = 1000;
  m.j_max_mm_per_s3 = 20000;
  m.feed_mm_per_s = 40;
  m.tolerance_mm = 0.01;
  m.rate_hz = 1000;
  host::SimulationOptions options;
  const double full = host::simulate(job, m, options).summary.duration_s;
  options.overrides = {{0, {50, 100}}};
  const double half = host::simulate(job, m, options).summary.duration_s;
  // Rest to rest at v with v < a²/j = 50 mm/s: each ramp takes 2 sqrt(v/j), T = L/v + 2 sqrt(v/j).
  const double full_expected = 200.0 / 40 + 2 * std::sqrt(40.0 / 20000);  // 5.0894 s
  const double half_expected = 200.0 / 20 + 2 * std::sqrt(20.0 / 20000);  // 10.0632 s
  CHECK(std::fabs(full - full_expected) <= 2e-3);
  CHECK(std::fabs(half - half_expected) <= 2e-3);
  CHECK(half / full == Approx(1.977).epsilon(0.002));
}

TEST_CASE("sim override: an override after the job's end, out of order or out of range is refused with one line",
          "[host_tools][sim][override]") {
  const auto job = zigzag();
  const auto length = static_cast<std::uint64_t>(simulated(job, {}).size());
  const auto refused = [&](const std::vector<host::FeedOverrideEvent>& overrides, const std::string& part) {
    check_refused_in_one_line([&] { (void)simulated(job, overrides); }, part);
  };
  refused({{length + 5, {50, 100}}}, "before the override at setpoint " + std::to_string(length + 5));
  refused({{500, {50, 100}}, {400, {60, 100}}}, "in time order");
  refused({{500, {201, 100}}}, "10..200");
}
