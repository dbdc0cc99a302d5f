// SPDX-License-Identifier: MIT
// LinuxCNC's coordinate system rotation (G10 L2 P R) in the interpreter. Expected points are worked
// by hand from LinuxCNC's rule (emccanon.cc rotate_and_offset): machine XY = R(program + G92) + work
// offset, R the system's rotation counter-clockwise about Z; Z never turns. Two cases replay
// LinuxCNC's own interpreter tests (tests/interp/g10/g10-with-g92 and g10-l20-while-active) and
// compare with the positions its expected output prints.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>

#include <curvestep/gcode.hpp>

#include "run_lines.hpp"

using namespace curvestep;
using namespace curvestep::gcode;

namespace {

using curvestep::gcode::testing::Machine;
using curvestep::gcode::testing::run;
using curvestep::gcode::testing::run_failing;

constexpr double tolerance = 1e-9;

void check_point(const Point& p, double x, double y, double z = 0, double margin = tolerance) {
  CHECK(p[0] == Approx(x).margin(margin));
  CHECK(p[1] == Approx(y).margin(margin));
  CHECK(p[2] == Approx(z).margin(margin));
}

}  // namespace

TEST_CASE("rotation: G10 L2 R90 turns program X onto machine Y about the system origin", "[gcode][interpreter][rotation]") {
  Machine m;
  // Origin (10, 0), turned 90 degrees: program (1, 0) is one unit along machine +Y from the origin.
  check_point(run(m, {"G21 G90 G10 L2 P1 X10 Y0 R90", "G54 G1 X1 Y0 F100"}).end, 10, 1);
  CHECK(m.rotation_deg(0) == 90);
  // Program (1, 1): R90 (1, 1) = (-1, 1), + (10, 0).
  check_point(run(m, {"G1 Y1"}).end, 9, 1);
  // G91 X1 moves along the turned X axis: machine +Y.
  check_point(run(m, {"G91 G1 X1"}).end, 9, 2);
  // The position in the system (LinuxCNC's #5420, #5421) is program (2, 1).
  check_point(m.program_position(), 2, 1);
  // Z never turns and keeps its offset.
  check_point(run(m, {"G90 G1 Z-2"}).end, 9, 2, -2);
}

TEST_CASE("rotation: an arc turns with its end point and its I J, and keeps its direction", "[gcode][interpreter][rotation]") {
  // Origin (5, 5), R90, start program (10, 0) = machine (5, 15); both arcs turn about program
  // (0, 0) = machine (5, 5). G3 to program (0, 10): R90 (0, 10) = (-10, 0), + (5, 5) = (-5, 5); G2
  // to program (0, -10): R90 (0, -10) = (10, 0), + (5, 5) = (15, 5).
  struct Case {
    std::string_view line;
    ArcDirection direction;
    double end_x, end_y;
  };
  // G91.1: I J are turned offsets from the start; G90.1: they are the centre in program coordinates.
  const Case cases[] = {{"G3 X0 Y10 I-10 J0 F100", ArcDirection::CounterClockwise, -5, 5},
                        {"G90.1 G2 X0 Y-10 I0 J0 F100", ArcDirection::Clockwise, 15, 5}};
  for (const Case& c : cases) {
    INFO(c.line);
    Machine m;
    run(m, {"G21 G90 G10 L2 P1 X5 Y5 R90", "G54 G0 X10 Y0"});
    const Motion arc = run(m, {c.line});
    REQUIRE(arc.kind == MotionKind::Arc);
    CHECK(arc.direction == c.direction);
    check_point(arc.start, 5, 15);
    check_point(arc.center, 5, 5);
    check_point(arc.end, c.end_x, c.end_y);
  }
  SECTION("R form at 45 degrees: the centre is on the turned bisector") {
    // Program: from (0, 0) to (10, 0) with R5 (a half circle), centre program (5, 0). R45 turns
    // (5, 0) to (5/sqrt2, 5/sqrt2) and (10, 0) to (10/sqrt2, 10/sqrt2).
    Machine m;
    run(m, {"G21 G90 G10 L2 P1 R45", "G54 G0 X0 Y0"});
    const Motion arc = run(m, {"G2 X10 Y0 R5 F100"});
    const double h = 5 / std::sqrt(2.0);
    check_point(arc.center, h, h);
    check_point(arc.end, 2 * h, 2 * h);
  }
}

