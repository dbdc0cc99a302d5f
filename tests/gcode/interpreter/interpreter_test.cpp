// SPDX-License-Identifier: MIT
// The G-code modal interpreter: motions with hand-computed geometry (LinuxCNC's documented
// formulas), modal state, and every error with the column of the word at fault.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstddef>
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

Point pt(double x, double y, double z = 0) { return Point{{x, y, z}}; }

}  // namespace

TEST_CASE("gcode interpreter: G0 and G1 lines in absolute and incremental distance mode", "[gcode][interpreter]") {
  Machine m;
  auto motion = run(m, {"G0 X10 Y5"});
  CHECK(motion.kind == MotionKind::Rapid);
  CHECK(motion.start == pt(0, 0));
  CHECK(motion.end == pt(10, 5));
  motion = run(m, {"G1 Z-1 F300"});
  CHECK(motion.kind == MotionKind::Line);
  CHECK(motion.end == pt(10, 5, -1));
  CHECK(motion.feed_mm_per_min == 300.0);
  motion = run(m, {"G91 X2 Y-3"});  // modal G1, incremental
  CHECK(motion.kind == MotionKind::Line);
  CHECK(motion.end == pt(12, 2, -1));
  motion = run(m, {"G90 X0"});
  CHECK(motion.end == pt(0, 2, -1));
  motion = run(m, {"X0"});  // no move
  CHECK(motion.kind == MotionKind::None);
}

TEST_CASE("gcode interpreter: G20 multiplies lengths and the feed by 25.4", "[gcode][interpreter]") {
  Machine m;
  auto motion = run(m, {"G20 G1 X1 Y-0.5 F10"});
  CHECK(motion.end == pt(25.4, -12.7));
  CHECK(motion.feed_mm_per_min == 254.0);
  CHECK(m.units() == Units::Inches);
  motion = run(m, {"G21 X1"});  // back to mm; F is read in the units of the motion
  CHECK(motion.end == pt(1, -12.7));
  CHECK(motion.feed_mm_per_min == 10.0);
}

TEST_CASE("gcode interpreter: G2 and G3 centre form with incremental and absolute centres", "[gcode][interpreter]") {
  Machine m;
  auto motion = run(m, {"G0 X10 Y0", "G3 X0 Y10 I-10 J0"});
  CHECK(motion.kind == MotionKind::Arc);
  CHECK(motion.direction == ArcDirection::CounterClockwise);
  CHECK(motion.center == pt(0, 0));
  CHECK(motion.end == pt(0, 10));
  CHECK(motion.full_turns == 0);
  // G90.1: I J are the centre itself.
  motion = run(m, {"G90.1 G2 X10 Y0 I0 J0"});
  CHECK(motion.direction == ArcDirection::Clockwise);
  CHECK(motion.center == pt(0, 0));
  CHECK(m.arc_centers_absolute());
}

TEST_CASE("gcode interpreter: G91 with G91.1 arcs are relative to the start", "[gcode][interpreter]") {
  Machine m;
  const auto motion = run(m, {"G0 X5 Y5", "G91 G91.1", "G2 X10 Y0 I5 J0"});
  CHECK(motion.kind == MotionKind::Arc);
  CHECK(motion.start == pt(5, 5));
  CHECK(motion.end == pt(15, 5));
  CHECK(motion.center == pt(10, 5));
  CHECK(motion.direction == ArcDirection::Clockwise);
}

TEST_CASE("gcode interpreter: the radius form picks the centre by the sign of R", "[gcode][interpreter]") {
  // Chord (0,0)-(6,0), |R| = 5: centre at distance sqrt(25 - 9) = 4 from the chord midpoint (3,0).
  Machine a;
  CHECK(run(a, {"G3 X6 Y0 R5"}).center == pt(3, 4));  // counter-clockwise, short arc: centre left of the chord
  Machine b;
  CHECK(run(b, {"G2 X6 Y0 R5"}).center == pt(3, -4));
  Machine c;
  CHECK(run(c, {"G3 X6 Y0 R-5"}).center == pt(3, -4));  // long arc
  Machine d;
  CHECK(run(d, {"G2 X10 Y0 R5"}).center == pt(5, 0));  // half circle
}

