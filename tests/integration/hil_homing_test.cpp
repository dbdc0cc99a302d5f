// SPDX-License-Identifier: MIT
// HIL: `curvestep home` against the real `curvestep device --switch` (simulated switches at
// hand-chosen positions) on a pseudo-terminal: after homing, the controller's position is the
// machine file's home position exactly, and both approaches stopped within one step (1/80 mm) of
// where the switches were placed; a switch that never closes is an error naming it. The console's
// `h` homes the same way. SIGINT or SIGTERM during `home` aborts the running move through the
// protocol: the real-time device stops at once and stands idle (no link timeout), exit status 6.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "hil_support.hpp"
#include "key_terminal.hpp"
#include "process.hpp"

namespace ct = curvestep::test;

namespace {

/// 80 steps/mm on x and y; y homes first on its max switch (to 100 mm), then x on its min (to 0),
/// seeking at `seek` mm/s.
std::filesystem::path homing_machine(const std::string& seek = "10") {
  return ct::trapezoid_machine("homing_machine_" + seek, R"("homing": {"order": ["y", "x"],
    "x": {"switch": "min", "seek": )" + seek + R"(, "locate": 2, "pull_off": 1, "position": 0, "distance": 20},
    "y": {"switch": "max", "seek": )" + seek + R"(, "locate": 2, "pull_off": 1.5, "position": 100, "distance": 20}})");
}

/// The seek and locate close points `home` printed for `axis` ("x"), mm.
std::pair<double, double> close_points(const std::string& output, const std::string& axis) {
  const std::regex line(axis + R"(: \S+ \S+ switch closed at (\S+) mm \(seek, setpoint \d+\) and (\S+) mm \(locate)");
  std::smatch m;
  REQUIRE(std::regex_search(output, m, line));
  return {std::stod(m[1].str()), std::stod(m[2].str())};
}

/// `home`'s or the console's lines: both axes closed within one step of the switches, y first.
void check_homed_lines(const std::string& output) {
  const double step = 1.0 / 80;
  const auto [x_seek, x_locate] = close_points(output, "x");
  CHECK(std::fabs(x_seek - -3.3) <= step);
  CHECK(std::fabs(x_locate - -3.3) <= step);
  const auto [y_seek, y_locate] = close_points(output, "y");
  CHECK(std::fabs(y_seek - 7.7) <= step);
  CHECK(std::fabs(y_locate - 7.7) <= step);
  CHECK(output.find("  y: ") < output.find("  x: "));  // the section's order
}

}  // namespace

TEST_CASE("hil homing: the axes end at their home positions and the switches closed within one step of where they are",
          "[integration][hil][homing]") {
  ct::Process device({"device", "--fast", "--machine", homing_machine().string(), "--switch", "x-:-3.3", "--switch", "y+:7.7"},
                     "device_homing.stderr");
  const std::string port = device.first_line();
  std::string errors;
  std::string output;
  REQUIRE(ct::run_program({"home", "--machine", homing_machine().string(), "--port", port}, errors, "home", std::chrono::seconds(120),
                          &output) == 0);
  INFO(errors << output);
  check_homed_lines(output);
  const auto status = ct::controller_status(port);
  CHECK(status.position == curvestep::protocol::WirePoint{0, 100 * 65536, 0});
  CHECK(status.limit_switches == 0);  // pulled off both switches
}

TEST_CASE("hil homing: a switch that does not close within the seek distance is an error naming it", "[integration][hil][homing]") {
  ct::Process device({"device", "--fast", "--machine", homing_machine().string(), "--switch", "x-:-30"}, "device_homing_far.stderr");
  const std::string port = device.first_line();
  std::string errors;
  CHECK(ct::run_program({"home", "--machine", homing_machine().string(), "--port", port, "--axes", "x"}, errors, "home_far",
                        std::chrono::seconds(120)) == 4);
  CHECK_THAT(errors, Catch::Contains("homing x: the x min switch did not close within 20 mm"));
}

TEST_CASE("hil homing: the console's h homes the axes as home does", "[integration][hil][homing][console]") {
  ct::Process device({"device", "--fast", "--machine", homing_machine().string(), "--switch", "x-:-3.3", "--switch", "y+:7.7"},
                     "device_console_homing.stderr");
  const std::string port = device.first_line();
  const ct::KeyPipe keys("\x1b[C\x1b[Ch?q");  // first away from 0: x 2
  ct::Process console({"console", "--port", port, "--machine", homing_machine().string(), "--keys"}, "console_homing.stderr",
                      keys.read_end());
  const int exit_status = console.wait(std::chrono::seconds(120));
  const std::string output = console.rest_of_stdout();
  INFO(console.stderr_text() << output);
  REQUIRE(exit_status == 0);
  CHECK_THAT(output, Catch::Contains("jog X+1: at x 2 y 0 z 0 mm") && Catch::Contains("homed: at x 0 y 100 z 0 mm") &&
                         Catch::Contains("<Idle|MPos:0,100,0|"));
  check_homed_lines(output);
  const auto status = ct::controller_status(port);
  CHECK(status.position == curvestep::protocol::WirePoint{0, 100 * 65536, 0});
  CHECK(status.limit_switches == 0);
}

TEST_CASE("hil homing: SIGINT or SIGTERM during home aborts the seek through the protocol, the device stands idle, exit 6",
          "[integration][hil][homing]") {
  const int signal_number = GENERATE(SIGINT, SIGTERM);
  INFO("signal " << signal_number);
  // Real time (no --fast) and a slow seek: 20 mm at 2 mm/s toward a switch that never closes (-30).
  const auto machine = homing_machine("2");
  ct::Process device({"device", "--machine", machine.string(), "--switch", "x-:-30"}, "device_homing_sigint.stderr");
  const std::string port = device.first_line();
  ct::Process home({"home", "--machine", machine.string(), "--port", port, "--axes", "x"}, "home_sigint.stderr");
  REQUIRE(ct::wait_for_log(device, "running at tick"));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const std::size_t log_at_signal = device.stderr_text().size();
  REQUIRE(::kill(home.pid(), signal_number) == 0);
  const int exit_status = home.wait(std::chrono::seconds(30));
  const std::string errors = home.stderr_text();
  INFO(errors << device.stderr_text());
  CHECK(exit_status == 6);
  CHECK_THAT(errors, Catch::Contains("homing x aborted by the operator: the controller stopped at once and stands at x -"));
  CHECK(ct::wait_for_log(device, "idle at tick", log_at_signal));
  CHECK(device.stderr_text().find("LinkTimeout") == std::string::npos);
  const auto status = ct::controller_status(port);
  CHECK(status.state == curvestep::protocol::MachineState::Idle);
  CHECK(status.position[0] < 0);           // it had moved toward the switch ...
  CHECK(status.position[0] > -20 * 65536);  // ... and stopped long before the seek's end
}
