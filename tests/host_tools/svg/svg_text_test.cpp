// SPDX-License-Identifier: MIT
// <text> and <tspan> drawn in the Hershey Roman simplex font. Expected coordinates are worked out by
// hand from the font's own numbers in /usr/share/hershey-fonts/rowmans.jhf (Debian hershey-fonts-data),
// one character per line, value = character - 'R', x right, y down, first pair the bearings:
//   'L' (Hershey 512) "HYLFL[ RL[X[":        bearings -10, 7 (advance 17); (-6,-12)-(-6,9), (-6,9)-(6,9)
//   'H' (Hershey 508) "G]KFK[ RYFY[ RKPYP":  bearings -11, 11 (advance 22); (-7,-12)-(-7,9), (7,-12)-(7,9), (-7,-2)-(7,-2)
//   'I' (Hershey 509) "NVRFR[":              bearings -4, 4 (advance 8); (0,-12)-(0,9)
//   ' ' (Hershey 699) "JZ":                  bearings -8, 8 (advance 16)
// With 1 em = 32 Hershey units and the baseline at Hershey y = 9, a point (hx, hy) of a glyph whose
// pen is at (x, y) lands at (x + (hx - left)·s, y + (hy - 9)·s), s = font-size / 32.
#include <fstream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/host/svg_import.hpp>

#include "svg_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::testing;

namespace {

/// The drawn pieces of a text on the 100 x 100 mm page (user unit 1 mm).
std::vector<SourceSegment> text_pieces(const std::string& body) { return drawn(import_page(body).job); }

/// 'L' of size 32 (s = 1) with its pen at (x, y): stem (x+4, y-21)-(x+4, y), foot (x+4, y)-(x+16, y).
void check_l(const std::vector<SourceSegment>& pieces, std::size_t first, double x, double y, double s = 1) {
  REQUIRE(pieces.size() >= first + 2);
  check_points(pieces[first], {on_page(x + 4 * s, y - 21 * s), on_page(x + 4 * s, y)});
  check_points(pieces[first + 1], {on_page(x + 4 * s, y), on_page(x + 16 * s, y)});
}

/// Imports `body` and checks it draws exactly one 'L' of size 32 per pen x in `pens`, on the baseline y = 50.
void check_ls(const std::string& body, const std::vector<double>& pens) {
  const auto pieces = text_pieces(body);
  REQUIRE(pieces.size() == 2 * pens.size());
  for (std::size_t i = 0; i < pens.size(); ++i) check_l(pieces, 2 * i, pens[i], 50);
}

}  // namespace

TEST_CASE("svg text: the glyph L at a known size and position", "[host_tools][svg][text]") {
  // font-size 32 user units = 32 mm: s = 1 mm per Hershey unit; the pen at (10, 50).
  const auto pieces = text_pieces("<text x=\"10\" y=\"50\" font-size=\"32\">L</text>");
  REQUIRE(pieces.size() == 2);
  check_l(pieces, 0, 10, 50);
  // font-size 16: s = 1/2.
  const auto half = text_pieces("<text x=\"10\" y=\"50\" font-size=\"16\">L</text>");
  REQUIRE(half.size() == 2);
  check_l(half, 0, 10, 50, 0.5);
  // No font-size: SVG's default 16 px = 16 user units here.
  const auto initial = text_pieces("<text x=\"10\" y=\"50\">L</text>");
  REQUIRE(initial.size() == 2);
  check_l(initial, 0, 10, 50, 0.5);
}

TEST_CASE("svg text: font-size and positions with units, on a page without viewBox", "[host_tools][svg][text]") {
  // No viewBox: the user unit is 1 px; 32mm of font-size gives s = 1 mm, x/y in mm land where they say.
  const std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100mm\" height=\"100mm\">"
                          "<text x=\"10mm\" y=\"50mm\" style=\"font-size:32mm\">L</text></svg>";
  const auto pieces = drawn(parse_svg(svg, "units.svg").job);
  REQUIRE(pieces.size() == 2);
  for (const auto& piece : pieces) {
    for (const auto& point : piece.points) INFO("(" << point[0] << ", " << point[1] << ")");
  }
  // Same coordinates as above; the conversion through px may leave a grid step or two.
  CHECK(near(pieces[0].points[0], on_page(14, 29), 2 * grid_mm));
  CHECK(near(pieces[0].points[1], on_page(14, 50), 2 * grid_mm));
  CHECK(near(pieces[1].points[1], on_page(26, 50), 2 * grid_mm));
}

