// SPDX-License-Identifier: MIT
// <switch>, <symbol> and <svg> through <use>, style attributes and <style> sheets (display,
// visibility, stroke and fill), and XML entities in attribute values.
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/host/svg_import.hpp>

#include <support/load_error_checks.hpp>

#include "svg_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::testing;

namespace {

/// The x of the end of each drawn line, in order (lines from (0, y) to (x, y) identify themselves by x).
std::vector<double> line_ends(const std::string& body) {
  std::vector<double> out;
  for (const auto& piece : drawn(import_page(body).job)) out.push_back(piece.points.back()[0]);
  return out;
}

}  // namespace

TEST_CASE("svg: <switch> draws its first renderable child only", "[host_tools][svg][structure]") {
  CHECK(line_ends("<switch><line x2=\"1\"/><line x2=\"2\"/></switch>") == std::vector<double>{1});
  // title/desc and other namespaces are skipped; requiredExtensions (none supported) fails.
  CHECK(line_ends("<switch xmlns:i=\"urn:x\"><title>t</title><i:pgf/><foreignObject requiredExtensions=\"urn:x\"/>"
                  "<g><line x2=\"3\"/><line x2=\"4\"/></g><line x2=\"5\"/></switch>") == std::vector<double>{3, 4});
  // A chosen child hidden by display is not drawn, and nothing else is.
  CHECK(line_ends("<switch><line x2=\"6\" display=\"none\"/><line x2=\"7\"/></switch><line x2=\"8\"/>") == std::vector<double>{8});
}

TEST_CASE("svg: <symbol> and <svg> through <use> are viewports with their viewBox", "[host_tools][svg][structure]") {
  // Symbol viewBox 0 0 10 10 shown at (20, 30) in 40 x 20 (meet: scale 2, centred: x offset 10):
  // (0,0)-(10,0) -> (30, 30)-(50, 30).
  auto pieces = drawn(import_page("<defs><symbol id=\"s\" viewBox=\"0 0 10 10\"><line x2=\"10\"/></symbol></defs>"
                                  "<use href=\"#s\" x=\"20\" y=\"30\" width=\"40\" height=\"20\"/>")
                          .job);
  REQUIRE(pieces.size() == 1);
  check_points(pieces[0], {on_page(30, 30), on_page(50, 30)});
  // preserveAspectRatio none on the symbol: x scale 4, y scale 2; (0,0)-(10,10) -> (20,30)-(60,50).
  pieces = drawn(import_page("<defs><symbol id=\"s\" viewBox=\"0 0 10 10\" preserveAspectRatio=\"none\"><line x2=\"10\" y2=\"10\"/>"
                             "</symbol></defs><use href=\"#s\" x=\"20\" y=\"30\" width=\"40\" height=\"20\"/>")
                     .job);
  REQUIRE(pieces.size() == 1);
  check_points(pieces[0], {on_page(20, 30), on_page(60, 50)});
  // An <svg> with a viewBox: the use's width and height replace its own (80 x 80 -> 20 x 20: scale 2).
  pieces = drawn(import_page("<defs><svg id=\"v\" width=\"80\" height=\"80\" viewBox=\"0 0 10 10\"><line x2=\"10\"/></svg></defs>"
                             "<use href=\"#v\" x=\"5\" y=\"5\" width=\"20\" height=\"20\"/>")
                     .job);
  REQUIRE(pieces.size() == 1);
  check_points(pieces[0], {on_page(5, 5), on_page(25, 5)});
  // Without the use's size it keeps its own: scale 8.
  pieces = drawn(import_page("<defs><svg id=\"v\" width=\"80\" height=\"80\" viewBox=\"0 0 10 10\"><line x2=\"10\"/></svg></defs>"
                             "<use href=\"#v\" x=\"5\" y=\"5\"/>")
                     .job);
  REQUIRE(pieces.size() == 1);
  check_points(pieces[0], {on_page(5, 5), on_page(85, 5)});
}

TEST_CASE("svg: <style> sheets and style attributes decide display and visibility", "[host_tools][svg][css]") {
  const std::string sheet =
      "<style>/* hidden things */ .off { display: none } #gone, rect { visibility: hidden }\n"
      "line.x { display: none } @media print { line { display: none } } .on { visibility: visible }</style>";
  // .off hides x=1; #gone hides x=2; a compound selector never matches (x=3 drawn); @media is skipped.
  CHECK(line_ends(sheet + "<line class=\"a off\" x2=\"1\"/><line id=\"gone\" x2=\"2\"/><line class=\"x\" x2=\"3\"/>") ==
        std::vector<double>{3});
  // rect is hidden by the element rule; visibility is inherited but a child may be visible again.
  CHECK(line_ends(sheet + "<rect width=\"9\" height=\"9\"/><g visibility=\"hidden\"><line x2=\"4\"/><line class=\"on\" x2=\"5\"/></g>") ==
        std::vector<double>{5});
  // The style attribute beats the sheet, the sheet beats the attribute; id beats class.
  CHECK(line_ends("<style>.h { display: none } #s { display: inline } .v { visibility: visible }</style>"
                  "<line class=\"h\" style=\"display: inline\" x2=\"6\"/><line class=\"v\" visibility=\"hidden\" x2=\"7\"/>"
                  "<line class=\"h\" id=\"s\" x2=\"8\"/>") == std::vector<double>{6, 7, 8});
  // A hidden layer by style sheet (Inkscape writes the style attribute; other tools a class).
  CHECK(line_ends("<style>.layer-off{display:none}</style><g class=\"layer-off\"><line x2=\"9\"/></g><line x2=\"10\"/>") ==
        std::vector<double>{10});
}

