// SPDX-License-Identifier: MIT
// Relative lengths: % of the nearest viewport (width, height or the normalised diagonal), em/ex of
// the computed font-size, vw/vh/vmin/vmax of the root viewport; expected points worked out by hand.
#include <cmath>
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/host/svg_import.hpp>

#include <support/load_error_checks.hpp>

#include "svg_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::testing;

namespace {

/// The drawn pieces of a whole document.
std::vector<SourceSegment> pieces_of(const std::string& svg_attributes, const std::string& body) {
  const auto text = "<svg xmlns=\"http://www.w3.org/2000/svg\" " + svg_attributes + ">" + body + "</svg>";
  return drawn(parse_svg(text, "units.svg").job);
}

/// 200 mm x 100 mm, user unit 1 mm: machine (x, y) = (x_user, 100 - y_user).
const std::string wide_page = "width=\"200mm\" height=\"100mm\" viewBox=\"0 0 200 100\"";
MachinePoint on_wide(double x, double y) { return MachinePoint{{x, 100 - y, 0.0}}; }

}  // namespace

TEST_CASE("svg: percentages are of the viewBox width, height or normalised diagonal", "[host_tools][svg][units]") {
  // x, width: of 200; y, height: of 100. The rect is (20, 10) .. (120, 60).
  const auto rect = pieces_of(wide_page, "<rect x=\"10%\" y=\"10%\" width=\"50%\" height=\"50%\"/>");
  REQUIRE(rect.size() == 4);
  check_points(rect[0], {on_wide(20, 10), on_wide(120, 10)});
  check_points(rect[1], {on_wide(120, 10), on_wide(120, 60)});
  // r: of sqrt((200² + 100²)/2) = sqrt(25000) = 158.113883; 10% = 15.8113883. Centre (100, 50).
  const auto circle = pieces_of(wide_page, "<circle cx=\"50%\" cy=\"50%\" r=\"10%\"/>");
  REQUIRE(circle.size() == 4);
  CHECK(near(circle[0].points[0], on_wide(115.8113883, 50)));
  CHECK(near(circle[0].points[2], on_wide(100, 50 + 15.8113883)));
  // ellipse rx of the width (20), ry of the height (10).
  const auto ellipse = pieces_of(wide_page, "<ellipse cx=\"100\" cy=\"50\" rx=\"10%\" ry=\"10%\"/>");
  REQUIRE(ellipse.size() == 4);
  CHECK(near(ellipse[0].points[0], on_wide(120, 50)));
  CHECK(near(ellipse[0].points[2], on_wide(100, 60)));
  // line: x1, x2 of the width, y1, y2 of the height.
  const auto line = pieces_of(wide_page, "<line x1=\"25%\" y1=\"25%\" x2=\"75%\" y2=\"100%\"/>");
  REQUIRE(line.size() == 1);
  check_points(line[0], {on_wide(50, 25), on_wide(150, 100)});
}

TEST_CASE("svg: percentages inside a nested viewport are of its viewBox, width and height default to 100%",
          "[host_tools][svg][units]") {
  // Inner viewBox 5 x 2 shown in 50 x 20 at (10, 10): scale 10. 100% = 5, 50% = 1: (0,1)-(5,1) -> (10,20)-(60,20).
  const auto inner = drawn(import_page("<svg x=\"10\" y=\"10\" width=\"50\" height=\"20\" viewBox=\"0 0 5 2\">"
                                       "<line x2=\"100%\" y1=\"50%\" y2=\"50%\"/></svg>")
                               .job);
  REQUIRE(inner.size() == 1);
  check_points(inner[0], {on_page(10, 20), on_page(60, 20)});
  // No width/height: 100% of the page's 100 x 100, so viewBox 10 x 10 is scaled by 10.
  const auto full = drawn(import_page("<svg viewBox=\"0 0 10 10\"><line x1=\"1\" x2=\"10\" y1=\"5\" y2=\"5\"/></svg>").job);
  REQUIRE(full.size() == 1);
  check_points(full[0], {on_page(10, 50), on_page(100, 50)});
  // width="50%" of the page: 50 x 100 shows the 10 x 10 viewBox at scale 5, centred vertically (y offset 25).
  const auto half = drawn(import_page("<svg width=\"50%\" viewBox=\"0 0 10 10\"><line x2=\"10\"/></svg>").job);
  REQUIRE(half.size() == 1);
  check_points(half[0], {on_page(0, 25), on_page(50, 25)});
}

