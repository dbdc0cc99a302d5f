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
