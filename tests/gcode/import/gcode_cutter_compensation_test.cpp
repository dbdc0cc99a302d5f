// SPDX-License-Identifier: MIT
// Cutter radius compensation (issue 17.1): G41/G42 D<tool>, G41.1/G42.1 D<diameter>, G40, in G17.
// Every expected point is worked out by hand from the rules in docs/gcode.md: lines shift by the
// tool radius r to the side, arcs change radius by ±r, outside corners get an arc of radius r about
// the programmed corner, inside corners cut the offsets at their crossing, the entry move ends where
// the first offset move begins and the exit move starts where the tool is.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include <curvestep/host/gcode_import.hpp>

#include "compensation_path.hpp"
#include "load_message.hpp"

using namespace curvestep;
using namespace curvestep::host;

namespace {

using testing::arc;
using testing::check_path;
using testing::to;
using testing::tool_table;

Job load(const std::string& text) { return testing::load_compensated(text); }

std::string message_of(const std::string& text) {
  try {
    (void)load(text);
  } catch (const LoadError& e) {
    return e.what();
  }
  FAIL("no LoadError for: " << text);
  return {};
}

constexpr double h = 1.4142135623730951;  // r·cos 45° = r·sin 45° for r = 2

}  // namespace

TEST_CASE("cutter compensation: G41 outside a clockwise 20 x 20 square, quarter arcs at the corners", "[gcode][import][compensation]") {
  // Clockwise (0,0) (0,20) (20,20) (20,0): the tool's left is outside. The entry move ends at the
  // first side's offset start (-2,0); each corner gets a clockwise quarter arc of radius 2 about it;
  // G40 ends the last side square at (0,-2); the exit move goes to the programmed (-10,-10).
  const std::string program =
      "G21 G17 G90\nG0 X-10 Y-10\nG41 D1\nG1 X0 Y0 F600\nY20\nX20\nY0\nX0\nG40\nG1 X-10 Y-10\nM2\n";
  const Job job = load(program);
  check_path(job, {to(-10, -10), to(-2, 0), to(-2, 20), arc(0, 22, 0, 20, -h, 20 + h), to(20, 22), arc(22, 20, 20, 20, 20 + h, 20 + h),
                   to(22, 0), arc(20, -2, 20, 0, 20 + h, -h), to(0, -2), to(-10, -10)});
  CHECK(job.segments[0].rapid());
  CHECK_FALSE(job.segments[3].rapid());
  CHECK(job.segments[3].arc_radius() == Approx(2.0).margin(1e-4));
  CHECK(job.segments[3].feed_mm_per_s() == Approx(10.0));
  // Each corner arc belongs to the move after the corner (program line 6 turns the first corner).
  CHECK(job.sources[job.source_index[3]].line == 6);
  CHECK(job.sources[job.source_index[2]].line == 5);

  SECTION("G41.1 D4 gives the diameter directly: the same path") {
    std::string direct = program;
    direct.replace(direct.find("G41 D1"), 6, "G41.1 D4");
    const Job same = parse_gcode_job(direct, "comp.ngc");  // no tool table needed
    REQUIRE(same.segments.size() == job.segments.size());
    for (std::size_t i = 0; i < job.segments.size(); ++i) CHECK(same.segments[i].end() == job.segments[i].end());
  }
  SECTION("G41 D0 is no offset: the programmed square") {
    std::string none = program;
    none.replace(none.find("G41 D1"), 6, "G41 D0");
    check_path(load(none), {to(-10, -10), to(0, 0), to(0, 20), to(20, 20), to(20, 0), to(0, 0), to(-10, -10)});
  }
  SECTION("G20: G41.1 D is in inches") {
    const Job inches = parse_gcode_job("G20 G17 G90\nG0 X0 Y-1\nG41.1 D0.1\nG1 X0 Y0 F10\nY1\nG40\nG1 X0 Y2\n", "comp.ngc");
    // r = 0.05 in = 1.27 mm; going up (+Y) the left is -X.
    check_path(inches, {to(0, -25.4), to(-1.27, 0), to(-1.27, 25.4), to(0, 50.8)});
  }
}

TEST_CASE("cutter compensation: G42 outside a counter-clockwise square, arcs the other way", "[gcode][import][compensation]") {
  // Counter-clockwise (0,0) (20,0) (20,20) (0,20): the tool's right is outside; counter-clockwise
  // quarter arcs about the corners.
  const Job job = load("G21 G17\nG0 X-10 Y-10\nG42 D1 G1 X0 Y0 F600\nX20\nY20\nX0\nY0\nG40 G1 X-10 Y-10\n");
  check_path(job, {to(-10, -10), to(0, -2), to(20, -2), arc(22, 0, 20, 0, 20 + h, -h), to(22, 20), arc(20, 22, 20, 20, 20 + h, 20 + h),
                   to(0, 22), arc(-2, 20, 0, 20, -h, 20 + h), to(-2, 0), to(-10, -10)});
}

