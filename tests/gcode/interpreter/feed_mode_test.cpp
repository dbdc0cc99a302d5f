// SPDX-License-Identifier: MIT
// G93 inverse-time and G94 units-per-minute feed (LinuxCNC's G-code reference, "G93, G94, G95 Feed
// Rate Mode", and interp_inverse.cc): feeds from hand-computed lengths, the missing-F errors, what
// G94 after G93 leaves, and what G93 refuses.
#include <catch2/catch.hpp>

#include <cmath>
#include <initializer_list>
#include <numbers>
#include <string_view>

#include <curvestep/gcode.hpp>

#include "run_lines.hpp"

using namespace curvestep;
using namespace curvestep::gcode;

namespace {

using curvestep::gcode::testing::Machine;
using curvestep::gcode::testing::run;
using curvestep::gcode::testing::run_failing;

constexpr double pi = std::numbers::pi;

/// Runs `lines` on a new machine; the last must fail; returns its failure and why it was refused for its feed.
struct Refused {
  Failure failure;
  FeedRefusal why = FeedRefusal::None;
};
Refused refused(std::initializer_list<std::string_view> lines) {
  Machine m;
  const Failure failure = run_failing(m, lines);
  return {failure, m.refused_feed()};
}

}  // namespace

TEST_CASE("gcode feed mode: a G93 line takes 1/F minutes, its feed is its length times F", "[gcode][interpreter][feed]") {
  Machine m;
  CHECK(m.feed_mode() == FeedMode::UnitsPerMinute);
  auto motion = run(m, {"G21 G90 G0 X0 Y0", "G93 G1 X30 Y40 F2"});  // 50 mm in half a minute
  CHECK(m.feed_mode() == FeedMode::InverseTime);
  CHECK(motion.kind == MotionKind::Line);
  CHECK(motion.feed_mm_per_min == 100.0);
  CHECK(motion.feed_given);
  motion = run(m, {"X30 Y0 F0.5"});  // 40 mm in two minutes
  CHECK(motion.feed_mm_per_min == 20.0);
  motion = run(m, {"G91 Z-3 F10"});  // 3 mm in 6 s
  CHECK(motion.feed_mm_per_min == 30.0);
  // G0 is not affected: no F needed.
  motion = run(m, {"G90 G0 X0 Y0 Z0"});
  CHECK(motion.kind == MotionKind::Rapid);
  // Inches: the length in mm, so the feed in mm/min: 1 in at F2 is 50.8 mm/min.
  motion = run(m, {"G20 G1 X1 F2"});
  CHECK(motion.feed_mm_per_min == 25.4 * 2);
}

TEST_CASE("gcode feed mode: a G93 arc's feed is its exact arc or helix length times F", "[gcode][interpreter][feed]") {
  Machine m;
  // Half a circle of radius 10 at F3: 10π mm in 20 s, 30π mm/min.
  auto motion = run(m, {"G21 G90 G0 X10 Y0", "G93 G3 X-10 Y0 I-10 J0 F3"});
  REQUIRE(motion.kind == MotionKind::Arc);
  CHECK(motion.feed_mm_per_min == Approx(30 * pi).epsilon(1e-14));
  // A whole circle (end = start) at F1: 20π.
  motion = run(m, {"G3 X-10 Y0 I10 J0 F1"});
  CHECK(motion.feed_mm_per_min == Approx(20 * pi).epsilon(1e-14));
  // A clockwise quarter from (−10, 0) about (0, 0) to (0, 10), falling 5 mm: hypot(10·π/2, 5).
  motion = run(m, {"G2 X0 Y10 Z-5 I10 J0 F1"});
  CHECK(motion.feed_mm_per_min == Approx(std::hypot(5 * pi, 5.0)).epsilon(1e-14));
  // P2: the quarter counter-clockwise from (0, 10) to (−10, 0) plus one whole turn, 10·(π/2 + 2π).
  motion = run(m, {"G3 X-10 Y0 I0 J-10 P2 F1"});
  CHECK(motion.feed_mm_per_min == Approx(10 * 2.5 * pi).epsilon(1e-14));
  // G18: half a circle of radius 10 in Z-X rising 4 in Y (the helix axis): hypot(10π, 4) at F0.5.
  motion = run(m, {"G18 G0 X0 Y0 Z10", "G93 G2 X0 Z-10 Y4 I0 K-10 F0.5"});
  CHECK(motion.plane == Plane::ZX);
  CHECK(motion.feed_mm_per_min == Approx(std::hypot(10 * pi, 4.0) * 0.5).epsilon(1e-14));
  // Inches: a half circle of radius 1 in at F1 is π in a minute, 25.4π mm/min.
  motion = run(m, {"G17 G20 G0 X1 Y0", "G3 X-1 Y0 I-1 J0 F1"});
  CHECK(motion.feed_mm_per_min == Approx(25.4 * pi).epsilon(1e-14));
}

TEST_CASE("gcode feed mode: a G93 feed is at least LinuxCNC's 0.1 units per minute", "[gcode][interpreter][feed]") {
  Machine m;
  auto motion = run(m, {"G21 G93 G1 X0.01 F1"});  // 0.01 mm/min -> 0.1 mm/min
  CHECK(motion.feed_mm_per_min == 0.1);
  motion = run(m, {"X0.02 F0"});  // F0: LinuxCNC's MAX(0.1, 0)
  CHECK(motion.feed_mm_per_min == 0.1);
  motion = run(m, {"G20 X0.001 F1"});  // 0.0054 mm at F1 -> 0.1 in/min = 2.54 mm/min
  CHECK(motion.feed_mm_per_min == Approx(2.54).epsilon(1e-15));
}

