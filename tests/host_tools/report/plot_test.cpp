// SPDX-License-Identifier: MIT
// `curvestep plot`: the real program writes a well-formed SVG with the dashed rapid, both markers,
// a true scale bar and the right colours, and fails cleanly on a bad job or an unwritable file.
#include <array>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <tinyxml2.h>

#include <curvestep/host/job.hpp>
#include <curvestep/host/report.hpp>

#include "report_test_support.hpp"

namespace {

using report_test::run_curvestep;
using report_test::scratch;
using report_test::source;

using Pixel = std::array<double, 2>;

/// The polyline's "points" attribute as pixels.
std::vector<Pixel> points_of(const tinyxml2::XMLElement* polyline) {
  std::vector<Pixel> points;
  std::istringstream in(polyline->Attribute("points"));
  std::string pair;
  while (in >> pair) {
    const auto comma = pair.find(',');
    points.push_back({std::stod(pair.substr(0, comma)), std::stod(pair.substr(comma + 1))});
  }
  return points;
}

/// Every element named `name` below `root`, depth first.
void collect(const tinyxml2::XMLElement* root, const std::string& name, std::vector<const tinyxml2::XMLElement*>& out) {
  for (auto* e = root->FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
    if (name == e->Name()) out.push_back(e);
    collect(e, name, out);
  }
}

std::vector<const tinyxml2::XMLElement*> elements(const tinyxml2::XMLDocument& doc, const std::string& name) {
  std::vector<const tinyxml2::XMLElement*> out;
  collect(doc.RootElement(), name, out);
  return out;
}

std::string class_of(const tinyxml2::XMLElement* e) { return e->Attribute("class") != nullptr ? e->Attribute("class") : ""; }

/// Checks what both kinds of plot share for examples/jobs/every_type.json; returns the feed polylines' colours.
std::set<std::string> check_every_type_plot(const std::string& file) {
  tinyxml2::XMLDocument doc;
  REQUIRE(doc.LoadFile(file.c_str()) == tinyxml2::XML_SUCCESS);  // well formed
  REQUIRE(std::string(doc.RootElement()->Name()) == "svg");
  CHECK(std::string(doc.RootElement()->Attribute("xmlns")) == "http://www.w3.org/2000/svg");

  std::vector<const tinyxml2::XMLElement*> feeds, rapids;
  for (auto* p : elements(doc, "polyline")) (class_of(p) == "rapid" ? rapids : feeds).push_back(p);
  REQUIRE(!feeds.empty());
  REQUIRE(!rapids.empty());
  std::set<std::string> feed_colours;
  for (auto* f : feeds) {
    CHECK(f->Attribute("stroke-dasharray") == nullptr);  // feed moves are solid
    feed_colours.insert(f->Attribute("stroke"));
  }
  for (auto* r : rapids) CHECK(r->Attribute("stroke-dasharray") != nullptr);

  // The job starts at (0,0) and its last move is a rapid to (20,0): the markers sit on them.
  const tinyxml2::XMLElement* start = nullptr;
  const tinyxml2::XMLElement* end = nullptr;
  for (auto* c : elements(doc, "circle")) {
    if (class_of(c) == "start-marker") start = c;
  }
  for (auto* r : elements(doc, "rect")) {
    if (class_of(r) == "end-marker") end = r;
  }
  REQUIRE(start != nullptr);
  REQUIRE(end != nullptr);
  const Pixel start_px{start->DoubleAttribute("cx"), start->DoubleAttribute("cy")};
  const Pixel end_px{end->DoubleAttribute("x") + end->DoubleAttribute("width") / 2, end->DoubleAttribute("y") + end->DoubleAttribute("height") / 2};
  const auto last_rapid = points_of(rapids.back());
  REQUIRE(last_rapid.size() >= 2);
  CHECK(end_px[0] == Approx(last_rapid.back()[0]).margin(0.02));
  CHECK(end_px[1] == Approx(last_rapid.back()[1]).margin(0.02));
  // Start and end lie on one horizontal line (y = 0 in the job), the start 20 mm left of the end.
  CHECK(start_px[1] == Approx(end_px[1]).margin(0.02));
  const double pixels_per_mm = (end_px[0] - start_px[0]) / 20.0;
  REQUIRE(pixels_per_mm > 0);

  // The scale bar: 1, 2 or 5 × 10^k mm; its length in pixels matches the path's own scale.
  // The drawing spans 48 mm in y, so a quarter is 12 mm and the bar is 10 mm.
  const tinyxml2::XMLElement* bar = nullptr;
  for (auto* g : elements(doc, "g")) {
    if (class_of(g) == "scale-bar") bar = g;
  }
  REQUIRE(bar != nullptr);
  const auto* line = bar->FirstChildElement("line");
  const auto* label = bar->FirstChildElement("text");
  REQUIRE(line != nullptr);
  REQUIRE(label != nullptr);
  CHECK(std::string(label->GetText()) == "10 mm");
  CHECK(line->DoubleAttribute("x2") - line->DoubleAttribute("x1") == Approx(10 * pixels_per_mm).margin(0.05));
  return feed_colours;
}

}  // namespace