TEST_CASE("gcode interpreter: full circles, extra turns and helical arcs", "[gcode][interpreter]") {
  Machine m;
  auto motion = run(m, {"G0 X10", "G2 X10 Y0 I-10"});
  CHECK(motion.kind == MotionKind::Arc);
  CHECK(motion.start == motion.end);
  CHECK(motion.center == pt(0, 0));
  motion = run(m, {"G3 I-10 Z-3 P3"});  // helix: three turns down 3 mm
  CHECK(motion.kind == MotionKind::Arc);
  CHECK(motion.end == pt(10, 0, -3));
  CHECK(motion.center == pt(0, 0, 0));
  CHECK(motion.full_turns == 2);
  motion = run(m, {"G3 X0 Y10 Z-5 I-10"});
  CHECK(motion.end == pt(0, 10, -5));
}

TEST_CASE("gcode interpreter: arc radius tolerance follows LinuxCNC", "[gcode][interpreter]") {
  // LinuxCNC (rs274ngc interp_internal.hh, interp_arc.cc): t = 2 x 0.01 x sqrt(2) = 0.028284 mm; an
  // arc fails if |r1 - r0| > 100 t (2.8284 mm), or if |r1 - r0| > t and > 0.1 % of max(r0, r1).
  // Within: 0.028 <= t at r0 = 10; 0.09 at r0 = 100 (0.0899 % of 100.09); 2.8 <= 100 t at r0 = 3000.
  Machine a;
  CHECK(run(a, {"G0 X10", "G3 X0 Y10.028 I-10"}).kind == MotionKind::Arc);
  Machine b;
  CHECK(run(b, {"G0 X100", "G3 X0 Y100.09 I-100"}).kind == MotionKind::Arc);
  Machine c;
  CHECK(run(c, {"G0 X3000", "G3 X0 Y3002.8 I-3000"}).kind == MotionKind::Arc);
  // Beyond: 0.03 at r0 = 10 (> t and 0.3 %), 0.11 at r0 = 100 (> t and 0.1099 %), and 2.9 > 100 t at
  // r0 = 3000 although only 0.0966 %.
  auto f = run_failing({"G0 X10", "G3 X0 Y10.03 I-10"});
  CHECK(f.code == Error::GcodeArcRadiusMismatch);
  CHECK(f.index == 1);
  CHECK(run_failing({"G0 X100", "G3 X0 Y100.11 I-100"}).code == Error::GcodeArcRadiusMismatch);
  f = run_failing({"G0 X3000", "G3 X0 Y3002.9 I-3000"});
  CHECK(f.code == Error::GcodeArcRadiusMismatch);
  // Under G20 the tolerance is 2 x 0.001 x sqrt(2) in: 0.0028 in off at r0 = 0.1 in passes, 0.0029 in fails.
  Machine d;
  CHECK(run(d, {"G20 G0 X0.1", "G3 X0 Y0.1028 I-0.1"}).kind == MotionKind::Arc);
  CHECK(run_failing({"G20 G0 X0.1", "G3 X0 Y0.1029 I-0.1"}).code == Error::GcodeArcRadiusMismatch);
  // LinuxCNC's zero-radius arc: a radius below 0.00005 in (0.00127 mm).
  CHECK(run_failing({"G0 X0.001", "G3 X0 Y0.001 I-0.001"}).code == Error::GcodeArcRadiusMismatch);
  // A radius too small to reach the end.
  f = run_failing({"G2 X10 Y0 R4"});
  CHECK(f.code == Error::GcodeArcRadiusMismatch);
  CHECK(f.index == 11);
}

TEST_CASE("gcode interpreter: G5 control points are P0, P0 plus IJ, P1 plus PQ, P1", "[gcode][interpreter][spline]") {
  Machine m;
  const auto motion = run(m, {"G5 I0 J3 P0 Q-3 X1 Y1"});  // LinuxCNC's documentation example
  REQUIRE(motion.kind == MotionKind::Cubic);
  CHECK(motion.control[0] == pt(0, 0));
  CHECK(motion.control[1] == pt(0, 3));
  CHECK(motion.control[2] == pt(1, -2));
  CHECK(motion.control[3] == pt(1, 1));
}

