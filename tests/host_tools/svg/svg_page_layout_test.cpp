// SPDX-License-Identifier: MIT
// Page layout (vpype-style): page sizes, --fit with margins, --center, --landscape, --rotate and the
// check that the drawing fits the page; expected scales and offsets worked out by hand.
#include <cmath>
#include <stdexcept>
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/host/page_layout.hpp>
#include <curvestep/host/svg_import.hpp>

#include <support/load_error_checks.hpp>

#include "svg_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::testing;

namespace {

/// A 100 x 50 mm rectangle: machine x 0 .. 100, y 50 .. 100 (user (0,0)-(100,50) on the 100 mm page).
Job rectangle() { return import_page("<rect width=\"100\" height=\"50\"/>").job; }

PageLayout on(const std::string& page) {
  PageLayout layout;
  layout.page = parse_page_size(page);
  return layout;
}

void check_box(const PageLayoutReport& report, double x0, double x1, double y0, double y1) {
  INFO("box x " << report.low[0] << " .. " << report.high[0] << ", y " << report.low[1] << " .. " << report.high[1]);
  CHECK(report.low[0] == Approx(x0).margin(grid_mm));
  CHECK(report.high[0] == Approx(x1).margin(grid_mm));
  CHECK(report.low[1] == Approx(y0).margin(grid_mm));
  CHECK(report.high[1] == Approx(y1).margin(grid_mm));
}

}  // namespace

TEST_CASE("page: named sizes, WxH with units and margins", "[host_tools][svg][page]") {
  CHECK(parse_page_size("a4").width_mm == 210);
  CHECK(parse_page_size("A4").height_mm == 297);
  CHECK(parse_page_size("a3").width_mm == 297);
  CHECK(parse_page_size("letter").height_mm == Approx(279.4));
  CHECK(parse_page_size("legal").height_mm == Approx(355.6));
  const auto custom = parse_page_size("210x297mm");
  CHECK((custom.width_mm == 210 && custom.height_mm == 297));
  const auto inches = parse_page_size("8.5x11in");
  CHECK(inches.width_mm == Approx(215.9));
  CHECK(inches.height_mm == Approx(279.4));
  CHECK(parse_page_size("21cmx29.7cm").height_mm == Approx(297));
  for (const char* bad : {"a9", "10x10", "10x10ft", "x10mm", "0x10mm", ""}) {
    INFO(bad);
    CHECK_THROWS_AS(parse_page_size(bad), std::invalid_argument);
  }
  CHECK(parse_page_length("10") == 10);
  CHECK(parse_page_length("1cm") == 10);
  CHECK(parse_page_length("0.5in") == Approx(12.7));
  CHECK_THROWS_AS(parse_page_length("-1mm"), std::invalid_argument);
  CHECK_THROWS_AS(parse_page_length("1ft"), std::invalid_argument);
}

TEST_CASE("page: --fit on A4 with a 10 mm margin scales a 100 x 50 drawing by 1.9 and centres it", "[host_tools][svg][page]") {
  // Room 190 x 277: s = min(190/100, 277/50) = 1.9 -> 190 x 95, centred on (105, 148.5): x 10 .. 200, y 101 .. 196.
  Job job = rectangle();
  PageLayout layout = on("a4");
  layout.fit = true;
  layout.margin_mm = 10;
  const auto report = lay_out_on_page(job, layout);
  CHECK(report.scale == Approx(1.9));
  check_box(report, 10, 200, 101, 196);
  // The rect starts at its top-left corner (0, 100) -> (10, 196) and runs right to (200, 196).
  const auto pieces = drawn(job);
  REQUIRE(pieces.size() == 4);
  check_points(pieces[0], {{{10, 196, 0}}, {{200, 196, 0}}});
  check_connected(job);
  // The first segment is the rapid from the start (0, 0).
  CHECK(job.segments.front().rapid());
  CHECK(job.segments.front().start() == MachinePoint{});
}