TEST_CASE("rotation: canned-cycle holes and G91 repeats follow the turned axes", "[gcode][interpreter][rotation][cycle]") {
  SECTION("G90: the hole at program (2, 0) of a system at (10, 20) turned 90 degrees is machine (10, 22)") {
    Machine m;
    const Motion cycle = run(m, {"G21 G90 G10 L2 P1 X10 Y20 R90", "G54 G0 X0 Y0 Z5", "G99 G81 X2 Y0 Z-1 R1 F60"});
    REQUIRE(cycle.kind == MotionKind::Cycle);
    check_point(cycle.cycle.first_hole, 10, 22);
    CHECK(cycle.cycle.r_z == Approx(1));
    CHECK(cycle.cycle.bottom_z == Approx(-1));
    check_point(cycle.end, 10, 22, 1);
  }
  SECTION("G91 X2 L3: three holes 2 apart along the turned X axis (machine +Y)") {
    Machine m;
    const Motion cycle = run(m, {"G21 G90 G10 L2 P1 X10 Y20 R90", "G54 G0 X0 Y0 Z5", "G91 G98 G81 X2 Y0 R-4 Z-2 L3 F60"});
    REQUIRE(cycle.kind == MotionKind::Cycle);
    CHECK(cycle.cycle.repeats == 3);
    for (std::uint32_t k = 0; k < 3; ++k) check_point(cycle_hole(cycle.cycle, k), 10, 22 + 2.0 * k);
    check_point(cycle.end, 10, 26, 5);
  }
  SECTION("G90 with Y only: X keeps its program coordinate") {
    // From program (3, 0) (machine (10, 23)), Y4: program (3, 4) -> R90 = (-4, 3), + (10, 20).
    Machine m;
    const Motion cycle = run(m, {"G21 G90 G10 L2 P1 X10 Y20 R90", "G54 G0 X3 Y0 Z5", "G81 Y4 Z-1 R1 F60"});
    check_point(cycle.cycle.first_hole, 6, 23);
  }
}

TEST_CASE("rotation: G92 is added before the rotation, along the turned axes", "[gcode][interpreter][rotation]") {
  // System at (10, 0), R90. At program (0, 0) (machine (10, 0)), G92 X1 makes here program (1, 0),
  // so the program origin lies one unit back along the turned X axis: machine (10, -1). Had G92
  // been added after the rotation (in machine axes), it would be (9, 0).
  Machine m;
  run(m, {"G21 G90 G10 L2 P1 X10 Y0 R90", "G54 G0 X0 Y0", "G92 X1 Y0"});
  check_point(m.program_position(), 1, 0);
  check_point(m.g92_offset(), -1, 0);
  check_point(run(m, {"G1 X0 Y0 F100"}).end, 10, -1);
  check_point(run(m, {"G1 X1 Y0"}).end, 10, 0);
}