TEST_CASE("gcode interpreter: G5 without I J continues the previous G5's end tangent", "[gcode][interpreter][spline]") {
  // I,J = -(P,Q) of the PREVIOUS G5 (LinuxCNC), not of this block (the grblHAL reading): the second
  // block's own P Q differ, so the two readings give different control points.
  Machine m;
  const auto motion = run(m, {"G5 I0 J3 P-1 Q-2 X1 Y1", "G5 P4 Q5 X2 Y2"});
  REQUIRE(motion.kind == MotionKind::Cubic);
  CHECK(motion.control[0] == pt(1, 1));
  CHECK(motion.control[1] == pt(2, 3));  // (1,1) + (1,2)
  CHECK(motion.control[2] == pt(6, 7));
  CHECK(motion.control[3] == pt(2, 2));
}

TEST_CASE("gcode interpreter: G5 errors as LinuxCNC reports them", "[gcode][interpreter][spline]") {
  auto f = run_failing({"G5 P0 Q1 X1 Y1"});  // first of a series without I J
  CHECK(f.code == Error::GcodeSplineNoTangent);
  CHECK(f.index == 1);
  f = run_failing({"G5 I1 J1 P0 Q1 X1 Y1", "G1 X3", "G5 P0 Q1 X4 Y1"});  // the series was broken by G1
  CHECK(f.code == Error::GcodeSplineNoTangent);
  f = run_failing({"G18", "G5 I1 J1 P0 Q1 X1 Y1"});
  CHECK(f.code == Error::GcodeSplineNotG17);
  CHECK(f.index == 1);
  f = run_failing({"G5 I1 P0 Q1 X1 Y1"});  // I without J
  CHECK(f.code == Error::GcodeMissingWord);
  f = run_failing({"G5 I1 J1 P0 X1 Y1"});  // Q missing
  CHECK(f.code == Error::GcodeMissingWord);
  f = run_failing({"G5 I1 J1 P0 Q1 X1 Y1 Z2"});  // only X and Y may move
  CHECK(f.code == Error::GcodeConflictingWords);
  CHECK(f.index == 22);
}

TEST_CASE("gcode interpreter: G5.1 is the quadratic P0, P0 plus IJ, P1", "[gcode][interpreter][spline]") {
  Machine m;
  const auto motion = run(m, {"G0 X1 Y1", "G5.1 I1 J2 X4 Y1"});
  REQUIRE(motion.kind == MotionKind::Quadratic);
  CHECK(motion.control[0] == pt(1, 1));
  CHECK(motion.control[1] == pt(2, 3));
  CHECK(motion.control[2] == pt(4, 1));
  auto f = run_failing({"G5.1 X4 Y1"});
  CHECK(f.code == Error::GcodeMissingWord);
  // LinuxCNC refuses either offset alone ("Must specify both I and J with G5.1").
  f = run_failing({"G5.1 I1 X4 Y1"});
  CHECK(f.code == Error::GcodeMissingWord);
  f = run_failing({"G5.1 J1 X4 Y1"});
  CHECK(f.code == Error::GcodeMissingWord);
  f = run_failing({"G19 G5.1 I1 X4"});
  CHECK(f.code == Error::GcodeSplineNotG17);
  CHECK(f.index == 5);
}

