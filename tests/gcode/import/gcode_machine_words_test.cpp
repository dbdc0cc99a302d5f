// SPDX-License-Identifier: MIT
// G-code import of the machine words CAM posts emit (issue 17): modal words that change nothing in
// the path, work offsets (G54-G59.3, G10 L2/L20, G92, G53), G28, tool length (G43/G49), path control
// (G61/G64 P) into the per-joint blend tolerance, and S/T/M words as job events in LinuxCNC's order of
// execution. Expected positions are worked out by hand from the LinuxCNC reference's definitions.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <curvestep/host/gcode_import.hpp>

#include "load_message.hpp"

using namespace curvestep;
using namespace curvestep::host;

namespace {

MachinePoint pt(double x, double y, double z = 0) { return MachinePoint{{x, y, z}}; }

std::string message_of(const std::string& text) { return testing::load_error_message(text, "inline.ngc"); }

}  // namespace

TEST_CASE("gcode machine words: a Fusion-style program loads with its events in order", "[gcode][import][machine]") {
  const Job job = parse_gcode_job(
      "%\n(1001)\nN10 G90 G94 G17 G91.1\nN15 G21\nN20 G53 G0 Z0.\nN25 T1 M6\nN30 S12000 M3\nN35 G54\nN40 M8\n"
      "N45 G0 X10. Y10.\nN50 G43 Z15. H1\nN55 G1 Z-1. F600.\nN60 X40.\nN65 M9\nN70 M5\nN75 M30\n%\n",
      "fusion.nc");
  // Motion: rapid (0,0,0)->(10,10,0), rapid ->(10,10,15), feed ->(10,10,-1), feed ->(40,10,-1).
  REQUIRE(job.segments.size() == 4);
  CHECK(job.segments[0].end() == pt(10, 10, 0));
  CHECK(job.segments[1].end() == pt(10, 10, 15));
  CHECK(job.segments[2].end() == pt(10, 10, -1));
  CHECK(job.segments[3].end() == pt(40, 10, -1));
  CHECK(job.segments[0].rapid());
  CHECK(job.segments[2].feed_mm_per_s() == Approx(10.0));  // F600 mm/min
  // Events: M6 (tool 1), M3 at 12000, M8 before any motion; M9, M5 after the last move; M30 at the end.
  REQUIRE(job.events.size() == 6);
  const JobEventKind kinds[] = {JobEventKind::ToolChange, JobEventKind::SpindleOn, JobEventKind::CoolantFlood,
                                JobEventKind::CoolantOff, JobEventKind::SpindleOff, JobEventKind::ProgramEnd};
  const std::size_t before[] = {0, 0, 0, 4, 4, 4};
  for (std::size_t i = 0; i < 6; ++i) {
    INFO("event " << i);
    CHECK(job.events[i].kind == kinds[i]);
    CHECK(job.events[i].before_segment == before[i]);
  }
  CHECK(job.events[0].value == 1);
  CHECK(job.events[1].value == 12000);
  CHECK_FALSE(job.events[1].flag);  // M3: clockwise
  CHECK(job.events[0].line == 6);
  CHECK(job.events[0].text == "M6");
}

TEST_CASE("gcode machine words: work offsets, G92, G53 and G10 L20 move the path as LinuxCNC defines", "[gcode][import][machine]") {
  const Job job = parse_gcode_job(
      "G21 G90\n"
      "G10 L2 P1 X100 Y50\n"   // G54 origin at (100, 50, 0)
      "G0 X0 Y0\n"             // -> (100, 50, 0)
      "G0 X5 Y5\n"             // -> (105, 55, 0)
      "G92 X0 Y0\n"            // here is (0, 0): G92 offset (5, 5)
      "G0 X1\n"                // -> (106, 55, 0)
      "G53 G0 X0 Y0\n"         // machine coordinates: (0, 0, 0)
      "G92.1\n"                // G92 off
      "G55 G0 X0\n"            // G55 origin (0, 0, 0): (0, 0, 0) -> no move... Y stays 0
      "G0 X30\n"               // -> (30, 0, 0)
      "G10 L20 P2 X0\n"        // G55 x origin so that here is x 0: 30
      "G0 X2\n",               // -> (32, 0, 0)
      "offsets.ngc");
  REQUIRE(job.segments.size() == 6);
  CHECK(job.segments[0].end() == pt(100, 50));
  CHECK(job.segments[1].end() == pt(105, 55));
  CHECK(job.segments[2].end() == pt(106, 55));
  CHECK(job.segments[3].end() == pt(0, 0));
  CHECK(job.segments[4].end() == pt(30, 0));
  CHECK(job.segments[5].end() == pt(32, 0));
}

