// SPDX-License-Identifier: MIT
// HIL: the operator's keys and signals on a running `curvestep stream` (its stdin a real terminal:
// a pseudo-terminal the test types into) act on the real `curvestep device --fast` through the
// protocol; a held and resumed job matches `curvestep sim --hold-at` bit for bit.
#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <map>
#include <regex>
#include <string>
#include <termios.h>
#include <thread>
#include <unistd.h>

#include "hil_support.hpp"
#include "key_terminal.hpp"
#include "process.hpp"

namespace ct = curvestep::test;
using ct::KeyTerminal;
using ct::wait_for_log;
using namespace std::chrono_literals;

namespace {

std::vector<std::string> stream_arguments(const std::filesystem::path& job, const std::filesystem::path& machine,
                                          const std::string& port, const std::filesystem::path& capture) {
  return {"stream", job.string(), "--machine", machine.string(), "--port", port, "--capture", capture.string()};
}

}  // namespace

TEST_CASE("hil operator: ! holds and ~ resumes a streamed job, which then equals curvestep sim --hold-at bit for bit",
          "[integration][hil][operator]") {
  const auto machine = ct::wire_exact_machine();
  const auto job = ct::zigzag_job(400);
  ct::Process device({"device", "--fast"}, "device_hold.stderr");
  const std::string port = device.first_line();
  KeyTerminal terminal;
  const tcflag_t cooked = terminal.local_mode();
  REQUIRE((cooked & ICANON) != 0);
  const auto capture = ct::scratch_dir() / "held.csv";
  ct::Process stream(stream_arguments(job, machine, port, capture), "stream_hold.stderr", terminal.slave());
  REQUIRE(wait_for_log(device, "running at tick"));
  std::this_thread::sleep_for(100ms);
  terminal.type("!");
  REQUIRE(wait_for_log(device, "holding at tick"));
  std::this_thread::sleep_for(300ms);  // held: a fast device does not tick
  terminal.type("~");
  const int status = stream.wait(120s);
  const std::string output = stream.rest_of_stdout();
  INFO(stream.stderr_text());
  INFO(output);
  REQUIRE(status == 0);
  CHECK(terminal.local_mode() == cooked);  // raw mode undone at exit

  // The streamer names the sim options that replay its hold: T = the hold's setpoint index / 1000 Hz, R = 0.
  std::smatch found;
  REQUIRE(std::regex_search(output, found, std::regex("curvestep sim --hold-at ([0-9.e-]+):([0-9.e-]+) gives")));
  const double hold_s = std::stod(found[1].str());
  CHECK(std::stod(found[2].str()) == 0.0);
  const auto hold_tick = static_cast<std::size_t>(std::llround(hold_s * 1000));

  const auto unheld = ct::simulate(job, machine);
  REQUIRE(hold_tick > 0);
  REQUIRE(hold_tick < unheld.size());
  const auto held_csv = ct::scratch_dir() / "sim_held.csv";
  std::string errors;
  REQUIRE(ct::run_program({"sim", job.string(), "--machine", machine.string(), "--lookahead", "16", "--hold-at",
                           found[1].str() + ":" + found[2].str(), "-o", held_csv.string()},
                          errors, "sim_held") == 0);
  const auto held = ct::read_raw_setpoints(held_csv);
  // The hold changed the motion (braking to rest and starting again takes longer) ...
  CHECK(held.size() > unheld.size());
  // ... the setpoints before it are the unheld job's (an independent run of the same plan) ...
  CHECK(ct::first_difference(held, unheld) >= static_cast<long>(hold_tick));
  // ... and the device's stream is the held simulation's, every setpoint.
  ct::check_same_setpoints(held, capture);
  CHECK(held.back().raw == unheld.back().raw);
}

TEST_CASE("hil operator: a real-time device held for a while streams sim --hold-at T:R's setpoints, R its standing time",
          "[integration][hil][operator]") {
  const auto machine = ct::wire_exact_machine();
  const auto job = ct::zigzag_job(30);  // about 9 s at 1 kHz in real time
  ct::Process device({"device"}, "device_realtime_hold.stderr");
  const std::string port = device.first_line();
  KeyTerminal terminal;
  const auto capture = ct::scratch_dir() / "held_realtime.csv";
  ct::Process stream(stream_arguments(job, machine, port, capture), "stream_realtime_hold.stderr", terminal.slave());
  REQUIRE(wait_for_log(device, "running at tick"));
  std::this_thread::sleep_for(1000ms);
  terminal.type("!");
  REQUIRE(wait_for_log(device, "holding at tick"));
  std::this_thread::sleep_for(800ms);  // held: a real-time device keeps ticking without streaming
  terminal.type("~");
  const int status = stream.wait(60s);
  const std::string output = stream.rest_of_stdout();
  INFO(stream.stderr_text());
  INFO(output);
  REQUIRE(status == 0);
  std::smatch found;
  REQUIRE(std::regex_search(output, found, std::regex("curvestep sim --hold-at ([0-9.e-]+):([0-9.e-]+) gives")));
  const auto standing = static_cast<std::size_t>(std::llround(std::stod(found[2].str()) * 1000));
  CHECK(standing > 300);  // most of the 800 ms (the braking takes some of it)
  const auto held_csv = ct::scratch_dir() / "sim_held_realtime.csv";
  std::string errors;
  REQUIRE(ct::run_program({"sim", job.string(), "--machine", machine.string(), "--lookahead", "16", "--hold-at",
                           found[1].str() + ":" + found[2].str(), "-o", held_csv.string()},
                          errors, "sim_held_realtime") == 0);
  const auto simulated = ct::read_raw_setpoints(held_csv);
  const auto captured = ct::read_raw_setpoints(capture);
  // Every captured setpoint is the simulation's at its index; the simulation's others are the
  // standing ticks, consecutive and all at the point where the machine stopped.
  std::map<std::uint64_t, ct::RawSetpoint> by_index;
  for (const auto& r : simulated) by_index[r.index] = r;
  std::size_t mismatches = 0;
  for (const auto& r : captured) {
    const auto it = by_index.find(r.index);
    if (it == by_index.end() || it->second.raw != r.raw) ++mismatches;
    if (it != by_index.end()) by_index.erase(it);
  }
  CHECK(mismatches == 0);
  REQUIRE(by_index.size() == standing);
  const std::uint64_t first = by_index.begin()->first;
  for (const auto& [index, r] : by_index) CHECK(r.raw == simulated.at(first - 1).raw);  // sim's index = its position
  CHECK(by_index.rbegin()->first == first + standing - 1);  // with the count: consecutive
}