TEST_CASE("gcode interpreter: a spline whose middle control points sit on its end still moves (fuzz finding)", "[gcode][interpreter][spline]") {
  // Regression of tests/fuzz/regressions/gcode/disconnected_after_g5_1_comment.ngc: from (10, 40),
  // "G5.1 I-10 J0 X0" has P0 = (10, 40), P1 = P0 + (-10, 0) = (0, 40) = P2. The curve runs from
  // (10, 40) to (0, 40), so it is a motion; it used to be reported as None (nothing moves) while the
  // position still advanced, and the importer dropped it, leaving a gap in the job.
  Machine m;
  auto motion = run(m, {"G0 X10 Y40", "G5.1 I-10 J0 X0"});
  REQUIRE(motion.kind == MotionKind::Quadratic);
  CHECK(motion.start == pt(10, 40));
  CHECK(motion.end == pt(0, 40));
  CHECK(motion.control[0] == pt(10, 40));
  CHECK(motion.control[1] == pt(0, 40));
  CHECK(motion.control[2] == pt(0, 40));
  CHECK(m.position() == pt(0, 40));
  // The same for a cubic: P0 = (10, 40), P0 + (I, J) = (0, 40), P1 + (P, Q) = (0, 40), P1 = (0, 40).
  Machine c;
  motion = run(c, {"G0 X10 Y40", "G5 I-10 J0 P0 Q0 X0"});
  REQUIRE(motion.kind == MotionKind::Cubic);
  CHECK(motion.control[0] == pt(10, 40));
  CHECK(motion.control[1] == pt(0, 40));
  CHECK(motion.control[2] == pt(0, 40));
  CHECK(motion.control[3] == pt(0, 40));
  // Only a spline whose every control point is the start moves nothing.
  Machine n;
  motion = run(n, {"G0 X10 Y40", "G5.1 I0 J0 X10 Y40"});
  CHECK(motion.kind == MotionKind::None);
  motion = run(n, {"G5 I0 J0 P0 Q0 X10 Y40"});
  CHECK(motion.kind == MotionKind::None);
}

TEST_CASE("gcode interpreter: a G5.2 G5.3 block collects weighted control points", "[gcode][interpreter][nurbs]") {
  Machine m;
  for (const auto line : {"G0 X0 Y0", "F10", "G5.2 P1 L3", "X0 Y1 P1", "X2 Y2 P1", "X2 Y0 P1"}) {
    CHECK(run(m, {line}).kind == MotionKind::None);
  }
  CHECK(m.in_nurbs_block());
  CHECK(run(m, {"X0 Y0 P2"}).kind == MotionKind::None);
  const auto motion = run(m, {"G5.3"});
  REQUIRE(motion.kind == MotionKind::Nurbs);
  CHECK_FALSE(m.in_nurbs_block());
  CHECK(motion.nurbs_order == 3);
  CHECK(motion.start == pt(0, 0));
  CHECK(motion.end == pt(0, 0));
  const auto points = m.nurbs_points();
  const auto weights = m.nurbs_weights();
  REQUIRE(points.size() == 5);
  CHECK(points[0] == pt(0, 0));
  CHECK(points[1] == pt(0, 1));
  CHECK(points[2] == pt(2, 2));
  CHECK(points[3] == pt(2, 0));
  CHECK(points[4] == pt(0, 0));
  CHECK(weights[0] == 1.0);
  CHECK(weights[4] == 2.0);
  // X Y on the G5.2 line: the current point has weight 1, the G5.2 point the given weight.
  Machine n;
  run(n, {"G0 X1", "G5.2 X2 Y1 P3 L2", "X4 Y0"});
  const auto line = run(n, {"G5.3"});
  REQUIRE(line.kind == MotionKind::Nurbs);
  CHECK(line.nurbs_order == 2);
  REQUIRE(n.nurbs_points().size() == 3);
  CHECK(n.nurbs_weights()[0] == 1.0);
  CHECK(n.nurbs_weights()[1] == 3.0);
  CHECK(n.nurbs_points()[1] == pt(2, 1));
}

TEST_CASE("gcode interpreter: malformed NURBS blocks are GcodeNurbsBlock", "[gcode][interpreter][nurbs]") {
  auto f = run_failing({"G5.3"});
  CHECK(f.code == Error::GcodeNurbsBlock);
  f = run_failing({"G5.2", "X1 Y1", "G1 X2"});
  CHECK(f.code == Error::GcodeNurbsBlock);
  CHECK(f.index == 1);
  f = run_failing({"G5.2", "X1 Y1 L4"});
  CHECK(f.code == Error::GcodeNurbsBlock);
  CHECK(f.index == 7);
  f = run_failing({"G5.2 L4", "X1 Y1", "X2 Y0", "G5.3"});  // order 4 needs 4 control points
  CHECK(f.code == Error::GcodeNurbsBlock);
  f = run_failing({"G5.2 L9"});
  CHECK(f.code == Error::GcodeNurbsBlock);
  CHECK(f.index == 6);
  f = run_failing({"G5.2", "X1 Y1 P0"});
  CHECK(f.code == Error::GcodeNurbsBlock);
  CHECK(f.index == 7);
  f = run_failing({"G5.2", "X1 Y1", "M2"});
  CHECK(f.code == Error::GcodeNurbsBlock);
  f = run_failing({"G5.2", "X1 Y1 Z1"});
  CHECK(f.code == Error::GcodeConflictingWords);
  f = run_failing({"G18 G5.2"});
  CHECK(f.code == Error::GcodeSplineNotG17);
  f = run_failing({"G5.2", "X1 Y1", "X2 Y0", "G5.3", "X3 Y3"});  // no motion mode after G5.3
  CHECK(f.code == Error::GcodeMissingWord);
  CHECK(f.index == 1);
}

