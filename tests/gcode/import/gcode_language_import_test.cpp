// SPDX-License-Identifier: MIT
// The language layer wired into the importer (issue 18): a parametric LinuxCNC program (a bolt
// circle drilled by a subroutine called from a while loop) becomes the moves worked out by hand;
// the machine layer's system parameters (#5420 position, #5220 coordinate system, #5221 offsets)
// are readable by the next line; (MSG,...) becomes a job event; errors keep file:line:column.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <curvestep/host/gcode_import.hpp>

#include "load_message.hpp"

using namespace curvestep;
using namespace curvestep::host;

namespace {

std::string message_of(const std::string& text) { return testing::load_error_message(text, "lang.ngc"); }

constexpr double pi = 3.14159265358979323846;

}  // namespace

TEST_CASE("language import: a bolt circle from a sub and a while loop drills six holes", "[gcode][import][language]") {
  const Job job = parse_gcode_job(
      "(MSG, bolt circle)\n"
      "#<radius> = 20\n"
      "#<holes> = 6\n"
      "o100 sub\n"
      "  G0 X#1 Y#2\n"
      "  G1 Z-2 F120\n"
      "  G0 Z1\n"
      "o100 endsub\n"
      "G21 G90 G0 Z1\n"
      "#<i> = 0\n"
      "o200 while [#<i> LT #<holes>]\n"
      "  o100 call [#<radius> * COS[#<i> * 360 / #<holes>]] [#<radius> * SIN[#<i> * 360 / #<holes>]]\n"
      "  #<i> = [#<i> + 1]\n"
      "o200 endwhile\n"
      "M2\n",
      "bolt.ngc");
  // Z1 first, then per hole: rapid to the hole at Z1, feed to -2, rapid to 1.
  REQUIRE(job.segments.size() == 1 + 6 * 3);
  for (int hole = 0; hole < 6; ++hole) {
    INFO("hole " << hole);
    const auto over = job.segments[static_cast<std::size_t>(1 + 3 * hole)].end();
    CHECK(over[0] == Approx(20 * std::cos(hole * pi / 3)).margin(1e-4));
    CHECK(over[1] == Approx(20 * std::sin(hole * pi / 3)).margin(1e-4));
    CHECK(over[2] == Approx(1).margin(1e-9));
    CHECK(job.segments[static_cast<std::size_t>(2 + 3 * hole)].end()[2] == Approx(-2).margin(1e-9));
  }
  // Each move's source line is the line inside the sub that made it.
  CHECK(job.sources[1].line == 5);
  CHECK(job.sources[2].line == 6);
  REQUIRE_FALSE(job.events.empty());
  CHECK(job.events[0].kind == JobEventKind::Message);
  CHECK(job.events[0].text == "bolt circle");
}

TEST_CASE("language import: the next line reads the machine layer's position and offsets", "[gcode][import][language]") {
  // G54 at x 100: after G0 X5 the position in G54 is 5 (#5420), machine 105; #5221 is 100, #5220 is 1.
  // The next line moves by what it read: X[#5420 + 1] = 6, Y[#5221 / 10] = 10, Z[#5220] = 1.
  const Job job = parse_gcode_job("G21 G90 G10 L2 P1 X100\nG54 G0 X5\nG0 X[#5420 + 1] Y[#5221 / 10] Z[#5220]\n", "sys.ngc");
  REQUIRE(job.segments.size() == 2);
  CHECK(job.segments[1].end()[0] == Approx(106));
  CHECK(job.segments[1].end()[1] == Approx(10));
  CHECK(job.segments[1].end()[2] == Approx(1));
  // In inches the parameters are in inches: at X1 (25.4 mm), #5420 is 1.
  const Job inch = parse_gcode_job("G20 G90 G0 X1\nG0 X[#5420 * 2]\n", "inch.ngc");
  CHECK(inch.segments.back().end()[0] == Approx(50.8));
}

TEST_CASE("language import: errors from both layers name file:line:column", "[gcode][import][language][errors]") {
  CHECK_THAT(message_of("G21\n#1 = [1 / 0]\n"), Catch::Contains("lang.ngc:2:") && Catch::Contains("division by zero"));
  CHECK_THAT(message_of("G21\no100 while [1]\no100 endwhile\n"), Catch::Contains("lang.ngc:2"));
  CHECK_THAT(message_of("G21\n#1 = 2\nG1 A#1 F100\n"), Catch::Contains("lang.ngc:3:4") && Catch::Contains("rotary"));
  CHECK_THAT(message_of("#1 = 99999\nG21 G0 X#1\n"), Catch::Contains("lang.ngc:2:8") && Catch::Contains("out-of-range"));
}

TEST_CASE("language import: assigning a work-offset or G92 parameter moves that coordinate system", "[gcode][import][language]") {
  // #5221 = 50 is G54's X offset (as G10 L2 P1 X50 would set it): G0 X0 then goes to machine x 50.
  // #5212 = 3 is the G92 Y offset: G0 Y0 goes to machine y 3.
  const Job job = parse_gcode_job("G21 G90 G54\n#5221 = 50\nG0 X0 Y1\n#5212 = 3\nG0 Y0\n", "offsets.ngc");
  REQUIRE(job.segments.size() == 2);
  CHECK(job.segments[0].end()[0] == Approx(50));
  CHECK(job.segments[0].end()[1] == Approx(1));
  CHECK(job.segments[1].end()[1] == Approx(3));
}

TEST_CASE("language import: a feed move at an explicit F0 is refused at the F word", "[gcode][import][errors]") {
  CHECK_THAT(message_of("G21 G90\nG1 X1 F0\n"), Catch::Contains("lang.ngc:2:7") && Catch::Contains("F0"));
  CHECK_THAT(message_of("G21 G90 F0\nG0 X1\nG1 X2\n"), Catch::Contains("lang.ngc:3:1") && Catch::Contains("zero"));
  // A rapid at F0 is fine, and with no F at all a feed move runs at the machine file's feed.
  CHECK_NOTHROW(parse_gcode_job("G21 G90 F0\nG0 X1\n", "rapid.ngc"));
  CHECK_NOTHROW(parse_gcode_job("G21 G90\nG1 X1\n", "no_f.ngc"));
}
