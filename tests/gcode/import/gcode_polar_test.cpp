// SPDX-License-Identifier: MIT
// LinuxCNC's polar coordinates (@ distance, ^ angle) through the host importer: a bolt circle about
// a G54 origin, with hand-computed hole positions, expressions in polar words, and every error as
// file:line:column with the polar word and LinuxCNC's meaning.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstddef>
#include <string>

#include <curvestep/host/gcode_import.hpp>

#include "load_message.hpp"

using namespace curvestep;
using namespace curvestep::host;

namespace {

std::string message_of(const std::string& text) { return testing::load_error_message(text, "polar.ngc"); }

/// Q16.16 quantisation moves a coordinate by at most 2^-17 mm.
constexpr double grid_tolerance = 1.0 / 131072.0;
constexpr double sqrt3_half = 0.86602540378443864676;

void check_point(const MachinePoint& p, double x, double y, double z) {
  CHECK(p[0] == Approx(x).margin(grid_tolerance));
  CHECK(p[1] == Approx(y).margin(grid_tolerance));
  CHECK(p[2] == Approx(z).margin(grid_tolerance));
}

}  // namespace

TEST_CASE("gcode polar: a bolt circle about a G54 origin with G91 angle steps", "[gcode][import][polar]") {
  // Centre (40, 30); holes 15 mm out at 0, 60, 120 degrees: (55, 30), (47.5, 30 + 15 sin 60) and
  // (32.5, 30 + 15 sin 60); 15 sin 60 = 12.990381.
  const Job job = parse_gcode_job(
      "G21 G90 G17\nG10 L2 P1 X40 Y30\nG54 F300\nG0 @15 ^0\n"
      "G91 ^60\n^[30*2]\nG90 G1 Z-1\n",
      "bolt.ngc");
  REQUIRE(job.segments.size() == 4);
  check_point(job.segments[0].end(), 55, 30, 0);
  check_point(job.segments[1].end(), 47.5, 30 + 15 * sqrt3_half, 0);
  check_point(job.segments[2].end(), 32.5, 30 + 15 * sqrt3_half, 0);
  check_point(job.segments[3].end(), 32.5, 30 + 15 * sqrt3_half, -1);
  CHECK(job.sources[1].line == 5);
  CHECK(job.sources[2].line == 6);
}

TEST_CASE("gcode polar: errors name file:line:column, the polar word and LinuxCNC's meaning", "[gcode][import][polar]") {
  std::string m = message_of("G21 G90 F100\nG1 X1 @10 ^30\n");
  CHECK_THAT(m, Catch::Contains("polar.ngc:2:7") && Catch::Contains("@10") && Catch::Contains("cannot be mixed with X or Y"));
  m = message_of("G21 G91 F100\nG1 ^90\n");
  CHECK_THAT(m, Catch::Contains("polar.ngc:2:4") && Catch::Contains("^90") && Catch::Contains("at the XY origin"));
  m = message_of("G21 G90 F100\nG1 @5\n");
  CHECK_THAT(m, Catch::Contains("polar.ngc:2:4") && Catch::Contains("give ^ with @"));
  m = message_of("G21 G18 F100\nG1 @10 ^30\n");
  CHECK_THAT(m, Catch::Contains("polar.ngc:2:4") && Catch::Contains("G17 (XY) plane only"));
  m = message_of("G21\nG92 @1 ^0\n");
  CHECK_THAT(m, Catch::Contains("polar.ngc:2:5") && Catch::Contains("for motion only"));
  m = message_of("G21 G0 X1\nG5 @1 ^0 I1 J0 P1 Q0 F100\n");
  CHECK_THAT(m, Catch::Contains("polar.ngc:2:4") && Catch::Contains("not with splines"));
}