TEST_CASE("cutter compensation: an L-shaped pocket, inside corners cut at the offsets' crossing", "[gcode][import][compensation]") {
  // Counter-clockwise L (0,0) (30,0) (30,10) (10,10) (10,30) (0,30), tool on the left (inside):
  // the offset lines y=2, x=28, y=8, x=8, y=28, x=2 meet at (28,2) (28,8) (8,28) (2,28) (2,2); the
  // reflex corner (10,10) is outside for the tool: a clockwise quarter arc (10,8) -> (8,10).
  const Job job = load("G21 G17\nG0 X5 Y5\nG41 D1\nG1 X5 Y0 F600\nX30\nY10\nX10\nY30\nX0\nY0\nX5\nG40\nG1 Y5\n");
  check_path(job, {to(5, 5), to(5, 2), to(28, 2), to(28, 8), to(10, 8), arc(8, 10, 10, 10, 10 - h, 10 - h), to(8, 28), to(2, 28),
                   to(2, 2), to(5, 2), to(5, 5)});
}

TEST_CASE("cutter compensation: a line into an arc at an inside corner", "[gcode][import][compensation]") {
  // Line (0,0) -> (10,0), then clockwise about (20,0) to (20,10): a left turn, inside for G41. Left
  // of a clockwise arc is away from its centre: radius 12. The line y=2 meets it at
  // x = 20 - sqrt(144 - 4); the arc ends at (20,12).
  const double x = 20 - std::sqrt(140.0);
  const double a = (std::atan2(2.0, -std::sqrt(140.0)) + 3.141592653589793 / 2) / 2;  // middle angle
  const Job job = load("G21 G17\nG0 X0 Y-10\nG41 D1\nG1 X0 Y0 F600\nX10\nG2 X20 Y10 I10 J0\nG40\nG1 X20 Y20\n");
  check_path(job, {to(0, -10), to(0, 2), to(x, 2), arc(20, 12, 20, 0, 20 + 12 * std::cos(a), 12 * std::sin(a)), to(20, 20)});
  CHECK(job.segments[3].arc_radius() == Approx(12.0).margin(1e-4));
}

TEST_CASE("cutter compensation: an arc into a line at an inside corner", "[gcode][import][compensation]") {
  // Counter-clockwise about (0,0) from (10,0) to (0,10), then down to (0,0) and right to (10,0): left
  // turns, inside for G41. Left of a counter-clockwise arc is towards its centre: radius 8, from
  // (8,0); the line x=2 meets it at (2, sqrt(60)); the lines x=2 and y=2 meet at (2,2).
  const double y = std::sqrt(60.0);
  const double a = std::atan2(y, 2.0) / 2;  // middle angle
  const Job job = load("G21 G17\nG0 X20 Y0\nG41 D1 G1 X10 Y0 F600\nG3 X0 Y10 I-10 J0\nG1 Y0\nX10\nG40 X20\n");
  check_path(job, {to(20, 0), to(8, 0), arc(2, y, 0, 0, 8 * std::cos(a), 8 * std::sin(a)), to(2, 2), to(10, 2), to(20, 0)});
  CHECK(job.segments[2].arc_radius() == Approx(8.0).margin(1e-4));
}

TEST_CASE("cutter compensation: a profile of lines and arcs (radius r+2 and r-2)", "[gcode][import][compensation]") {
  // Clockwise: (0,0) up to (0,20), right to (10,20), a convex clockwise arc about (10,10) to (20,10)
  // (tangent at both ends), down to (20,0), then a concave counter-clockwise arc about (10,-7.5)
  // (radius 12.5) back to (0,0). G41: the tool is outside (left of clockwise travel).
  //  * convex arc: left of clockwise = away from the centre, radius 12: (10,22) -> (22,10);
  //  * corner (20,0): the line goes (0,-1), the arc starts going (-0.6,0.8): a right turn, outside:
  //    clockwise arc about (20,0) from (22,0) to (20,0) + 2·(-0.8,-0.6) = (18.4,-1.2);
  //  * concave arc: left of counter-clockwise = towards the centre, radius 10.5: (18.4,-1.2) ->
  //    (10,-7.5) + 0.84·(-10,7.5) = (1.6,-1.2); G40 ends it there.
  const Job job = load(
      "G21 G17\nG0 X-10 Y-10\nG41 D1\nG1 X0 Y0 F600\nY20\nX10\nG2 X20 Y10 I0 J-10\nG1 Y0\nG3 X0 Y0 I-10 J-7.5\nG40\nG1 X-10 Y-10\n");
  const double corner_middle = (0 + std::atan2(-1.2, -1.6)) / 2;  // half way from angle 0 to -143.13°
  check_path(job, {to(-10, -10), to(-2, 0), to(-2, 20), arc(0, 22, 0, 20, -h, 20 + h), to(10, 22),
                   arc(22, 10, 10, 10, 10 + 12 * std::sqrt(0.5), 10 + 12 * std::sqrt(0.5)), to(22, 0),
                   arc(18.4, -1.2, 20, 0, 20 + 2 * std::cos(corner_middle), 2 * std::sin(corner_middle)),
                   arc(1.6, -1.2, 10, -7.5, 10, 3), to(-10, -10)});
  CHECK(job.segments[5].arc_radius() == Approx(12.0).margin(1e-4));
  CHECK(job.segments[8].arc_radius() == Approx(10.5).margin(1e-4));
}

