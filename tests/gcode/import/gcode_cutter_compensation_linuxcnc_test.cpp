// SPDX-License-Identifier: MIT
// Cutter radius compensation, LinuxCNC's further rules (issue 17): an arc as the entry move, G18
// (the Z X plane, left and counter-clockwise as seen from +Y), and corners within 0.05 rad of a
// reversal. Expected points are worked out by hand (in the comments); the distance checks measure the
// tool centre's distance from the programmed contour with the test's own geometry.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <curvestep/host/gcode_import.hpp>

#include "compensation_path.hpp"
#include "load_message.hpp"

using namespace curvestep;
using namespace curvestep::host;
using testing::arc;
using testing::check_path;
using testing::distance_to_ccw_arc;
using testing::distance_to_polygon;
using testing::distance_to_segment;
using testing::to;

namespace {

constexpr double h = 1.4142135623730951;  // r·cos 45° for r = 2
constexpr double r = 2.0;                  // tool 1 of testing::tool_table()

/// The programmed 20 x 20 square, clockwise in the plane's (first, second) coordinates.
const std::vector<std::array<double, 2>> square{{{0, 0}}, {{0, 20}}, {{20, 20}}, {{20, 0}}};

/// The entry arc of the square programs: G3 from (-8,-4) about (-5,0) (radius 5) to (0,0), tangent
/// there to the first side (0,0) -> (0,20). G41 keeps the tool left of it, towards the centre: its
/// offset end is E = (0,0) + 2·(-1,0) = (-2,0). LinuxCNC's rule: the entry arc goes from the tool
/// T = (-8,-4) to E about a centre B on the line from E towards the programmed centre, as far from T
/// as from E: B = E + s·(-1,0) with s² = (s - 6)² + 16, so s = 52/12 = 13/3: B = (-19/3, 0), radius 13/3.
constexpr double entry_cu = -19.0 / 3.0;
constexpr double entry_radius = 13.0 / 3.0;

/// Each source segment of a G18 job ends (its last piece) at the expected (Z, X), in order, with Y 0.
void check_zx_source_ends(const Job& job, const std::vector<std::array<double, 2>>& expected) {
  std::map<std::size_t, MachinePoint> ends;
  for (std::size_t j = 0; j < job.segments.size(); ++j) ends[job.source_index[j]] = job.segments[j].end();
  REQUIRE(ends.size() == expected.size());
  std::size_t i = 0;
  for (const auto& [index, end] : ends) {
    INFO("source " << index);
    CHECK(end[2] == Approx(expected[i][0]).margin(1e-4));
    CHECK(end[0] == Approx(expected[i][1]).margin(1e-4));
    CHECK(end[1] == Approx(0).margin(1e-9));
    ++i;
  }
}

/// Every piece of the sources [first, last] of `job`, sampled, is `expected` mm from the square, in
/// the plane coordinates that `plane_point` picks from a machine point.
template <typename PlanePoint>
void check_distance_from_square(const Job& job, std::size_t first, std::size_t last, PlanePoint plane_point) {
  std::size_t sampled = 0;
  for (std::size_t j = 0; j < job.segments.size(); ++j) {
    if (job.source_index[j] < first || job.source_index[j] > last) continue;
    for (int k = 0; k <= 20; ++k) {
      const auto [u, v] = plane_point(job.segments[j].point(k / 20.0));
      INFO("segment " << j << " at " << k / 20.0 << ": (" << u << ", " << v << ")");
      CHECK(distance_to_polygon(u, v, square) == Approx(r).margin(1e-3));
      ++sampled;
    }
  }
  CHECK(sampled >= 7 * 21);
}

/// Segments [first, last] of `job`, sampled, are r from the programmed line (20,0) -> (0,0) followed
/// by the counter-clockwise arc about `center` from (0,0) to angle 0 (the near-reversal programs).
void check_distance_from_line_and_arc(const Job& job, std::size_t first, std::size_t last, const std::array<double, 2>& center) {
  const double radius = std::hypot(center[0], center[1]);
  const double from = std::atan2(-center[1], -center[0]);
  for (std::size_t j = first; j <= last; ++j) {
    for (int k = 0; k <= 20; ++k) {
      const MachinePoint p = job.segments[j].point(k / 20.0);
      INFO("segment " << j << " at " << k / 20.0 << ": (" << p[0] << ", " << p[1] << ")");
      const double to_line = distance_to_segment(p[0], p[1], {{20, 0}}, {{0, 0}});
      const double to_arc = distance_to_ccw_arc(p[0], p[1], center, radius, from, 0.0);
      CHECK(std::min(to_line, to_arc) == Approx(r).margin(1e-3));
    }
  }
}

}  // namespace

