// SPDX-License-Identifier: MIT
// transform-origin: translate(origin) · transform · translate(-origin), with keywords, lengths and
// percentages of the viewport; expected points worked out by hand on the 100 x 100 mm test page.
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/host/svg_import.hpp>

#include <support/load_error_checks.hpp>

#include "svg_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::testing;

namespace {

/// The two machine points of the line (x1,y1)-(x2,y2) drawn with `attributes`.
std::vector<MachinePoint> line_with(const std::string& attributes, const std::string& coordinates) {
  const auto pieces = drawn(import_page("<line " + coordinates + " " + attributes + "/>").job);
  REQUIRE(pieces.size() == 1);
  return pieces[0].points;
}

void check_line(const std::vector<MachinePoint>& got, MachinePoint a, MachinePoint b) {
  INFO("got (" << got[0][0] << ", " << got[0][1] << ") - (" << got[1][0] << ", " << got[1][1] << ")");
  CHECK(near(got[0], a));
  CHECK(near(got[1], b));
}

}  // namespace

TEST_CASE("svg: transform-origin moves the centre of the transform", "[host_tools][svg][transform-origin]") {
  // rotate(90) about (10, 10): (20, 10) is (10, 0) from the origin, turned to (0, 10): (10, 20); (10, 10) stays.
  const std::string segment = "x1=\"20\" y1=\"10\" x2=\"10\" y2=\"10\"";
  check_line(line_with("transform=\"rotate(90)\" transform-origin=\"10 10\"", segment), on_page(10, 20), on_page(10, 10));
  check_line(line_with("transform=\"rotate(90)\" style=\"transform-origin: 10px 10px\"", segment), on_page(10, 20),
             on_page(10, 10));
  // Without transform-origin the rotation is about (0, 0): (20, 10) -> (-10, 20), (10, 10) -> (-10, 10).
  check_line(line_with("transform=\"rotate(90)\"", segment), on_page(-10, 20), on_page(-10, 10));
  // transform-origin alone does nothing.
  check_line(line_with("transform-origin=\"10 10\"", segment), on_page(20, 10), on_page(10, 10));
}

TEST_CASE("svg: transform-origin keywords and percentages are of the viewport", "[host_tools][svg][transform-origin]") {
  // center = (50, 50): scale(2) sends (60, 50) to (70, 50) and (50, 40) to (50, 30).
  const std::string segment = "x1=\"60\" y1=\"50\" x2=\"50\" y2=\"40\"";
  check_line(line_with("transform=\"scale(2)\" transform-origin=\"center\"", segment), on_page(70, 50), on_page(50, 30));
  check_line(line_with("transform=\"scale(2)\" transform-origin=\"50% 50%\"", segment), on_page(70, 50), on_page(50, 30));
  check_line(line_with("transform=\"scale(2)\" transform-origin=\"center center 0\"", segment), on_page(70, 50),
             on_page(50, 30));
  // bottom right = right bottom = (100, 100): scale(0.5) sends (60, 50) to (80, 75), (50, 40) to (75, 70).
  check_line(line_with("transform=\"scale(0.5)\" transform-origin=\"bottom right\"", segment), on_page(80, 75), on_page(75, 70));
  check_line(line_with("transform=\"scale(0.5)\" transform-origin=\"right bottom\"", segment), on_page(80, 75), on_page(75, 70));
  // "top" alone is (50, 0): rotate(180) sends (60, 50) to (40, -50) and (50, 40) to (50, -40).
  check_line(line_with("transform=\"rotate(180)\" transform-origin=\"top\"", segment), on_page(40, -50), on_page(50, -40));
  // "left" alone is (0, 50): scale(2) sends (60, 50) to (120, 50), (50, 40) to (100, 30).
  check_line(line_with("transform=\"scale(2)\" transform-origin=\"left\"", segment), on_page(120, 50), on_page(100, 30));
  // 25% 75% = (25, 75): scale(2) sends (60, 50) to (95, 25), (50, 40) to (75, 5).
  check_line(line_with("transform=\"scale(2)\" transform-origin=\"25% 75%\"", segment), on_page(95, 25), on_page(75, 5));
  // Inside a group's transform the origin is in the element's user space: translate(10 0) then the line.
  const auto grouped = drawn(import_page("<g transform=\"translate(10 0)\"><line " + segment +
                                         " transform=\"scale(2)\" transform-origin=\"center\"/></g>")
                                 .job);
  REQUIRE(grouped.size() == 1);
  check_line(grouped[0].points, on_page(80, 50), on_page(60, 30));
}

TEST_CASE("svg: a malformed transform-origin is an error naming it", "[host_tools][svg][transform-origin]") {
  for (const std::string origin : {"middle", "left right", "top bottom", "1 2 3 4", "10 10 10%"}) {
    INFO(origin);
    check_rejected([&] { return import_page("<line x2=\"1\" transform=\"scale(2)\" transform-origin=\"" + origin + "\"/>"); },
                   {"test.svg", 2, "<line> \"transform-origin\"", Error::InvalidJob, ""});
  }
}