TEST_CASE("cutter compensation: Z moves and events wait for the held move", "[gcode][import][compensation]") {
  // The plunge and M8 come after the first side's move in the program: they happen at its
  // compensated end (-2,20), before the corner arc.
  const Job job = load("G21 G17\nG0 X-10 Y-10 Z5\nG41 D1\nG1 X0 Y0 F600\nY20\nG1 Z-1\nM8\nX20\nG40\nG1 X20 Y30\n");
  check_path(job, {to(-10, -10), to(-2, 0), to(-2, 20), to(-2, 20), arc(0, 22, 0, 20, -h, 20 + h), to(20, 22), to(20, 30)});
  CHECK(job.segments[3].end()[2] == Approx(-1));
  CHECK(job.segments[4].start()[2] == Approx(-1));
  REQUIRE(job.events.size() == 1);
  CHECK(job.events[0].kind == JobEventKind::CoolantFlood);
  CHECK(job.events[0].before_segment == 4);
}

TEST_CASE("cutter compensation: what cannot be compensated is refused with file:line:column", "[gcode][import][compensation][errors]") {
  testing::check_refusals({
      // A concave arc (left of counter-clockwise) of radius 1.5 with a tool of radius 2.
      {"G21\nG0 X0 Y-10\nG41 D1\nG1 X0 Y0 F600\nG3 X3 Y0 I1.5 J0\n", "comp.ngc:5:1: G3", "not larger than the tool radius"},
      // Inside corner on a move 1 mm long: the offsets cross at y = 2, beyond its offset end y = 1.
      {"G21\nG0 X0 Y-10\nG41 D1\nG1 X0 Y0 F600\nX20\nY1\nX0\n", "comp.ngc:6:1: Y1", "this move is too short"},
      // G41 while on (and changing side).
      {"G21\nG41 D1\nG1 X0 Y10 F600\nG41 D1 X5\n", "comp.ngc:4:1: G41", "already on"},
      {"G21\nG41 D1\nG1 X0 Y10 F600\nG42 D1 X5\n", "comp.ngc:4:1: G42", "already on"},
      // Not in G19 (LinuxCNC compensates in G17 and G18).
      {"G21\nG19 G41 D1\n", "comp.ngc:2:5: G41", "G17 (XY) and G18 (XZ) planes only"},
      {"G21\nG41 D1\nG19\n", "comp.ngc:3:1: G19", "plane cannot change"},
      // The tool table does not give tool 3.
      {"G21\nG41 D3\n", "comp.ngc:2:5: D3", "tool 3 has no diameter"},
      {"G21\nG41.1 X1\n", "comp.ngc:2:1: G41.1", "need D"},
      {"G21\nG42.1 D4 L3\n", "comp.ngc:2:10: L3", "lathe"},
      // Splines and cycles with compensation on.
      {"G21\nG41 D1\nG1 X0 Y10 F600\nG5.1 X10 Y10 I5 J5\n", "comp.ngc:4:1: G5.1", "splines"},
      {"G21\nG41 D1\nG1 X0 Y10 F600\nG81 X5 Y5 Z-1 R1\n", "comp.ngc:4:1: G81", "canned cycles"},
      {"G21\nG41 D1\nG1 X0 Y10 F600\nG28\n", "comp.ngc:4:1: G28", "G28/G30"},
      // The exit move is an arc.
      {"G21\nG0 X0 Y-10\nG41 D1\nG1 X0 Y0 F600\nY10\nG40\nG2 X10 Y10 I5 J0\n", "comp.ngc:7:1: G2", "exit move"},
      // The entry move does not end farther than the tool radius from the tool (a line or an arc).
      {"G21\nG41 D1\nG1 X1 Y1 F600\nX10\n", "comp.ngc:3:1: G1", "farther than the tool radius"},
      {"G21\nG41 D1\nG2 X1 Y1 I1 J0 F600\nX10\n", "comp.ngc:3:1: G2", "farther than the tool radius"},
  });
}

TEST_CASE("cutter compensation: G41 with the loaded tool and no D", "[gcode][import][compensation]") {
  // T1 M6 loads tool 1 (radius 2): G41 without D uses it.
  const Job job = load("G21 G17\nT1 M6\nG0 X0 Y-10\nG41\nG1 X0 Y0 F600\nY10\nG40\nG1 X0 Y20\n");
  check_path(job, {to(0, -10), to(-2, 0), to(-2, 10), to(0, 20)});
  // No tool loaded (tool 0): no offset.
  check_path(load("G21 G17\nG0 X0 Y-10\nG41\nG1 X0 Y0 F600\nY10\nG40\nG1 X0 Y20\n"), {to(0, -10), to(0, 0), to(0, 10), to(0, 20)});
  // A loaded tool without a diameter.
  const std::string message = message_of("G21\nT2 M6\nG41\n");
  CHECK(message.find("comp.ngc:3:1: G41") != std::string::npos);
  CHECK(message.find("loaded tool") != std::string::npos);
}