TEST_CASE("svg text: advance widths and text-anchor", "[host_tools][svg][text]") {
  // "LL": the second L's pen is 17 to the right.
  check_ls("<text x=\"10\" y=\"50\" font-size=\"32\">LL</text>", {10, 27});
  // "HI" has the advance 22 + 8 = 30; middle shifts it by 15: H's pen at 35, I's at 57.
  const auto middle = text_pieces("<text x=\"50\" y=\"50\" font-size=\"32\" text-anchor=\"middle\">HI</text>");
  REQUIRE(middle.size() == 4);
  check_points(middle[0], {on_page(39, 29), on_page(39, 50)});   // 35 + (-7 + 11)
  check_points(middle[1], {on_page(53, 29), on_page(53, 50)});   // 35 + (7 + 11)
  check_points(middle[2], {on_page(39, 39), on_page(53, 39)});   // crossbar at 50 + (-2 - 9)
  check_points(middle[3], {on_page(61, 29), on_page(61, 50)});   // 57 + (0 + 4)
  // end: shifted by the whole advance 51 of "LLL" (the anchor is inherited from the group).
  check_ls("<g text-anchor=\"end\"><text x=\"60\" y=\"50\" font-size=\"32\">LLL</text></g>", {9, 26, 43});
}

TEST_CASE("svg text: tspans with their own position, offsets and font-size", "[host_tools][svg][text]") {
  const auto pieces = text_pieces(
      "<text x=\"10\" y=\"50\" font-size=\"32\">L<tspan x=\"60\" y=\"80\" font-size=\"16\">L</tspan>"
      "<tspan dx=\"5\" dy=\"-10\">L</tspan></text>");
  REQUIRE(pieces.size() == 6);
  check_l(pieces, 0, 10, 50);
  check_l(pieces, 2, 60, 80, 0.5);
  // After the half-size L the pen is at 60 + 8.5; dx 5, dy -10 move it to (73.5, 70); the text's size again.
  check_l(pieces, 4, 73.5, 70);
  // A tspan with x starts a new chunk with its own anchor; only the first value of a list is used.
  check_ls("<text x=\"10 90\" y=\"50\" font-size=\"32\">L<tspan x=\"60\" text-anchor=\"end\">L</tspan></text>", {10, 43});
}

TEST_CASE("svg text: transforms of the text and its parents", "[host_tools][svg][text]") {
  // rotate(90 10 50) maps (x, y) to (10 - (y - 50), 50 + (x - 10)); then translate(20, 0).
  // Stem (14, 29)-(14, 50) -> (31, 54)-(10, 54) -> (51, 54)-(30, 54); foot end (26, 50) -> (10, 66) -> (30, 66).
  const auto pieces = text_pieces(
      "<g transform=\"translate(20,0)\"><text transform=\"rotate(90 10 50)\" x=\"10\" y=\"50\" font-size=\"32\">L</text></g>");
  REQUIRE(pieces.size() == 2);
  check_points(pieces[0], {on_page(51, 54), on_page(30, 54)});
  check_points(pieces[1], {on_page(30, 54), on_page(30, 66)});
}

TEST_CASE("svg text: white space is collapsed unless xml:space is preserve", "[host_tools][svg][text]") {
  // "  L \n  L  " -> "L L": the second pen at 10 + 17 + 16.
  check_ls("<text x=\"10\" y=\"50\" font-size=\"32\">  L \n  L  </text>", {10, 43});
  // Trailing spaces do not count for the anchor: "L " with end anchor at 60 puts the pen at 43.
  check_ls("<text x=\"60\" y=\"50\" font-size=\"32\" text-anchor=\"end\">L   </text>", {43});
  // preserve: the two leading spaces advance 32.
  check_ls("<text xml:space=\"preserve\" x=\"10\" y=\"50\" font-size=\"32\">  L</text>", {42});
}

TEST_CASE("svg text: a character the font lacks is a gap the width of a space, with a warning", "[host_tools][svg][text]") {
  const SvgImport result = import_page("<text x=\"10\" y=\"50\" font-size=\"32\">\xC3\xA9L\xC3\xA9</text>");
  const auto pieces = drawn(result.job);
  REQUIRE(pieces.size() == 2);
  check_l(pieces, 0, 26, 50);  // after the gap of 16
  REQUIRE(result.warnings.size() == 1);  // once per file
  CHECK(result.warnings[0] ==
        "test.svg:2: <text> has characters \"\xC3\xA9\" (U+00E9) x2, which the Hershey Roman simplex font has no glyph for: "
        "each drawn as a gap the width of a space");
  // One character once: singular.
  const SvgImport one = import_page("<text x=\"10\" y=\"50\" font-size=\"32\">L\xC3\xA9</text>");
  REQUIRE(one.warnings.size() == 1);
  CHECK(one.warnings[0] ==
        "test.svg:2: <text> has the character \"\xC3\xA9\" (U+00E9), which the Hershey Roman simplex font has no glyph for: "
        "drawn as a gap the width of a space");
}