TEST_CASE("page: --landscape, --center and --rotate", "[host_tools][svg][page]") {
  // Landscape A4 is 297 x 210: room 277 x 190, s = min(2.77, 3.8) = 2.77 -> 277 x 138.5 centred on (148.5, 105).
  Job job = rectangle();
  PageLayout layout = on("a4");
  layout.landscape = true;
  layout.fit = true;
  layout.margin_mm = 10;
  auto report = lay_out_on_page(job, layout);
  CHECK(report.page_width_mm == 297);
  CHECK(report.scale == Approx(2.77));
  check_box(report, 10, 287, 35.75, 174.25);
  // --center alone: 100 x 50 centred on (105, 148.5).
  job = rectangle();
  layout = on("a4");
  layout.center = true;
  report = lay_out_on_page(job, layout);
  CHECK(report.scale == 1);
  check_box(report, 55, 155, 123.5, 173.5);
  // --rotate 90 (clockwise) about the drawing's centre (50, 75): 50 wide, 100 tall; the top-left
  // corner (0, 100), (-50, 25) from the centre, turns to (25, 50): (75, 125), the top-right corner.
  job = rectangle();
  layout = PageLayout{};
  layout.rotate_deg = 90;
  report = lay_out_on_page(job, layout);
  check_box(report, 25, 75, 25, 125);
  CHECK(near(drawn(job)[0].points[0], MachinePoint{{75, 125, 0}}));
  // 180: the top-left corner goes to the bottom-right (100, 50).
  job = rectangle();
  layout.rotate_deg = 180;
  (void)lay_out_on_page(job, layout);
  CHECK(near(drawn(job)[0].points[0], MachinePoint{{100, 50, 0}}));
}

TEST_CASE("page: curves stay exact under the layout and their tight extent is fitted", "[host_tools][svg][page]") {
  // Circle r = 10 at (50, 50): extent 40 .. 60 both ways; A4 fit margin 10: s = min(190/20, 277/20) = 9.5,
  // radius 95 about (105, 148.5).
  Job job = import_page("<circle cx=\"50\" cy=\"50\" r=\"10\"/>").job;
  PageLayout layout = on("a4");
  layout.fit = true;
  layout.margin_mm = 10;
  const auto report = lay_out_on_page(job, layout);
  CHECK(report.scale == Approx(9.5));
  check_box(report, 10, 200, 53.5, 243.5);
  for (const auto& segment : job.segments) {
    if (segment.rapid()) continue;
    for (int k = 0; k <= 8; ++k) {
      const auto p = segment.point(k / 8.0);
      CHECK(std::hypot(p[0] - 105, p[1] - 148.5) == Approx(95).margin(95 * 4e-7 + 1e-4));
    }
  }
}

TEST_CASE("page: a drawing that leaves the page is refused with the overflow in mm", "[host_tools][svg][page]") {
  // A 300 mm line on A4 (210 wide): 90 mm right of the page.
  Job job = parse_svg("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"400mm\" height=\"100mm\" viewBox=\"0 0 400 100\">"
                      "<line y1=\"50\" x2=\"300\" y2=\"50\"/></svg>",
                      "wide.svg")
                .job;
  const auto error = check_rejected([&] { return lay_out_on_page(job, on("a4")); },
                                    {"wide.svg", 0, "page", Error::OutsideTravel, "it reaches 90 mm right of the page"});
  REQUIRE(error);
  CHECK(contains(error->message(), "a4 (210 x 297 mm)"));
  // --fit makes it fit; --landscape alone does not (297 wide: 3 mm right).
  PageLayout landscape = on("a4");
  landscape.landscape = true;
  check_rejected([&] { return lay_out_on_page(job, landscape); },
                 {"wide.svg", 0, "page", Error::OutsideTravel, "3 mm right of the page"});
  PageLayout fit = on("a4");
  fit.fit = true;
  CHECK_NOTHROW(lay_out_on_page(job, fit));
  // Options that do not go together.
  Job other = rectangle();
  PageLayout centred;
  centred.center = true;
  CHECK_THROWS_AS(lay_out_on_page(other, centred), std::invalid_argument);
  PageLayout turned;
  turned.rotate_deg = 45;
  CHECK_THROWS_AS(lay_out_on_page(other, turned), std::invalid_argument);
}
