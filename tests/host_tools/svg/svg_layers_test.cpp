// SPDX-License-Identifier: MIT
// Inkscape layers: drawn layer by layer in document order with a LayerChange event between two
// layers, selected by label; expected segments worked out by hand on the 100 mm page of page().
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/host/page_layout.hpp>
#include <curvestep/host/svg_import.hpp>

#include "svg_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::testing;

namespace {

/// Two layers, "Red" with one stroke and "Blue" with two, and a stroke outside layers between them
/// in the file (drawn where the content outside layers first appears: between them).
const std::string two_layers =
    "<g inkscape:groupmode=\"layer\" inkscape:label=\"Red\" id=\"layer1\"><path d=\"M 10 10 L 20 10\"/></g>\n"
    "<path d=\"M 70 70 L 80 70\"/>\n"
    "<g inkscape:groupmode=\"layer\" inkscape:label=\"Blue\" id=\"layer2\"><path d=\"M 30 10 L 40 10 M 50 10 L 60 10\"/></g>\n";

std::string layered_page(const std::string& body) {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\" "
         "width=\"100mm\" height=\"100mm\" viewBox=\"0 0 100 100\">\n" + body + "</svg>\n";
}

void check_line(const Job& job, std::size_t k, bool rapid, const MachinePoint& from, const MachinePoint& to) {
  INFO("segment " << k);
  REQUIRE(k < job.segments.size());
  CHECK(job.segments[k].rapid() == rapid);
  CHECK(job.segments[k].start() == from);
  CHECK(job.segments[k].end() == to);
}

}  // namespace

TEST_CASE("svg layers: two Inkscape layers are drawn in layer order with one LayerChange between them", "[host_tools][svg]") {
  const SvgImport imported = parse_svg(layered_page(two_layers), "layers.svg");
  const Job& job = imported.job;
  // Red: rapid (0,0)->(10,90), line to (20,90). Outside layers: rapid to (70,30), line to (80,30).
  // Blue: rapid to (30,90), line to (40,90), rapid to (50,90), line to (60,90).
  REQUIRE(job.segments.size() == 8);
  check_line(job, 0, true, on_page(0, 100), on_page(10, 10));
  check_line(job, 1, false, on_page(10, 10), on_page(20, 10));
  check_line(job, 2, true, on_page(20, 10), on_page(70, 70));
  check_line(job, 3, false, on_page(70, 70), on_page(80, 70));
  check_line(job, 4, true, on_page(80, 70), on_page(30, 10));
  check_line(job, 5, false, on_page(30, 10), on_page(40, 10));
  check_line(job, 7, false, on_page(50, 10), on_page(60, 10));
  REQUIRE(job.events.size() == 2);
  CHECK(job.events[0].kind == JobEventKind::LayerChange);
  CHECK(job.events[0].before_segment == 2);  // after Red's last segment, before the travel on
  CHECK(job.events[0].text == "(outside layers)");
  CHECK(job.events[1].kind == JobEventKind::LayerChange);
  CHECK(job.events[1].before_segment == 4);
  CHECK(job.events[1].text == "Blue");
  CHECK(imported.layers == std::vector<std::string>{"Red", "(outside layers)", "Blue"});
}

TEST_CASE("svg layers: the optimiser reorders within a layer, never across layers", "[host_tools][svg]") {
  // Blue's second stroke (machine (1,1)..(2,1)) is the nearest to the origin, but Red comes first.
  const std::string body =
      "<g inkscape:groupmode=\"layer\" inkscape:label=\"Red\"><path d=\"M 10 10 L 20 10\"/></g>\n"
      "<g inkscape:groupmode=\"layer\" inkscape:label=\"Blue\"><path d=\"M 80 10 L 90 10\"/><path d=\"M 1 99 L 2 99\"/></g>\n";
  SvgOptions options;
  options.optimize = true;
  const Job job = parse_svg_job(layered_page(body), "layers.svg", options);
  REQUIRE(job.segments.size() == 6);
  check_line(job, 1, false, on_page(10, 10), on_page(20, 10));  // Red first, although (1,1) is nearer the origin
  // From (20,90): (80,90) is 60 mm away, (1,1) and (2,1) about 91 mm: Blue's first stroke in the file first.
  check_line(job, 3, false, on_page(80, 10), on_page(90, 10));
  check_line(job, 5, false, on_page(2, 99), on_page(1, 99));  // reversed: its end (2,1) is nearer (90,90)
  REQUIRE(job.events.size() == 1);
  CHECK(job.events[0].before_segment == 2);
  CHECK(job.events[0].text == "Blue");
}

