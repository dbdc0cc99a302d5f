// SPDX-License-Identifier: MIT
// HIL: `curvestep home` against the real `curvestep device --switch` (simulated switches at
// hand-chosen positions) on a pseudo-terminal: after homing, the controller's position is the
// machine file's home position exactly, and both approaches stopped within one step (1/80 mm) of
// where the switches were placed; a switch that never closes is an error naming it.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include <curvestep/host/link/status_query.hpp>
#include <curvestep/host/link/transport.hpp>

#include "hil_support.hpp"
#include "process.hpp"

namespace ct = curvestep::test;

namespace {

/// 80 steps/mm on x and y; y homes first on its max switch (to 100 mm), then x on its min (to 0).
std::filesystem::path homing_machine() {
  return ct::trapezoid_machine("homing_machine", R"("homing": {"order": ["y", "x"],
    "x": {"switch": "min", "seek": 10, "locate": 2, "pull_off": 1, "position": 0, "distance": 20},
    "y": {"switch": "max", "seek": 10, "locate": 2, "pull_off": 1.5, "position": 100, "distance": 20}})");
}

/// The seek and locate close points `home` printed for `axis` ("x"), mm.
std::pair<double, double> close_points(const std::string& output, const std::string& axis) {
  const std::regex line(axis + R"(: \S+ \S+ switch closed at (\S+) mm \(seek, setpoint \d+\) and (\S+) mm \(locate)");
  std::smatch m;
  REQUIRE(std::regex_search(output, m, line));
  return {std::stod(m[1].str()), std::stod(m[2].str())};
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
  const double step = 1.0 / 80;
  const auto [x_seek, x_locate] = close_points(output, "x");
  CHECK(std::fabs(x_seek - -3.3) <= step);
  CHECK(std::fabs(x_locate - -3.3) <= step);
  const auto [y_seek, y_locate] = close_points(output, "y");
  CHECK(std::fabs(y_seek - 7.7) <= step);
  CHECK(std::fabs(y_locate - 7.7) <= step);
  CHECK(output.find("  y: ") < output.find("  x: "));  // the section's order
  auto transport = curvestep::host::link::open_port(port, 115200);
  const auto status = curvestep::host::link::read_status(*transport, curvestep::protocol::SenderSettings{100, 10, 3000});
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