TEST_CASE("svg text: characters the font lacks in many elements give one warning at the first, counting each", "[host_tools][svg][text]") {
  // Ten distinct characters over three elements (U+00E0 .. U+00E9, the last twice): eight listed, two counted.
  const SvgImport result = import_page(
      "<text x=\"10\" y=\"50\">L</text>\n"
      "<text x=\"10\" y=\"60\">\xC3\xA0\xC3\xA1\xC3\xA2<tspan>\xC3\xA3\xC3\xA4</tspan></text>\n"
      "<text x=\"10\" y=\"70\">\xC3\xA5\xC3\xA6\xC3\xA7\xC3\xA8\xC3\xA9\xC3\xA9</text>");
  REQUIRE(result.warnings.size() == 1);
  CHECK(result.warnings[0] ==
        "test.svg:3: <text> has characters \"\xC3\xA0\" (U+00E0), \"\xC3\xA1\" (U+00E1), \"\xC3\xA2\" (U+00E2), \"\xC3\xA3\" (U+00E3), "
        "\"\xC3\xA4\" (U+00E4), \"\xC3\xA5\" (U+00E5), \"\xC3\xA6\" (U+00E6), \"\xC3\xA7\" (U+00E7) and 2 other distinct characters, "
        "which the Hershey Roman simplex font has no glyph for: each drawn as a gap the width of a space "
        "(11 characters in 3 elements, the first here)");
}

TEST_CASE("svg text: a text-only drawing imports, font-family gets one note, hidden text is not drawn", "[host_tools][svg][text]") {
  const SvgImport result = import_page(
      "<text x=\"10\" y=\"50\" font-family=\"Arial\">L</text>\n<text x=\"10\" y=\"80\" font-family=\"Times\">L</text>");
  CHECK(drawn(result.job).size() == 4);
  REQUIRE(result.warnings.size() == 1);
  CHECK(result.warnings[0] ==
        "test.svg:2: <text> font-family Arial is not used: text is drawn in the Hershey Roman simplex single-stroke font "
        "(noted once per file)");
  // Inherited from a group (Batik writes it on the root): the same note, at the text.
  const SvgImport inherited = import_page("<g style=\"font-family:'Dialog'\"><text x=\"10\" y=\"50\">L</text></g>");
  REQUIRE(inherited.warnings.size() == 1);
  CHECK(inherited.warnings[0] ==
        "test.svg:2: <text> font-family 'Dialog' is not used: text is drawn in the Hershey Roman simplex single-stroke font "
        "(noted once per file)");
  // A hidden tspan advances but draws nothing; display:none neither.
  check_ls("<text x=\"10\" y=\"50\" font-size=\"32\"><tspan visibility=\"hidden\">L</tspan><tspan display=\"none\">LL</tspan>L</text>",
           {27});
  // A hidden text draws nothing, except a tspan made visible again (visibility is inherited).
  check_ls("<text x=\"10\" y=\"50\" font-size=\"32\" visibility=\"hidden\">L<tspan visibility=\"visible\">L</tspan>L</text>", {27});
  // Only spaces: nothing to draw, which is still an error.
  CHECK_THROWS_WITH(import_page("<text x=\"10\" y=\"50\">   </text>"), Catch::Contains("no paths or shapes to draw"));
}

TEST_CASE("svg text: every glyph against the font file of the Debian package, when it is installed", "[host_tools][svg][text]") {
  // A second reading of rowmans.jhf, independent of the generator and the decoder: each line is a
  // glyph of ASCII 32 + i; after the 8-character header, pairs value = character - 'R'.
  std::ifstream font("/usr/share/hershey-fonts/rowmans.jhf");
  if (!font) {
    WARN("hershey-fonts-data is not installed: the glyph-by-glyph comparison is skipped");
    return;
  }
  std::string line;
  for (int code = 32; code <= 126 && std::getline(font, line); ++code) {
    const std::string data = line.substr(8);
    const double left = data[0] - 'R';
    // Expected lines with the pen at (10, 50) and s = 1: (10 + hx - left, 50 + hy - 9).
    std::vector<std::pair<MachinePoint, MachinePoint>> expected;
    std::optional<MachinePoint> previous;
    for (std::size_t i = 2; i + 1 < data.size(); i += 2) {
      if (data[i] == ' ' && data[i + 1] == 'R') {
        previous.reset();
        continue;
      }
      const MachinePoint point = on_page(10 + (data[i] - 'R') - left, 50 + (data[i + 1] - 'R') - 9);
      if (previous && !(*previous == point)) expected.emplace_back(*previous, point);
      previous = point;
    }
    if (expected.empty()) continue;  // the space
    const std::string character = code == '<' ? "&lt;" : code == '&' ? "&amp;" : std::string(1, static_cast<char>(code));
    INFO("character " << character);
    const auto pieces = text_pieces("<text x=\"10\" y=\"50\" font-size=\"32\">" + character + "</text>");
    REQUIRE(pieces.size() == expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) check_points(pieces[i], {expected[i].first, expected[i].second});
  }
}
