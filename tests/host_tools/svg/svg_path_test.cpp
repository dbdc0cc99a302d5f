// SPDX-License-Identifier: MIT
// Path data: every command, absolute and relative, gives the control points worked out by hand.
#include <catch2/catch.hpp>

#include <curvestep/host/svg_import.hpp>

#include "svg_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::testing;

namespace {

std::vector<SourceSegment> pieces_of(const std::string& d) {
  const auto result = import_page("<path d=\"" + d + "\"/>");
  check_connected(result.job);
  return drawn(result.job);
}

}  // namespace

TEST_CASE("svg: M L H V Z absolute and relative give the same four lines", "[host_tools][svg]") {
  for (const char* d : {"M 10 20 L 30 20 H 50 V 40 Z", "m 10 20 l 20 0 h 20 v 20 z", "M10,20L30,20H50V40z", "m10 20 20 0h20v20Z"}) {
    INFO(d);
    const auto pieces = pieces_of(d);
    REQUIRE(pieces.size() == 4);
    for (const auto& p : pieces) CHECK(p.type == SegmentType::Line);
    check_points(pieces[0], {on_page(10, 20), on_page(30, 20)});
    check_points(pieces[1], {on_page(30, 20), on_page(50, 20)});
    check_points(pieces[2], {on_page(50, 20), on_page(50, 40)});
    check_points(pieces[3], {on_page(50, 40), on_page(10, 20)});
  }
}

TEST_CASE("svg: C and S keep cubic control points and S reflects the previous one", "[host_tools][svg]") {
  for (const char* d : {"M 0 0 C 10 0 20 10 20 20 S 30 40 40 40", "m0 0c10 0 20 10 20 20s10 20 20 20"}) {
    INFO(d);
    const auto pieces = pieces_of(d);
    REQUIRE(pieces.size() == 2);
    CHECK(pieces[0].type == SegmentType::Bezier);
    CHECK(pieces[0].degree == 3);
    check_points(pieces[0], {on_page(0, 0), on_page(10, 0), on_page(20, 10), on_page(20, 20)});
    // Reflection of (20,10) about (20,20) is (20,30).
    check_points(pieces[1], {on_page(20, 20), on_page(20, 30), on_page(30, 40), on_page(40, 40)});
  }
  // S after a line: the first control point is the current point.
  const auto after_line = pieces_of("M 0 0 L 10 0 S 20 10 30 10");
  REQUIRE(after_line.size() == 2);
  check_points(after_line[1], {on_page(10, 0), on_page(10, 0), on_page(20, 10), on_page(30, 10)});
}

TEST_CASE("svg: Q and T keep quadratic control points and T reflects the previous one", "[host_tools][svg]") {
  for (const char* d : {"M 0 50 Q 10 70 20 50 T 40 50", "m0 50q10 20 20 0t20 0", "M0 50Q10 70 20 50T40 50"}) {
    INFO(d);
    const auto pieces = pieces_of(d);
    REQUIRE(pieces.size() == 2);
    CHECK(pieces[0].type == SegmentType::Bezier);
    CHECK(pieces[0].degree == 2);
    check_points(pieces[0], {on_page(0, 50), on_page(10, 70), on_page(20, 50)});
    // Reflection of (10,70) about (20,50) is (30,30).
    check_points(pieces[1], {on_page(20, 50), on_page(30, 30), on_page(40, 50)});
  }
  // T after a cubic does not reflect: its control point is the current point.
  const auto after_cubic = pieces_of("M 0 0 C 0 10 10 10 10 0 T 20 0");
  REQUIRE(after_cubic.size() == 2);
  check_points(after_cubic[1], {on_page(10, 0), on_page(10, 0), on_page(20, 0)});
}