TEST_CASE("gcode feed mode: in G93 every G1 G2 G3 needs its own F, an F elsewhere is ignored", "[gcode][interpreter][feed]") {
  // The column: the motion's G word, or its first axis word on a modal line.
  auto r = refused({"G93 G1 X1"});
  CHECK(r.failure.code == Error::GcodeMissingWord);
  CHECK(r.failure.index == 5);
  CHECK(r.why == FeedRefusal::InverseTimeWithoutF);
  r = refused({"G93 G1 X1 F1", "X2"});  // F is not modal in G93
  CHECK(r.failure.index == 1);
  CHECK(r.why == FeedRefusal::InverseTimeWithoutF);
  r = refused({"G93 G1 X1 F1", "F100", "Y2"});  // an F without a move is ignored
  CHECK(r.failure.index == 1);
  CHECK(r.why == FeedRefusal::InverseTimeWithoutF);
  r = refused({"G0 X10", "G93", "G2 X0 Y10 I-10 J0"});
  CHECK(r.failure.code == Error::GcodeMissingWord);
  CHECK(r.failure.index == 1);
  CHECK(r.why == FeedRefusal::InverseTimeWithoutF);
  r = refused({"G1 X1 F600", "G93 G3 X0 Y0 R1"});  // a G94 feed does not carry into G93
  CHECK(r.why == FeedRefusal::InverseTimeWithoutF);
  // A motion mode alone moves nothing and needs no F; so does G0.
  Machine m;
  CHECK(run(m, {"G93 G1", "G0 X5"}).kind == MotionKind::Rapid);
}

TEST_CASE("gcode feed mode: G94 after G93 leaves no feed in force until a new F (LinuxCNC)", "[gcode][interpreter][feed]") {
  auto r = refused({"G1 X1 F600", "G93", "G1 X2 F1", "G94", "G1 X3"});
  CHECK(r.failure.code == Error::GcodeMissingWord);
  CHECK(r.failure.index == 1);
  CHECK(r.why == FeedRefusal::NoFeedAfterG94);
  r = refused({"G93 G1 X1 F1", "G94 X2"});  // the modal G1, the same line as G94
  CHECK(r.failure.index == 5);
  CHECK(r.why == FeedRefusal::NoFeedAfterG94);
  r = refused({"G93", "G94", "G5.1 I1 J0 X2 Y0"});  // splines and cycles feed too
  CHECK(r.why == FeedRefusal::NoFeedAfterG94);
  r = refused({"G93", "G94", "G81 X1 Y1 Z-1 R1"});
  CHECK(r.why == FeedRefusal::NoFeedAfterG94);
  Machine m;
  auto motion = run(m, {"G1 X1 F600", "G93 G1 X2 F1", "G94 G1 X4 F300"});  // F on the G94 line
  CHECK(m.feed_mode() == FeedMode::UnitsPerMinute);
  CHECK(motion.feed_mm_per_min == 300.0);
  motion = run(m, {"G93", "G94", "G0 X0", "F200", "G1 X5"});  // a rapid needs none; F on its own line counts
  CHECK(motion.feed_mm_per_min == 200.0);
  // G94 while already in G94 keeps the feed (LinuxCNC clears it there too: a documented difference).
  motion = run(m, {"G94", "G1 X6"});
  CHECK(motion.feed_mm_per_min == 200.0);
  // M2 returns to G94.
  Machine ended;
  run(ended, {"G93", "M2"});
  CHECK(ended.feed_mode() == FeedMode::UnitsPerMinute);
}

TEST_CASE("gcode feed mode: G93 refuses splines and canned cycles", "[gcode][interpreter][feed]") {
  auto r = refused({"G93 G5 I1 J0 P-1 Q0 X2 Y0 F1"});
  CHECK(r.failure.code == Error::GcodeUnsupportedWord);
  CHECK(r.failure.index == 5);
  CHECK(r.why == FeedRefusal::SplineInInverseTime);
  r = refused({"G93 G5.1 I1 J0 X2 Y0 F1"});
  CHECK(r.why == FeedRefusal::SplineInInverseTime);
  r = refused({"G93 G5.2 X1 Y1 F1"});
  CHECK(r.why == FeedRefusal::SplineInInverseTime);
  r = refused({"G93 G5.2 P1"});
  CHECK(r.why == FeedRefusal::SplineInInverseTime);
  r = refused({"G5.2 X1 Y1", "G93", "X2 Y0", "X3 Y1", "G5.3"});  // G93 inside the block: refused at G5.3
  CHECK(r.failure.code == Error::GcodeUnsupportedWord);
  CHECK(r.failure.index == 1);
  CHECK(r.why == FeedRefusal::SplineInInverseTime);
  r = refused({"G93 G81 X1 Y1 Z-1 R1 F1"});
  CHECK(r.failure.code == Error::GcodeCannedCycle);
  CHECK(r.failure.index == 5);
  CHECK(r.why == FeedRefusal::CycleInInverseTime);
  // Refusals that are not about the feed leave refused_feed() at None.
  CHECK(refused({"G93 G1 X1 F1", "G2 X1 Y1 F1"}).why == FeedRefusal::None);
}
