// SPDX-License-Identifier: MIT
// Basic shapes: circle, ellipse, rect (square and rounded corners), line, polyline, polygon.
#include <cmath>

#include <catch2/catch.hpp>

#include <curvestep/host/svg_import.hpp>

#include "svg_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::testing;

namespace {

const double half_root_two = std::sqrt(2.0) / 2;

/// Quarter arcs carry the weight √2/2 rounded to Q16.16, as the wire does.
void check_quarter_weights(const std::vector<SourceSegment>& pieces) {
  for (const auto& p : pieces) {
    CHECK(p.type == SegmentType::RationalBezier);
    REQUIRE(p.weights.size() == 3);
    CHECK(p.weights[0] == 1);
    CHECK(p.weights[1] == quarter_weight);
    CHECK(p.weights[2] == 1);
  }
}

/// The rounded quarter weight keeps |P|² within this of r² in the unit frame (svg_test_support.hpp),
/// plus 1e-12 for evaluating the curve in double.
const double quarter_bound = conic_off_circle_bound(half_root_two, quarter_weight) + 1e-12;

}  // namespace

TEST_CASE("svg: a 10 mm circle at (20,30) is four quarter arcs with weights sqrt(2)/2 rounded to Q16.16", "[host_tools][svg]") {
  const auto result = import_page("<circle cx=\"20\" cy=\"30\" r=\"10\"/>");
  check_connected(result.job);
  const auto pieces = drawn(result.job);
  REQUIRE(pieces.size() == 4);
  check_quarter_weights(pieces);
  // Machine centre (20, 70); SVG starts at (cx + r, cy) and turns towards +y of user space (down).
  check_points(pieces[0], {{{30, 70, 0}}, {{30, 60, 0}}, {{20, 60, 0}}});
  check_points(pieces[1], {{{20, 60, 0}}, {{10, 60, 0}}, {{10, 70, 0}}});
  check_points(pieces[2], {{{10, 70, 0}}, {{10, 80, 0}}, {{20, 80, 0}}});
  check_points(pieces[3], {{{20, 80, 0}}, {{30, 80, 0}}, {{30, 70, 0}}});
  // Every point of every piece is 10 mm from the centre, up to the weight's rounding: the control
  // points are on the grid exactly, and |P|/r lies in [sqrt(1 - bound), sqrt(1 + bound)], so
  // |P| is within r (1 - sqrt(1 - bound)) = 1.85e-6 mm of r = 10.
  const double radius_margin = 10 * (1 - std::sqrt(1 - quarter_bound));
  CHECK(radius_margin < 1.9e-6);  // the documented 1.9e-7 r
  for (std::size_t i = 1; i < result.job.segments.size(); ++i) {
    for (int k = 0; k <= 32; ++k) {
      const auto p = result.job.segments[i].point(k / 32.0);
      CHECK(std::hypot(p[0] - 20, p[1] - 70) == Approx(10).margin(radius_margin));
    }
  }
  // The weight rounding is visible: the middle of a quarter lies off the circle, at
  // r sqrt(2) (1 + 2w) / (2 (1 + w)) for weight w (the conic at t = 1/2), not at r.
  const auto middle = result.job.segments[1].point(0.5);
  const double w = quarter_weight;
  CHECK(std::hypot(middle[0] - 20, middle[1] - 70) == Approx(10 * std::sqrt(2.0) * (1 + 2 * w) / (2 * (1 + w))).margin(1e-12));
}

TEST_CASE("svg: an ellipse is four quarters whose points satisfy the ellipse equation", "[host_tools][svg]") {
  const auto result = import_page("<ellipse cx=\"50\" cy=\"40\" rx=\"30\" ry=\"12.5\"/>");
  const auto pieces = drawn(result.job);
  REQUIRE(pieces.size() == 4);
  check_quarter_weights(pieces);
  check_points(pieces[0], {on_page(80, 40), on_page(80, 52.5), on_page(50, 52.5)});
  check_points(pieces[2], {on_page(20, 40), on_page(20, 27.5), on_page(50, 27.5)});
  for (std::size_t i = 1; i < result.job.segments.size(); ++i) {
    for (int k = 0; k <= 32; ++k) {
      const auto p = result.job.segments[i].point(k / 32.0);
      const double u = (p[0] - 50) / 30;
      const double v = (p[1] - 60) / 12.5;
      // The control points are on the grid exactly; the rounded weight bounds the equation.
      CHECK(u * u + v * v == Approx(1).margin(quarter_bound));
    }
  }
  // ry omitted: the same as rx (a circle).
  const auto circle = drawn(import_page("<ellipse cx=\"50\" cy=\"50\" rx=\"5\"/>").job);
  REQUIRE(circle.size() == 4);
  check_points(circle[0], {on_page(55, 50), on_page(55, 55), on_page(50, 55)});
}

