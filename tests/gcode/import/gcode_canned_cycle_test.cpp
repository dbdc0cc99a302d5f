// SPDX-License-Identifier: MIT
// Canned cycles (issue 17.2): G81 G82 G83 G73 G85 G86 G89 with G98/G99 and L, expanded into the
// moves the LinuxCNC g-code reference describes. Expected moves are worked out by hand from the
// reference's own examples (G81 absolute and incremental with L3) and its step lists per cycle.
#include <catch2/catch.hpp>

#include <array>
#include <string>
#include <vector>

#include <curvestep/host/gcode_import.hpp>

#include "load_message.hpp"

using namespace curvestep;
using namespace curvestep::host;

namespace {

struct Move {
  bool rapid;
  double x, y, z;
};

/// Checks the job's segments against `moves` (ends on the Q16.16 grid: within 1e-4 mm).
void check_moves(const Job& job, const std::vector<Move>& moves) {
  REQUIRE(job.segments.size() == moves.size());
  for (std::size_t i = 0; i < moves.size(); ++i) {
    INFO("segment " << i);
    const auto end = job.segments[i].end();
    CHECK(job.segments[i].rapid() == moves[i].rapid);
    CHECK(end[0] == Approx(moves[i].x).margin(1e-4));
    CHECK(end[1] == Approx(moves[i].y).margin(1e-4));
    CHECK(end[2] == Approx(moves[i].z).margin(1e-4));
  }
}

std::string message_of(const std::string& text) { return testing::load_error_message(text, "cycle.ngc"); }

constexpr bool R = true;   // rapid
constexpr bool F = false;  // feed

}  // namespace

TEST_CASE("canned cycles: G81 absolute, the reference's example", "[gcode][import][cycle]") {
  // From (1,2,3): XY traverse at Z3, Z traverse to R 2.8, feed to 1.5, G98: back to the old Z 3.
  const Job job = parse_gcode_job("G21 G90 G0 X1 Y2 Z3\nG98 G81 X4 Y5 Z1.5 R2.8 F60\n", "g81.ngc");
  check_moves(job, {{R, 1, 2, 3}, {R, 4, 5, 3}, {R, 4, 5, 2.8}, {F, 4, 5, 1.5}, {R, 4, 5, 3}});
  CHECK(job.segments[3].feed_mm_per_s() == Approx(1.0));
  CHECK(job.sources.back().line == 2);
}

TEST_CASE("canned cycles: G81 incremental with L3, the reference's example", "[gcode][import][cycle]") {
  // From (1,2,3): R = 3 + 1.8 = 4.8, Z = 4.8 - 0.6 = 4.2; below R first, so Z up to 4.8 once; three
  // holes 4, 5 apart; G98 clears at max(3, 4.8) = 4.8.
  const Job job = parse_gcode_job("G21 G90 G0 X1 Y2 Z3\nG91 G98 G81 X4 Y5 Z-0.6 R1.8 L3 F60\n", "g81_l3.ngc");
  check_moves(job, {{R, 1, 2, 3},
                    {R, 1, 2, 4.8},
                    {R, 5, 7, 4.8}, {F, 5, 7, 4.2}, {R, 5, 7, 4.8},
                    {R, 9, 12, 4.8}, {F, 9, 12, 4.2}, {R, 9, 12, 4.8},
                    {R, 13, 17, 4.8}, {F, 13, 17, 4.2}, {R, 13, 17, 4.8}});
}

TEST_CASE("canned cycles: G99 series with sticky Z and R, cancelled by G80", "[gcode][import][cycle]") {
  const Job job = parse_gcode_job("G21 G90 G0 X0 Y0 Z10\nG99 G81 X10 Y0 Z-2 R1 F120\nX20\nY5\nG80\nG0 Z10\n", "g99.ngc");
  check_moves(job, {{R, 0, 0, 10},
                    {R, 10, 0, 10}, {R, 10, 0, 1}, {F, 10, 0, -2}, {R, 10, 0, 1},
                    {R, 20, 0, 1}, {F, 20, 0, -2}, {R, 20, 0, 1},
                    {R, 20, 5, 1}, {F, 20, 5, -2}, {R, 20, 5, 1},
                    {R, 20, 5, 10}});
  CHECK(job.segments[3].feed_mm_per_s() == Approx(2.0));
  // After G80 axis words need a motion G word again.
  CHECK_THAT(message_of("G21 G90 G0 Z10\nG81 X1 Z-1 R1 F60\nG80\nX5\n"), Catch::Contains("cycle.ngc:4:1") && Catch::Contains("no motion mode"));
}