TEST_CASE("gcode interpreter: a NURBS block longer than the capacity is refused", "[gcode][interpreter][nurbs]") {
  Interpreter<3> m;
  for (const auto line : {"G5.2", "X1 Y1", "X2 Y1"}) {
    REQUIRE(m.execute(parse_line(line).value()));
  }
  const auto r = m.execute(parse_line("X3 Y1").value());
  REQUIRE_FALSE(r);
  CHECK(r.error() == Error::GcodeNurbsBlock);
}

TEST_CASE("gcode interpreter: unsupported and conflicting words are errors that point at the word", "[gcode][interpreter]") {
  struct Case {
    std::initializer_list<std::string_view> lines;
    Error code;
    std::size_t column;
  };
  const Case cases[] = {
      {{"G33 X1"}, Error::GcodeUnsupportedWord, 1},    // threading
      {{"G1 G81 X1"}, Error::GcodeConflictingWords, 4},  // two motion words
      {{"G1 G84 X1"}, Error::GcodeUnsupportedWord, 4},   // tapping
      {{"M66"}, Error::GcodeUnsupportedWord, 1},       // wait on input
      {{"G1.5 X1"}, Error::GcodeUnsupportedWord, 1},
      {{"G0 G1 X1"}, Error::GcodeConflictingWords, 4},
      {{"G20 G21"}, Error::GcodeConflictingWords, 5},
      {{"X1 Y2"}, Error::GcodeMissingWord, 1},          // no motion mode yet
      {{"G1 X1 I1"}, Error::GcodeConflictingWords, 7},  // I has no use in G1
      {{"G2 X1 Y1 R1 I1"}, Error::GcodeConflictingWords, 10},
      {{"G2 X1 Y1 I1 K1"}, Error::GcodeConflictingWords, 13},
      {{"G2 X1 Y1"}, Error::GcodeMissingWord, 1},       // neither I J nor R
      {{"G2 X0 Y0 R1"}, Error::GcodeMissingWord, 10},   // R cannot describe a full circle
      {{"G2 X0 Y0 I0 J0"}, Error::GcodeArcRadiusMismatch, 1},  // zero radius
      {{"G18", "G2 X1 Z1 I1 J1"}, Error::GcodeConflictingWords, 13},  // J is the G18 normal
      {{"G2 X2 I1 P1.5"}, Error::GcodeBadNumber, 10},
      {{"G1 X40000"}, Error::GcodeBadNumber, 4},        // beyond the Q16.16 range
      {{"G20 G1 X2000"}, Error::GcodeBadNumber, 8},     // 50800 mm
      {{"G91 G1 X30000", "X30000"}, Error::GcodeBadNumber, 1},
      {{"G1 X1 F-5"}, Error::GcodeBadNumber, 7},
  };
  for (const auto& c : cases) {
    INFO(*(c.lines.end() - 1));
    const auto f = run_failing(c.lines);
    CHECK(f.code == c.code);
    CHECK(f.index == c.column);
  }
}

TEST_CASE("gcode interpreter: M2 and M30 end the program", "[gcode][interpreter]") {
  Machine m;
  auto motion = run(m, {"G1 X1 M2"});
  CHECK(motion.kind == MotionKind::Line);
  CHECK(motion.program_end);
  CHECK(m.ended());
  Machine n;
  CHECK(run(n, {"M30"}).program_end);
}

