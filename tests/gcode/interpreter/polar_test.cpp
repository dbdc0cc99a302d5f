// SPDX-License-Identifier: MIT
// LinuxCNC's polar coordinates (@ distance, ^ angle in degrees) in the interpreter. Expected end
// points are worked by hand from the LinuxCNC G-code reference ("Polar Coordinates"): the distance
// and angle are about the XY origin of the coordinate system in force, the angle counter-clockwise
// from +X; G90 replaces them, G91 adds to the current point's. Its two examples (the spiral and the
// square) and its errors are checked as the reference states them.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string_view>

#include <curvestep/gcode.hpp>

#include "run_lines.hpp"

using namespace curvestep;
using namespace curvestep::gcode;

namespace {

using curvestep::gcode::testing::Machine;
using curvestep::gcode::testing::run;
using curvestep::gcode::testing::run_failing;

void check_end(const Motion& motion, double x, double y, double z = 0) {
  CHECK(motion.end[0] == Approx(x).margin(1e-9));
  CHECK(motion.end[1] == Approx(y).margin(1e-9));
  CHECK(motion.end[2] == Approx(z).margin(1e-9));
}

constexpr double sqrt3_half = 0.86602540378443864676;  // cos 30 = sin 60

}  // namespace

TEST_CASE("polar: G90 @ ^ end points about the origin", "[gcode][interpreter][polar]") {
  Machine m;
  // 10 at 30 degrees: (10 cos 30, 10 sin 30) = (8.660254, 5).
  auto motion = run(m, {"G21 G90 G1 @10 ^30 F100"});
  CHECK(motion.kind == MotionKind::Line);
  check_end(motion, 10 * sqrt3_half, 5);
  // The reference: "G1 @1^90 is the same as G1 Y1".
  check_end(run(m, {"G1 @1^90"}), 0, 1);
  // @ alone keeps the current angle: from (3, 4) (angle atan2(4, 3)) at distance 10: (6, 8).
  check_end(run(m, {"G0 X3 Y4", "G1 @10"}), 6, 8);
  // ^ alone keeps the current distance 10: at 180 degrees, (-10, 0); Z moves with it.
  check_end(run(m, {"G1 ^180 Z-1"}), -10, 0, -1);
  // A negative angle turns clockwise: 2 at -90 degrees is (0, -2); G0 takes polar words too.
  motion = run(m, {"G0 @2 ^-90"});
  CHECK(motion.kind == MotionKind::Rapid);
  check_end(motion, 0, -2, -1);
}

TEST_CASE("polar: a hexagon drawn with G90 angles only", "[gcode][interpreter][polar]") {
  // Vertices of the regular hexagon of circumradius 10: (10 cos k60, 10 sin k60).
  Machine m;
  check_end(run(m, {"G21 G90 G0 @10 ^0"}), 10, 0);
  const double h = 10 * sqrt3_half;
  const double expected[6][2] = {{5, h}, {-5, h}, {-10, 0}, {-5, -h}, {5, -h}, {10, 0}};
  const char* lines[6] = {"G1 ^60 F300", "^120", "^180", "^240", "^300", "^360"};
  for (std::size_t k = 0; k < 6; ++k) {
    INFO(lines[k]);
    const Motion side = run(m, {lines[k]});
    CHECK(side.kind == MotionKind::Line);
    check_end(side, expected[k][0], expected[k][1]);
    // Every side of the hexagon is as long as its circumradius.
    CHECK(std::hypot(side.end[0] - side.start[0], side.end[1] - side.start[1]) == Approx(10).margin(1e-9));
  }
}

TEST_CASE("polar: G91 adds to the distance and angle about the origin (the reference's spiral and square)", "[gcode][interpreter][polar]") {
  SECTION("F100 G1 @.5 ^90 then G91 @.5 ^90 four times: a spiral") {
    // Distance 0.5, 1, 1.5, 2, 2.5 at 90, 180, 270, 360, 450 degrees.
    Machine m;
    check_end(run(m, {"F100 G1 @.5 ^90"}), 0, 0.5);
    check_end(run(m, {"G91 @.5 ^90"}), -1, 0);
    check_end(run(m, {"@.5 ^90"}), 0, -1.5);
    check_end(run(m, {"@.5 ^90"}), 2, 0);
    check_end(run(m, {"@.5 ^90"}), 0, 2.5);
  }
  SECTION("F100 G1 @.5 ^90 then G91 ^90 four times: a square") {
    Machine m;
    check_end(run(m, {"F100 G1 @.5 ^90"}), 0, 0.5);
    check_end(run(m, {"G91 ^90"}), -0.5, 0);
    check_end(run(m, {"^90"}), 0, -0.5);
    check_end(run(m, {"^90"}), 0.5, 0);
    check_end(run(m, {"^90"}), 0, 0.5);
  }
  SECTION("G91 @ alone moves along the ray from the origin, not from the current point") {
    // From (3, 4) (distance 5): 5 + 5 = 10 on the same ray, (6, 8); Z is incremental as usual.
    Machine m;
    check_end(run(m, {"G90 G0 X3 Y4 Z1", "G91 G1 @5 Z1 F100"}), 6, 8, 2);
  }
}