TEST_CASE("gcode machine words: G28 goes home through the given point, G43 applies the tool length", "[gcode][import][machine]") {
  const Job job = parse_gcode_job("G21 G90\nG0 X10 Y10 Z5\nG28 Z20\nG0 X10\nG91 G28 X0\n", "home.ngc");
  // G28 Z20: rapid to (10,10,20) then Z home (0): (10,10,0); G0 X10 no move; G91 G28 X0: X home (0,10,0).
  REQUIRE(job.segments.size() == 4);
  CHECK(job.segments[1].end() == pt(10, 10, 20));
  CHECK(job.segments[2].end() == pt(10, 10, 0));
  CHECK(job.segments[3].end() == pt(0, 10, 0));
  for (const auto& s : job.segments) CHECK(s.rapid());
}

TEST_CASE("gcode machine words: G4 dwells between moves, G61/G64 P set each joint's blend tolerance", "[gcode][import][machine]") {
  const Job job = parse_gcode_job("G21 G90 G1 X10 F600\nG4 P0.5\nG64 P0.05 X20\nG61 X30\nG64 X40\n", "dwell.ngc");
  REQUIRE(job.segments.size() == 4);
  REQUIRE(job.events.size() == 1);
  CHECK(job.events[0].kind == JobEventKind::Dwell);
  CHECK(job.events[0].value == 0.5);
  CHECK(job.events[0].before_segment == 1);
  REQUIRE(job.blend_tolerance_mm.size() == 4);
  CHECK(job.blend_tolerance_mm[0] == 0);
  CHECK(job.blend_tolerance_mm[1] == 0.05);
  CHECK(job.blend_tolerance_mm[2] < 0);  // G61: exact stop
  CHECK(job.blend_tolerance_mm[3] == 0);  // G64 without P: the machine file's tolerance
  // G64 P in inches is converted: P0.002 in = 0.0508 mm.
  const Job inches = parse_gcode_job("G20 G90 G64 P0.002 G1 X1 F10\n", "inch.ngc");
  CHECK(inches.blend_tolerance_mm[0] == Approx(0.0508));
}

TEST_CASE("gcode machine words: block delete, lower case, coolant together, overrides and outputs", "[gcode][import][machine]") {
  const Job job = parse_gcode_job("g21 g90\n/ g1 x5 f300\nM7 M8\nM48\nM62 P3\ng1 x6\nM65 P3\n", "misc.ngc");
  REQUIRE(job.segments.size() == 2);  // the block-delete line runs (the switch is off)
  CHECK(job.segments[0].end() == pt(5, 0));
  REQUIRE(job.events.size() == 4);
  CHECK(job.events[0].kind == JobEventKind::CoolantMist);
  CHECK(job.events[1].kind == JobEventKind::CoolantFlood);
  CHECK(job.events[2].kind == JobEventKind::DigitalOutput);
  CHECK(job.events[2].value == 3);
  CHECK(job.events[2].flag);
  CHECK(job.events[3].kind == JobEventKind::DigitalOutput);
  CHECK_FALSE(job.events[3].flag);
  CHECK(job.events[3].before_segment == 2);
}

TEST_CASE("gcode machine words: what is not supported says why, with file:line:column", "[gcode][import][machine][errors]") {
  const struct {
    const char* text;
    const char* says;
  } cases[] = {
      {"G21\nG19 G41 D1 G1 X1 F100\n", "cutter radius compensation works in the G17 (XY) and G18 (XZ) planes only"},
      {"G21\nG84 X1 Y1 Z-1 R1 F100\n", "tapping cycles"},
      {"G21\nG1 A10 F100\n", "rotary"},
      {"G21\nG95 G1 X1 F1\n", "spindle model"},
      {"G21\nM66 P1\n", "unsupported M code"},
      {"G21\nM100 P100\n", "M100-M199 are user M codes"},
      {"G21\nM199\n", "M100-M199 are user M codes"},
      {"G21\nM98 P[1] L[#1]\n", "no numbered program O1"},
  };
  for (const auto& c : cases) {
    INFO(c.text);
    const std::string message = message_of(c.text);
    CHECK(message.find("inline.ngc:2:") != std::string::npos);
    CHECK(message.find(c.says) != std::string::npos);
  }
}
