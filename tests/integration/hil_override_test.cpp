// SPDX-License-Identifier: MIT
// HIL: feed and rapid override on a running `curvestep stream` (a start option and the operator's
// keys typed into its stdin, a real pseudo-terminal) act on the real `curvestep device --fast`
// through FeedOverride, or on the host's plan for `curvestep device --executor`; the streamed
// setpoints equal `curvestep sim --override-at` with the setpoint indices printed, bit for bit.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "hil_support.hpp"
#include "key_terminal.hpp"
#include "process.hpp"

namespace ct = curvestep::test;
using namespace std::chrono_literals;

namespace {

/// `curvestep stream --feed-override 150` of a long job to a new `curvestep device DEVICE...`, with
/// override keys typed while it runs; its stream equals `curvestep sim [sim_options]
/// --override-at` with the events it printed, bit for bit. Returns those events.
std::string check_override_keys(const std::vector<std::string>& device_arguments, const std::vector<std::string>& sim_options,
                                const std::string& tag) {
  const auto machine = ct::wire_exact_machine();
  const auto job = ct::zigzag_job(400);
  ct::Process device(device_arguments, "device_" + tag + ".stderr");
  const std::string port = device.first_line();
  ct::KeyTerminal terminal;
  const auto capture = ct::scratch_dir() / (tag + ".csv");
  auto arguments = ct::stream_arguments(job, machine, port, capture);
  arguments.insert(arguments.end(), {"--feed-override", "150"});
  ct::Process stream(arguments, "stream_" + tag + ".stderr", terminal.slave());
  REQUIRE(ct::wait_for_log(device, "running at tick"));
  std::this_thread::sleep_for(100ms);
  terminal.type("[[[[[");  // feed 150 -> 100 %
  std::this_thread::sleep_for(100ms);
  terminal.type("{{(");  // feed 98 %, rapid 25 %
  const int status = stream.wait(120s);
  const std::string output = stream.rest_of_stdout();
  INFO(stream.stderr_text());
  INFO(output);
  REQUIRE(status == 0);
  CHECK_THAT(stream.stderr_text(), !Catch::Contains("warning"));

  // The streamer names the overrides the device took and the sim option that replays them.
  const std::string events = ct::override_replay(output);
  CHECK(events.rfind("0:150:100,", 0) == 0);  // the start option, before the job moved
  CHECK(std::count(events.begin(), events.end(), ',') >= 1);
  CHECK_THAT(output, Catch::Contains("feed 150 %, rapid 100 % from the start"));

  const auto plain = ct::simulate_with(job, machine, sim_options, tag + "_plain");
  auto replay = sim_options;
  replay.insert(replay.end(), {"--override-at", events});
  const auto replayed = ct::simulate_with(job, machine, replay, tag + "_replay");
  // The overrides changed the motion (150 % at the start: the job's length in setpoints differs) ...
  CHECK(replayed.size() != plain.size());
  // ... and the device's stream is the simulation's with the reported overrides, every setpoint.
  ct::check_same_setpoints(replayed, capture);
  CHECK(replayed.back().raw == plain.back().raw);
  return events;
}

}  // namespace

TEST_CASE("hil override: --feed-override and override keys change a streamed job, which equals curvestep sim --override-at",
          "[integration][hil][override]") {
  check_override_keys({"device", "--fast"}, {"--lookahead", "16"}, "override");
}

TEST_CASE("hil override: override keys on curvestep device --executor change the host's plan, which equals curvestep sim --override-at",
          "[integration][hil][override][pieces]") {
  // No planner on the device: the host sets each override on its own planner before the setpoint
  // it has planned up to (no FeedOverride is sent); the pieces use the distance window, sim's default.
  const std::string events = check_override_keys({"device", "--fast", "--executor"}, {}, "executor_override");
  CHECK(std::count(events.begin(), events.end(), ',') >= 2);  // the start option and both key groups, at their own ticks
}