TEST_CASE("gcode interpreter: splines in G91 and G20 use incremental ends and scaled offsets", "[gcode][interpreter][spline]") {
  Machine m;
  auto motion = run(m, {"G0 X1 Y1", "G91 G5 I0 J1 P0 Q-1 X2 Y0"});
  REQUIRE(motion.kind == MotionKind::Cubic);
  CHECK(motion.control[0] == pt(1, 1));
  CHECK(motion.control[1] == pt(1, 2));
  CHECK(motion.control[2] == pt(3, 0));
  CHECK(motion.control[3] == pt(3, 1));
  Machine n;
  motion = run(n, {"G20 G5.1 I1 J2 X4 Y0"});
  REQUIRE(motion.kind == MotionKind::Quadratic);
  CHECK(motion.control[1] == pt(25.4, 50.8));
  CHECK(motion.control[2] == pt(101.6, 0));
  // The continuation offsets were stored in mm: a G21 block continues with -(P,Q) in mm.
  Machine k;
  motion = run(k, {"G20 G5 I0 J1 P0 Q-1 X1 Y1", "G21 G5 P0 Q0 X30 Y30"});
  CHECK(motion.control[1] == pt(25.4, 25.4 + 25.4));
}

TEST_CASE("gcode interpreter: G40 G41 G42 G41.1 G42.1 set the compensation each motion carries", "[gcode][interpreter][compensation]") {
  Machine m;
  m.set_tool_diameter_mm(1, 6.0);
  CHECK(m.tool_diameter_mm(1) == 6.0);
  CHECK(m.tool_diameter_mm(2) < 0);  // not in the table
  auto motion = run(m, {"G41 D1 G1 X10 F100"});
  CHECK(motion.compensation_side == CompensationSide::Left);
  CHECK(motion.compensation_radius_mm == 3.0);
  CHECK(motion.end == pt(10, 0));  // the programmed path: the host offsets it
  motion = run(m, {"G40 X20"});
  CHECK(motion.compensation_side == CompensationSide::Off);
  motion = run(m, {"G20 G42.1 D0.5 X1"});  // diameter in inches
  CHECK(motion.compensation_side == CompensationSide::Right);
  CHECK(motion.compensation_radius_mm == Approx(6.35));
  motion = run(m, {"G40 G21", "G42 D0"});  // D0: no offset
  CHECK(motion.compensation_side == CompensationSide::Right);
  CHECK(motion.compensation_radius_mm == 0.0);
  run(m, {"M2"});
  CHECK(m.compensation_side() == CompensationSide::Off);  // M2 resets to G40
  Machine g18;  // LinuxCNC compensates in G18 too (not G19)
  g18.set_tool_diameter_mm(1, 6.0);
  motion = run(g18, {"G18 G41 D1 G2 X10 Z0 I5 K0 F100"});
  CHECK(motion.compensation_side == CompensationSide::Left);
  CHECK(motion.compensation_radius_mm == 3.0);
  CHECK(motion.plane == Plane::ZX);
}

TEST_CASE("gcode interpreter: a negative G41.1/G42.1 diameter compensates on the other side, as LinuxCNC does",
          "[gcode][interpreter][compensation]") {
  // LinuxCNC's convert_cutter_compensation_on: radius = D / 2; a negative radius switches the side
  // and keeps its size (tests/interp/crazy-paths runs its paths with G41.1 D-.5 and D.5).
  Machine m;
  auto motion = run(m, {"G41.1 D-2", "G1 X10 F100"});
  CHECK(motion.compensation_side == CompensationSide::Right);
  CHECK(motion.compensation_radius_mm == 1.0);
  Machine n;
  motion = run(n, {"G20 G42.1 D-0.5", "G1 X10 F100"});
  CHECK(motion.compensation_side == CompensationSide::Left);
  CHECK(motion.compensation_radius_mm == Approx(6.35));  // 0.25 in
}

