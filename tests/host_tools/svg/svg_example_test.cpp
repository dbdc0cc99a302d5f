// SPDX-License-Identifier: MIT
// The bundled example drawing imports into a connected job of curves, and optimising shortens travel.
#include <cmath>

#include <catch2/catch.hpp>

#include <curvestep/host/svg_import.hpp>

#include "svg_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::testing;

TEST_CASE("svg: the demo drawing imports as curves and the optimiser saves travel", "[host_tools][svg]") {
  const auto plain = load_svg(svg_example("curvestep_demo.svg"));
  SvgOptions options;
  options.optimize = true;
  const auto optimised = load_svg(svg_example("curvestep_demo.svg"), options);
  for (const auto* result : {&plain, &optimised}) {
    check_connected(result->job);
    CHECK(result->warnings.empty());
    // frame, wave, bumps, 5 petals, flower centre, 2 circles, ellipse, star, zig-zag
    CHECK(result->subpath_count == 14);
    std::size_t cubic = 0, quadratic = 0, rational = 0, lines = 0;
    for (const auto& source : result->job.sources) {
      if (source.type == SegmentType::Bezier && source.degree == 3) ++cubic;
      if (source.type == SegmentType::Bezier && source.degree == 2) ++quadratic;
      if (source.type == SegmentType::RationalBezier) ++rational;
      if (source.type == SegmentType::Line) ++lines;
    }
    CHECK(cubic == 4);
    CHECK(quadratic == 4);
    // frame 4 corners, 5 petals x 2 half ellipses x 2 quarters, 3 circles + 1 ellipse x 4 quarters
    CHECK(rational == 4 + 20 + 16);
    CHECK(lines == 4 + 10 + 5);
    // Everything lies on the 200 x 140 mm page.
    for (const auto& segment : result->job.segments) {
      for (int k = 0; k <= 8; ++k) {
        const auto p = segment.point(k / 8.0);
        CHECK(p[0] >= 0);
        CHECK(p[0] <= 200);
        CHECK(p[1] >= 0);
        CHECK(p[1] <= 140);
      }
    }
  }
  CHECK(plain.travel_saved_mm() == 0);
  CHECK(optimised.travel_document_mm == Approx(plain.travel_mm));
  CHECK(optimised.travel_mm < plain.travel_mm);
  CHECK(optimised.travel_saved_mm() == Approx(plain.travel_mm - optimised.travel_mm));
}
