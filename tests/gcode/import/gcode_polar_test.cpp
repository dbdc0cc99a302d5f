// SPDX-License-Identifier: MIT
// LinuxCNC's polar coordinates (@ distance, ^ angle) through the host importer: a bolt circle about
// a G54 origin, with hand-computed hole positions, expressions in polar words, and every error as
// file:line:column with the polar word and LinuxCNC's meaning.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstddef>
#include <string>

#include <curvestep/host/gcode_import.hpp>

#include "grid_point.hpp"
#include "load_message.hpp"

using namespace curvestep;
using namespace curvestep::host;

namespace {

std::string message_of(const std::string& text) { return testing::load_error_message(text, "polar.ngc"); }

constexpr double sqrt3_half = 0.86602540378443864676;

}  // namespace

TEST_CASE("gcode polar: a bolt circle about a G54 origin with G91 angle steps", "[gcode][import][polar]") {
  // Centre (40, 30); holes 15 mm out at 0, 60, 120 degrees: (55, 30), (47.5, 30 + 15 sin 60) and
  // (32.5, 30 + 15 sin 60); 15 sin 60 = 12.990381.
  const Job job = parse_gcode_job(
      "G21 G90 G17\nG10 L2 P1 X40 Y30\nG54 F300\nG0 @15 ^0\n"
      "G91 ^60\n^[30*2]\nG90 G1 Z-1\n",
      "bolt.ngc");
  REQUIRE(job.segments.size() == 4);
  testing::check_grid_point(job.segments[0].end(), 55, 30, 0);
  testing::check_grid_point(job.segments[1].end(), 47.5, 30 + 15 * sqrt3_half, 0);
  testing::check_grid_point(job.segments[2].end(), 32.5, 30 + 15 * sqrt3_half, 0);
  testing::check_grid_point(job.segments[3].end(), 32.5, 30 + 15 * sqrt3_half, -1);
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
  m = message_of("G21 G0 X1\nG5.2 X2 Y0\n@1 ^90\nG5.3\n");
  CHECK_THAT(m, Catch::Contains("polar.ngc:3:1") && Catch::Contains("@1") && Catch::Contains("takes X and Y, not polar words"));
}

TEST_CASE("gcode polar: a G5 spline ends at its polar end point", "[gcode][import][polar]") {
  // From (10, 0) to 10 at 90 degrees, (0, 10); the cubic's controls (10, 5) and (5, 10) make it
  // leave along +Y and arrive along -X.
  const Job job = parse_gcode_job("G21 G90 G0 X10 Y0\nG5 @10 ^90 I0 J5 P5 Q0 F100\n", "spline.ngc");
  REQUIRE(job.segments.size() >= 2);
  testing::check_grid_point(job.segments.back().end(), 0, 10, 0);
  CHECK(job.sources.back().line == 2);
}
