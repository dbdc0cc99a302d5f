// SPDX-License-Identifier: MIT
// HIL: `curvestep jog` against the real `curvestep device --fast` on a pseudo-terminal: the controller
// ends exactly (Q16.16) at its start plus the jog, a jog leaving the machine's travel is refused
// before anything moves, and Esc on the jog's terminal aborts it through the protocol.
#include <catch2/catch.hpp>

#include <array>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <unistd.h>

#include "hil_support.hpp"
#include "process.hpp"

namespace ct = curvestep::test;
using namespace std::chrono_literals;

namespace {

int jog(const std::string& port, const std::vector<std::string>& moves, std::string& errors, std::string* output = nullptr) {
  std::vector<std::string> arguments{"jog", "--port", port, "--machine", ct::travel_machine().string()};
  arguments.insert(arguments.end(), moves.begin(), moves.end());
  return ct::run_program(arguments, errors, "jog", std::chrono::seconds(60), output);
}

}  // namespace

TEST_CASE("hil jog: the controller ends at its start plus the jog exactly, several axes at once", "[integration][hil][jog]") {
  ct::Process device({"device", "--fast"}, "device_jog.stderr");
  const std::string port = device.first_line();
  std::string errors;
  std::string output;
  REQUIRE(jog(port, {"X+3.25"}, errors, &output) == 0);
  INFO(errors << output);
  const auto start = ct::controller_position(port);
  CHECK(start == std::array<std::int32_t, 3>{3 * 65536 + 65536 / 4, 0, 0});  // from 0: the first jog
  REQUIRE(jog(port, {"X+10", "y-2.5", "Z+0.125", "--feed", "20"}, errors, &output) == 0);
  INFO(errors << output);
  const auto end = ct::controller_position(port);
  CHECK(end[0] == start[0] + 10 * 65536);
  CHECK(end[1] == start[1] - 5 * 65536 / 2);
  CHECK(end[2] == start[2] + 65536 / 8);
  CHECK_THAT(output, Catch::Contains("to:                  x 13.25 y -2.5 z 0.125 mm"));
}

TEST_CASE("hil jog: a jog leaving the travel is refused before anything moves", "[integration][hil][jog]") {
  ct::Process device({"device", "--fast"}, "device_jog_refused.stderr");
  const std::string port = device.first_line();
  std::string errors;
  REQUIRE(jog(port, {"X+90"}, errors) == 0);
  const auto before = ct::controller_position(port);
  const std::size_t log_before = device.stderr_text().size();
  CHECK(jog(port, {"X+20", "Y+1"}, errors) == 3);  // x would reach 110, beyond 100
  CHECK_THAT(errors, Catch::Contains("refused, nothing moved") && Catch::Contains("x = 110 mm, 10 mm beyond") &&
                         Catch::Contains("travel"));
  CHECK(ct::controller_position(port) == before);
  CHECK(device.stderr_text().find("running", log_before) == std::string::npos);
  CHECK(jog(port, {"Q+1"}, errors) == 1);
  CHECK_THAT(errors, Catch::Contains("\"Q+1\" is no move"));
}

TEST_CASE("hil jog: Esc on the jog's terminal aborts the move through the protocol", "[integration][hil][jog]") {
  ct::Process device({"device", "--fast"}, "device_jog_abort.stderr");
  const std::string port = device.first_line();
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  REQUIRE(master >= 0);
  REQUIRE(::grantpt(master) == 0);
  REQUIRE(::unlockpt(master) == 0);
  const int slave = ::open(::ptsname(master), O_RDWR | O_NOCTTY);
  REQUIRE(slave >= 0);
  ct::Process jogging({"jog", "--port", port, "--machine", ct::travel_machine().string(), "X+90", "--feed", "0.5"}, "jog_abort.stderr",
                      slave);
  for (int i = 0; i < 500 && device.stderr_text().find("running") == std::string::npos; ++i) std::this_thread::sleep_for(20ms);
  REQUIRE(device.stderr_text().find("running") != std::string::npos);
  std::this_thread::sleep_for(100ms);
  REQUIRE(::write(master, "\x1b", 1) == 1);
  const int status = jogging.wait(60s);
  const std::string output = jogging.rest_of_stdout();
  INFO(jogging.stderr_text() << output);
  CHECK(status == 6);
  CHECK_THAT(output, Catch::Contains("aborted:             by the operator"));
  const auto stopped = ct::controller_position(port);
  CHECK(stopped[0] > 0);
  CHECK(stopped[0] < 90 * 65536);
  ::close(slave);
  ::close(master);
}