TEST_CASE("rotation: LinuxCNC's g10-with-g92 test reports its expected positions", "[gcode][interpreter][rotation]") {
  // tests/interp/g10/g10-with-g92 of LinuxCNC: nine systems at (1,2,3), (4,5,6), ... turned 10, 20,
  // ..., 80, 0 degrees; G0 X0 Y0 Z-10 in G54, G92 X.1 Y.2 Z.3, then #5420-#5422 printed in each
  // system, with G92 and after G92.1. The numbers are those of its expected output.
  Machine m;
  run(m, {"G92.1", "G21"});
  for (int p = 1; p <= 9; ++p) {
    const int base = 3 * (p - 1);
    const int angle = p == 9 ? 0 : 10 * p;
    std::string line = "G10 L2 P" + std::to_string(p) + " X" + std::to_string(base + 1) + " Y" + std::to_string(base + 2) + " Z" +
                       std::to_string(base + 3) + " R" + std::to_string(angle);
    run(m, {std::string_view(line)});
  }
  run(m, {"G54", "G0 X0 Y0 Z-10", "G92 X.1 Y.2 Z.3"});
  check_point(m.g92_offset(), -0.1, -0.2, -10.3, 1e-9);
  constexpr std::array<std::string_view, 9> systems{"G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3"};
  constexpr double with_g92[9][3] = {{0.1, 0.2, 0.3},           {-3.745138, -1.593017, -2.7},  {-8.096152, -1.996152, -5.7},
                                     {-12.579488, -0.909312, -8.7}, {-16.805985, 1.679082, -11.7}, {-20.390381, 5.690381, -14.7},
                                     {-22.970830, 10.958105, -17.7}, {-24.227575, 17.234351, -20.7}, {-23.9, -23.8, -23.7}};
  constexpr double without_g92[9][3] = {{0, 0, -10},         {-3.845138, -1.793017, -13},  {-8.196152, -2.196152, -16},
                                        {-12.679488, -1.109312, -19}, {-16.905985, 1.479082, -22}, {-20.490381, 5.490381, -25},
                                        {-23.070830, 10.758105, -28}, {-24.327575, 17.034351, -31}, {-24, -24, -34}};
  for (std::size_t s = 0; s < systems.size(); ++s) {
    INFO(systems[s]);
    run(m, {systems[s]});
    check_point(m.program_position(), with_g92[s][0], with_g92[s][1], with_g92[s][2], 5e-7);  // LinuxCNC prints 6 decimals
  }
  run(m, {"G54", "G92.1"});
  for (std::size_t s = 0; s < systems.size(); ++s) {
    INFO(systems[s] << " after G92.1");
    run(m, {systems[s]});
    check_point(m.program_position(), without_g92[s][0], without_g92[s][1], without_g92[s][2], 5e-7);
  }
}

TEST_CASE("rotation: G10 L20 while the turned system is active (LinuxCNC's g10-l20-while-active)", "[gcode][interpreter][rotation]") {
  // LinuxCNC's tests/interp/g10/g10-l20-while-active, in inches: its expected output prints the
  // positions ("Should be ...") and the G54 offsets it sets (0.7071 0.7071, then 0 1.4142, then 0 0).
  Machine m;
  const auto program_inches = [&m] { return m.program_position() * (1.0 / millimetres_per_inch); };
  const auto offset_inches = [&m] { return m.work_offset(0) * (1.0 / millimetres_per_inch); };
  run(m, {"G54", "G20", "G10 L2 P1 X0 Y0 Z0 R45", "G0 G53 X0 Y0 Z0"});
  check_point(program_inches(), 0, 0);
  run(m, {"G10 L20 P1 X-1"});
  check_point(program_inches(), -1, 0);
  check_point(offset_inches(), 0.70710678, 0.70710678, 0, 1e-8);
  check_point(run(m, {"G1 X0 F60"}).end * (1.0 / millimetres_per_inch), 0.70710678, 0.70710678, 0, 1e-8);
  check_point(program_inches(), 0, 0);
  run(m, {"G10 L20 P1 Y-1"});
  check_point(program_inches(), 0, -1);
  check_point(offset_inches(), 0, 1.41421356, 0, 1e-8);
  run(m, {"G1 Y0"});
  check_point(program_inches(), 0, 0);
  run(m, {"G10 L20 P1 X1 Y1"});
  check_point(program_inches(), 1, 1);
  check_point(offset_inches(), 0, 0, 0, 1e-12);
  run(m, {"G1 X0 Y0"});
  check_point(program_inches(), 0, 0);
  // Turning the active system back to 0 keeps the machine where it is: still program (0, 0).
  run(m, {"G10 L2 P1 R0"});
  CHECK(m.rotation_deg(0) == 0);
  check_point(program_inches(), 0, 0, 0, 1e-12);
}

