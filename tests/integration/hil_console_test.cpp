// SPDX-License-Identifier: MIT
// HIL: `curvestep console --keys` against the real `curvestep device --fast` on a pseudo-terminal,
// fed a key script through a pipe: two right arrows at the 1 mm start step move x by exactly 2 mm
// (Q16.16) and `?` prints that position; a jog that would leave the travel is refused and nothing
// moves; letters jog as the arrows do. (Homing from the console: hil_homing_test.cpp.)
#include <catch2/catch.hpp>

#include <array>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include <curvestep/host/link/status_query.hpp>
#include <curvestep/host/link/transport.hpp>

#include "key_terminal.hpp"
#include "process.hpp"

namespace ct = curvestep::test;
using namespace std::chrono_literals;

namespace {

/// Soft limits x -5 .. 100, y -5 .. 100, z -10 .. 10 mm.
std::filesystem::path console_machine() {
  const auto path = ct::scratch_dir() / "console_machine.json";
  std::ofstream(path) << R"({
  "version": 1, "v_max": 200, "a_max": 2000, "j_max": 50000, "feed": 50, "rapid": 150,
  "tolerance": 0.01, "rate_hz": 1000, "junction_deviation": 0.02, "max_step_rate": 100000, "profile": "scurve",
  "axes": {
    "x": {"steps_per_mm": 80, "v_max": 200, "a_max": 2000, "travel": [-5, 100]},
    "y": {"steps_per_mm": 80, "v_max": 200, "a_max": 2000, "travel": [-5, 100]},
    "z": {"steps_per_mm": 400, "v_max": 20, "a_max": 500, "travel": [-10, 10]}
  }
})";
  return path;
}

/// The controller's commanded position, raw Q16.16 (a StatusReport read by a second client).
std::array<std::int32_t, 3> position_of(const std::string& port) {
  auto transport = curvestep::host::link::open_port(port, 115200);
  const auto report = curvestep::host::link::read_status(*transport, curvestep::protocol::SenderSettings{100, 10, 3000});
  return {report.position[0], report.position[1], report.position[2]};
}

/// Runs `curvestep console --keys` with `keys` on its standard input; returns the exit status.
int console(const std::string& port, const std::string& keys, std::string& output, std::string& errors) {
  const ct::KeyPipe pipe(keys);
  ct::Process p({"console", "--port", port, "--machine", console_machine().string(), "--keys"}, "console.stderr", pipe.read_end());
  const int status = p.wait(60s);
  output = p.rest_of_stdout();
  errors = p.stderr_text();
  return status;
}

constexpr std::int32_t mm = 65536;  // one millimetre in Q16.16

}  // namespace

TEST_CASE("hil console: two right arrows at the 1 mm step move x by exactly 2 mm and ? shows it", "[integration][hil][console]") {
  ct::Process device({"device", "--fast"}, "device_console.stderr");
  const std::string port = device.first_line();
  const auto start = position_of(port);
  std::string output;
  std::string errors;
  REQUIRE(console(port, "\x1b[C\x1b[C?q", output, errors) == 0);
  INFO(output << errors);
  CHECK(position_of(port) == std::array<std::int32_t, 3>{start[0] + 2 * mm, start[1], start[2]});
  CHECK_THAT(output, Catch::Contains("jog X+1: at x 1 y 0 z 0 mm") && Catch::Contains("jog X+1: at x 2 y 0 z 0 mm") &&
                         Catch::Contains("<Idle|MPos:2,0,0|") && Catch::Contains("|Switches:none|Step:1>"));
  // Up, down, Page Up and Page Down, and the letters, move their axes by the step.
  REQUIRE(console(port, "\x1b[A\x1b[A\x1b[B\x1b[5~\x1b[5~\x1b[6~" "dwr", output, errors) == 0);
  INFO(output << errors);
  CHECK(position_of(port) == std::array<std::int32_t, 3>{start[0] + 3 * mm, start[1] + 2 * mm, start[2] + 2 * mm});
}

TEST_CASE("hil console: a jog beyond the travel is refused and nothing moves", "[integration][hil][console]") {
  ct::Process device({"device", "--fast"}, "device_console_refused.stderr");
  const std::string port = device.first_line();
  std::string output;
  std::string errors;
  // Left arrow at 1 mm: x -1; t: step 10 mm; a (x-): x would reach -11, 6 mm below the travel's -5.
  REQUIRE(console(port, "\x1b[D", output, errors) == 0);
  const auto before = position_of(port);
  CHECK(before == std::array<std::int32_t, 3>{-1 * mm, 0, 0});
  const std::size_t log_before = device.stderr_text().size();
  REQUIRE(console(port, "ta?q", output, errors) == 0);
  INFO(output << errors);
  CHECK_THAT(output, Catch::Contains("jog step 10 mm") && Catch::Contains("jog X-10 refused, nothing moved") &&
                         Catch::Contains("x = -11 mm, 6 mm below the machine's travel -5 .. 100 mm") &&
                         Catch::Contains("<Idle|MPos:-1,0,0|"));
  CHECK(position_of(port) == before);
  CHECK(device.stderr_text().find("running", log_before) == std::string::npos);
}

TEST_CASE("hil console: without a terminal and without --keys it refuses to start", "[integration][hil][console]") {
  ct::Process device({"device", "--fast"}, "device_console_no_keys.stderr");
  const std::string port = device.first_line();
  std::string errors;
  CHECK(ct::run_program({"console", "--port", port, "--machine", console_machine().string()}, errors, "console_no_keys", 60s) == 1);
  CHECK_THAT(errors, Catch::Contains("standard input is no terminal (use --keys"));
}
