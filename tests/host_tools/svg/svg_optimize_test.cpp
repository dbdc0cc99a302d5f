// SPDX-License-Identifier: MIT
// Subpath ordering: greedy nearest neighbour with reversal of open subpaths, and the travel saved.
#include <cmath>

#include <catch2/catch.hpp>

#include <curvestep/host/svg_import.hpp>

#include "svg_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::testing;

namespace {

// On the mm page y_user = 100 is machine y = 0: A (50..60), B (10..20), C drawn from 40 to 30.
const char* const three_lines = "<path d=\"M 50 100 H 60\"/><path d=\"M 10 100 H 20\"/><path d=\"M 40 100 H 30\"/>";

}  // namespace

TEST_CASE("svg: without optimize subpaths keep document order", "[host_tools][svg]") {
  const auto result = import_page(three_lines);
  // travel 0 -> 50, 60 -> 10, 20 -> 40
  CHECK(result.travel_document_mm == Approx(120).margin(1e-9));
  CHECK(result.travel_mm == Approx(120).margin(1e-9));
  CHECK(result.travel_saved_mm() == Approx(0).margin(1e-9));
  CHECK(result.reversed_count == 0);
  const auto pieces = drawn(result.job);
  REQUIRE(pieces.size() == 3);
  check_points(pieces[0], {{{50, 0, 0}}, {{60, 0, 0}}});
}

TEST_CASE("svg: optimize visits the nearest subpath next and reverses open ones", "[host_tools][svg]") {
  SvgOptions options;
  options.optimize = true;
  const auto result = import_page(three_lines, options);
  check_connected(result.job);
  // From 0: B (start 10, 10 mm); from 20: C's end at 30 (10 mm, reversed) beats C's start at 40 and
  // A at 50; from 40: A at 50 (10 mm). Travel 30 instead of 120.
  const auto pieces = drawn(result.job);
  REQUIRE(pieces.size() == 3);
  check_points(pieces[0], {{{10, 0, 0}}, {{20, 0, 0}}});
  check_points(pieces[1], {{{30, 0, 0}}, {{40, 0, 0}}});
  check_points(pieces[2], {{{50, 0, 0}}, {{60, 0, 0}}});
  CHECK(result.travel_document_mm == Approx(120).margin(1e-9));
  CHECK(result.travel_mm == Approx(30).margin(1e-9));
  CHECK(result.travel_saved_mm() == Approx(90).margin(1e-9));
  CHECK(result.reversed_count == 1);
  // The rapids in the job add up to the reported travel.
  double rapid_length = 0;
  for (const auto& segment : result.job.segments) {
    if (segment.rapid()) rapid_length += std::hypot(segment.end()[0] - segment.start()[0], segment.end()[1] - segment.start()[1]);
  }
  CHECK(rapid_length == Approx(30).margin(1e-9));
}

TEST_CASE("svg: reversing a curved subpath reverses its control points and weights", "[host_tools][svg]") {
  SvgOptions options;
  options.optimize = true;
  options.start = MachinePoint{{100, 0, 0}};
  // Open: a cubic then a half ellipse, ending at (90, 0) on the machine, nearest to the start.
  const auto result = import_page("<path d=\"M 0 100 C 10 90 20 90 30 100 A 30 10 0 0 0 90 100\"/>", options);
  const auto pieces = drawn(result.job);
  REQUIRE(pieces.size() == 3);
  CHECK(result.reversed_count == 1);
  CHECK(pieces[0].type == SegmentType::RationalBezier);
  CHECK(near(pieces[0].points.front(), {{90, 0, 0}}));
  CHECK(pieces[2].type == SegmentType::Bezier);
  check_points(pieces[2], {{{30, 0, 0}}, {{20, 10, 0}}, {{10, 10, 0}}, {{0, 0, 0}}});
  // The reversed curve passes through the same points: the middle of the cubic is (15, 7.5).
  const auto& segment = result.job.segments.back();
  CHECK(near(segment.point(0.5), {{15, 7.5, 0}}, 1e-9));
  CHECK(result.travel_mm == Approx(10).margin(1e-9));
  CHECK(result.travel_document_mm == Approx(100).margin(1e-9));
}

TEST_CASE("svg: closed subpaths are entered at their start and never reversed", "[host_tools][svg]") {
  SvgOptions options;
  options.optimize = true;
  const auto result = import_page("<rect x=\"50\" y=\"50\" width=\"10\" height=\"10\"/><rect x=\"10\" y=\"80\" width=\"10\" height=\"10\"/>", options);
  const auto pieces = drawn(result.job);
  REQUIRE(pieces.size() == 8);
  CHECK(result.reversed_count == 0);
  // The second rect (corner at machine (10, 20)) comes first; its outline keeps its direction.
  check_points(pieces[0], {on_page(10, 80), on_page(20, 80)});
  check_points(pieces[4], {on_page(50, 50), on_page(60, 50)});
}
