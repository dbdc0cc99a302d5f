// SPDX-License-Identifier: MIT
// HIL: feed and rapid override on a running `curvestep stream` (a start option and the operator's
// keys typed into its stdin, a real pseudo-terminal) act on the real `curvestep device --fast`
// through FeedOverride; the streamed setpoints equal `curvestep sim --override-at` with the
// setpoint indices the device reported, bit for bit.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <regex>
#include <string>
#include <thread>

#include "hil_support.hpp"
#include "key_terminal.hpp"
#include "process.hpp"

namespace ct = curvestep::test;
using namespace std::chrono_literals;

TEST_CASE("hil override: --feed-override and override keys change a streamed job, which equals curvestep sim --override-at",
          "[integration][hil][override]") {
  const auto machine = ct::wire_exact_machine();
  const auto job = ct::zigzag_job(400);
  ct::Process device({"device", "--fast"}, "device_override.stderr");
  const std::string port = device.first_line();
  ct::KeyTerminal terminal;
  const auto capture = ct::scratch_dir() / "overridden.csv";
  ct::Process stream({"stream", job.string(), "--machine", machine.string(), "--port", port, "--capture", capture.string(),
                      "--feed-override", "150"},
                     "stream_override.stderr", terminal.slave());
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

  // The streamer names the overrides the device took and the sim option that replays them.
  std::smatch found;
  REQUIRE(std::regex_search(output, found, std::regex("curvestep sim (--override-at [0-9.e:,-]+) gives")));
  const std::string events = found[1].str().substr(std::string("--override-at ").size());
  CHECK(events.rfind("0:150:100,", 0) == 0);  // the start option, before the job moved
  CHECK(std::count(events.begin(), events.end(), ',') >= 1);
  CHECK_THAT(output, Catch::Contains("feed 150 %, rapid 100 % from the start"));

  const auto plain = ct::simulate(job, machine);
  const auto replay_csv = ct::scratch_dir() / "sim_overridden.csv";
  std::string errors;
  REQUIRE(ct::run_program({"sim", job.string(), "--machine", machine.string(), "--lookahead", "16", "--override-at", events, "-o",
                           replay_csv.string()},
                          errors, "sim_override") == 0);
  const auto replayed = ct::read_raw_setpoints(replay_csv);
  // The overrides changed the motion (150 % at the start: the job's length in setpoints differs) ...
  CHECK(replayed.size() != plain.size());
  // ... and the device's stream is the simulation's with the reported overrides, every setpoint.
  ct::check_same_setpoints(replayed, capture);
  CHECK(replayed.back().raw == plain.back().raw);
}