TEST_CASE("rotation: changing the active system's rotation mid-program keeps the machine still", "[gcode][interpreter][rotation]") {
  Machine m;
  check_point(run(m, {"G21 G90 G54 G0 X10 Y0"}).end, 10, 0);
  // P0 is the system in use. Machine (10, 0) is program R(-90) (10, 0) = (0, -10) once turned 90.
  const Motion none = run(m, {"G10 L2 P0 R90"});
  CHECK(none.kind == MotionKind::None);
  check_point(m.position(), 10, 0);
  check_point(m.program_position(), 0, -10);
  check_point(run(m, {"G1 X0 Y0 F100"}).end, 0, 0);
  check_point(run(m, {"G1 X10"}).end, 0, 10);
  // Another system's rotation does not touch the one in use.
  run(m, {"G10 L2 P2 R30"});
  check_point(run(m, {"G1 X0 Y10"}).end, -10, 0);
}

TEST_CASE("rotation: G53, G28 and G30 use machine coordinates", "[gcode][interpreter][rotation]") {
  SECTION("G53 is not turned") {
    Machine m;
    check_point(run(m, {"G21 G90 G10 L2 P1 X10 Y0 R90", "G54 G53 G0 X5 Y1"}).end, 5, 1);
  }
  SECTION("G28 with no axis word and with X and Y goes to the stored position") {
    Machine m;
    m.set_home_positions(Point{{1, 2, 3}}, Point{{4, 5, 6}});
    run(m, {"G21 G90 G10 L2 P1 X10 Y0 R90", "G54 G0 X3 Y4 Z0"});
    check_point(run(m, {"G28"}).end, 1, 2, 3);
    // G30 X0 Y0: through program (0, 0) = machine (10, 0), then to the G30 position.
    const Motion g30 = run(m, {"G30 X0 Y0"});
    REQUIRE(g30.has_pre_rapid);
    check_point(g30.pre_rapid, 10, 0, 3);
    check_point(g30.end, 4, 5, 3, 1e-9);
  }
  SECTION("G28 X only keeps the waypoint's program Y (LinuxCNC's convert_home)") {
    // System (10, 0) turned 90; at program (3, 4) = machine (6, 3). G28 X0: waypoint program (0, 4) =
    // machine (6, 0). The stored position (1, 2) is program R(-90) ((1, 2) - (10, 0)) = (2, 9); the
    // end takes its program X and the waypoint's program Y: (2, 4), machine R90 (2, 4) + (10, 0) = (6, 2).
    Machine m;
    m.set_home_positions(Point{{1, 2, 0}}, Point{});
    run(m, {"G21 G90 G10 L2 P1 X10 Y0 R90", "G54 G0 X3 Y4 Z0"});
    const Motion g28 = run(m, {"G28 X0"});
    REQUIRE(g28.has_pre_rapid);
    check_point(g28.pre_rapid, 6, 0);
    check_point(g28.end, 6, 2);
  }
}

