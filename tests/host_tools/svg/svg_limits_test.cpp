// SPDX-License-Identifier: MIT
// SVG limits and messages (issue 19 items 7 and 9): <use> fan-out is bounded in total, and ids
// quoted in errors are escaped and cut short.
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/host/load_error.hpp>
#include <curvestep/host/svg_import.hpp>

using namespace curvestep;
using namespace curvestep::host;

namespace {

/// A drawing whose groups g1..g`levels` each hold `fan` <use> of the group below; g0 holds one
/// path; the page uses the top group `top_uses` times. It draws top_uses * fan^levels paths.
std::string fan_out(int levels, int fan, int top_uses) {
  std::string text = R"(<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" width="100mm" height="100mm" viewBox="0 0 100 100">)"
                     "\n<defs>\n<g id=\"g0\"><path d=\"M 1 1 L 2 2\"/></g>\n";
  for (int level = 1; level <= levels; ++level) {
    text += "<g id=\"g" + std::to_string(level) + "\">";
    for (int k = 0; k < fan; ++k) text += "<use href=\"#g" + std::to_string(level - 1) + "\"/>";
    text += "</g>\n";
  }
  text += "</defs>\n";
  for (int k = 0; k < top_uses; ++k) text += "<use href=\"#g" + std::to_string(levels) + "\"/>\n";
  return text + "</svg>\n";
}

}  // namespace

TEST_CASE("svg limits: nested <use> expanding past the total limit is refused at the outer use", "[host_tools][svg][limits]") {
  // 2 x 10^5 paths from a 1.5 KB file (the limit is 100 000 expanded elements).
  const std::string text = fan_out(5, 10, 2);
  CHECK(text.size() < 2000);
  try {
    (void)parse_svg(text, "fan.svg");
    FAIL("the drawing loaded");
  } catch (const LoadError& e) {
    CHECK(e.location().file == "fan.svg");
    CHECK_THAT(e.message(), Catch::Contains("expand to more than 100000 elements"));
    CHECK(e.location().line >= 10);  // one of the page's <use> lines, after the defs
  }
}

TEST_CASE("svg limits: a moderate <use> fan-out still loads every copy", "[host_tools][svg][limits]") {
  const SvgImport imported = parse_svg(fan_out(2, 10, 3), "fan.svg");  // 300 paths
  // Each copy is the same one-line path: 300 line segments plus the travel between them.
  std::size_t lines = 0;
  for (const auto& segment : imported.job.segments) if (!segment.rapid()) ++lines;
  CHECK(lines == 300);
}

TEST_CASE("svg limits: an id with control characters is quoted escaped and short", "[host_tools][svg][messages]") {
  const std::string long_id = "&#27;[2J" + std::string(5000, 'x');
  const std::string text = R"(<svg xmlns="http://www.w3.org/2000/svg" width="10mm" height="10mm" viewBox="0 0 10 10">)"
                           "<path d=\"M 0 0 L 1 1\"/><use href=\"#" + long_id + "\"/></svg>";
  try {
    (void)parse_svg(text, "escape.svg");
    FAIL("the drawing loaded");
  } catch (const LoadError& e) {
    const std::string what = e.what();
    CHECK(what.find('\x1b') == std::string::npos);
    CHECK_THAT(what, Catch::Contains("no element has id \"\\x1b[2Jxxx"));
    CHECK(what.size() < 200);
  }
}
