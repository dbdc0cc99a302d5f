// SPDX-License-Identifier: MIT
// Transforms (every form, lists, nested groups) and units, viewBox and preserveAspectRatio.
#include <cmath>
#include <numbers>

#include <catch2/catch.hpp>

#include <curvestep/host/svg_import.hpp>

#include "svg_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::testing;

namespace {

/// The machine points of "M 10 0 L 0 10" (user units) under `transform` on the mm page.
std::vector<MachinePoint> transformed(const std::string& transform) {
  const auto pieces = drawn(import_page("<path transform=\"" + transform + "\" d=\"M 10 0 L 0 10\"/>").job);
  REQUIRE(pieces.size() == 1);
  return pieces[0].points;
}

/// The machine points of the line from (x1,y1) to (x2,y2) in user units of a whole document.
std::vector<MachinePoint> line_in(const std::string& svg_attributes, const std::string& line_attributes) {
  const auto text = "<svg xmlns=\"http://www.w3.org/2000/svg\" " + svg_attributes + "><line " + line_attributes + "/></svg>";
  const auto pieces = drawn(parse_svg(text, "units.svg").job);
  REQUIRE(pieces.size() == 1);
  return pieces[0].points;
}

void check_line(const std::vector<MachinePoint>& got, MachinePoint a, MachinePoint b) {
  INFO("got (" << got[0][0] << ", " << got[0][1] << ") - (" << got[1][0] << ", " << got[1][1] << ")");
  CHECK(near(got[0], a));
  CHECK(near(got[1], b));
}

}  // namespace

TEST_CASE("svg: each transform form maps the points as worked out by hand", "[host_tools][svg]") {
  // Points (10,0) and (0,10) in user space; expected user-space images, then on_page.
  check_line(transformed("translate(5 7)"), on_page(15, 7), on_page(5, 17));
  check_line(transformed("translate(5)"), on_page(15, 0), on_page(5, 10));
  check_line(transformed("scale(2 3)"), on_page(20, 0), on_page(0, 30));
  check_line(transformed("scale(2)"), on_page(20, 0), on_page(0, 20));
  check_line(transformed("rotate(90)"), on_page(0, 10), on_page(-10, 0));
  check_line(transformed("rotate(-90)"), on_page(0, -10), on_page(10, 0));
  check_line(transformed("rotate(180 5 5)"), on_page(0, 10), on_page(10, 0));
  check_line(transformed("rotate(90 10 10)"), on_page(20, 10), on_page(10, 0));
  const double c = std::cos(std::numbers::pi / 6);
  const double s = 0.5;
  check_line(transformed("rotate(30)"), on_page(10 * c, 10 * s), on_page(-10 * s, 10 * c));
  check_line(transformed("skewX(45)"), on_page(10, 0), on_page(10, 10));
  check_line(transformed("skewY(45)"), on_page(10, 10), on_page(0, 10));
  check_line(transformed("matrix(1 2 3 4 5 6)"), on_page(15, 26), on_page(35, 46));
  check_line(transformed("matrix(1,2,3,4,5,6)"), on_page(15, 26), on_page(35, 46));
}

TEST_CASE("svg: transform lists apply right to left and nest through groups", "[host_tools][svg]") {
  // translate(10 0) scale(2): scale first: (10,0) -> (20,0) -> (30,0); (0,10) -> (0,20) -> (10,20).
  check_line(transformed("translate(10 0) scale(2)"), on_page(30, 0), on_page(10, 20));
  check_line(transformed("translate(10,0),scale(2)"), on_page(30, 0), on_page(10, 20));
  const auto nested = drawn(import_page("<g transform=\"translate(10 0)\"><g transform=\"scale(2)\">"
                                        "<path transform=\"rotate(90)\" d=\"M 10 0 L 0 10\"/></g></g>")
                                .job);
  REQUIRE(nested.size() == 1);
  // rotate: (10,0) -> (0,10), (0,10) -> (-10,0); scale 2: (0,20), (-20,0); translate: (10,20), (-10,0).
  check_line(nested[0].points, on_page(10, 20), on_page(-10, 0));
  // A shape's own transform applies to the shape (circle about the origin moved to (50,50)).
  const auto circle = drawn(import_page("<circle transform=\"translate(50 50)\" r=\"10\"/>").job);
  REQUIRE(circle.size() == 4);
  CHECK(near(circle[0].points[0], on_page(60, 50)));
}

TEST_CASE("svg: a sheared arc stays an exact rational image of the ellipse", "[host_tools][svg]") {
  // circle r=10 at the origin under skewX(30) and translate(50 50): points satisfy |S^-1 (p - c)| = 10.
  const auto result = import_page("<circle transform=\"translate(50 50) skewX(30)\" r=\"10\"/>");
  const double t = std::tan(std::numbers::pi / 6);
  for (std::size_t i = 1; i < result.job.segments.size(); ++i) {
    for (int k = 0; k <= 16; ++k) {
      const auto p = result.job.segments[i].point(k / 16.0);
      const double y = (100 - p[1]) - 50;  // user y after translate
      const double x = (p[0] - 50) - t * y;
      CHECK(std::hypot(x, y) == Approx(10).margin(1e-4));
    }
  }
}