TEST_CASE("svg: A and a give the same rational quadratic pieces", "[host_tools][svg]") {
  // A half circle of radius 10 about (50,50) from (40,50) to (60,50), sweep 1 (positive angles
  // in user space, y down): through (50,40). Two quarter pieces with weight √2/2, rounded to
  // Q16.16 as the wire carries it (46341/65536).
  for (const char* d : {"M 40 50 A 10 10 0 0 1 60 50", "m40 50a10 10 0 0 1 20 0", "M40 50A10,10,0,0,1,60,50", "M40 50a10 10 0 0120 0"}) {
    INFO(d);
    const auto pieces = pieces_of(d);
    REQUIRE(pieces.size() == 2);
    for (const auto& p : pieces) {
      CHECK(p.type == SegmentType::RationalBezier);
      REQUIRE(p.weights.size() == 3);
      CHECK(p.weights[0] == 1);
      CHECK(p.weights[1] == quarter_weight);
      CHECK(p.weights[2] == 1);
    }
    check_points(pieces[0], {on_page(40, 50), on_page(40, 40), on_page(50, 40)});
    check_points(pieces[1], {on_page(50, 40), on_page(60, 40), on_page(60, 50)});
  }
}

TEST_CASE("svg: implicit repetition, packed numbers and exponents", "[host_tools][svg]") {
  // After M extra pairs are L; after m they are l.
  const auto absolute = pieces_of("M 0 0 10 0 10 10");
  REQUIRE(absolute.size() == 2);
  check_points(absolute[1], {on_page(10, 0), on_page(10, 10)});
  const auto relative = pieces_of("m 1 1 2 2 3 3");
  REQUIRE(relative.size() == 2);
  check_points(relative[1], {on_page(3, 3), on_page(6, 6)});
  // "M10-5.5.5e1-1" is M 10 -5.5 L 5 -1 ... in a y-down page: -5.5 -> 105.5.
  const auto packed = pieces_of("M10-5.5.5e1-1");
  REQUIRE(packed.size() == 1);
  check_points(packed[0], {on_page(10, -5.5), on_page(5, -1)});
  const auto exponents = pieces_of("M 1e1 2E+1 L +3.0e-0 .4e2");
  REQUIRE(exponents.size() == 1);
  check_points(exponents[0], {on_page(10, 20), on_page(3, 40)});
  // A number too small for a double is zero.
  const auto tiny = pieces_of("M 0 0 L 1e-400 10");
  REQUIRE(tiny.size() == 1);
  check_points(tiny[0], {on_page(0, 0), on_page(0, 10)});
  // Repeated curve arguments make several curves.
  const auto curves = pieces_of("M0 0 q 5 5 10 0 5 5 10 0");
  REQUIRE(curves.size() == 2);
  check_points(curves[1], {on_page(10, 0), on_page(15, 5), on_page(20, 0)});
}

TEST_CASE("svg: subpaths are joined by rapids and Z starts the next subpath at the start", "[host_tools][svg]") {
  const auto result = import_page("<path d=\"M 10 10 L 20 10 M 30 10 L 40 10 z l 0 10\"/>");
  const Job& job = result.job;
  check_connected(job);
  REQUIRE(job.sources.size() == 6);
  // rapid from the origin, line, rapid, line, closing line, line from the start of the closed subpath
  CHECK(job.sources[0].type == SegmentType::Rapid);
  check_points(job.sources[0], {MachinePoint{}, on_page(10, 10)});
  CHECK(job.sources[2].type == SegmentType::Rapid);
  check_points(job.sources[2], {on_page(20, 10), on_page(30, 10)});
  check_points(job.sources[4], {on_page(40, 10), on_page(30, 10)});
  check_points(job.sources[5], {on_page(30, 10), on_page(30, 20)});
  CHECK(result.subpath_count == 3);
  CHECK(job.segments[0].rapid());
  CHECK(result.travel_mm == Approx(std::hypot(10.0, 90.0) + 10.0));
}

TEST_CASE("svg: zero-length segments and lone movetos draw nothing", "[host_tools][svg]") {
  const auto pieces = pieces_of("M 5 5 M 10 10 L 10 10 L 20 10 C 20 10 20 10 20 10 A 5 5 0 0 1 20 10");
  REQUIRE(pieces.size() == 1);
  check_points(pieces[0], {on_page(10, 10), on_page(20, 10)});
}

TEST_CASE("svg: the feed option is set on drawing segments but not on rapids", "[host_tools][svg]") {
  SvgOptions options;
  options.feed_mm_per_s = 25;
  const auto result = import_page("<path d=\"M 10 10 L 20 10\"/>", options);
  REQUIRE(result.job.segments.size() == 2);
  CHECK(result.job.segments[1].feed_mm_per_s() == 25);
  CHECK(result.job.sources[1].feed_mm_per_s == 25);
  CHECK(result.job.sources[1].line == 2);
}