TEST_CASE("cutter compensation: an arc entry into a square, LinuxCNC's entry arc", "[gcode][import][compensation]") {
  const Job job = testing::load_compensated("G21 G17 G90\nG0 X-8 Y-4\nG41 D1\nG3 X0 Y0 I3 J4 F600\nG1 Y20\nX20\nY0\nX0\nG40\nG1 X-10 Y-10\nM2\n");
  // The entry arc runs counter-clockwise from T at angle atan2(-4, -5/3) (about -112.6°) to E at 0°;
  // its middle is at half that angle. It ends tangent to the first side's offset x = -2, so no
  // corner arc follows; the square's other corners get quarter arcs as in the G41 square above.
  const double a0 = std::atan2(-4.0, -5.0 / 3.0);
  check_path(job, {to(-8, -4), arc(-2, 0, entry_cu, 0, entry_cu + entry_radius * std::cos(a0 / 2), entry_radius * std::sin(a0 / 2)),
                   to(-2, 20), arc(0, 22, 0, 20, -h, 20 + h), to(20, 22), arc(22, 20, 20, 20, 20 + h, 20 + h), to(22, 0),
                   arc(20, -2, 20, 0, 20 + h, -h), to(0, -2), to(-10, -10)});
  CHECK(job.segments[1].arc_radius() == Approx(entry_radius).margin(1e-4));
  CHECK(job.sources[job.source_index[1]].line == 4);
  // After the entry the tool centre stays r from the programmed square (sides and corner arcs).
  check_distance_from_square(job, job.source_index[2], job.source_index[8], [](const MachinePoint& p) { return std::pair{p[0], p[1]}; });

  SECTION("a helical entry arc: Z goes down along it, and the path in XY is the same") {
    const Job helix = testing::load_compensated("G21 G17\nG0 X-8 Y-4 Z1\nG41 D1\nG3 X0 Y0 Z-1 I3 J4 F600\nG1 Y20\nG40\nG1 X-10 Y20\n");
    REQUIRE(helix.segments.size() >= 3);
    CHECK(helix.segments[1].end()[0] == Approx(-2).margin(1e-4));
    CHECK(helix.segments[1].end()[1] == Approx(0).margin(1e-4));
    CHECK(helix.segments[1].end()[2] == Approx(-1).margin(1e-4));
    CHECK(helix.segments[1].start()[2] == Approx(1).margin(1e-4));
  }
}

TEST_CASE("cutter compensation: the same square in G18, Z the first axis and X the second", "[gcode][import][compensation]") {
  // The G17 program with (X, Y) -> (Z, X): G3 K3 I4 is the centre (Z-5, X0). LinuxCNC compensates in
  // the Z X plane as in X Y (left and counter-clockwise seen from +Y), so every point of the G17 path
  // reappears with Z = its x and X = its y; Y stays 0.
  const Job job = testing::load_compensated("G21 G18 G90\nG0 X-4 Z-8\nG41 D1\nG3 X0 Z0 K3 I4 F600\nG1 X20\nZ20\nX0\nZ0\nG40\nG1 X-10 Z-10\nM2\n");
  const std::vector<std::array<double, 2>> expected{{{-8, -4}}, {{-2, 0}},  {{-2, 20}}, {{0, 22}}, {{20, 22}},
                                                    {{22, 20}}, {{22, 0}}, {{20, -2}}, {{0, -2}}, {{-10, -10}}};
  check_zx_source_ends(job, expected);
  // The entry arc: on the circle about B (Z -19/3, X 0) of radius 13/3, through X < 0 (counter-
  // clockwise seen from +Y from T to E; the other way round it would pass X > 0).
  for (std::size_t j = 0; j < job.segments.size(); ++j) {
    if (job.source_index[j] != 1) continue;
    for (int k = 0; k <= 10; ++k) {
      const MachinePoint p = job.segments[j].point(k / 10.0);
      CHECK(std::hypot(p[2] - entry_cu, p[0]) == Approx(entry_radius).margin(1e-3));
      CHECK(p[0] <= 1e-6);
    }
  }
  check_distance_from_square(job, 2, 8, [](const MachinePoint& p) { return std::pair{p[2], p[0]}; });

  SECTION("G42 in G18: the tool on the other side, inside the square") {
    // Right of the clockwise square is inside: the sides shift inwards and meet at (2,18), (18,18),
    // (18,2) (Z, X) with no corner arcs; the straight entry ends at the first side's offset start
    // (2,0), G40 ends the last side square at (0,2).
    const Job inside = testing::load_compensated("G21 G18\nG0 X10 Z10\nG42 D1\nG1 X0 Z0 F600\nX20\nZ20\nX0\nZ0\nG40\nG1 X10 Z10\n");
    const std::vector<std::array<double, 2>> corners{{{10, 10}}, {{2, 0}}, {{2, 18}}, {{18, 18}}, {{18, 2}}, {{0, 2}}, {{10, 10}}};
    check_zx_source_ends(inside, corners);
  }
}