TEST_CASE("svg: physical units of the page map user units to millimetres", "[host_tools][svg]") {
  // Without a viewBox the user unit is the px, 1/96 in; y is flipped about the page height.
  check_line(line_in("width=\"4in\" height=\"2in\"", "x2=\"96\""), {{0, 50.8, 0}}, {{25.4, 50.8, 0}});
  check_line(line_in("width=\"96px\" height=\"96px\"", "x2=\"96\""), {{0, 25.4, 0}}, {{25.4, 25.4, 0}});
  check_line(line_in("width=\"96\" height=\"96\"", "x2=\"48\""), {{0, 25.4, 0}}, {{12.7, 25.4, 0}});
  // With a viewBox the page size decides the scale.
  check_line(line_in("width=\"10cm\" height=\"10cm\" viewBox=\"0 0 10 10\"", "x1=\"1\" y1=\"1\" x2=\"2\""), {{10, 90, 0}}, {{20, 100, 0}});
  check_line(line_in("width=\"72pt\" height=\"72pt\" viewBox=\"0 0 72 72\"", "x2=\"72\""), {{0, 25.4, 0}}, {{25.4, 25.4, 0}});
  check_line(line_in("width=\"6pc\" height=\"12pc\" viewBox=\"0 0 6 12\"", "x2=\"1\""), {{0, 50.8, 0}}, {{25.4 / 6, 50.8, 0}});
  check_line(line_in("width=\"40Q\" height=\"40Q\" viewBox=\"0 0 10 10\"", "x2=\"10\""), {{0, 10, 0}}, {{10, 10, 0}});
  check_line(line_in("width=\"210mm\" height=\"297mm\" viewBox=\"0 0 210 297\"", "x1=\"10\" y1=\"10\" x2=\"200\" y2=\"287\""),
             {{10, 287, 0}}, {{200, 10, 0}});
  // Units on an element's lengths: 10mm in a px document is 10 mm.
  check_line(line_in("width=\"100mm\" height=\"100mm\"", "x1=\"1in\" x2=\"10mm\" y1=\"2.54cm\""), {{25.4, 74.6, 0}}, {{10, 100, 0}});
  // No page size at all: px, flipped about y = 0.
  check_line(line_in("", "x2=\"96\" y2=\"96\""), {{0, 0, 0}}, {{25.4, -25.4, 0}});
  // viewBox only: the page is the viewBox in px.
  check_line(line_in("viewBox=\"0 0 96 48\"", "x2=\"96\""), {{0, 12.7, 0}}, {{25.4, 12.7, 0}});
  // Only the width: the height follows the viewBox's aspect ratio (100 mm x 50 mm).
  check_line(line_in("width=\"100mm\" viewBox=\"0 0 10 5\"", "x2=\"10\""), {{0, 50, 0}}, {{100, 50, 0}});
  // A viewBox with an offset.
  check_line(line_in("width=\"100mm\" height=\"100mm\" viewBox=\"-50 -50 100 100\"", "x2=\"10\""), {{50, 50, 0}}, {{60, 50, 0}});
}

TEST_CASE("svg: preserveAspectRatio meet, slice and none", "[host_tools][svg]") {
  const std::string page_size = "width=\"100mm\" height=\"50mm\" viewBox=\"0 0 100 100\" ";
  // Default xMidYMid meet: scale 0.5, centred horizontally (x offset 25 mm).
  check_line(line_in(page_size, "x2=\"100\" y2=\"100\""), {{25, 50, 0}}, {{75, 0, 0}});
  check_line(line_in(page_size + "preserveAspectRatio=\"xMaxYMax meet\"", "x2=\"100\""), {{50, 50, 0}}, {{100, 50, 0}});
  // slice: scale 1; xMinYMin keeps the top-left corner.
  check_line(line_in(page_size + "preserveAspectRatio=\"xMinYMin slice\"", "x2=\"100\" y2=\"100\""), {{0, 50, 0}}, {{100, -50, 0}});
  // xMidYMid slice: centred vertically (y offset -25 mm from the top).
  check_line(line_in(page_size + "preserveAspectRatio=\"xMidYMid slice\"", "y1=\"25\" x2=\"100\" y2=\"75\""), {{0, 50, 0}}, {{100, 0, 0}});
  // none: x scale 1, y scale 0.5.
  check_line(line_in(page_size + "preserveAspectRatio=\"none\"", "x2=\"100\" y2=\"100\""), {{0, 50, 0}}, {{100, 0, 0}});
}

TEST_CASE("svg: a nested svg element is a viewport at x, y with its own viewBox", "[host_tools][svg]") {
  const auto pieces = drawn(
      import_page("<svg x=\"10\" y=\"20\" width=\"20\" height=\"20\" viewBox=\"0 0 2 2\"><line x2=\"1\" y2=\"1\"/></svg>").job);
  REQUIRE(pieces.size() == 1);
  check_points(pieces[0], {on_page(10, 20), on_page(20, 30)});
}