TEST_CASE("rotation: spline offsets and polar words turn with the system", "[gcode][interpreter][rotation][polar]") {
  Machine m;
  run(m, {"G21 G90 G10 L2 P1 X10 Y0 R90", "G54 G0 X0 Y0"});
  // G5 from program (0, 0) to (10, 0), I J = (2, 0), P Q = (-2, 0): machine controls (10, 0),
  // (10, 2), (10, 8), (10, 10).
  const Motion cubic = run(m, {"G5 X10 Y0 I2 J0 P-2 Q0 F100"});
  REQUIRE(cubic.kind == MotionKind::Cubic);
  check_point(cubic.control[0], 10, 0);
  check_point(cubic.control[1], 10, 2);
  check_point(cubic.control[2], 10, 8);
  check_point(cubic.control[3], 10, 10);
  // G5.1 back to program (0, 0) through control program (10, 5): machine R90 (10, 5) = (-5, 10), + (10, 0).
  const Motion quadratic = run(m, {"G5.1 X0 Y0 I0 J5"});
  REQUIRE(quadratic.kind == MotionKind::Quadratic);
  check_point(quadratic.control[1], 5, 10);
  check_point(quadratic.end, 10, 0);
  // Polar angles are from the turned X axis: @5 ^0 is program (5, 0), machine (10, 5); ^90 is
  // program (0, 5), machine (5, 0).
  check_point(run(m, {"G1 @5 ^0"}).end, 10, 5);
  check_point(run(m, {"G1 ^90"}).end, 5, 0);
  // A polar canned-cycle hole: @2 ^180 is program (-2, 0), machine (10, -2).
  const Motion cycle = run(m, {"G0 Z5", "G81 @2 ^180 Z-1 R1"});
  check_point(cycle_hole(cycle.cycle, 0), 10, -2);
}

TEST_CASE("rotation: what LinuxCNC refuses, and G18 G19 arcs in a turned system", "[gcode][interpreter][rotation]") {
  // LinuxCNC: "R not allowed in G10 L20" (at the R word).
  Failure f = run_failing({"G10 L20 P1 X0 R45"});
  CHECK(f.code == Error::GcodeUnsupportedWord);
  CHECK(f.index == 15);
  // An arc in G18 would turn in a tilted plane: refused at its G word.
  f = run_failing({"G21 G10 L2 P1 R30", "G54 G18 G0 X0 Y0 Z0", "G2 X10 Z0 R5 F100"});
  CHECK(f.code == Error::GcodeUnsupportedWord);
  CHECK(f.index == 1);
  // LinuxCNC: "Cannot change the active coordinate system with cutter radius compensation on";
  // another system may change.
  f = run_failing({"G21 G90 G41.1 D2 G1 X10 Y0 F100", "G10 L2 P0 R30"});
  CHECK(f.code == Error::GcodeCutterCompensation);
  CHECK(f.index == 1);
  Machine other;
  CHECK(run(other, {"G21 G90 G41.1 D2 G1 X10 Y0 F100", "G10 L2 P2 R30", "G1 X20"}).end[0] == Approx(20));
  // The same arc with R0 runs; a rotated system still runs G18 lines.
  Machine m;
  CHECK(run(m, {"G21 G10 L2 P1 R0", "G54 G18 G0 X0 Y0 Z0", "G2 X10 Z0 R5 F100"}).kind == MotionKind::Arc);
  CHECK(run(m, {"G10 L2 P1 R30", "G1 X1"}).kind == MotionKind::Line);
}

TEST_CASE("rotation: XyRotation turns counter-clockwise about Z and back", "[gcode][interpreter][rotation]") {
  const XyRotation quarter(90);
  check_point(quarter.turned(Point{{1, 0, 7}}), 0, 1, 7);
  check_point(quarter.turned(Point{{0, 1, 0}}), -1, 0);
  // 30 degrees: (2, 0) -> (2 cos30, 2 sin30) = (1.7320508, 1); turned_back undoes it.
  const XyRotation thirty(30);
  check_point(thirty.turned(Point{{2, 0, 0}}), 1.7320508075688772, 1);
  check_point(thirty.turned_back(thirty.turned(Point{{3, -4, 5}})), 3, -4, 5);
  // No angle: the point itself, bit for bit.
  const Point p{{0.1, 0.2, 0.3}};
  CHECK(XyRotation(0).turned(p) == p);
  CHECK(XyRotation{}.turned_back(p) == p);
  CHECK(XyRotation(0).none());
  CHECK_FALSE(thirty.none());
}
