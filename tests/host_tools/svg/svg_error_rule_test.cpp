// SPDX-License-Identifier: MIT
// SVG's error rule: by default a path is drawn up to its first path-data error and a points list
// up to its error or odd last number, with a warning naming file, line, element, attribute and
// character; strict import refuses the file as before.
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/host/svg_import.hpp>

#include <support/load_error_checks.hpp>

#include "svg_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::testing;

namespace {

SvgOptions strict_options() {
  SvgOptions options;
  options.strict = true;
  return options;
}

}  // namespace

TEST_CASE("svg: path data is drawn up to its first error, with a located warning", "[host_tools][svg][error-rule]") {
  // "M 0 0 L 10 0 L 10 10 X 5 5": the X is character 22; the two lines before it are drawn.
  const auto result = import_page("<path id=\"p\" d=\"M 0 0 L 10 0 L 10 10 X 5 5\"/>");
  const auto pieces = drawn(result.job);
  REQUIRE(pieces.size() == 2);
  check_points(pieces[0], {on_page(0, 0), on_page(10, 0)});
  check_points(pieces[1], {on_page(10, 0), on_page(10, 10)});
  REQUIRE(result.warnings.size() == 1);
  INFO(result.warnings[0]);
  CHECK(result.warnings[0].rfind("test.svg:2: <path id=\"p\"> \"d\": at character 22: expected a path command or a number, got \"X\"", 0) == 0);
  CHECK(contains(result.warnings[0], "drawn up to character 22"));
  // Strict: the same error refuses the file.
  check_rejected([] { return import_page("<path id=\"p\" d=\"M 0 0 L 10 0 L 10 10 X 5 5\"/>", strict_options()); },
                 {"test.svg", 2, "<path id=\"p\"> \"d\"", Error::InvalidJob, "at character 22: expected a path command or a number"});
}

TEST_CASE("svg: an incomplete command, a bad arc flag or a bad first command draw what comes before", "[host_tools][svg][error-rule]") {
  // A trailing L without numbers: the M subpath and its line.
  auto result = import_page("<path d=\"M 0 0 L 10 0 L\"/>");
  auto pieces = drawn(result.job);
  REQUIRE(pieces.size() == 1);
  check_points(pieces[0], {on_page(0, 0), on_page(10, 0)});
  CHECK(result.warnings.size() == 1);
  // A repetition cut short: "L 10 0 20" draws the first pair only.
  result = import_page("<path d=\"M 0 0 L 10 0 20\"/>");
  pieces = drawn(result.job);
  REQUIRE(pieces.size() == 1);
  check_points(pieces[0], {on_page(0, 0), on_page(10, 0)});
  // An arc flag of 2 (character 22): the line before it is drawn, the arc is not.
  result = import_page("<path d=\"M 0 0 L 10 0 A 5 5 0 2 1 20 0\"/>");
  pieces = drawn(result.job);
  REQUIRE(pieces.size() == 1);
  CHECK(contains(result.warnings.at(0), "at character 22: expected the large-arc flag (0 or 1)"));
  // A path starting without a moveto draws nothing; the next path is still drawn.
  result = import_page("<path d=\"L 10 10\"/>\n<line x2=\"5\"/>");
  pieces = drawn(result.job);
  REQUIRE(pieces.size() == 1);
  check_points(pieces[0], {on_page(0, 0), on_page(5, 0)});
  REQUIRE(result.warnings.size() == 1);
  CHECK(result.warnings[0].rfind("test.svg:2: <path> \"d\": at character 1: path data must begin with a moveto", 0) == 0);
  // A file whose only path fails at once has nothing to draw: still an error.
  check_rejected([] { return import_page("<path d=\"X\"/>"); },
                 {"test.svg", 1, "<svg>", Error::InvalidJob, "the drawing has no paths or shapes to draw"});
}

