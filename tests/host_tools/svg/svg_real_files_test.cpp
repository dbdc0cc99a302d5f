// SPDX-License-Identifier: MIT
// Files as Inkscape and Illustrator write them: editor namespaces, layers, DOCTYPE with entities.
#include <catch2/catch.hpp>

#include <curvestep/host/svg_import.hpp>

#include "svg_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::testing;

TEST_CASE("svg: an Inkscape file with a translated layer and editor metadata", "[host_tools][svg]") {
  const auto result = load_svg(svg_data("inkscape_layer.svg"));
  CHECK(result.warnings.empty());
  const auto pieces = drawn(result.job);
  REQUIRE(pieces.size() == 1);
  // A4 page, user unit 1 mm; layer translate(-12.5, 3): m 42.5,47 -> (30, 50), machine y = 297 - y.
  CHECK(pieces[0].degree == 3);
  check_points(pieces[0], {{{30, 247, 0}}, {{40, 257, 0}}, {{50, 237, 0}}, {{60, 247, 0}}});
  CHECK(pieces[0].line == 11);
}

TEST_CASE("svg: an Illustrator file with a DOCTYPE and entity declarations", "[host_tools][svg]") {
  const auto result = load_svg(svg_data("illustrator_doctype.svg"));
  const auto pieces = drawn(result.job);
  REQUIRE(pieces.size() == 4);
  // 100 px page: 1 px = 25.4/96 mm; the circle starts at (60, 50) px.
  const double px = 25.4 / 96;
  check_points(pieces[0], {{{60 * px, 50 * px, 0}}, {{60 * px, 40 * px, 0}}, {{50 * px, 40 * px, 0}}});
}
