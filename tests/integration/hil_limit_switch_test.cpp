// SPDX-License-Identifier: MIT
// HIL: limit switches through the real `curvestep device --switch` (simulated switches on the host
// board) on a pseudo-terminal: a job crossing a switch faults at the setpoint the job's geometry
// gives, naming the axis and side; a job that stays inside runs as before; after the fault a new
// session moves off the closed switch (motion away from a closed switch is allowed).
//
// Hand computation of the setpoint: a trapezoid profile at a = 1000 mm/s^2 up to the feed of
// 50 mm/s covers 1.25 mm in the first 0.05 s (50 ticks at 1000 Hz), then 0.05 mm per tick, so
// setpoint k (time k / 1000 s) of a 30 mm line is at 1.25 + 0.05 (k - 50) mm while it cruises:
// 10 mm (800 steps at 80 steps/mm) at k = 225 and 10.05 mm (804 steps) at k = 226. A switch at
// 10.025 mm (802 steps) is first closed at setpoint 226; no setpoint lies within 2 steps of it.
#include <catch2/catch.hpp>

#include <array>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <curvestep/host/link/status_query.hpp>
#include <curvestep/host/link/transport.hpp>

#include "hil_support.hpp"
#include "process.hpp"

namespace ct = curvestep::test;

namespace {

/// The machine of the hand computation above.
std::filesystem::path switch_machine() { return ct::trapezoid_machine("switch_machine"); }

/// A one-line job from the origin to `end`.
std::filesystem::path line_job(const std::string& name, const std::string& end) {
  const auto path = ct::scratch_dir() / (name + ".json");
  std::ofstream(path) << R"({"version": 1, "units": "mm", "segments": [{"type": "line", "points": [[0, 0, 0], )" << end
                      << R"(], "feed": 50}]})";
  return path;
}

int stream(const std::string& port, const std::filesystem::path& job, std::string& errors, std::string& output) {
  return ct::run_program({"stream", job.string(), "--machine", switch_machine().string(), "--port", port}, errors, "stream_switch",
                         std::chrono::seconds(60), &output);
}

/// The controller's StatusReport, read over the protocol.
curvestep::protocol::StatusReport status_of(const std::string& port) {
  auto transport = curvestep::host::link::open_port(port, 115200);
  return curvestep::host::link::read_status(*transport, curvestep::protocol::SenderSettings{100, 10, 3000});
}

std::vector<std::string> device_with(const std::vector<std::string>& switches) {
  std::vector<std::string> arguments{"device", "--fast", "--machine", switch_machine().string()};
  for (const auto& s : switches) {
    arguments.push_back("--switch");
    arguments.push_back(s);
  }
  return arguments;
}

}  // namespace

TEST_CASE("hil limit switch: a job crossing the x max switch faults at the hand-computed setpoint and names the axis",
          "[integration][hil][limits]") {
  ct::Process device(device_with({"x+:10.025", "x-:-5"}), "device_switch_x.stderr");
  const std::string port = device.first_line();
  std::string errors;
  std::string output;
  CHECK(stream(port, line_job("switch_x", "[30, 0, 0]"), errors, output) != 0);
  INFO(errors << output);
  CHECK_THAT(errors, Catch::Contains("hard limit: X max at setpoint 226"));
  const auto status = status_of(port);  // a new session: it leaves the Fault, the position stays
  CHECK(status.state == curvestep::protocol::MachineState::Idle);
  CHECK(status.setpoint_index == 226);
  CHECK(status.limit_switches == 0x02);  // x max (bit 1) still closed: the machine stands on it
  // 1.25 + 0.05 * 176 = 10.05 mm, where the machine stopped (within Q16.16 rounding of the plan).
  CHECK(std::abs(status.position[0] - static_cast<std::int32_t>(10.05 * 65536)) < 8);
  CHECK(status.position[1] == 0);
}

TEST_CASE("hil limit switch: a job crossing the y min switch faults naming Y min", "[integration][hil][limits]") {
  ct::Process device(device_with({"y-:-10.025", "y+:5"}), "device_switch_y.stderr");
  const std::string port = device.first_line();
  std::string errors;
  std::string output;
  CHECK(stream(port, line_job("switch_y", "[0, -30, 0]"), errors, output) != 0);
  INFO(errors << output);
  CHECK_THAT(errors, Catch::Contains("hard limit: Y min at setpoint 226"));
}

TEST_CASE("hil limit switch: a job that stays inside the switches runs to its end as before", "[integration][hil][limits]") {
  ct::Process device(device_with({"x+:10.025", "x-:-0.5", "y-:-1", "y+:1"}), "device_switch_inside.stderr");
  const std::string port = device.first_line();
  std::string errors;
  std::string output;
  REQUIRE(stream(port, line_job("switch_inside", "[10, 0, 0]"), errors, output) == 0);
  INFO(errors << output);
  const auto status = status_of(port);
  CHECK(status.state == curvestep::protocol::MachineState::Idle);
  CHECK(status.error == 0);
  CHECK(status.limit_switches == 0);
  CHECK(status.position == curvestep::protocol::WirePoint{10 * 65536, 0, 0});
}

TEST_CASE("hil limit switch: after a hard limit a new session moves off the closed switch, not further onto it",
          "[integration][hil][limits]") {
  ct::Process device(device_with({"x+:10.025"}), "device_switch_off.stderr");
  const std::string port = device.first_line();
  std::string errors;
  std::string output;
  REQUIRE(stream(port, line_job("switch_off", "[30, 0, 0]"), errors, output) != 0);
  const std::vector<std::string> jog{"jog", "--port", port, "--machine", switch_machine().string()};
  std::vector<std::string> further = jog;
  further.push_back("X+1");
  CHECK(ct::run_program(further, errors, "jog_onto_switch", std::chrono::seconds(60)) == 4);  // the device faults at once
  INFO(errors);
  // The first tick toward the switch faults: setpoint 1, a t^2 / 2 = 1000 * 0.001^2 / 2 = 0.0005 mm on.
  CHECK_THAT(errors, Catch::Contains("hard limit: X max at setpoint 1 "));
  std::vector<std::string> back = jog;
  back.push_back("X-5");
  CHECK(ct::run_program(back, errors, "jog_off_switch", std::chrono::seconds(60)) == 0);
  const auto status = status_of(port);
  CHECK(status.limit_switches == 0);
  CHECK(std::abs(status.position[0] - static_cast<std::int32_t>((10.05 + 0.0005 - 5) * 65536)) < 8);
}

TEST_CASE("hil limit switch: a malformed --switch or one without --machine is refused naming it", "[integration][hil][limits]") {
  std::string errors;
  CHECK(ct::run_program({"device", "--machine", switch_machine().string(), "--switch", "q+:5"}, errors, "device_bad_switch",
                        std::chrono::seconds(20)) != 0);
  CHECK_THAT(errors, Catch::Contains("--switch \"q+:5\""));
  CHECK(ct::run_program({"device", "--switch", "x+:5"}, errors, "device_switch_no_machine", std::chrono::seconds(20)) != 0);
  CHECK_THAT(errors, Catch::Contains("--switch needs --machine"));
}