TEST_CASE("svg layers: --layers draws the selected layers only, in document order", "[host_tools][svg]") {
  SvgOptions options;
  options.layers = {"Blue"};
  const SvgImport blue = parse_svg(layered_page(two_layers), "layers.svg", options);
  REQUIRE(blue.job.segments.size() == 4);
  check_line(blue.job, 0, true, on_page(0, 100), on_page(30, 10));
  check_line(blue.job, 3, false, on_page(50, 10), on_page(60, 10));
  CHECK(blue.job.events.empty());
  CHECK(blue.layers == std::vector<std::string>{"Blue"});

  options.layers = {"Blue", "Red"};  // the file's order, not the option's
  const SvgImport both = parse_svg(layered_page(two_layers), "layers.svg", options);
  REQUIRE(both.job.segments.size() == 6);
  check_line(both.job, 1, false, on_page(10, 10), on_page(20, 10));
  check_line(both.job, 2, true, on_page(20, 10), on_page(30, 10));
  REQUIRE(both.job.events.size() == 1);
  CHECK(both.job.events[0].before_segment == 2);
  CHECK(both.job.events[0].text == "Blue");
}

TEST_CASE("svg layers: an unknown layer is refused with the list of layers", "[host_tools][svg]") {
  SvgOptions options;
  options.layers = {"Green"};
  REQUIRE_THROWS_WITH(parse_svg(layered_page(two_layers), "layers.svg", options),
                      Catch::Contains("no layer is labelled \"Green\" (the layers are \"Red\", \"Blue\")"));
  REQUIRE_THROWS_WITH(parse_svg(page("<path d=\"M 1 1 L 2 2\"/>"), "plain.svg", options),
                      Catch::Contains("no layer is labelled \"Green\" (the drawing has no Inkscape layers)"));
  // A hidden layer exists but draws nothing.
  options.layers = {"Hidden"};
  REQUIRE_THROWS_WITH(parse_svg(layered_page(two_layers + "<g inkscape:groupmode=\"layer\" inkscape:label=\"Hidden\" "
                                                          "style=\"display:none\"><path d=\"M 1 1 L 2 2\"/></g>\n"),
                                "layers.svg", options),
                      Catch::Contains("the selected layers draw nothing"));
}

TEST_CASE("svg layers: a drawing without layers has no events, and nested groups stay in their layer", "[host_tools][svg]") {
  const SvgImport plain = parse_svg(page("<path d=\"M 10 10 L 20 10\"/><g><path d=\"M 30 10 L 40 10\"/></g>"), "plain.svg");
  CHECK(plain.job.events.empty());
  CHECK(plain.job.segments.size() == 4);
  CHECK(plain.layers == std::vector<std::string>{"(outside layers)"});
  // A sublayer is part of its top-level layer; a layer without a label is named by its id.
  const SvgImport nested = parse_svg(
      layered_page("<g inkscape:groupmode=\"layer\" id=\"top\"><g inkscape:groupmode=\"layer\" inkscape:label=\"sub\">"
                   "<path d=\"M 10 10 L 20 10\"/></g><path d=\"M 30 10 L 40 10\"/></g>\n"),
      "nested.svg");
  CHECK(nested.job.events.empty());
  CHECK(nested.layers == std::vector<std::string>{"top"});
}

TEST_CASE("svg layers: the page layout keeps the LayerChange events in place", "[host_tools][svg]") {
  Job job = parse_svg_job(layered_page(two_layers), "layers.svg");
  PageLayout layout;
  layout.page = parse_page_size("a4");
  layout.center = true;
  (void)lay_out_on_page(job, layout);
  REQUIRE(job.segments.size() == 8);
  REQUIRE(job.events.size() == 2);
  CHECK(job.events[0].before_segment == 2);
  CHECK(job.segments[2].rapid());
  CHECK(job.events[1].before_segment == 4);
  CHECK(job.segments[4].rapid());
  CHECK(job.events[1].text == "Blue");
}
