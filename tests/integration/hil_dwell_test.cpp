// SPDX-License-Identifier: MIT
// HIL: G4 dwells and exact stops reach the real `curvestep device` (QueueSegment's stop and rest
// fields; QueuePiece rest pieces for --executor) and its setpoints equal `curvestep sim`'s bit
// for bit, the dwells included.
#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "hil_support.hpp"
#include "process.hpp"

namespace ct = curvestep::test;

namespace {

/// A program with a dwell on a straight joint, a tool change (a stop), a dwell at a corner and
/// two dwells at one joint.
std::filesystem::path dwell_program() {
  const auto path = ct::scratch_dir() / "dwell.ngc";
  std::ofstream(path) << "G21 G90\nG1 X10 F600\nG4 P0.5\nG1 X20\nT2 M6\nG1 X30\nG1 Y10\nG4 P0.25\nG1 X0\nG4 P0.1\nG4 P0.0015\n"
                         "G1 Y0\nM2\n";
  return path;
}

/// The number of setpoints at rest (the same position as the one before) in `setpoints`.
std::size_t still_setpoints(const std::vector<ct::RawSetpoint>& setpoints) {
  std::size_t still = 0;
  for (std::size_t i = 1; i < setpoints.size(); ++i) {
    if (setpoints[i].raw == setpoints[i - 1].raw) ++still;
  }
  return still;
}

/// A dwell after the job's last move: the job ends 2 s after its last move, on the device too.
std::filesystem::path final_dwell_program() {
  const auto path = ct::scratch_dir() / "final_dwell.ngc";
  std::ofstream(path) << "G21 G90\nG1 X10 F600\nG1 Y5\nG4 P2\nM2\n";
  return path;
}

void check_final_dwell(const std::vector<std::string>& device_options, const std::string& tag) {
  const auto machine = ct::wire_exact_machine();
  const auto job = final_dwell_program();
  const auto expected = ct::simulate(job, machine);
  // The simulated stream is the job without the dwell and then 2 s x 1 kHz = 2000 setpoints at its
  // end point (10, 5).
  const auto plain_job = ct::scratch_dir() / "final_dwell_plain.ngc";
  std::ofstream(plain_job) << "G21 G90\nG1 X10 F600\nG1 Y5\nM2\n";
  const auto plain = ct::simulate(plain_job, machine);
  REQUIRE(expected.size() == plain.size() + 2000);
  for (std::size_t i = 0; i < plain.size(); ++i) REQUIRE(expected[i].raw == plain[i].raw);
  for (std::size_t i = plain.size(); i < expected.size(); ++i) REQUIRE(expected[i].raw == plain.back().raw);
  std::string output;
  // The device's stream equals sim's, the 2000 setpoints of the final rest included (same count).
  (void)ct::stream_to_new_device(job, machine, device_options, tag, expected, output);
}

void check_streamed(const std::vector<std::string>& device_options, const std::string& tag) {
  const auto machine = ct::wire_exact_machine();
  const auto job = dwell_program();
  const auto expected = ct::simulate(job, machine);
  // The dwells are in the simulated stream: 500 + 250 + 100 + 2 ticks at rest, and more at stops.
  REQUIRE(still_setpoints(expected) >= 852);
  std::string output;
  // The M6 pauses the device until the operator goes on; --resume-pauses goes on at once.
  (void)ct::stream_to_new_device(job, machine, device_options, tag, expected, output, {"--resume-pauses"});
}

}  // namespace

TEST_CASE("hil: a G-code job with dwells and a tool change streams to curvestep device bit for bit with curvestep sim",
          "[integration][hil][dwell]") {
  check_streamed({"device", "--fast"}, "device_dwell");
}

TEST_CASE("hil: the same job to curvestep device --executor replays its rests as rest pieces, bit for bit",
          "[integration][hil][dwell][pieces]") {
  check_streamed({"device", "--fast", "--executor"}, "executor_dwell");
}

TEST_CASE("hil: a dwell after the last move (G4 P2 then M2) rests on curvestep device as in sim, same setpoint count",
          "[integration][hil][dwell]") {
  check_final_dwell({"device", "--fast"}, "device_final_dwell");
}

TEST_CASE("hil: the dwell after the last move reaches curvestep device --executor as rest pieces, bit for bit",
          "[integration][hil][dwell][pieces]") {
  check_final_dwell({"device", "--fast", "--executor"}, "executor_final_dwell");
}

// An M0 after the last move: the controller reports the pause and ends the job with it, so the
// host tells the operator and sends no Resume (the controller would refuse it, InvalidState). Before,
// `stream --resume-pauses` raced the job's end: it either told nothing or sent that Resume.
TEST_CASE("hil: an M0 after the last move is told by curvestep stream, which sends no Resume for it", "[integration][hil][pause]") {
  const auto machine = ct::wire_exact_machine();
  const auto job = ct::scratch_dir() / "end_pause.ngc";
  std::ofstream(job) << "G21 G90\nG1 X10 F600\nM0\nM2\n";
  for (const bool executor : {false, true}) {
    INFO((executor ? "executor" : "device with a planner"));
    std::vector<std::string> device_options{"device", "--fast"};
    if (executor) device_options.push_back("--executor");
    ct::Process device(device_options, executor ? "end_pause_executor.stderr" : "end_pause_device.stderr");
    const std::string port = device.first_line();
    REQUIRE(port.rfind("/dev/pts/", 0) == 0);
    std::string errors;
    std::string output;
    const int status = ct::run_program({"stream", job.string(), "--machine", machine.string(), "--port", port, "--resume-pauses"}, errors,
                                       executor ? "end_pause_stream_executor" : "end_pause_stream", std::chrono::seconds(60), &output);
    INFO(errors);
    INFO(output);
    CHECK(status == 0);
    CHECK(errors.find("program pause (M0/M1), after the job's last move: the job ended there, nothing is left to resume") !=
          std::string::npos);
    CHECK(output.find("going on") == std::string::npos);  // no Resume sent
    CHECK(device.stop() == 0);
  }
}