TEST_CASE("svg: an element with neither stroke nor fill is invisible and not drawn", "[host_tools][svg][css]") {
  const auto result = import_page("<style>.guide { stroke: none }</style>"
                                  "<line x2=\"1\" fill=\"none\"/><line x2=\"2\" fill=\"none\" stroke=\"black\"/>"
                                  "<g stroke=\"red\"><line x2=\"3\" fill=\"none\"/><line class=\"guide\" x2=\"4\" fill=\"none\"/></g>"
                                  "<line x2=\"5\"/>");
  std::vector<double> ends;
  for (const auto& piece : drawn(result.job)) ends.push_back(piece.points.back()[0]);
  // x=1: no stroke (initial none) and no fill; x=4: the sheet's stroke none; x=5: the initial fill (black).
  CHECK(ends == std::vector<double>{2, 3, 5});
  REQUIRE(result.warnings.size() == 2);
  CHECK(result.warnings[0] == "test.svg:2: <line> is not drawn (stroke and fill are none: invisible)");
}

TEST_CASE("svg: markers and a white fill without stroke are drawn as the pen can, with one note each per file", "[host_tools][svg][css]") {
  // A renderer draws the arrowhead and hides the white background; the pen draws the shape's
  // outline alone, and says so once.
  const auto result = import_page("<style>.bg { fill: #FFF }</style>\n"
                                  "<rect class=\"bg\" width=\"20\" height=\"10\"/>\n"
                                  "<rect class=\"bg\" width=\"5\" height=\"5\"/>\n"
                                  "<path style=\"marker-end: url(#head)\" stroke=\"black\" fill=\"none\" d=\"M 0 0 L 10 0\"/>\n"
                                  "<line marker-start=\"url(#dot)\" stroke=\"black\" x2=\"3\"/>\n"
                                  "<rect fill=\"rgb(255, 255, 255)\" stroke=\"black\" width=\"1\" height=\"1\"/>\n"
                                  "<line marker-end=\"none\" stroke=\"black\" x2=\"4\"/>");
  CHECK(drawn(result.job).size() == 3 * 4 + 3);  // every shape is drawn: three rectangles of four sides, three lines
  REQUIRE(result.warnings.size() == 2);
  CHECK(result.warnings[0] ==
        "test.svg:3: <rect> has a white fill and no stroke, invisible on white paper, and is drawn as an outline (a background? noted once "
        "per file)");
  CHECK(result.warnings[1] == "test.svg:5: <path> marker-end url(#head): markers (arrowheads, dots) are not drawn (noted once per file)");
  // Markers are inherited; "none" on a shape turns them off there; white text (drawn in strokes) is no background.
  const auto inherited = import_page("<text fill=\"#fff\" x=\"1\" y=\"5\">L</text>\n"
                                     "<g marker-end=\"url(#a)\" stroke=\"black\">\n"
                                     "<path marker-end=\"none\" d=\"M 0 0 L 1 0\"/>\n"
                                     "<path d=\"M 0 0 L 2 0\"/>\n"
                                     "<rect fill=\"white\" stroke=\"none\" width=\"3\" height=\"3\"/></g>");
  REQUIRE(inherited.warnings.size() == 2);
  CHECK(inherited.warnings[0] == "test.svg:5: <path> marker-end url(#a): markers (arrowheads, dots) are not drawn (noted once per file)");
  CHECK(inherited.warnings[1].rfind("test.svg:6: <rect> has a white fill and no stroke", 0) == 0);
}

TEST_CASE("svg: entities and character references in attribute values", "[host_tools][svg][structure]") {
  // &#32; and &#x20; are spaces; &amp; in an id and in the reference to it.
  const auto pieces = drawn(import_page("<path d=\"M&#32;0 0&#x20;L 10&#x2C;0\"/>"
                                        "<defs><line id=\"a&amp;b\" x2=\"&#55;\"/></defs><use href=\"#a&amp;b\" y=\"&#x35;\"/>")
                                .job);
  REQUIRE(pieces.size() == 2);
  check_points(pieces[0], {on_page(0, 0), on_page(10, 0)});
  check_points(pieces[1], {on_page(0, 5), on_page(7, 5)});
  // &lt; &gt; &quot; &apos; in a style sheet's text and attribute values.
  CHECK(line_ends("<style>/* &lt;&gt; */ .q { display: none }</style><line class=\"q\" x2=\"1\" id=\"&quot;&apos;\"/><line x2=\"2\"/>") ==
        std::vector<double>{2});
}