TEST_CASE("cutter compensation: a near-reversal inside corner cut at the offsets' crossing", "[gcode][import][compensation]") {
  // G42 along y = 0 to the left, then G3 about C = (-0.4, 10) (radius R = sqrt(100.16)), leaving
  // (0,0) in direction (10, 0.4)/R: a right turn of 180° - atan(0.04) = 177.7°, inside for G42. The
  // tool is above the line (y = 2) and outside the arc (radius R + 2), which curves away from it
  // (LinuxCNC's "h" shape, which it also cuts at the crossing). By hand: (x + 0.4)² + (2 - 10)² =
  // (R + 2)², x = -0.4 + sqrt(144.19200 - 64) = -0.4 + 8.95500 = 8.55500.
  const double big_r = std::sqrt(100.16);
  const double x = -0.4 + std::sqrt((big_r + r) * (big_r + r) - 64.0);
  CHECK(x == Approx(8.555).margin(1e-3));
  CHECK(std::hypot(x + 0.4, 2.0 - 10.0) - big_r == Approx(r));  // r from the circle, as from the line
  const double a0 = std::atan2(2.0 - 10.0, x + 0.4);           // the offset arc from there to angle 0
  const Job job = testing::load_compensated("G21 G17\nG0 X30 Y10\nG42 D1\nG1 X20 Y0 F600\nX0\nG3 X9.608 Y10 I-0.4 J10\nG40\nG1 X30 Y10\n");
  check_path(job, {to(30, 10), to(20, 2), to(x, 2),
                   arc(11.608, 10, -0.4, 10, -0.4 + (big_r + r) * std::cos(a0 / 2), 10 + (big_r + r) * std::sin(a0 / 2)), to(30, 10)});
  check_distance_from_line_and_arc(job, 2, 3, {{-0.4, 10}});
}

TEST_CASE("cutter compensation: LinuxCNC's h shape, a near-reversal turning the outside way onto an arc curving away",
          "[gcode][import][compensation]") {
  // As above but mirrored: G3 about C = (0.4, 10) leaves (0,0) in direction (10, -0.4)/R, a left
  // turn of 180° - 0.04 rad: the outside way for G42, yet the tool (above the line, outside the arc)
  // would swing round into the arc's side. LinuxCNC cuts it at the crossing of y = 2 with the circle
  // of radius R + 2 behind the corner: (x - 0.4)² + 64 = (R + 2)², x = 0.4 + 8.95500 = 9.35500 (the
  // other crossing, x = -8.555, lies beyond the line's end, before the arc's offset start).
  const double big_r = std::sqrt(100.16);
  const double x = 0.4 + std::sqrt((big_r + r) * (big_r + r) - 64.0);
  CHECK(x == Approx(9.355).margin(1e-3));
  const double a0 = std::atan2(2.0 - 10.0, x - 0.4);
  const Job job = testing::load_compensated("G21 G17\nG0 X30 Y10\nG42 D1\nG1 X20 Y0 F600\nX0\nG3 X10.408 Y10 I0.4 J10\nG40\nG1 X30 Y10\n");
  check_path(job, {to(30, 10), to(20, 2), to(x, 2),
                   arc(12.408, 10, 0.4, 10, 0.4 + (big_r + r) * std::cos(a0 / 2), 10 + (big_r + r) * std::sin(a0 / 2)), to(30, 10)});
  check_distance_from_line_and_arc(job, 2, 3, {{0.4, 10}});
}

