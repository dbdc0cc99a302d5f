// SPDX-License-Identifier: MIT
// G43.1 dynamic tool length offset (LinuxCNC's G-code reference and convert_tool_length_offset):
// Z replaces the offset in force, G49 cancels, G43 H replaces it; with G91, G92, G53 and arcs; errors.
// Positions are machine coordinates, computed by hand: program Z + G92 offset + tool length.
#include <catch2/catch.hpp>

#include <curvestep/gcode.hpp>

#include "run_lines.hpp"

using namespace curvestep;
using namespace curvestep::gcode;

namespace {

using curvestep::gcode::testing::Machine;
using curvestep::gcode::testing::run;
using curvestep::gcode::testing::run_failing;

Point pt(double x, double y, double z) { return Point{{x, y, z}}; }

}  // namespace

TEST_CASE("gcode tool length: G43.1 Z replaces the offset, G91 does not apply, G49 and G43 H replace it", "[gcode][interpreter][tools]") {
  Machine m;
  REQUIRE(m.set_tool_length_mm(3, 7.0));
  auto motion = run(m, {"G21 G90 G0 X0 Y0 Z10", "G43.1 Z2.5"});
  CHECK(motion.kind == MotionKind::None);  // G43.1 moves nothing
  CHECK(m.tool_length_offset_mm() == 2.5);
  CHECK(m.program_position()[2] == 7.5);  // the tool tip is 2.5 lower than the spindle
  CHECK(run(m, {"G0 Z0"}).end == pt(0, 0, 2.5));
  // G91: the value still replaces the offset (not added), and incremental moves are not shifted.
  run(m, {"G91 G43.1 Z1", "G43.1 Z1"});
  CHECK(m.tool_length_offset_mm() == 1.0);
  CHECK(run(m, {"G0 Z1"}).end == pt(0, 0, 3.5));
  CHECK(run(m, {"G90 G0 Z1"}).end == pt(0, 0, 2.0));
  // In the program's units: 0.1 in is 2.54 mm.
  run(m, {"G20 G43.1 Z0.1"});
  CHECK(m.tool_length_offset_mm() == Approx(2.54).epsilon(1e-15));
  CHECK(run(m, {"G0 Z0", "G21"}).end == pt(0, 0, 2.54));
  // G43 H replaces a G43.1 offset, G49 cancels it, G43.1 without Z keeps it.
  CHECK(run(m, {"G43.1 Z2", "G43 H3", "G0 Z1"}).end == pt(0, 0, 8));
  CHECK(run(m, {"G43.1 Z2", "G49", "G0 Z1"}).end == pt(0, 0, 1));
  CHECK(run(m, {"G43.1 Z4", "G43.1", "G0 Z1"}).end == pt(0, 0, 5));
  // With a motion mode in force the Z is G43.1's: no move.
  motion = run(m, {"G1 X1 F100", "G43.1 Z5"});
  CHECK(motion.kind == MotionKind::None);
  CHECK(m.position() == pt(1, 0, 5));
}

TEST_CASE("gcode tool length: G43.1 with G92, G53 and arcs", "[gcode][interpreter][tools]") {
  Machine m;
  run(m, {"G21 G90 G0 X0 Y0 Z10", "G92 Z0"});  // the G92 offset: 10
  run(m, {"G43.1 Z2"});
  CHECK(m.program_position()[2] == -2.0);  // 10 - 10 - 2: the G92 offset is not recomputed
  CHECK(run(m, {"G0 Z0"}).end == pt(0, 0, 12));
  CHECK(run(m, {"G53 G0 Z1"}).end == pt(0, 0, 1));  // G53: machine coordinates, no tool length
  // A helix's end height carries the offset; its centre lies at the start's height.
  auto motion = run(m, {"G92.1", "G0 X10 Y0 Z0", "G3 X-10 Y0 I-10 J0 Z1 F100"});
  CHECK(motion.start == pt(10, 0, 2));
  CHECK(motion.end == pt(-10, 0, 3));
  CHECK(motion.center == pt(0, 0, 2));
  // G18 with absolute centres (G90.1): the centre's Z (K) is shifted by the offset like any Z.
  motion = run(m, {"G18 G90.1 G0 X0 Z10", "G2 X10 Z0 I0 K0"});
  CHECK(motion.start == pt(0, 0, 12));
  CHECK(motion.end == pt(10, 0, 2));
  CHECK(motion.center == pt(0, 0, 2));
}

TEST_CASE("gcode tool length: G43.1 errors name the word", "[gcode][interpreter][tools]") {
  struct Case {
    std::initializer_list<std::string_view> lines;
    Error code;
    std::size_t column;
  };
  const Case cases[] = {
      {{"G43.1 X1"}, Error::GcodeUnsupportedWord, 7},  // a 3-axis machine: Z only
      {{"G43.1 Z1 Y1"}, Error::GcodeUnsupportedWord, 10},
      {{"G1 G43.1 Z1 F100"}, Error::GcodeConflictingWords, 1},  // no motion on the line (LinuxCNC)
      {{"G43.1 G0 Z1"}, Error::GcodeConflictingWords, 7},
      {{"G43.1 G92 Z1"}, Error::GcodeConflictingWords, 7},  // both would use the axis words
      {{"G43.1 Z40000"}, Error::GcodeBadNumber, 7},
      {{"G41.1 D2 G0 X10", "G43.1 Z1"}, Error::GcodeCutterCompensation, 1},  // not while compensating
      {{"G41.1 D2 G0 X10", "G49"}, Error::GcodeCutterCompensation, 1},
      {{"G41.1 D2 G0 X10", "G43 H1"}, Error::GcodeCutterCompensation, 1},
  };
  for (const auto& c : cases) {
    INFO(*(c.lines.end() - 1));
    const Failure f = run_failing(c.lines);
    CHECK(f.code == c.code);
    CHECK(f.index == c.column);
  }
  Machine m;
  run(m, {"G41.1 D2 G0 X10", "G40 G49 G0 X20"});  // G40 first on the same line: allowed
}
