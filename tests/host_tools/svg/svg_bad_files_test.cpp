// SPDX-License-Identifier: MIT
// Every malformed drawing in data/ is rejected with a message naming file, line, element and cause.
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/core/error.hpp>
#include <curvestep/host/svg_import.hpp>

#include <support/load_error_checks.hpp>

#include "svg_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using curvestep::testing::check_bad_files;
using curvestep::testing::contains;
using curvestep::testing::svg_data;

namespace {

struct BadFile {
  const char* file;
  std::size_t line;
  const char* field;  ///< element and attribute, "" for the document
  Error code;
  const char* cause;  ///< a phrase of the message
};

}  // namespace

TEST_CASE("svg: each malformed file names the file, line, element and what is wrong", "[host_tools][svg]") {
  const BadFile cases[] = {
      {"bad_xml_mismatch.svg", 3, "", Error::InvalidJob, "invalid XML: an end tag does not match its start tag (XMLElement name=g)"},
      {"bad_xml_attribute.svg", 4, "", Error::InvalidJob, "invalid XML"},
      {"bad_xml_unclosed.svg", 4, "", Error::InvalidJob, "invalid XML"},
      {"bad_empty.svg", 0, "", Error::InvalidJob, "invalid XML: the file is empty"},
      {"bad_root.svg", 2, "<html>", Error::InvalidJob, "the root element is <html>, expected <svg>"},
      {"bad_path_missing_number.svg", 4, "<path id=\"wing\"> \"d\"", Error::InvalidJob,
       "at character 13: expected a coordinate, got the end of the data"},
      {"bad_path_nan.svg", 4, "<path> \"d\"", Error::InvalidJob, "at character 9: expected a coordinate, got \"NaN\""},
      {"bad_path_first_command.svg", 3, "<path> \"d\"", Error::InvalidJob,
       "at character 1: path data must begin with a moveto (M or m), got \"L\""},
      {"bad_path_flag.svg", 4, "<path> \"d\"", Error::InvalidJob, "at character 15: expected the large-arc flag (0 or 1), got \"2\""},
      {"bad_path_letter.svg", 3, "<path> \"d\"", Error::InvalidJob, "at character 15: expected a path command or a number, got \"X\""},
      {"bad_path_huge_number.svg", 3, "<path> \"d\"", Error::InvalidJob, "the number 1e400 is too large"},
      {"bad_out_of_range.svg", 4, "<circle id=\"sun\">", Error::FixedOverflow, "outside the Q16.16 range"},
      {"bad_huge_scale.svg", 4, "<path>", Error::FixedOverflow, "lands at (1e+06, -999900) mm, outside the Q16.16 range"},
      {"bad_arc_huge.svg", 3, "<path> \"d\"", Error::InvalidJob, "at character 31: the arc's ellipse is too large to compute (radii 1e+300 and 1e+300 for a chord of 10)"},
      {"bad_transform.svg", 3, "<g> \"transform\"", Error::InvalidJob, "rotate takes 1 or 3 numbers, got 2"},
      {"bad_transform_name.svg", 3, "<path> \"transform\"", Error::InvalidJob, "at character 1: unknown transform \"spin\""},
      {"bad_unit.svg", 1, "<svg> \"width\"", Error::InvalidJob, "unsupported unit \"ft\""},
      {"bad_points_odd.svg", 3, "<polyline> \"points\"", Error::InvalidJob, "odd count (5 numbers)"},
      {"bad_negative_radius.svg", 5, "<circle> \"r\"", Error::InvalidJob, "must not be negative, got -2"},
      {"bad_viewbox.svg", 1, "<svg> \"viewBox\"", Error::InvalidJob, "expected 4 numbers (min-x min-y width height), got 3"},
      {"bad_nothing_to_draw.svg", 2, "<svg>", Error::InvalidJob, "the drawing has no paths or shapes to draw"},
  };
  // Strict import: path data and points errors refuse the file (svg_error_rule_test.cpp: the default).
  SvgOptions strict;
  strict.strict = true;
  check_bad_files(cases, svg_data, [&](const auto& path) { return load_svg(path, strict); },
                  [](const BadFile& bad, const LoadError&, const std::string& path, const std::string& what) {
                    const std::string prefix = path + (bad.line > 0 ? ":" + std::to_string(bad.line) : std::string()) + ": ";
                    CHECK(what.rfind(prefix, 0) == 0);
                  });
}

TEST_CASE("svg: a missing file is a runtime error naming it", "[host_tools][svg]") {
  const auto path = svg_data("does_not_exist.svg");
  try {
    (void)import_svg(path);
    FAIL("no error");
  } catch (const std::runtime_error& error) {
    CHECK(contains(error.what(), "does_not_exist.svg"));
  }
}
