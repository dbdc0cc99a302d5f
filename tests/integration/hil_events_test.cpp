// SPDX-License-Identifier: MIT
// HIL: machine events (M3 S1000, M8, M62 P1, M5, M9, M2 around a G4 P0.5) travel as QueueEvents
// to the real `curvestep device`, whose host board logs a line per board hook with the setpoint
// index; the lines equal `curvestep sim`'s event timeline, in order and at the same setpoints.
#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "hil_support.hpp"
#include "process.hpp"

namespace ct = curvestep::test;

namespace {

std::filesystem::path events_program() {
  const auto path = ct::scratch_dir() / "events.ngc";
  std::ofstream(path) << "G21 G90\nG1 X10 F600\nM3 S1000\nM8\nG4 P0.5\nM62 P1\nG1 X20\nM5\nM9\nM2\n";
  return path;
}

/// The "event ... at setpoint N" parts of the lines of `text`, in order.
std::vector<std::string> event_lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    const auto at = line.find("event ");
    if (at == std::string::npos || line.find(" at setpoint ") == std::string::npos) continue;
    out.push_back(line.substr(at));
  }
  return out;
}

/// `curvestep sim` on `job`: its event timeline (the event lines of its output) and its setpoints.
std::vector<std::string> simulate_timeline(const std::filesystem::path& job, const std::filesystem::path& machine,
                                           std::vector<ct::RawSetpoint>& setpoints) {
  std::string sim_output;
  std::string errors;
  const auto csv = ct::scratch_dir() / (job.stem().string() + "_sim.csv");
  REQUIRE(ct::run_program({"sim", job.string(), "--machine", machine.string(), "--lookahead", "16", "-o", csv.string()}, errors,
                          "sim", std::chrono::seconds(60), &sim_output) == 0);
  UNSCOPED_INFO(sim_output);
  setpoints = ct::read_raw_setpoints(csv);
  return event_lines(sim_output);
}

/// The setpoint number at the end of an event line.
unsigned long setpoint_of(const std::string& line) { return std::stoul(line.substr(line.rfind(' ') + 1)); }

void check_events(const std::vector<std::string>& device_options, const std::string& tag) {
  const auto machine = ct::wire_exact_machine();
  const auto job = events_program();
  std::vector<ct::RawSetpoint> expected;
  const auto timeline = simulate_timeline(job, machine, expected);
  REQUIRE(timeline.size() == 6);
  CHECK(timeline[0].rfind("event spindle_on value 1000 flag 0 at setpoint ", 0) == 0);
  CHECK(timeline[1].rfind("event coolant_flood value 0 flag 0 at setpoint ", 0) == 0);
  CHECK(timeline[2].rfind("event digital_output value 1 flag 1 at setpoint ", 0) == 0);
  CHECK(timeline[3].rfind("event spindle_off ", 0) == 0);
  CHECK(timeline[4].rfind("event coolant_off ", 0) == 0);
  CHECK(timeline[5].rfind("event program_end ", 0) == 0);
  CHECK(setpoint_of(timeline[1]) == setpoint_of(timeline[0]));
  CHECK(setpoint_of(timeline[2]) == setpoint_of(timeline[0]) + 500);  // after the 0.5 s dwell at 1 kHz
  CHECK(setpoint_of(timeline[5]) == expected.back().index);  // the job's end

  std::string output;
  const std::string log = ct::stream_to_new_device(job, machine, device_options, tag, expected, output);
  INFO(log);
  CHECK(event_lines(log) == timeline);
}

}  // namespace

TEST_CASE("hil: spindle, coolant, output and end events reach curvestep device's board hooks at sim's setpoints",
          "[integration][hil][events]") {
  check_events({"device", "--fast"}, "device_events");
}

TEST_CASE("hil: the same events reach curvestep device --executor at sim's setpoints", "[integration][hil][events][pieces]") {
  check_events({"device", "--fast", "--executor"}, "executor_events");
}

TEST_CASE("hil: M0 and a tool change pause curvestep device at sim's setpoints, stream --resume-pauses goes on, bit for bit",
          "[integration][hil][events][pause]") {
  const auto machine = ct::wire_exact_machine();
  const auto job = ct::scratch_dir() / "pauses.ngc";
  std::ofstream(job) << "G21 G90\nG1 X10 F600\nM0\nG1 Y10\nT2 M6\nG1 X0\nM2\n";
  std::vector<ct::RawSetpoint> expected;
  const auto timeline = simulate_timeline(job, machine, expected);
  REQUIRE(timeline.size() == 3);
  REQUIRE(timeline[0].rfind("event program_pause ", 0) == 0);
  REQUIRE(timeline[1].rfind("event tool_change value 2 ", 0) == 0);
  std::string output;
  const std::string log =
      ct::stream_to_new_device(job, machine, {"device", "--fast"}, "device_pauses", expected, output, {"--resume-pauses"});
  INFO(output);
  INFO(log);
  CHECK(event_lines(log) == timeline);
  CHECK_THAT(output, Catch::Contains("paused at setpoint " + std::to_string(setpoint_of(timeline[0])) + ": program pause (M0/M1)"));
  CHECK_THAT(output, Catch::Contains("paused at setpoint " + std::to_string(setpoint_of(timeline[1])) + ": tool change to tool 2"));
}

