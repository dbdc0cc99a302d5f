// SPDX-License-Identifier: MIT
// G93 inverse-time feed and G43.1 through the importer: the segments' feeds (hand-computed: length ×
// F per minute, in mm/s), the compensated path at the programmed move's feed (LinuxCNC), and the
// messages with file:line:column.
#include <catch2/catch.hpp>

#include <cstddef>
#include <string>

#include <curvestep/host/gcode_import.hpp>

#include "load_message.hpp"

using namespace curvestep;
using namespace curvestep::host;
using curvestep::host::testing::load_error_message;

namespace {

/// The feed (mm/s) of every segment of program line `line`; fails if the line has none or they differ.
double feed_of_line(const Job& job, std::size_t line) {
  double feed = -1;
  for (std::size_t j = 0; j < job.segments.size(); ++j) {
    if (job.sources[job.source_index[j]].line != line) continue;
    if (feed >= 0) REQUIRE(job.segments[j].feed_mm_per_s() == feed);
    feed = job.segments[j].feed_mm_per_s();
  }
  REQUIRE(feed >= 0);
  return feed;
}

/// The LoadError of `text` (as file feed.ngc) begins with `expected`.
void check_message(const std::string& text, const std::string& expected) {
  INFO(text);
  CHECK_THAT(load_error_message(text, "feed.ngc"), Catch::StartsWith(expected));
}

}  // namespace

TEST_CASE("gcode import feed mode: G93 segments run at their length times F", "[gcode][import][feed]") {
  // 10 mm at F6 (10 s): 1 mm/s; 10 mm at F3: 0.5 mm/s; 10 mm at F60: 10 mm/s; half a circle of
  // radius 5 (5π mm) at F6: π/2 mm/s; 1 inch at F12 (5 s): 5.08 mm/s; G94 F600: 10 mm/s.
  const Job job = parse_gcode_job(
      "G21 G90 G0 X0 Y0\nG93 G1 X10 F6\nY10 F3\nG0 X0\nG1 Y0 F60\nG3 Y10 I0 J5 F6\nG20 G1 X1 F12\nG94 G21 G1 X0 F600\n",
      "inverse.ngc");
  CHECK(feed_of_line(job, 2) == 1.0);
  CHECK(feed_of_line(job, 3) == 0.5);
  CHECK(feed_of_line(job, 4) == 0.0);  // a rapid: no feed of its own
  CHECK(feed_of_line(job, 5) == 10.0);
  CHECK(feed_of_line(job, 6) == Approx(3.14159265358979 / 2).margin(1.0 / 65536));  // Q16.16 on the wire
  CHECK(feed_of_line(job, 7) == Approx(5.08).margin(1.0 / 65536));
  CHECK(feed_of_line(job, 8) == 10.0);
}

TEST_CASE("gcode import feed mode: compensated G93 moves keep the programmed move's feed, corner arcs too",
          "[gcode][import][feed]") {
  // Left of the path, radius 2, turning right twice after the entry: two outside corners, whose
  // arcs belong to the move after them (the entry move goes straight to the next offset: no arc).
  // Feeds from the programmed lengths (LinuxCNC): 10 mm × F12 = 2 mm/s, × F6 = 1, × F3 = 0.5, × F1.5 = 0.25.
  const Job job = parse_gcode_job("G21 G90 G0 X0 Y0\nG41.1 D4\nG93 G1 X10 Y0 F12\nY-10 F6\nX0 F3\nY0 F1.5\nG40 G94 G1 X-10 F600\n",
                                  "comp.ngc");
  CHECK(feed_of_line(job, 3) == 2.0);
  CHECK(feed_of_line(job, 4) == 1.0);
  CHECK(feed_of_line(job, 5) == 0.5);
  CHECK(feed_of_line(job, 6) == 0.25);
  CHECK(feed_of_line(job, 7) == 10.0);
  std::size_t corner_arcs = 0;
  for (std::size_t j = 0; j < job.segments.size(); ++j) corner_arcs += job.segments[j].arc_radius() > 0 ? 1U : 0U;
  CHECK(corner_arcs == 2);
}

TEST_CASE("gcode import feed mode: what G93 and G94 refuse, with file, line, column and LinuxCNC's meaning",
          "[gcode][import][feed]") {
  check_message("G21\nG93 G1 X1 F1\n  Y2\n", "feed.ngc:3:3: Y2: F word missing with an inverse-time move");
  check_message("G93\nG2 X0 Y10 I-10 J0\n", "feed.ngc:2:1: G2: F word missing");
  check_message("G1 X1 F600\nG93 G1 X2 F1\nG94\nG1 X3\n", "feed.ngc:4:1: G1: no feed rate in force: G94 after G93");
  check_message("G93\nG5.1 I1 J0 X2 Y0 F1\n", "feed.ngc:2:1: G5.1: splines (G5, G5.1, G5.2) cannot run in inverse-time feed mode (G93)");
  check_message("G93\nG81 X1 Y1 Z-1 R1 F1\n", "feed.ngc:2:1: G81: cannot use inverse-time feed (G93) with canned cycles");
  check_message("G95\n", "feed.ngc:1:1: G95: feed per revolution (G95)");
}

TEST_CASE("gcode import tool length: G43.1 Z offsets the moves after it, its refusals say why", "[gcode][import][tools]") {
  // G43.1 Z2.5 then G1 Z0: machine Z 2.5; G49 then G0 Z-1: machine Z -1.
  const Job job = parse_gcode_job("G21 G90 G0 X0 Y0 Z10\nG43.1 Z2.5\nG1 Z0 F60\nG49\nG0 Z-1\n", "tlo.ngc");
  REQUIRE(job.segments.size() == 3);
  CHECK(job.segments[1].end()[2] == 2.5);
  CHECK(job.segments[2].end()[2] == -1.0);
  check_message("G43.1 X1\n", "feed.ngc:1:7: X1: G43.1 takes the tool length offset along Z only");
  check_message("G43.2 H1\n", "feed.ngc:1:1: G43.2: additional tool length offsets (G43.2) are not supported");
  check_message("G41.1 D2\nG0 X10\nG43.1 Z1\n",
                "feed.ngc:3:1: G43.1: the tool length offset (G43, G43.1, G49) cannot change while cutter radius compensation");
}