TEST_CASE("svg: em and ex follow the computed font-size", "[host_tools][svg][units]") {
  // Default 16 px: 1em = 16 user units (1 mm each on the test page), 1ex = 8.
  auto pieces = drawn(import_page("<line x1=\"1ex\" x2=\"1em\"/>").job);
  REQUIRE(pieces.size() == 1);
  check_points(pieces[0], {on_page(8, 0), on_page(16, 0)});
  // font-size 20 on a group: 1em = 20, 0.5em = 10, 2ex = 20.
  pieces = drawn(import_page("<g font-size=\"20\"><line x1=\"1em\" y1=\"0.5em\" x2=\"2em\" y2=\"2ex\"/></g>").job);
  REQUIRE(pieces.size() == 1);
  check_points(pieces[0], {on_page(20, 10), on_page(40, 20)});
  // From the style attribute, on the element itself.
  pieces = drawn(import_page("<line style=\"font-size: 20px\" x2=\"1em\"/>").job);
  REQUIRE(pieces.size() == 1);
  check_points(pieces[0], {on_page(0, 0), on_page(20, 0)});
  // Relative font sizes: 150% and 2em of the parent's 20 are 30 and 40; "large" is 18; 5mm is 5 mm in user units (1 mm).
  pieces = drawn(import_page("<g font-size=\"20\"><line font-size=\"150%\" x2=\"1em\"/><line font-size=\"2em\" x2=\"1em\"/>"
                             "<line font-size=\"large\" x2=\"1em\"/><line font-size=\"10\" x2=\"1em\"/></g>")
                     .job);
  REQUIRE(pieces.size() == 4);
  CHECK(near(pieces[0].points[1], on_page(30, 0)));
  CHECK(near(pieces[1].points[1], on_page(40, 0)));
  CHECK(near(pieces[2].points[1], on_page(18, 0)));
  CHECK(near(pieces[3].points[1], on_page(10, 0)));
  // A circle r in em, inherited through <use>.
  pieces = drawn(import_page("<defs><circle id=\"c\" r=\"1em\"/></defs><use href=\"#c\" font-size=\"10\" x=\"50\" y=\"50\"/>").job);
  REQUIRE(pieces.size() == 4);
  CHECK(near(pieces[0].points[0], on_page(60, 50)));
}

TEST_CASE("svg: vw, vh, vmin and vmax are of the root viewport", "[host_tools][svg][units]") {
  // 200 mm x 100 mm without a viewBox: user unit = px; 10vw = 20 mm, 10vh = 10 mm, vmin = vh, vmax = vw;
  // (20, 10) - (20, 30) mm with y down, i.e. (20, 90) - (20, 70) on the machine.
  const auto pieces = pieces_of("width=\"200mm\" height=\"100mm\"",
                                "<line x1=\"10vw\" y1=\"10vh\" x2=\"10vmax\" y2=\"30vmin\"/><line x2=\"50vmin\"/>");
  REQUIRE(pieces.size() == 2);
  check_points(pieces[0], {{{20, 90, 0}}, {{20, 70, 0}}});
  check_points(pieces[1], {{{0, 100, 0}}, {{50, 100, 0}}});
}

TEST_CASE("svg: a relative length without a reference, or an unknown unit, is an error", "[host_tools][svg][units]") {
  const std::string no_size = "<svg xmlns=\"http://www.w3.org/2000/svg\">\n<line x2=\"50%\"/></svg>";
  check_rejected([&] { return parse_svg(no_size, "none.svg"); },
                 {"none.svg", 2, "<line> \"x2\"", Error::InvalidJob, "a percentage needs the viewport's size"});
  const std::string no_root = "<svg xmlns=\"http://www.w3.org/2000/svg\">\n<line x2=\"5vw\"/></svg>";
  check_rejected([&] { return parse_svg(no_root, "none.svg"); },
                 {"none.svg", 2, "<line> \"x2\"", Error::InvalidJob, "\"vw\" needs the root viewport's size"});
  check_rejected([&] { return import_page("<line x2=\"5ft\"/>"); },
                 {"test.svg", 2, "<line> \"x2\"", Error::InvalidJob, "unsupported unit \"ft\""});
  check_rejected([&] { return import_page("<line font-size=\"-2\" x2=\"1em\"/>"); },
                 {"test.svg", 2, "<line> \"font-size\"", Error::InvalidJob, "must not be negative"});
}