TEST_CASE("canned cycles: G80 beside G0 or G1 (a Fanuc post's safety line) ends the cycle, the move stays", "[gcode][import][cycle]") {
  // LinuxCNC puts G80 in the motion group and refuses the pair; Fanuc gives G80 a group of its own.
  const Job job = parse_gcode_job("G0 G17 G40 G49 G80 G90 G21\nG0 X0 Y0 Z10\nG99 G81 X10 Y0 Z-2 R1 F120\nG80 G0 X0 Y0\nG1 G80 Z5 F60\nX3\n",
                                  "safety.ngc");
  check_moves(job, {{R, 0, 0, 10},
                    {R, 10, 0, 10}, {R, 10, 0, 1}, {F, 10, 0, -2}, {R, 10, 0, 1},
                    {R, 0, 0, 1}, {F, 0, 0, 5}, {F, 3, 0, 5}});
  // G80 alone still ends the motion mode; two G80s, or G80 with a cycle, are still refused.
  CHECK_THAT(message_of("G21 G0 Z10\nG80 G80\n"), Catch::Contains("cycle.ngc:2:5") && Catch::Contains("cannot appear with"));
  CHECK_THAT(message_of("G21 G0 Z10\nG0 G80 G80 X1\n"), Catch::Contains("cycle.ngc:2:8") && Catch::Contains("cannot appear with"));
  CHECK_THAT(message_of("G21 G0 Z10\nG80 G0 G80 X1\n"), Catch::Contains("cycle.ngc:2:8") && Catch::Contains("cannot appear with"));
  CHECK_THAT(message_of("G21 G0 Z10\nG0 G80 G1 X1\n"), Catch::Contains("cycle.ngc:2:8") && Catch::Contains("cannot appear with"));
  CHECK_THAT(message_of("G21 G0 Z10\nG81 G80 X1 Z-1 R1 F60\n"), Catch::Contains("cycle.ngc:2:5") && Catch::Contains("cannot appear with"));
}

TEST_CASE("canned cycles: G83 pecks out to R, G73 breaks chips by the backoff", "[gcode][import][cycle]") {
  // R 1, bottom -5, Q 2, backoff 0.254 mm: pecks to -1, -3, -5.
  const Job g83 = parse_gcode_job("G21 G90 G0 Z5\nG98 G83 X0 Y0 Z-5 R1 Q2 F60\n", "g83.ngc");
  check_moves(g83, {{R, 0, 0, 5},
                    {R, 0, 0, 1}, {F, 0, 0, -1},
                    {R, 0, 0, 1}, {R, 0, 0, -0.746}, {F, 0, 0, -3},
                    {R, 0, 0, 1}, {R, 0, 0, -2.746}, {F, 0, 0, -5},
                    {R, 0, 0, 5}});
  const Job g73 = parse_gcode_job("G21 G90 G0 Z5\nG98 G73 X0 Y0 Z-5 R1 Q2 F60\n", "g73.ngc");
  check_moves(g73, {{R, 0, 0, 5},
                    {R, 0, 0, 1}, {F, 0, 0, -1},
                    {R, 0, 0, -0.746}, {F, 0, 0, -3},
                    {R, 0, 0, -2.746}, {F, 0, 0, -5},
                    {R, 0, 0, 5}});
  // In inches every length scales by 25.4; the backoff stays 0.010 in = 0.254 mm.
  const Job inch = parse_gcode_job("G20 G90 G0 Z0.2\nG99 G73 X0 Y0 Z-0.1 R0.04 Q0.1 F6\n", "g73_inch.ngc");
  check_moves(inch, {{R, 0, 0, 5.08}, {R, 0, 0, 1.016}, {F, 0, 0, -1.524}, {R, 0, 0, -1.27}, {F, 0, 0, -2.54}, {R, 0, 0, 1.016}});
}