TEST_CASE("svg: an odd points count drops the last number, a points error keeps the pairs before it", "[host_tools][svg][error-rule]") {
  auto result = import_page("<polyline points=\"0,0 10,0 10\"/>");
  auto pieces = drawn(result.job);
  REQUIRE(pieces.size() == 1);
  check_points(pieces[0], {on_page(0, 0), on_page(10, 0)});
  REQUIRE(result.warnings.size() == 1);
  CHECK(result.warnings[0].rfind("test.svg:2: <polyline> \"points\": an odd count (5 numbers): the last number is dropped", 0) == 0);
  // A polygon closes over the pairs it has: (0,0) (10,0) (10,10) and back.
  result = import_page("<polygon points=\"0 0 10 0 10 10 7\"/>");
  CHECK(drawn(result.job).size() == 3);
  // A malformed list: the numbers before the error, in pairs (0,0 10,0 10,10; the lone 5 is dropped).
  result = import_page("<polyline points=\"0,0 10,0 10,10 5 x\"/>");
  pieces = drawn(result.job);
  REQUIRE(pieces.size() == 2);
  check_points(pieces[1], {on_page(10, 0), on_page(10, 10)});
  REQUIRE(result.warnings.size() == 1);
  CHECK(contains(result.warnings[0], "<polyline> \"points\": at character 18:"));
  // Strict refuses both.
  check_rejected([] { return import_page("<polyline points=\"0,0 10,0 10\"/>", strict_options()); },
                 {"test.svg", 2, "<polyline> \"points\"", Error::InvalidJob, "odd count (5 numbers)"});
  check_rejected([] { return import_page("<polyline points=\"0,0 10,0 10,10 5 x\"/>", strict_options()); },
                 {"test.svg", 2, "<polyline> \"points\"", Error::InvalidJob, "at character 18:"});
}

TEST_CASE("svg: the malformed test files import by default and name their error in a warning", "[host_tools][svg][error-rule]") {
  // bad_path_missing_number.svg: the first path is whole, the second stops at character 13.
  const auto result = load_svg(svg_data("bad_path_missing_number.svg"));
  REQUIRE(drawn(result.job).size() == 1);
  REQUIRE(result.warnings.size() == 1);
  CHECK(contains(result.warnings[0], "bad_path_missing_number.svg:4: <path id=\"wing\"> \"d\": at character 13: expected a coordinate"));
}

TEST_CASE("svg: a drawing with nothing to draw names what it skipped", "[host_tools][svg][error-rule]") {
  // Inkscape's flowed text (an SVG 1.2 draft no browser draws) alone: the error says so.
  const auto message = [](const std::string& body) {
    try {
      (void)import_page(body);
    } catch (const LoadError& error) {
      return std::string(error.what());
    }
    FAIL("imported: " << body);
    return std::string();
  };
  CHECK(message("<flowRoot><flowRegion><rect width=\"10\" height=\"10\"/></flowRegion><flowPara>x</flowPara></flowRoot>") ==
        "test.svg:1: <svg>: the drawing has no paths or shapes to draw (test.svg:2: <flowRoot> is not drawn (unknown element))");
  CHECK(message("<path d=\"X\"/>\n<image href=\"a.png\"/>")
            .rfind("test.svg:1: <svg>: the drawing has no paths or shapes to draw (test.svg:2: <path> \"d\": at character 1: ", 0) == 0);
  CHECK(contains(message("<path d=\"X\"/>\n<image href=\"a.png\"/>"), "; test.svg:3: <image> is not drawn)"));
  // The first three are named (a font-family note must not hide the cause), the rest counted.
  const std::string four = message("<text font-family=\"Arial\">\xE6\x97\xA5</text>\n<image/>\n<image/>\n<image/>");
  CHECK(contains(four, "(test.svg:2: <text> font-family Arial is not used"));
  CHECK(contains(four, "; test.svg:2: <text> has the character"));
  CHECK(contains(four, "; test.svg:3: <image> is not drawn; and 2 more warnings)"));
  // Nothing skipped: nothing to add.
  CHECK(message("<g/>") == "test.svg:1: <svg>: the drawing has no paths or shapes to draw");
}