TEST_CASE("cutter compensation: an inside corner within 0.05 rad of a reversal whose offsets do not meet is gone around",
          "[gcode][import][compensation]") {
  // LinuxCNC's crazy-paths shape: G42 along y = 0 to the left, then G2 about C = (0.4, -10) (radius
  // R = sqrt(100.16)) leaving (0,0) in direction (10, 0.4)/R: a right turn of 180° - 0.04 rad, inside
  // for G42. The tool is above the line (y = 2) and inside the arc (radius R - 2), below: the line
  // y = 2 is 12 from C, the circle only R - 2 = 8.008: they never meet. LinuxCNC counts a corner
  // within 0.05 rad of a reversal as convex and goes around it: a counter-clockwise arc of radius 2
  // about (0,0) from (0,2) to 2·(0.4,-10)/R, sweeping 180° + 0.04 rad (its middle at angle
  // 180° + 0.02 rad), then the offset arc of radius R - 2 to (0.8,0)'s offset, its middle straight
  // above C at (0.4, -10 + R - 2).
  const double big_r = std::sqrt(100.16);
  const double turn = std::atan(0.04);
  const double pi = 3.141592653589793;
  const Job job = testing::load_compensated("G21 G17\nG0 X30 Y10\nG42 D1\nG1 X20 Y0 F600\nX0\nG2 X0.8 Y0 I0.4 J-10\nG40\nG1 X0.8 Y-20\n");
  check_path(job, {to(30, 10), to(20, 2), to(0, 2),
                   arc(r * 0.4 / big_r, -r * 10 / big_r, 0, 0, r * std::cos(pi + turn / 2), r * std::sin(pi + turn / 2)),
                   arc(0.4 + (big_r - r) * 0.4 / big_r, -10 + (big_r - r) * 10 / big_r, 0.4, -10, 0.4, -10 + big_r - r), to(0.8, -20)});
  CHECK(job.sources[job.source_index[3]].line == 6);  // the corner arc belongs to the arc after it
}

TEST_CASE("cutter compensation: LinuxCNC's gouges and impossible entry arcs are refused with file:line:column",
          "[gcode][import][compensation][errors]") {
  testing::check_refusals({
      // As the near-reversal above, but turning 180° - atan(0.1) = 174.3°: 0.0997 rad from a
      // reversal, beyond LinuxCNC's 0.05; the line y = 2 is 12 from C = (1,-10), the offset circle R - 2 = 8.05.
      {"G21 G17\nG0 X30 Y10\nG42 D1\nG1 X20 Y0 F600\nX0\nG2 X2 Y0 I1 J-10\n", "comp.ngc:6:1: G2", "do not meet at their inside corner"},
      // G18: (Z, X) = (0,0) -> (20,0) -> (20,1) -> (0,1), G41: the left turns are inside; the offsets of the
      // 1 mm side X1 (Z = 18) and of the first side (X = 2) cross at X = 2, beyond its end.
      {"G21 G18\nG0 X-10 Z0\nG41 D1\nG1 X0 Z0 F600\nZ20\nX1\nZ0\n", "comp.ngc:6:1: X1", "this move is too short"},
      // An entry arc about (-5,0) from T = (-2,-4) to (0,0): its offset end is E = (-2,0), and T lies on the
      // tangent there (T - E is square to the line from E to the centre): no arc from T ends square.
      {"G21\nG0 X-2 Y-4\nG41 D1\nG3 X0 Y0 I-3 J4 F600\nY20\n", "comp.ngc:4:1: G3", "entry arc cannot reach"},
      // A concave entry arc (G41 inside a counter-clockwise arc) of radius 1.5 with a tool of radius 2.
      {"G21\nG0 X-3 Y0\nG41 D1\nG3 X0 Y0 I1.5 J0 F600\n", "comp.ngc:4:1: G3", "not larger than the tool radius"},
      // The exit move stays a line (LinuxCNC's bad/ccomp-arcexit), in G18 too.
      {"G21 G18\nG0 X-10 Z0\nG41 D1\nG1 X0 Z0 F600\nZ20\nG40\nG2 X0 Z30 K5 I0\n", "comp.ngc:7:1: G2", "exit move"},
  });
}