TEST_CASE("polar: the origin is that of the coordinate system in force, and G20 scales @ only", "[gcode][interpreter][polar]") {
  Machine m;
  // G54 at machine (100, 50): @10 ^90 is program (0, 10), machine (100, 60).
  check_end(run(m, {"G21 G90 G10 L2 P1 X100 Y50", "G54 G1 @10 ^90 F100"}), 100, 60);
  // G91 ^90 from program (10, 0) turns about the G54 origin: program (0, 10) again.
  check_end(run(m, {"G1 X10 Y0", "G91 ^90"}), 100, 60);
  // Inches: @1 is 25.4 mm; ^ stays in degrees.
  check_end(run(m, {"G90 G20 G1 @1 ^0"}), 100 + 25.4, 50);
}

TEST_CASE("polar: a G3 arc to a polar end point", "[gcode][interpreter][polar]") {
  // From (10, 0) counter-clockwise about the origin (I-10 J0) to 10 at 90 degrees: (0, 10).
  Machine m;
  const Motion arc = run(m, {"G21 G90 G0 X10 Y0", "G3 @10 ^90 I-10 J0 F100"});
  CHECK(arc.kind == MotionKind::Arc);
  check_end(arc, 0, 10);
  CHECK(arc.center[0] == Approx(0).margin(1e-9));
  CHECK(arc.center[1] == Approx(0).margin(1e-9));
}

TEST_CASE("polar: the reference's errors and this controller's limits, at the polar word", "[gcode][interpreter][polar]") {
  // "A mix of Polar and X or Y words": named at the first polar word.
  auto f = run_failing({"G1 X1 @10 ^30 F100"});
  CHECK(f.code == Error::GcodeConflictingWords);
  CHECK(f.index == 7);
  f = run_failing({"G1 @10 Y1 F100"});
  CHECK(f.code == Error::GcodeConflictingWords);
  CHECK(f.index == 4);
  // "An incremental move is started at the origin".
  f = run_failing({"G91 G1 ^90 F100"});
  CHECK(f.code == Error::GcodeMissingWord);
  CHECK(f.index == 8);
  // LinuxCNC: "Must specify angle in polar coordinate if at the origin".
  f = run_failing({"G90 G1 @5 F100"});
  CHECK(f.code == Error::GcodeMissingWord);
  CHECK(f.index == 8);
  // LinuxCNC: "Cannot use polar coordinate except in G17 plane".
  f = run_failing({"G18 G1 @10 ^30 F100"});
  CHECK(f.code == Error::GcodeUnsupportedWord);
  CHECK(f.index == 8);
  // LinuxCNC: "Polar coordinates can only be used for motion", "Cannot use polar coordinates with G53".
  f = run_failing({"G92 @1 ^0"});
  CHECK(f.code == Error::GcodeConflictingWords);
  CHECK(f.index == 5);
  f = run_failing({"G0 X5", "G28 @1 ^0"});
  CHECK(f.code == Error::GcodeConflictingWords);
  CHECK(f.index == 5);
  f = run_failing({"G53 G0 @1 ^0"});
  CHECK(f.code == Error::GcodeConflictingWords);
  CHECK(f.index == 8);
  f = run_failing({"G80 @1 ^0"});
  CHECK(f.code == Error::GcodeConflictingWords);
  CHECK(f.index == 5);
  // No motion mode yet: the polar word is an axis word without a G code that uses it.
  f = run_failing({"@1 ^0"});
  CHECK(f.code == Error::GcodeMissingWord);
  CHECK(f.index == 1);
  // Canned cycles: X or Y with polar words; G91 polar holes from the origin (LinuxCNC: "Incremental
  // motion with polar coordinates is indeterminate when at the origin").
  f = run_failing({"G0 Z5", "G81 @10 X1 Z-1 R1 F100"});
  CHECK(f.code == Error::GcodeConflictingWords);
  CHECK(f.index == 5);
  f = run_failing({"G0 Z5", "G91 G81 @1 ^33 R1 Z-1 L5 F100"});
  CHECK(f.code == Error::GcodeMissingWord);
  CHECK(f.index == 9);
  // LinuxCNC adds a G5.2 control point only for X and Y together: polar words are refused there.
  f = run_failing({"G0 X1", "G5.2 @1 ^0 P1"});
  CHECK(f.code == Error::GcodeNurbsBlock);
  CHECK(f.index == 6);
  f = run_failing({"G0 X1", "G5.2 X2 Y0", "@1 ^90"});
  CHECK(f.code == Error::GcodeNurbsBlock);
  CHECK(f.index == 1);
}