TEST_CASE("svg: a rect with rounded corners is four lines and four quarter arcs", "[host_tools][svg]") {
  const auto pieces = drawn(import_page("<rect x=\"10\" y=\"10\" width=\"40\" height=\"20\" rx=\"5\"/>").job);
  REQUIRE(pieces.size() == 8);
  check_points(pieces[0], {on_page(15, 10), on_page(45, 10)});
  check_points(pieces[1], {on_page(45, 10), on_page(50, 10), on_page(50, 15)});
  check_points(pieces[2], {on_page(50, 15), on_page(50, 25)});
  check_points(pieces[3], {on_page(50, 25), on_page(50, 30), on_page(45, 30)});
  check_points(pieces[4], {on_page(45, 30), on_page(15, 30)});
  check_points(pieces[5], {on_page(15, 30), on_page(10, 30), on_page(10, 25)});
  check_points(pieces[6], {on_page(10, 25), on_page(10, 15)});
  check_points(pieces[7], {on_page(10, 15), on_page(10, 10), on_page(15, 10)});
  for (std::size_t i = 1; i < 8; i += 2) CHECK(pieces[i].weights[1] == quarter_weight);
  // Radii larger than half the size are clamped (rx 30 -> 20, ry given 4): the horizontal sides
  // vanish, leaving four arcs and the two vertical sides.
  const auto clamped = drawn(import_page("<rect x=\"10\" y=\"10\" width=\"40\" height=\"20\" rx=\"30\" ry=\"4\"/>").job);
  REQUIRE(clamped.size() == 6);
  check_points(clamped[0], {on_page(30, 10), on_page(50, 10), on_page(50, 14)});
  check_points(clamped[1], {on_page(50, 14), on_page(50, 26)});
  check_points(clamped[2], {on_page(50, 26), on_page(50, 30), on_page(30, 30)});
  // Only ry given: rx = ry.
  const auto only_ry = drawn(import_page("<rect width=\"40\" height=\"20\" ry=\"2\"/>").job);
  check_points(only_ry[0], {on_page(2, 0), on_page(38, 0)});
}

TEST_CASE("svg: a rect without radii is four lines from its corner", "[host_tools][svg]") {
  const auto pieces = drawn(import_page("<rect x=\"1\" y=\"2\" width=\"3\" height=\"4\"/>").job);
  REQUIRE(pieces.size() == 4);
  check_points(pieces[0], {on_page(1, 2), on_page(4, 2)});
  check_points(pieces[1], {on_page(4, 2), on_page(4, 6)});
  check_points(pieces[2], {on_page(4, 6), on_page(1, 6)});
  check_points(pieces[3], {on_page(1, 6), on_page(1, 2)});
}

TEST_CASE("svg: line, polyline and polygon", "[host_tools][svg]") {
  const auto line = drawn(import_page("<line x1=\"1\" y1=\"2\" x2=\"30\" y2=\"40\"/>").job);
  REQUIRE(line.size() == 1);
  check_points(line[0], {on_page(1, 2), on_page(30, 40)});
  const auto polyline = drawn(import_page("<polyline points=\"0,0 10,0 10,10\"/>").job);
  REQUIRE(polyline.size() == 2);
  check_points(polyline[1], {on_page(10, 0), on_page(10, 10)});
  const auto polygon = drawn(import_page("<polygon points=\"0 0,10 0 10 10\"/>").job);
  REQUIRE(polygon.size() == 3);
  check_points(polygon[2], {on_page(10, 10), on_page(0, 0)});
}

TEST_CASE("svg: zero-size shapes, hidden elements and definitions are not drawn", "[host_tools][svg]") {
  const auto result = import_page(
      "<rect width=\"0\" height=\"5\"/><circle r=\"0\"/><ellipse rx=\"3\" ry=\"0\"/>"
      "<g style=\"display:none\"><line x2=\"5\"/></g><line display=\"none\" x2=\"6\"/>"
      "<defs><line x2=\"7\"/></defs><foreignObject/><image href=\"a.png\"/>"
      "<line x1=\"1\" x2=\"8\"/>");
  const auto pieces = drawn(result.job);
  REQUIRE(pieces.size() == 1);
  check_points(pieces[0], {on_page(1, 0), on_page(8, 0)});
  REQUIRE(result.warnings.size() == 2);
  CHECK(result.warnings[0] == "test.svg:2: <foreignObject> is not drawn");
  CHECK(result.warnings[1] == "test.svg:2: <image> is not drawn");
}

TEST_CASE("svg: use draws the referenced element or symbol at x, y under its transform", "[host_tools][svg]") {
  const auto pieces = drawn(import_page(
                                "<defs><line id=\"dash\" x1=\"0\" y1=\"0\" x2=\"5\" y2=\"0\"/>"
                                "<symbol id=\"tick\" viewBox=\"0 0 1 1\"><line x2=\"1\" y2=\"1\"/></symbol></defs>"
                                "<use href=\"#dash\" x=\"10\" y=\"20\"/>"
                                "<use xlink:href=\"#dash\" transform=\"scale(2)\" y=\"5\"/>"
                                "<use href=\"#tick\" x=\"50\" y=\"50\" width=\"10\" height=\"10\"/>")
                                .job);
  REQUIRE(pieces.size() == 3);
  check_points(pieces[0], {on_page(10, 20), on_page(15, 20)});
  check_points(pieces[1], {on_page(0, 10), on_page(10, 10)});
  check_points(pieces[2], {on_page(50, 50), on_page(60, 60)});
}

TEST_CASE("svg: a use that refers to itself or to nothing is an error", "[host_tools][svg]") {
  CHECK_THROWS_WITH(import_page("<g id=\"loop\"><use href=\"#loop\"/></g>"),
                    Catch::Contains("test.svg:2: <use> \"href\": the reference \"#loop\" refers back to itself"));
  CHECK_THROWS_WITH(import_page("<use href=\"#missing\"/>"), Catch::Contains("<use> \"href\": no element has id \"missing\""));
}