TEST_CASE("hil operator: Ctrl-C holds and asks, r resumes, SIGTERM aborts through the protocol, and the terminal is restored",
          "[integration][hil][operator]") {
  const auto machine = ct::wire_exact_machine();
  const auto job = ct::zigzag_job(400);
  ct::Process device({"device", "--fast"}, "device_signals.stderr");
  const std::string port = device.first_line();
  KeyTerminal terminal;
  const tcflag_t cooked = terminal.local_mode();
  ct::Process stream(stream_arguments(job, machine, port, ct::scratch_dir() / "signals.csv"), "stream_signals.stderr",
                     terminal.slave());
  REQUIRE(wait_for_log(device, "running at tick"));
  std::this_thread::sleep_for(100ms);
  ::kill(stream.pid(), SIGINT);
  REQUIRE(wait_for_log(device, "holding at tick"));
  for (int i = 0; i < 100 && stream.stderr_text().find("Feed hold (Ctrl-C)") == std::string::npos; ++i) std::this_thread::sleep_for(20ms);
  CHECK_THAT(stream.stderr_text(), Catch::Contains("Resume: ~, r or Enter"));
  const std::size_t held_at = device.stderr_text().size();
  terminal.type("r");
  REQUIRE(wait_for_log(device, "running at tick", held_at));
  ::kill(stream.pid(), SIGTERM);
  const int status = stream.wait(60s);
  const std::string output = stream.rest_of_stdout();
  INFO(stream.stderr_text());
  INFO(output);
  CHECK(status == 6);
  CHECK_THAT(output, Catch::Contains("aborted:             by the operator at setpoint"));
  CHECK_THAT(stream.stderr_text(), Catch::Contains("aborted by the operator"));
  CHECK(terminal.local_mode() == cooked);
  // The device stopped the job (Abort: back to idle with a flushed queue), it did not lose the link.
  CHECK(wait_for_log(device, "idle at tick", held_at));
  CHECK_THAT(device.stderr_text(), !Catch::Contains("LinkTimeout"));
}

TEST_CASE("hil operator: an arrow key is ignored and Esc aborts, a second Ctrl-C aborts a hold", "[integration][hil][operator]") {
  const auto machine = ct::wire_exact_machine();
  const auto job = ct::zigzag_job(400);
  // A real-time device: the job takes 111 s, so it is surely still running when the keys come (a
  // --fast device can finish it within the 300 ms the arrow-key check waits on a busy machine).
  ct::Process device({"device"}, "device_escape.stderr");
  const std::string port = device.first_line();
  SECTION("Esc") {
    KeyTerminal terminal;
    ct::Process stream(stream_arguments(job, machine, port, ct::scratch_dir() / "escape.csv"), "stream_escape.stderr",
                       terminal.slave());
    REQUIRE(wait_for_log(device, "running at tick"));
    terminal.type("\x1b[A");  // arrow up: not an abort
    std::this_thread::sleep_for(300ms);
    CHECK(stream.wait(0ms) == -1);
    terminal.type("\x1b");
    CHECK(stream.wait(60s) == 6);
    INFO(stream.stderr_text());
    CHECK_THAT(stream.rest_of_stdout(), Catch::Contains("aborted:"));
  }
  SECTION("Ctrl-C twice") {
    KeyTerminal terminal;
    ct::Process stream(stream_arguments(job, machine, port, ct::scratch_dir() / "twice.csv"), "stream_twice.stderr",
                       terminal.slave());
    REQUIRE(wait_for_log(device, "running at tick"));
    ::kill(stream.pid(), SIGINT);
    REQUIRE(wait_for_log(device, "holding at tick"));
    ::kill(stream.pid(), SIGINT);
    CHECK(stream.wait(60s) == 6);
    INFO(stream.stderr_text());
    CHECK_THAT(stream.rest_of_stdout(), Catch::Contains("not resumed") && Catch::Contains("aborted:"));
  }
}