TEST_CASE("hil: events around a dwell after the last move happen at its start and end on curvestep device, as in sim",
          "[integration][hil][events][dwell]") {
  // M5 before the dwell: at the first setpoint of the final rest (the last move's last + 1); M9 and
  // M2 after it: at the job's last setpoint, 1000 setpoints later (G4 P1 at 1 kHz).
  const auto machine = ct::wire_exact_machine();
  const auto job = ct::scratch_dir() / "final_dwell_events.ngc";
  std::ofstream(job) << "G21 G90\nM3 S1000\nG1 X10 F600\nM5\nG4 P1\nM9\nM2\n";
  std::vector<ct::RawSetpoint> expected;
  const auto timeline = simulate_timeline(job, machine, expected);
  REQUIRE(timeline.size() == 4);
  CHECK(timeline[1].rfind("event spindle_off ", 0) == 0);
  CHECK(timeline[2].rfind("event coolant_off ", 0) == 0);
  CHECK(timeline[3].rfind("event program_end ", 0) == 0);
  CHECK(setpoint_of(timeline[3]) == expected.back().index);
  CHECK(setpoint_of(timeline[2]) == expected.back().index);
  CHECK(setpoint_of(timeline[1]) == expected.back().index - 999);  // the first of the 1000 rest setpoints
  std::string output;
  const std::string log = ct::stream_to_new_device(job, machine, {"device", "--fast"}, "device_final_dwell_events", expected, output);
  INFO(log);
  CHECK(event_lines(log) == timeline);
}

namespace {

/// `program` (events between two moves, more than the device's 32-event ring) streamed to
/// curvestep device: every event reaches a board hook, in order, at the setpoint sim gives the
/// first of them (sim prints the first 40 lines of its timeline), M2 at the job's last, and the
/// setpoints equal sim's bit for bit (the joint is an exact stop, where the device waits for the
/// segment after the events). `events` are the "event NAME value V flag F" of each, in order.
void check_many_events(const std::string& name, const std::string& program, const std::vector<std::string>& events) {
  const auto machine = ct::wire_exact_machine();
  const auto job = ct::scratch_dir() / (name + ".ngc");
  std::ofstream(job) << program;
  std::vector<ct::RawSetpoint> expected;
  const auto timeline = simulate_timeline(job, machine, expected);
  REQUIRE(timeline.size() == 40);  // sim shows 40 lines and counts the rest
  const std::string at = " at setpoint " + std::to_string(setpoint_of(timeline[0]));
  std::vector<std::string> lines;
  for (const auto& e : events) lines.push_back(e + at);
  lines.push_back("event program_end value 0 flag 0 at setpoint " + std::to_string(expected.back().index));
  CHECK(std::vector<std::string>(lines.begin(), lines.begin() + 40) == timeline);
  std::string output;
  const std::string log = ct::stream_to_new_device(job, machine, {"device", "--fast"}, "device_" + name, expected, output);
  INFO(output);
  CHECK(event_lines(log) == lines);
}

}  // namespace

TEST_CASE("hil: 40 M62 and M63 lines between two moves run on curvestep device in order at sim's setpoints",
          "[integration][hil][events][credit]") {
  std::string program = "G21 G90\nG1 X10 F600\n";
  std::vector<std::string> events;
  for (int k = 0; k < 20; ++k) {
    const std::string n = std::to_string(k % 4);
    program += "M62 P" + n + "\nM63 P" + n + "\n";
    events.push_back("event digital_output value " + n + " flag 1");
    events.push_back("event digital_output value " + n + " flag 0");
  }
  program += "G1 X20\nM2\n";
  check_many_events("outputs40", program, events);
}

TEST_CASE("hil: 48 S and M words between two moves run on curvestep device in order at sim's setpoints",
          "[integration][hil][events][credit]") {
  std::string program = "G21 G90\nG1 X10 F600\n";
  std::vector<std::string> events;
  for (int k = 0; k < 12; ++k) {
    const std::string rpm = std::to_string(1000 + 100 * k);
    program += "M3 S" + rpm + "\nM8\nM5\nM9\n";
    events.push_back("event spindle_on value " + rpm + " flag 0");
    events.push_back("event coolant_flood value 0 flag 0");
    events.push_back("event spindle_off value 0 flag 0");
    events.push_back("event coolant_off value 0 flag 0");
  }
  program += "G1 Y10\nM2\n";
  check_many_events("spindle48", program, events);
}

TEST_CASE("hil: more events before the first move than curvestep device's ring holds are refused at load, naming the line",
          "[integration][hil][events][credit]") {
  // Before the first move nothing moves, so the device cannot work events off to make room: the
  // host refuses the 33rd (the device's ring holds 32) before anything is queued.
  const auto machine = ct::wire_exact_machine();
  const auto job = ct::scratch_dir() / "too_many_first.ngc";
  std::string program = "G21 G90\n";
  for (int k = 0; k < 20; ++k) program += "M62 P1\nM63 P1\n";
  program += "G1 X10 F600\nM2\n";
  std::ofstream(job) << program;
  ct::Process device({"device", "--fast"}, "too_many_first_device.stderr");
  const std::string port = device.first_line();
  REQUIRE(port.rfind("/dev/pts/", 0) == 0);
  std::string errors;
  std::string output;
  const int status = ct::run_program({"stream", job.string(), "--machine", machine.string(), "--port", port}, errors, "too_many_first",
                                     std::chrono::seconds(60), &output);
  INFO(output);
  CHECK(status != 0);
  // The 33rd event is line 34 (line 1 G21, then M62/M63 from line 2).
  CHECK_THAT(errors, Catch::Contains("too_many_first.ngc:34: M62: more than 32 machine events before the first move"));
  CHECK(device.stop() == 0);
}
