// SPDX-License-Identifier: MIT
// Arcs in every plane and LinuxCNC's radius tolerance in both unit systems (issue 17.1, 17.4).
// G18 turns in Z-X (K, I), G19 in Y-Z (J, K), counter-clockwise seen from the positive normal (Y,
// X); the importer makes them rational quadratic pieces. Expected points are hand-worked circle
// points; the samples are checked against the circle equation and the helix's linear rise.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <curvestep/host/gcode_import.hpp>

#include "load_message.hpp"

using namespace curvestep;
using namespace curvestep::host;

namespace {

std::string message_of(const std::string& text) { return testing::load_error_message(text, "arc.ngc"); }

constexpr double pi = 3.14159265358979323846;

}  // namespace

TEST_CASE("arc planes: a G18 quarter circle turns clockwise seen from +Y", "[gcode][import][arc][plane]") {
  // Centre z 10, x 0 (K10 from the start), radius 10: the start (z 0, x 0) is at angle 180 degrees in
  // (Z, X); clockwise by 90 degrees ends at (z 10, x 10), passing angle 135 at the middle.
  const Job job = parse_gcode_job("G21 G90 G18\nG2 X10 Z10 K10 F600\n", "g18.ngc");
  REQUIRE(job.sources.size() == 1);
  CHECK(job.sources[0].type == SegmentType::Arc);
  const MachinePoint middle = evaluate_segment(job, 0, 0.5);
  CHECK(middle[0] == Approx(10 * std::sin(3 * pi / 4)).margin(2e-4));       // x = 7.0711
  CHECK(middle[1] == Approx(0).margin(1e-9));
  CHECK(middle[2] == Approx(10 + 10 * std::cos(3 * pi / 4)).margin(2e-4));  // z = 2.9289
  for (int i = 0; i <= 32; ++i) {
    const MachinePoint p = evaluate_segment(job, 0, i / 32.0);
    CHECK(std::hypot(p[2] - 10, p[0]) == Approx(10).margin(2e-4));
  }
  const MachinePoint end = evaluate_segment(job, 0, 1.0);
  CHECK(end[0] == Approx(10).margin(1e-4));
  CHECK(end[2] == Approx(10).margin(1e-4));
  // G3 takes the long way round: three quarters, through (z 10, x -10).
  const Job ccw = parse_gcode_job("G21 G90 G18\nG3 X10 Z10 K10 F600\n", "g18_ccw.ngc");
  const MachinePoint third = evaluate_segment(ccw, 0, 1.0 / 3.0);
  CHECK(third[0] == Approx(-10).margin(2e-4));
  CHECK(third[2] == Approx(10).margin(2e-4));
}

TEST_CASE("arc planes: a G19 full-circle helix rises along X in proportion to the angle", "[gcode][import][arc][plane]") {
  // Start (x 0, y 10, z 0), centre (y 0, z 0): J-10. End = start in Y-Z: a full circle while X rises 5.
  const Job job = parse_gcode_job("G21 G90 G19\nG0 Y10\nG3 Y10 Z0 X5 J-10 F600\n", "g19.ngc");
  REQUIRE(job.sources.size() == 2);
  CHECK(job.sources[1].first_piece >= 1);
  CHECK(job.segments.size() - job.sources[1].first_piece >= 4);  // at most a quarter turn a piece
  for (int i = 0; i <= 64; ++i) {
    const MachinePoint p = evaluate_segment(job, 1, i / 64.0);
    INFO("sample " << i);
    CHECK(std::hypot(p[1], p[2]) == Approx(10).margin(2e-4));
    // Counter-clockwise seen from +X: from angle 0 (y 10, z 0) towards (y 0, z 10).
    double angle = std::atan2(p[2], p[1]);
    if (angle < 0) angle += 2 * pi;
    if (i == 64) angle = 2 * pi;
    if (i == 0) angle = 0;
    CHECK(p[0] == Approx(5 * angle / (2 * pi)).margin(2e-4));
  }
  const MachinePoint quarter = evaluate_segment(job, 1, 0.25);
  CHECK(quarter[1] == Approx(0).margin(2e-4));
  CHECK(quarter[2] == Approx(10).margin(2e-4));
  CHECK(job.segments.back().end()[0] == Approx(5).margin(1e-9));
}

TEST_CASE("arc planes: the offset letter along the normal is refused, R works in every plane", "[gcode][import][arc][plane]") {
  CHECK_THAT(message_of("G21 G18\nG2 X10 Z10 K10 J1 F600\n"), Catch::Contains("arc.ngc:2:16"));
  CHECK_THAT(message_of("G21 G19\nG2 Y10 Z10 I1 F600\n"), Catch::Contains("arc.ngc:2:12"));
  // A zero offset along the normal means nothing and is accepted (FreeCAD's grbl post writes K0.000).
  const Job k0 = parse_gcode_job("G21 G17\nG2 X10 Y10 I10 J0 K0.000 F600\n", "k0.ngc");
  CHECK(k0.segments.size() == 1);
  // R form in G19, clockwise seen from +X from (y 0, z 0) to (y 10, z 10), R10: the quarter about
  // the centre (y 10, z 0).
  const Job job = parse_gcode_job("G21 G19\nG2 Y10 Z10 R10 F600\n", "g19_r.ngc");
  for (int i = 0; i <= 16; ++i) {
    const MachinePoint p = evaluate_segment(job, 0, i / 16.0);
    CHECK(std::hypot(p[1] - 10, p[2]) == Approx(10).margin(2e-4));
  }
}

TEST_CASE("arc radius tolerance: LinuxCNC's figures in the program's units", "[gcode][import][arc]") {
  // LinuxCNC's t = 2 x 0.001 x sqrt(2) in = 0.0028284 in (2 x 0.01 x sqrt(2) mm under G21). Radius
  // 0.1 in, end radius longer by 0.0028 in: within t, accepted in G20; the same arc in mm (0.07112 mm
  // longer, 2.7 % of the radius) is beyond 0.028284 mm: refused with the metric figures.
  CHECK_NOTHROW(parse_gcode_job("G20 G90\nG2 X0.2028 Y0 I0.1 J0 F10\n", "inch.ngc"));
  CHECK_THAT(message_of("G21 G90\nG2 X5.15112 Y0 I2.54 J0 F10\n"),
             Catch::Contains("arc.ngc:2:1") && Catch::Contains("differs from radius to start") && Catch::Contains("0.0283 mm"));
  // 0.0029 in is beyond t and 0.1 %: refused in G20 too, with the inch figures.
  CHECK_THAT(message_of("G20 G90\nG2 X0.2029 Y0 I0.1 J0 F10\n"), Catch::Contains("0.00283 in"));
  // A large radius: 0.28 in off at 300 in (0.093 %) is within 100 t = 0.28284 in; 0.29 in is not.
  CHECK_NOTHROW(parse_gcode_job("G20 G90\nG2 X600.28 Y0 I300 J0 F10\n", "big_inch.ngc"));
  CHECK_THAT(message_of("G20 G90\nG2 X600.29 Y0 I300 J0 F10\n"), Catch::Contains("differs from radius to start"));
  // The same in mm: 2.8 mm at 3000 mm passes, 2.9 mm fails (100 t = 2.8284 mm).
  CHECK_NOTHROW(parse_gcode_job("G21 G90\nG2 X6002.8 Y0 I3000 J0 F10\n", "big_mm.ngc"));
  CHECK_THAT(message_of("G21 G90\nG2 X6002.9 Y0 I3000 J0 F10\n"), Catch::Contains("2.83 mm"));
}