TEST_CASE("plot: without a machine the SVG colours feed moves by segment and dashes the rapid", "[host_tools][report]") {
  const std::string svg = scratch("plot_segments.svg");
  std::remove(svg.c_str());
  const auto r = run_curvestep("plot " + source("examples/jobs/every_type.json") + " -o " + svg);
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(r.output.find("wrote " + svg) != std::string::npos);
  const auto colours = check_every_type_plot(svg);
  // every_type.json has 7 feed segments (line, 2 arcs, bezier, rational, bspline, nurbs), 7 colours.
  CHECK(colours.size() == 7);
  const std::string text = report_test::read_file(svg);
  CHECK(text.find("speed-key") == std::string::npos);
  CHECK(text.find("segment-key") != std::string::npos);
}

TEST_CASE("plot: with a machine the SVG colours feed moves by planned speed", "[host_tools][report]") {
  const std::string svg = scratch("plot_speed.svg");
  std::remove(svg.c_str());
  const auto r = run_curvestep("plot " + source("examples/jobs/every_type.json") + " --machine " + source("examples/jobs/machine.json") + " -o " + svg);
  INFO(r.output);
  REQUIRE(r.status == 0);
  const auto colours = check_every_type_plot(svg);
  // The speed runs from rest to the feed: many shades of the scale.
  CHECK(colours.size() > 10);
  const std::string text = report_test::read_file(svg);
  CHECK(text.find("speed-key") != std::string::npos);
  // The feed speed of the job is 50 mm/s (machine feed), the fastest feed move; rapids do not count.
  CHECK(text.find(">50 mm/s (planned speed)<") != std::string::npos);
}

TEST_CASE("plot: a job that does not load fails with the file named and writes nothing", "[host_tools][report]") {
  const std::string svg = scratch("plot_bad.svg");
  std::remove(svg.c_str());
  const auto r = run_curvestep("plot " + source("tests/host_tools/jobs/data/bad_nan.json") + " -o " + svg);
  INFO(r.output);
  CHECK(r.status == 1);
  CHECK(r.output.find("curvestep: ") == 0);
  CHECK(r.output.find("bad_nan.json") != std::string::npos);
  CHECK(report_test::read_file(svg).empty());
}

TEST_CASE("plot: a missing job file or a missing -o is refused", "[host_tools][report]") {
  auto r = run_curvestep("plot /nonexistent/job.json -o " + scratch("never.svg"));
  CHECK(r.status != 0);
  CHECK(r.output.find("/nonexistent/job.json") != std::string::npos);
  r = run_curvestep("plot " + source("examples/jobs/every_type.json"));
  CHECK(r.status != 0);
  CHECK(r.output.find("output") != std::string::npos);
}

TEST_CASE("plot: an unwritable output file fails with exit status 1 and the file named", "[host_tools][report]") {
  const auto r = run_curvestep("plot " + source("examples/jobs/every_type.json") + " -o /nonexistent_directory/out.svg");
  INFO(r.output);
  CHECK(r.status == 1);
  CHECK(r.output == "curvestep: cannot write /nonexistent_directory/out.svg\n");
}

TEST_CASE("plot: path_plot_svg escapes the title and refuses an empty job", "[host_tools][report]") {
  const auto job = curvestep::host::parse_job(R"({"version": 1, "units": "mm", "segments": [{"type": "line", "points": [[0,0],[3,4]]}]})",
                                              "inline.json");
  curvestep::host::PathPlotOptions options;
  options.title = "a <b> & \"c\"";
  const std::string svg = curvestep::host::path_plot_svg(job, nullptr, options);
  tinyxml2::XMLDocument doc;
  REQUIRE(doc.Parse(svg.c_str()) == tinyxml2::XML_SUCCESS);
  CHECK(svg.find("a &lt;b&gt; &amp; &quot;c&quot;") != std::string::npos);
  // A job without a rapid has no dashed line.
  CHECK(svg.find("stroke-dasharray") == std::string::npos);
  curvestep::host::Job empty;
  empty.name = "empty.json";
  CHECK_THROWS_AS(curvestep::host::path_plot_svg(empty, nullptr, options), std::invalid_argument);
}