TEST_CASE("polar: G5 and G5.1 take their end point from @ ^ (LinuxCNC's find_ends)", "[gcode][interpreter][polar]") {
  Machine m;
  run(m, {"G21 G90 G0 X0 Y0"});
  // End (0, 10); I J and P Q stay offsets from the start and end: controls (0, 2) and (0, 8).
  const Motion cubic = run(m, {"G5 @10 ^90 I0 J2 P0 Q-2 F100"});
  REQUIRE(cubic.kind == MotionKind::Cubic);
  check_end(cubic, 0, 10);
  CHECK(cubic.control[1][1] == Approx(2).margin(1e-9));
  CHECK(cubic.control[2][1] == Approx(8).margin(1e-9));
  // G91 ^-90 turns the end (0, 10) about the origin to (10, 0); the control stays an offset.
  const Motion quadratic = run(m, {"G91 G5.1 ^-90 I5 J0"});
  REQUIRE(quadratic.kind == MotionKind::Quadratic);
  check_end(quadratic, 10, 0);
  CHECK(quadratic.control[1][0] == Approx(5).margin(1e-9));
  CHECK(quadratic.control[1][1] == Approx(10).margin(1e-9));
  // Polar words with X or Y on a spline: LinuxCNC's "Cannot specify X or Y words with polar coordinate".
  Failure f = run_failing({"G0 X1", "G5.1 X2 @1 I1 J0 F100"});
  CHECK(f.code == Error::GcodeConflictingWords);
  CHECK(f.index == 9);
}

TEST_CASE("polar: canned-cycle holes, G90 at @ ^ and G91 turning per repeat", "[gcode][interpreter][polar][cycle]") {
  SECTION("LinuxCNC's hole-circle sample: G91 G81 ^60 L6 from X1.5 (inches)") {
    // Six holes 1.5 in = 38.1 mm from the origin at 60, 120, ..., 360 degrees; R .1 above the start
    // Z 0 (2.54 mm), Z -.5 below R (2.54 - 12.7 = -10.16 mm).
    Machine m;
    const Motion cycle = run(m, {"G20 G17 G90", "G0 X1.5 Y0 Z0", "G91 G81 R.1 Z-.5 ^60 L6 F10"});
    REQUIRE(cycle.kind == MotionKind::Cycle);
    CHECK(cycle.cycle.repeats == 6);
    CHECK(cycle.cycle.r_z == Approx(2.54));
    CHECK(cycle.cycle.bottom_z == Approx(-10.16));
    const double r = 38.1;
    const double expected[6][2] = {{r / 2, r * sqrt3_half}, {-r / 2, r * sqrt3_half}, {-r, 0},
                                   {-r / 2, -r * sqrt3_half}, {r / 2, -r * sqrt3_half}, {r, 0}};
    for (std::uint32_t k = 0; k < 6; ++k) {
      INFO("hole " << k);
      const CyclePoint hole = cycle_hole(cycle.cycle, k);
      CHECK(hole[0] == Approx(expected[k][0]).margin(1e-9));
      CHECK(hole[1] == Approx(expected[k][1]).margin(1e-9));
    }
    // The tool ends over the last hole at the clear level (G98: the start Z 0 is below R, so R).
    check_end(cycle, r, 0, 2.54);
  }
  SECTION("LinuxCNC's polar sample: G90 G81 @2.5^120 (inches) about a G54 origin") {
    // 2.5 in = 63.5 mm at 120 degrees: (-31.75, 63.5 sin 120) = (-31.75, 54.992613) plus (10, 20).
    Machine m;
    const Motion cycle = run(m, {"G21 G90 G10 L2 P1 X10 Y20", "G20 G54 G0 X0 Y0 Z0", "G81 @2.5^120 R.1 Z-0.5 F60"});
    REQUIRE(cycle.kind == MotionKind::Cycle);
    check_end(cycle, 10 - 31.75, 20 + 63.5 * sqrt3_half, 2.54);
  }
}

TEST_CASE("polar: the line parser reads @ and ^ as words with their columns", "[gcode][parser][polar]") {
  const auto block = parse_line("G1 @10 ^-30.5");
  REQUIRE(block);
  const Word* distance = block.value().find('@');
  const Word* angle = block.value().find('^');
  REQUIRE(distance != nullptr);
  REQUIRE(angle != nullptr);
  CHECK(distance->value == 10);
  CHECK(distance->column == 4);
  CHECK(angle->value == -30.5);
  CHECK(angle->column == 8);
  const auto twice = parse_line("G1 @1 @2");
  REQUIRE_FALSE(twice);
  CHECK(twice.failure().code == Error::GcodeConflictingWords);
  CHECK(twice.failure().index == 7);
}