TEST_CASE("gcode interpreter: compensation errors at the word at fault", "[gcode][interpreter][compensation]") {
  const struct {
    std::initializer_list<std::string_view> lines;
    Error code;
    std::size_t column;
  } cases[] = {
      {{"G41 D1"}, Error::GcodeCutterCompensation, 5},         // tool 1 has no diameter
      {{"T3 M6", "G42"}, Error::GcodeMissingWord, 1},           // the loaded tool has none either
      {{"G41 D0", "G42 D0"}, Error::GcodeCutterCompensation, 1},  // already on
      {{"G19 G41 D0"}, Error::GcodeUnsupportedWord, 5},         // G17 and G18 only (LinuxCNC)
      {{"G41 D0", "G19"}, Error::GcodeCutterCompensation, 1},   // no plane change while on
      {{"G41.1"}, Error::GcodeMissingWord, 1},
      {{"G41.1 D99999"}, Error::GcodeBadNumber, 7},             // beyond +-32767 mm
      {{"G41.1 D2 L1"}, Error::GcodeCutterCompensation, 10},    // lathe orientation
      {{"G41 D1.5"}, Error::GcodeBadNumber, 5},
      {{"G41 D0", "G5.1 X1 Y1 I1 J0"}, Error::GcodeCutterCompensation, 1},
      {{"G41 D0", "G81 X1 Y1 Z-1 R1"}, Error::GcodeCutterCompensation, 1},
      {{"G41 D0", "G53 G0 X1"}, Error::GcodeCutterCompensation, 1},
      {{"G41 D0", "G30"}, Error::GcodeCutterCompensation, 1},
  };
  for (const auto& c : cases) {
    INFO(*(c.lines.end() - 1));
    const Failure failure = run_failing(c.lines);
    CHECK(failure.code == c.code);
    CHECK(failure.index == c.column);
  }
}

TEST_CASE("gcode interpreter: tool numbers are any whole number up to 99999, the table keyed by number (CAM posts: M6 T102)",
          "[gcode][interpreter][tools]") {
  Machine m;
  REQUIRE(m.set_tool_length_mm(102, 12.5));
  REQUIRE(m.set_tool_diameter_mm(102, 3.175));
  REQUIRE(m.set_tool_length_mm(7, 40.0));
  CHECK(m.tool_length_mm(102) == 12.5);
  CHECK(m.tool_diameter_mm(102) == 3.175);
  CHECK(m.tool_diameter_mm(7) < 0);  // a length alone leaves the diameter unknown
  CHECK(m.tool_length_mm(8) == 0.0);  // not in the table
  // Carbide Create's tool change, then G43 with the loaded tool's length: Z5 is Z 17.5 in machine coordinates.
  auto motion = run(m, {"G21 G90 M6 T102", "G43 G0 Z5"});
  CHECK(m.loaded_tool() == 102);
  CHECK(motion.end == pt(0, 0, 17.5));
  motion = run(m, {"G43 H7 G0 Z5"});
  CHECK(motion.end == pt(0, 0, 45.0));
  motion = run(m, {"G41 D102 G1 X10 F100"});
  CHECK(motion.compensation_radius_mm == 3.175 / 2);
  // Beyond 99999, negative or fractional: a bad number at the word.
  CHECK(run_failing({"T100000"}).code == Error::GcodeBadNumber);
  CHECK(run_failing({"T-1"}).code == Error::GcodeBadNumber);
  CHECK(run_failing({"G43 H1.5"}).code == Error::GcodeBadNumber);
  // The table holds max_tools tools; one more is refused, numbers above 99999 too.
  Machine full;
  for (std::size_t tool = 0; tool < Machine::max_tools; ++tool) REQUIRE(full.set_tool_length_mm(1000 + tool, 1.0));
  CHECK(full.set_tool_length_mm(1000, 2.0));  // an existing tool can still change
  CHECK_FALSE(full.set_tool_length_mm(5, 1.0));
  CHECK_FALSE(m.set_tool_diameter_mm(100000, 1.0));
}

TEST_CASE("gcode interpreter: G10 L2 R0 is no rotation, the offset applies exactly", "[gcode][interpreter]") {
  // Rotations themselves: rotation_test.cpp.
  Machine m;
  CHECK(run(m, {"G10 L2 P1 X5 R0", "G54 G0 X0"}).end == pt(5, 0));
  CHECK(m.rotation_deg(0) == 0);
}