TEST_CASE("canned cycles: dwells, feed-out and G86's spindle stop become moves and events", "[gcode][import][cycle]") {
  const Job g82 = parse_gcode_job("G21 G90 G0 Z5\nG99 G82 X1 Z-2 R1 P0.25 F60\n", "g82.ngc");
  check_moves(g82, {{R, 0, 0, 5}, {R, 1, 0, 5}, {R, 1, 0, 1}, {F, 1, 0, -2}, {R, 1, 0, 1}});
  REQUIRE(g82.events.size() == 1);
  CHECK(g82.events[0].kind == JobEventKind::Dwell);
  CHECK(g82.events[0].value == 0.25);
  CHECK(g82.events[0].before_segment == 4);  // after the feed to the bottom
  CHECK(g82.events[0].line == 2);

  const Job g85 = parse_gcode_job("G21 G90 G0 Z5\nG98 G85 X1 Z-2 R1 F60\n", "g85.ngc");
  check_moves(g85, {{R, 0, 0, 5}, {R, 1, 0, 5}, {R, 1, 0, 1}, {F, 1, 0, -2}, {F, 1, 0, 1}, {R, 1, 0, 5}});

  const Job g89 = parse_gcode_job("G21 G90 G0 Z5\nG99 G89 X1 Z-2 R1 P1 F60\n", "g89.ngc");
  check_moves(g89, {{R, 0, 0, 5}, {R, 1, 0, 5}, {R, 1, 0, 1}, {F, 1, 0, -2}, {F, 1, 0, 1}});
  REQUIRE(g89.events.size() == 1);
  CHECK(g89.events[0].before_segment == 4);

  const Job g86 = parse_gcode_job("G21 G90 G0 Z5\nS900 M4\nG98 G86 X1 Z-2 R1 P0.5 F60\n", "g86.ngc");
  check_moves(g86, {{R, 0, 0, 5}, {R, 1, 0, 5}, {R, 1, 0, 1}, {F, 1, 0, -2}, {R, 1, 0, 5}});
  // M4 S900, then at the bottom: dwell, spindle stop; after the rapid out: restart counter-clockwise at 900.
  REQUIRE(g86.events.size() == 4);
  CHECK(g86.events[1].kind == JobEventKind::Dwell);
  CHECK(g86.events[1].before_segment == 4);
  CHECK(g86.events[2].kind == JobEventKind::SpindleOff);
  CHECK(g86.events[2].before_segment == 4);
  CHECK(g86.events[3].kind == JobEventKind::SpindleOn);
  CHECK(g86.events[3].before_segment == 5);
  CHECK(g86.events[3].value == 900);
  CHECK(g86.events[3].flag);
}

TEST_CASE("canned cycles: work offsets apply to the holes and both planes", "[gcode][import][cycle]") {
  // G54 at (100, 50, -10): X5 -> 105, R2 -> -8, Z-1 -> -11; the initial Z (machine 0) is above R.
  const Job job = parse_gcode_job("G21 G90 G10 L2 P1 X100 Y50 Z-10\nG54 G98 G81 X5 Y0 Z-1 R2 F60\n", "offset.ngc");
  check_moves(job, {{R, 105, 50, 0}, {R, 105, 50, -8}, {F, 105, 50, -11}, {R, 105, 50, 0}});
}

TEST_CASE("canned cycles: inconsistent words are refused naming the word", "[gcode][import][cycle][errors]") {
  CHECK_THAT(message_of("G21 G90\nG81 X1 Z1 R0 F60\n"), Catch::Contains("cycle.ngc:2:11") && Catch::Contains("below the hole bottom"));
  CHECK_THAT(message_of("G21 G90\nG83 X1 Z-1 R1 F60\n"), Catch::Contains("cycle.ngc:2:1") && Catch::Contains("positive Q"));
  CHECK_THAT(message_of("G21 G90\nG83 X1 Z-1 R1 Q0 F60\n"), Catch::Contains("cycle.ngc:2:15") && Catch::Contains("must be positive"));
  CHECK_THAT(message_of("G21 G90\nG82 X1 Z-1 R1 F60\n"), Catch::Contains("P in this block"));
  CHECK_THAT(message_of("G21 G90\nG86 X1 Z-1 R1 P1 F60\n"), Catch::Contains("spindle turning"));
  CHECK_THAT(message_of("G21 G90\nG81 X1 R1 F60\n"), Catch::Contains("cycle.ngc:2:1") && Catch::Contains("Z and R"));
  CHECK_THAT(message_of("G21 G90\nG18 G81 X1 Z-1 R1 F60\n"), Catch::Contains("G17 (XY) plane only"));
  CHECK_THAT(message_of("G21 G90\nG81 X1 Z-1 R1 L0 F60\n"), Catch::Contains("cycle.ngc:2:15"));
  CHECK_THAT(message_of("G21 G90\nG84 X1 Z-1 R1 F60\n"), Catch::Contains("tapping"));
  CHECK_THAT(message_of("G21 G90\nG81 X1 Z-1 R1 I2 F60\n"), Catch::Contains("cycle.ngc:2:15"));
}
