// SPDX-License-Identifier: MIT
// LinuxCNC's coordinate system rotation (G10 L2 R) through the host importer: a square cut in a
// system turned 30 degrees, the rotation parameters #5230 + 20 n read and assigned, and the cases
// refused, as file:line:column with the word and the reason. Expected points by hand:
// machine XY = R(program XY) + offset.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <curvestep/host/gcode_import.hpp>

#include "grid_point.hpp"
#include "load_message.hpp"

using namespace curvestep;
using namespace curvestep::host;

namespace {

std::string message_of(const std::string& text) { return testing::load_error_message(text, "turned.ngc"); }

constexpr double cos30 = 0.86602540378443864676;

}  // namespace

TEST_CASE("gcode rotation: a 10 mm square in G54 at (50, 20) turned 30 degrees", "[gcode][import][rotation]") {
  // Corners program (0,0) (10,0) (10,10) (0,10): R30 (10, 0) = (10 cos30, 5), R30 (10, 10) =
  // (10 cos30 - 5, 5 + 10 cos30), R30 (0, 10) = (-5, 10 cos30); all + (50, 20).
  const Job job = parse_gcode_job(
      "G21 G90 G17\nG10 L2 P1 X50 Y20 R30\nG54 G0 X0 Y0\nG1 Z-1 F300\nX10\nY10\nX0\nY0\n", "square.ngc");
  REQUIRE(job.segments.size() == 6);
  testing::check_grid_point(job.segments[0].end(), 50, 20, 0);
  testing::check_grid_point(job.segments[2].end(), 50 + 10 * cos30, 25, -1);
  testing::check_grid_point(job.segments[3].end(), 50 + 10 * cos30 - 5, 25 + 10 * cos30, -1);
  testing::check_grid_point(job.segments[4].end(), 45, 20 + 10 * cos30, -1);
  testing::check_grid_point(job.segments[5].end(), 50, 20, -1);
  // Every side is still 10 mm long.
  for (std::size_t i = 2; i < 6; ++i) {
    const MachinePoint a = job.segments[i].start();
    const MachinePoint b = job.segments[i].end();
    CHECK(std::hypot(b[0] - a[0], b[1] - a[1]) == Approx(10).margin(2 * testing::grid_tolerance));
  }
}

TEST_CASE("gcode rotation: #5230 + 20 n hold the rotations, read and assigned as LinuxCNC numbers them", "[gcode][import][rotation]") {
  // G10 L2 P1 R30 is #5230 = 30; X[#5230] is program X 30: machine (30 cos30, 15).
  Job job = parse_gcode_job("G21 G90\nG10 L2 P1 R30\nG54 G0 X[#5230] Y0\n", "read.ngc");
  REQUIRE(job.segments.size() == 1);
  testing::check_grid_point(job.segments[0].end(), 30 * cos30, 15, 0);
  // #5250 is G55's: assigning 90 turns G55 as G10 L2 P2 R90 would; program (1, 0) is machine (0, 1).
  job = parse_gcode_job("G21 G90\n#5250 = 90\nG55 G0 X1 Y0\nG0 X[#5250]\n", "assign.ngc");
  REQUIRE(job.segments.size() == 2);
  testing::check_grid_point(job.segments[0].end(), 0, 1, 0);
  testing::check_grid_point(job.segments[1].end(), 0, 90, 0);
  // #5420 #5421 report the position in the turned system: after G0 X3 Y4 in a system turned 90,
  // X[#5421] Y[#5420] (program (4, 3)) is machine (-3, 4).
  job = parse_gcode_job("G21 G90\nG10 L2 P1 R90\nG54 G0 X3 Y4\nG0 X[#5421] Y[#5420]\n", "position.ngc");
  REQUIRE(job.segments.size() == 2);
  testing::check_grid_point(job.segments[0].end(), -4, 3, 0);
  testing::check_grid_point(job.segments[1].end(), -3, 4, 0);
}

TEST_CASE("gcode rotation: refused cases name the word and say why", "[gcode][import][rotation]") {
  std::string m = message_of("G21\nG10 L20 P1 X0 R45\n");
  CHECK_THAT(m, Catch::Contains("turned.ngc:2:15") && Catch::Contains("R45") && Catch::Contains("R not allowed in G10 L20"));
  m = message_of("G21 G90\nG10 L2 P1 R30\nG54 G18 G0 X0 Z0\nG02 X10 Z0 R5 F100\n");
  CHECK_THAT(m, Catch::Contains("turned.ngc:4:1") && Catch::Contains("G02") && Catch::Contains("rotated coordinate system"));
  m = message_of("G21 G90 G41.1 D2 G1 X10 Y0 F100\nX20\nG10 L20 P1 X0\n");
  CHECK_THAT(m, Catch::Contains("turned.ngc:3:1") && Catch::Contains("G10") && Catch::Contains("cutter radius compensation is on"));
  // The modal arc without its G word: named at its first axis word.
  m = message_of("G21 G90 G18 G0 X0 Z0\nG2 X10 Z0 R5 F100\nG10 L2 P0 R30\nX0 Z0 R5\n");
  CHECK_THAT(m, Catch::Contains("turned.ngc:4:1") && Catch::Contains("rotated coordinate system"));
}
