// SPDX-License-Identifier: MIT
// HIL: `curvestep console --keys` against the real `curvestep device --fast` on a pseudo-terminal,
// fed a key script through a pipe: two right arrows at the 1 mm start step move x by exactly 2 mm
// (Q16.16) and `?` prints that position; every jog key and letter moves its axis by the step; a jog
// that would leave the travel is refused and nothing moves. On a real-time device and a terminal,
// Esc aborts a running jog and the session goes on; Ctrl-C aborts one and ends the session (6). (Homing from the console: hil_homing_test.cpp.)
#include <catch2/catch.hpp>

#include <array>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <string>
#include <thread>

#include "hil_support.hpp"
#include "key_terminal.hpp"
#include "process.hpp"

namespace ct = curvestep::test;
using namespace std::chrono_literals;

namespace {

/// Runs `curvestep console --keys` with `keys` on its standard input; returns the exit status.
int console(const std::string& port, const std::string& keys, std::string& output, std::string& errors) {
  const ct::KeyPipe pipe(keys);
  ct::Process p({"console", "--port", port, "--machine", ct::travel_machine().string(), "--keys"}, "console.stderr", pipe.read_end());
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
  const auto start = ct::controller_position(port);
  std::string output;
  std::string errors;
  REQUIRE(console(port, "\x1b[C\x1b[C?q", output, errors) == 0);
  INFO(output << errors);
  CHECK(ct::controller_position(port) == std::array<std::int32_t, 3>{start[0] + 2 * mm, start[1], start[2]});
  CHECK_THAT(output, Catch::Contains("jog X+1: at x 1 y 0 z 0 mm") && Catch::Contains("jog X+1: at x 2 y 0 z 0 mm") &&
                         Catch::Contains("<Idle|MPos:2,0,0|") && Catch::Contains("|Switches:none|Step:1>"));
  // Up, down, Page Up and Page Down, and the letters, move their axes by the step.
  REQUIRE(console(port, "\x1b[A\x1b[A\x1b[B\x1b[5~\x1b[5~\x1b[6~" "dwr", output, errors) == 0);
  INFO(output << errors);
  CHECK(ct::controller_position(port) == std::array<std::int32_t, 3>{start[0] + 3 * mm, start[1] + 2 * mm, start[2] + 2 * mm});
}

TEST_CASE("hil console: a jog beyond the travel is refused and nothing moves", "[integration][hil][console]") {
  ct::Process device({"device", "--fast"}, "device_console_refused.stderr");
  const std::string port = device.first_line();
  std::string output;
  std::string errors;
  // t: step 10 mm; Page Up: z 10, the top of the travel; Page Up again: z would reach 20, 10 mm beyond.
  REQUIRE(console(port, "t\x1b[5~", output, errors) == 0);
  const auto before = ct::controller_position(port);
  CHECK(before == std::array<std::int32_t, 3>{0, 0, 10 * mm});
  const std::size_t log_before = device.stderr_text().size();
  REQUIRE(console(port, "t\x1b[5~r?q", output, errors) == 0);
  INFO(output << errors);
  CHECK_THAT(output, Catch::Contains("jog step 10 mm") && Catch::Contains("jog Z+10 refused, nothing moved") &&
                         Catch::Contains("z = 20 mm, 10 mm beyond the machine's travel -10 .. 10 mm") &&
                         Catch::Contains("<Idle|MPos:0,0,10|"));
  CHECK(ct::controller_position(port) == before);
  CHECK(device.stderr_text().find("running", log_before) == std::string::npos);
}

TEST_CASE("hil console: without a terminal and without --keys it refuses to start", "[integration][hil][console]") {
  ct::Process device({"device", "--fast"}, "device_console_no_keys.stderr");
  const std::string port = device.first_line();
  std::string errors;
  CHECK(ct::run_program({"console", "--port", port, "--machine", ct::travel_machine().string()}, errors, "console_no_keys", 60s) == 1);
  CHECK_THAT(errors, Catch::Contains("standard input is no terminal (use --keys"));
}

TEST_CASE("hil console: Esc aborts a running jog and the session goes on, Ctrl-C aborts one and ends it with 6",
          "[integration][hil][console]") {
  // Real time (no --fast): a 10 mm jog at 0.5 mm/s takes 20 s, long enough to be stopped mid-way.
  ct::Process device({"device"}, "device_console_abort.stderr");
  const std::string port = device.first_line();
  const ct::KeyTerminal terminal;
  ct::Process console({"console", "--port", port, "--machine", ct::travel_machine().string(), "--feed", "0.5"},
                      "console_abort.stderr", terminal.slave());
  terminal.type("t\x1b[C");  // step 10 mm, X+10
  REQUIRE(ct::wait_for_log(device, "running at tick"));
  std::this_thread::sleep_for(300ms);
  std::size_t log_mark = device.stderr_text().size();
  terminal.type("\x1b");
  REQUIRE(ct::wait_for_log(device, "idle at tick", log_mark));
  const auto stopped = ct::controller_position(port);
  CHECK(stopped[0] > 0);
  CHECK(stopped[0] < 10 * mm);
  // Still there: the next jog starts from where the first one stopped; Ctrl-C (SIGINT) aborts it.
  log_mark = device.stderr_text().size();
  terminal.type("\x1b[C");
  REQUIRE(ct::wait_for_log(device, "running at tick", log_mark));
  std::this_thread::sleep_for(300ms);
  log_mark = device.stderr_text().size();
  REQUIRE(::kill(console.pid(), SIGINT) == 0);
  const int status = console.wait(30s);
  const std::string output = console.rest_of_stdout();
  INFO(output << console.stderr_text() << device.stderr_text());
  CHECK(status == 6);
  CHECK_THAT(output, Catch::Contains("jog X+10 aborted: the controller stopped at once at x "));
  CHECK(ct::wait_for_log(device, "idle at tick", log_mark));
  CHECK(device.stderr_text().find("LinkTimeout") == std::string::npos);
  const auto end = ct::controller_position(port);
  CHECK(end[0] > stopped[0]);
  CHECK(end[0] < stopped[0] + 10 * mm);
  CHECK((terminal.local_mode() & ICANON) != 0);  // the terminal's mode restored
}
