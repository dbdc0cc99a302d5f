// SPDX-License-Identifier: MIT
// HIL: the operator's keys and signals on a running `curvestep stream` (its stdin a real terminal:
// a pseudo-terminal the test types into) act on the real `curvestep device` through the protocol;
// a held and resumed job matches `curvestep sim --hold-at` bit for bit, also on `curvestep device
// --executor` (no planner: the host holds its own plan).
#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <map>
#include <string>
#include <termios.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "hil_support.hpp"
#include "key_terminal.hpp"
#include "process.hpp"

namespace ct = curvestep::test;
using ct::KeyTerminal;
using ct::stream_arguments;
using ct::wait_for_log;
using namespace std::chrono_literals;

namespace {

/// `curvestep stream` of `job` to a new `curvestep device DEVICE...` with `!` typed `before_hold`
/// after the device began moving and `~` `standing` after it reported holding; requires exit 0
/// and the terminal restored; returns the stream's standard output (the capture: `capture`).
std::string hold_and_resume(const std::vector<std::string>& device_arguments, const std::filesystem::path& job,
                            const std::filesystem::path& machine, const std::filesystem::path& capture, const std::string& tag,
                            std::chrono::milliseconds before_hold, std::chrono::milliseconds standing) {
  ct::Process device(device_arguments, "device_" + tag + ".stderr");
  const std::string port = device.first_line();
  KeyTerminal terminal;
  const tcflag_t cooked = terminal.local_mode();
  REQUIRE((cooked & ICANON) != 0);
  ct::Process stream(stream_arguments(job, machine, port, capture), "stream_" + tag + ".stderr", terminal.slave());
  REQUIRE(wait_for_log(device, "running at tick"));
  std::this_thread::sleep_for(before_hold);
  terminal.type("!");
  REQUIRE(wait_for_log(device, "holding at tick"));
  std::this_thread::sleep_for(standing);
  const std::size_t held_at = device.stderr_text().size();
  terminal.type("~");
  REQUIRE(wait_for_log(device, "running at tick", held_at));
  const int status = stream.wait(120s);
  const std::string output = stream.rest_of_stdout();
  INFO(stream.stderr_text());
  INFO(device.stderr_text());
  INFO(output);
  REQUIRE(status == 0);
  CHECK(terminal.local_mode() == cooked);  // raw mode undone at exit
  CHECK_THAT(device.stderr_text(), !Catch::Contains("fault"));
  return output;
}

/// A fast device held and resumed: the stream equals `curvestep sim [sim_options] --hold-at T:0`,
/// T the printed hold, and before T the unheld job's.
void check_fast_hold(const std::vector<std::string>& device_arguments, const std::vector<std::string>& sim_options,
                     const std::string& tag) {
  const auto machine = ct::wire_exact_machine();
  const auto job = ct::zigzag_job(400);
  const auto capture = ct::scratch_dir() / (tag + ".csv");
  const std::string output = hold_and_resume(device_arguments, job, machine, capture, tag, 100ms, 300ms);
  // The streamer names the sim options that replay its hold: T = the hold's setpoint index / 1000
  // Hz, R = 0 (a fast device does not tick while held; an executor never does).
  const auto found = ct::hold_replay(output);
  CHECK(std::stod(found[1]) == 0.0);
  const auto hold_tick = static_cast<long>(std::llround(std::stod(found[0]) * 1000));
  const auto unheld = ct::simulate_with(job, machine, sim_options, tag + "_unheld");
  REQUIRE(hold_tick > 0);
  REQUIRE(hold_tick < static_cast<long>(unheld.size()));
  auto replay = sim_options;
  replay.insert(replay.end(), {"--hold-at", found[0] + ":" + found[1]});
  const auto held = ct::simulate_with(job, machine, replay, tag + "_held");
  // The hold changed the motion (braking to rest and starting again takes longer) ...
  CHECK(held.size() > unheld.size());
  // ... the setpoints before it are the unheld job's (an independent run of the same plan) ...
  CHECK(ct::first_difference(held, unheld) >= hold_tick);
  // ... and the device's stream is the held simulation's, every setpoint.
  ct::check_same_setpoints(held, capture);
  CHECK(held.back().raw == unheld.back().raw);
}

}  // namespace

TEST_CASE("hil operator: ! holds and ~ resumes a streamed job, which then equals curvestep sim --hold-at bit for bit",
          "[integration][hil][operator]") {
  check_fast_hold({"device", "--fast"}, {"--lookahead", "16"}, "hold");
}

TEST_CASE("hil operator: ! and ~ on curvestep device --executor hold the host's plan, which equals curvestep sim --hold-at bit for bit",
          "[integration][hil][operator][pieces]") {
  // No planner on the device (the shipped STM32 images): the host brakes in its pieces, sends
  // FeedHold after them, and the device stands at their end. The pieces are planned with the
  // distance window, sim's default.
  check_fast_hold({"device", "--fast", "--executor"}, {}, "executor_hold");
}

TEST_CASE("hil operator: a real-time device held for a while streams sim --hold-at T:R's setpoints, R its standing time",
          "[integration][hil][operator]") {
  const auto machine = ct::wire_exact_machine();
  const auto job = ct::zigzag_job(30);  // about 9 s at 1 kHz in real time
  const auto capture = ct::scratch_dir() / "held_realtime.csv";
  // Held: a real-time device keeps ticking without streaming.
  const std::string output = hold_and_resume({"device"}, job, machine, capture, "realtime_hold", 1000ms, 800ms);
  const auto found = ct::hold_replay(output);
  const auto standing = static_cast<std::size_t>(std::llround(std::stod(found[1]) * 1000));
  CHECK(standing > 300);  // most of the 800 ms (the braking takes some of it)
  const auto simulated = ct::simulate_with(job, machine, {"--lookahead", "16", "--hold-at", found[0] + ":" + found[1]}, "held_realtime");
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

TEST_CASE("hil operator: a real-time executor held longer than its stall timeout stands without a fault and resumes as sim --hold-at T:0",
          "[integration][hil][operator][pieces]") {
  const auto machine = ct::wire_exact_machine();
  const auto job = ct::zigzag_job(30);  // about 9 s at 1 kHz in real time
  const auto capture = ct::scratch_dir() / "executor_held_realtime.csv";
  // Real time, a stream stalled for the link timeout (1 s) is a fault, and a queue run dry
  // QueueUnderrun: standing 1.8 s after FeedHold is neither.
  const std::string output =
      hold_and_resume({"device", "--executor"}, job, machine, capture, "executor_realtime_hold", 1500ms, 1800ms);
  const auto found = ct::hold_replay(output);
  CHECK(std::stod(found[1]) == 0.0);  // the executor does not tick while it stands
  CHECK(std::stod(found[0]) > 1.0);   // the hold acts after what was sent: about 1.5 s in
  const auto held = ct::simulate_with(job, machine, {"--hold-at", found[0] + ":0"}, "executor_held_realtime");
  ct::check_same_setpoints(held, capture);
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
