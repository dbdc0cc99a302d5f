// SPDX-License-Identifier: MIT
// G-code import: the conformance programs of tests/gcode/data become the expected paths, and every
// error names file:line:column and the word. Expected geometry is computed by hand from
// LinuxCNC's documented formulas; the NURBS block is checked against an independent Cox-de Boor
// evaluation written here.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstddef>
#include <iomanip>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <curvestep/host/flatten.hpp>
#include <curvestep/host/gcode_import.hpp>

#include "support/numeric.hpp"

using namespace curvestep;
using namespace curvestep::host;

namespace {

const std::string data = CURVESTEP_GCODE_TEST_DATA;
/// Q16.16 quantisation moves a coordinate by at most 2^-17 mm.
constexpr double grid_tolerance = 1.0 / 131072.0;

bool near(const MachinePoint& a, const MachinePoint& b, double tolerance) {
  for (std::size_t i = 0; i < 3; ++i) {
    if (!(std::fabs(a[i] - b[i]) <= tolerance)) return false;
  }
  return true;
}

MachinePoint pt(double x, double y, double z = 0) { return MachinePoint{{x, y, z}}; }

/// The LoadError of parsing `text`.
LoadError error_of(const std::string& text, const std::string& name = "inline.ngc") {
  try {
    (void)parse_gcode_job(text, name);
  } catch (const LoadError& e) {
    return e;
  }
  FAIL("no LoadError for: " << text);
  return LoadError({}, "", Error::InvalidArgument);
}

LoadError file_error_of(const std::string& path) {
  try {
    (void)import_gcode(path);
  } catch (const LoadError& e) {
    return e;
  }
  FAIL("no LoadError for " << path);
  return LoadError({}, "", Error::InvalidArgument);
}

/// Cox-de Boor basis N_{i,p}(u) on `knots` (right-open spans; the caller avoids the domain end).
double basis(const std::vector<double>& knots, std::size_t i, std::size_t p, double u) {
  if (p == 0) return knots[i] <= u && u < knots[i + 1] ? 1.0 : 0.0;
  double value = 0;
  if (knots[i + p] > knots[i]) value += (u - knots[i]) / (knots[i + p] - knots[i]) * basis(knots, i, p - 1, u);
  if (knots[i + p + 1] > knots[i + 1]) {
    value += (knots[i + p + 1] - u) / (knots[i + p + 1] - knots[i + 1]) * basis(knots, i + 1, p - 1, u);
  }
  return value;
}

}  // namespace

TEST_CASE("gcode import: lines, G20 inches, G91 increments and feeds", "[gcode][import]") {
  const Job job = import_gcode(data + "/lines_units.ngc");
  CHECK(job.name == data + "/lines_units.ngc");
  REQUIRE(job.sources.size() == 5);  // the line after M2 is not read
  REQUIRE(job.segments.size() == 5);
  CHECK(job.sources[0].type == SegmentType::Rapid);
  CHECK(job.sources[0].line == 3);
  CHECK(job.segments[0].rapid());
  CHECK(job.segments[0].end() == pt(10, 5));
  CHECK(job.sources[1].type == SegmentType::Line);
  CHECK(job.segments[1].end() == pt(10, 5, -1));
  CHECK(job.segments[1].feed_mm_per_s() == 10.0);  // F600 mm/min
  CHECK(job.segments[2].end() == pt(12, 2, -1));   // G91 X2 Y-3
  CHECK(near(job.segments[3].end(), pt(25.4, 12.7, -1), grid_tolerance));  // G20 X1 Y0.5
  CHECK(job.segments[3].feed_mm_per_s() == 277436.0 / 65536.0);  // F10 in/min = 4.2333 mm/s: round(277435.73) / 65536
  CHECK(job.sources[3].line == 6);
  CHECK(job.segments[4].rapid());
  CHECK(near(job.segments[4].end(), pt(25.4, 12.7, 5), grid_tolerance));
  for (std::size_t i = 1; i < job.segments.size(); ++i) CHECK(job.segments[i].start() == job.segments[i - 1].end());
}

TEST_CASE("gcode import: arcs in centre and radius form, full circles, helices, G91.1 and G90.1", "[gcode][import]") {
  const Job job = import_gcode(data + "/arcs.ngc");
  REQUIRE(job.segments.size() == 7);
  const double quarter = std::numbers::pi / 2;
  const double r = 10;
  const double diagonal = r * std::sqrt(0.5);
  struct Expected {
    MachinePoint start, end;
    double sweep;
    MachinePoint middle;  // point at u = 0.5
  };
  const std::array<Expected, 6> expected{{
      {pt(10, 0), pt(0, 10), quarter, pt(diagonal, diagonal)},
      {pt(0, 10), pt(-10, 0), quarter, pt(-diagonal, diagonal)},
      {pt(-10, 0), pt(-10, 0), -4 * quarter, pt(10, 0)},
      {pt(-10, 0), pt(-10, 0, -3), 12 * quarter, pt(10, 0, -1.5)},  // 1.5 of 3 turns, half-way down
      {pt(-10, 0, -3), pt(0, 10, -3), -quarter, pt(-diagonal, diagonal, -3)},
      {pt(0, 10, -3), pt(10, 0, -3), -quarter, pt(diagonal, diagonal, -3)},
  }};
  CHECK(job.segments[0].rapid());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    INFO("arc " << i);
    const PathSegment& s = job.segments[i + 1];
    REQUIRE(s.kind() == SegmentKind::Arc);
    CHECK(job.sources[i + 1].type == SegmentType::Arc);
    CHECK(job.sources[i + 1].line == i + 4);
    CHECK(near(s.start(), expected[i].start, grid_tolerance));
    CHECK(near(s.end(), expected[i].end, grid_tolerance));
    CHECK(near(s.arc_center(), pt(0, 0, expected[i].start[2]), grid_tolerance));
    CHECK(s.arc_radius() == Approx(r).margin(1e-5));
    CHECK(s.arc_sweep_rad() == Approx(expected[i].sweep).margin(1e-9));
    CHECK(near(s.point(0.5), expected[i].middle, 1e-5));
    CHECK(s.feed_mm_per_s() == 20.0);  // F1200 mm/min
  }
}

TEST_CASE("gcode import: G5 series with tangent continuation and G5.1", "[gcode][import][spline]") {
  const Job job = import_gcode(data + "/g5_series.ngc");
  REQUIRE(job.segments.size() == 4);  // G0 X0 Y0 does not move
  const std::array<std::vector<MachinePoint>, 4> control{{
      {pt(0, 0), pt(0, 3), pt(1, -2), pt(1, 1)},  // P0, P0+(I,J), P1+(P,Q), P1
      {pt(1, 1), pt(1, 4), pt(2, -1), pt(2, 2)},  // I J omitted: -(P,Q) of the block before = (0,3)
      {pt(2, 2), pt(2, 5), pt(5, 1), pt(4, 2)},   // again (0,3), although this block's P Q are (1,-1)
      {pt(4, 2), pt(5, 4), pt(6, 2)},             // G5.1: P0, P0+(I,J), P1
  }};
  for (std::size_t i = 0; i < control.size(); ++i) {
    INFO("segment " << i);
    const PathSegment& s = job.segments[i];
    REQUIRE(s.kind() == SegmentKind::Bezier);
    CHECK(job.sources[i].type == SegmentType::Bezier);
    CHECK(job.sources[i].degree == control[i].size() - 1);
    CHECK(job.sources[i].points == control[i]);
    const auto points = s.polynomial().control_points();
    REQUIRE(points.size() == control[i].size());
    for (std::size_t k = 0; k < points.size(); ++k) CHECK(points[k] == control[i][k]);
  }
  // The documented curve's midpoint: (P0 + 3 P1 + 3 P2 + P3) / 8 = (0.5, 0.5).
  CHECK(near(job.segments[0].point(0.5), pt(0.5, 0.5), 1e-12));
  // Tangent continuity at the joins: the end tangent of one equals the start tangent of the next.
  for (std::size_t i = 0; i + 2 < control.size(); ++i) {
    CHECK(near(job.segments[i].derivative(1, 1), job.segments[i + 1].derivative(0, 1), 1e-12));
  }
}

TEST_CASE("gcode import: the NURBS block matches an independent Cox-de Boor evaluation", "[gcode][import][nurbs]") {
  const Job job = import_gcode(data + "/nurbs.ngc");
  REQUIRE(job.sources.size() == 1);
  const SourceSegment& source = job.sources[0];
  CHECK(source.type == SegmentType::Nurbs);
  CHECK(source.line == 9);  // the G5.3 line
  CHECK(source.degree == 2);
  const std::vector<MachinePoint> points{pt(0, 0), pt(0, 1), pt(2, 2), pt(2, 0), pt(0, 0)};
  const std::vector<double> weights{1, 1, 1, 1, 2};
  const std::vector<double> knots{0, 0, 0, 1, 2, 3, 3, 3};
  CHECK(source.points == points);
  CHECK(source.weights == weights);
  CHECK(source.knots == knots);
  CHECK(source.piece_count() == 3);
  CHECK(job.segments.size() == 3);
  for (const double u : {0.0, 0.25, 0.5, 1.0, 1.5, 2.0, 2.7, 2.999}) {
    INFO("u = " << u);
    MachinePoint numerator{};
    double denominator = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double b = basis(knots, i, 2, u) * weights[i];
      for (std::size_t axis = 0; axis < 3; ++axis) numerator[axis] += b * points[i][axis];
      denominator += b;
    }
    const MachinePoint expected = pt(numerator[0] / denominator, numerator[1] / denominator);
    CHECK(near(evaluate_segment(job, 0, u), expected, 2e-5));
  }
  CHECK(job.segments.front().start() == pt(0, 0));
  CHECK(job.segments.back().end() == pt(0, 0));
  // F10 mm/min = 0.16667 mm/s, on the Q16.16 grid: round(10922.67) = 10923 / 65536.
  CHECK(job.segments.front().feed_mm_per_s() == 10923.0 / 65536.0);
}

TEST_CASE("gcode import: the CNC example loads", "[gcode][import]") {
  const Job job = import_gcode(std::string(CURVESTEP_GCODE_EXAMPLES) + "/cnc_pocket.ngc");
  CHECK(job.sources.size() > 10);
  bool arc = false;
  bool cubic = false;
  bool nurbs = false;
  for (const auto& s : job.sources) {
    arc = arc || s.type == SegmentType::Arc;
    cubic = cubic || (s.type == SegmentType::Bezier && s.degree == 3);
    nurbs = nurbs || s.type == SegmentType::Nurbs;
  }
  CHECK(arc);
  CHECK(cubic);
  CHECK(nurbs);
  for (std::size_t i = 1; i < job.segments.size(); ++i) CHECK(job.segments[i].start() == job.segments[i - 1].end());
}

TEST_CASE("gcode import: the fuzz regressions load as connected jobs", "[gcode][import][fuzz]") {
  // disconnected_after_g5_1_comment.ngc: line 13, "N100 G5.1 I-10 J0 X0(...)", starts at the end of
  // line 12's G5, (10, 40, -1); its control points are P0 = (10, 40, -1), P0 + (-10, 0) = (0, 40, -1)
  // and P1 = (0, 40, -1). It was dropped as "does not move", so line 14 started 10 mm away.
  const Job job = import_gcode(std::string(CURVESTEP_GCODE_FUZZ_REGRESSIONS) + "/disconnected_after_g5_1_comment.ngc");
  REQUIRE(!job.segments.empty());
  for (std::size_t i = 1; i < job.segments.size(); ++i) {
    INFO("segment " << i);
    CHECK(job.segments[i].start() == job.segments[i - 1].end());
  }
  const SourceSegment* quadratic = nullptr;
  for (const auto& s : job.sources) {
    if (s.line == 13) quadratic = &s;
  }
  REQUIRE(quadratic != nullptr);
  CHECK(quadratic->type == SegmentType::Bezier);
  REQUIRE(quadratic->points.size() == 3);
  CHECK(quadratic->points[0] == pt(10, 40, -1));
  CHECK(quadratic->points[1] == pt(0, 40, -1));
  CHECK(quadratic->points[2] == pt(0, 40, -1));
  CHECK(job.segments.back().end() == pt(6, 2, -1));  // "G5.1 I1 J2 X6 Y2", then M2 ends the program
}

TEST_CASE("gcode import: error programs name file, line, column and word", "[gcode][import][errors]") {
  struct Case {
    const char* file;
    std::size_t line, column;
    const char* word;
    Error code;
  };
  const Case cases[] = {
      {"error_g5_no_tangent.ngc", 3, 3, "G5", Error::GcodeSplineNoTangent},
      {"error_arc_radius.ngc", 2, 5, "G3", Error::GcodeArcRadiusMismatch},
      {"error_g5_plane.ngc", 2, 1, "G5", Error::GcodeSplineNotG17},
      {"error_unclosed_nurbs.ngc", 2, 1, "G5.2", Error::GcodeNurbsBlock},
  };
  for (const auto& c : cases) {
    INFO(c.file);
    const std::string path = data + "/" + c.file;
    const LoadError e = file_error_of(path);
    CHECK(e.code() == c.code);
    CHECK(e.location().file == path);
    CHECK(e.location().line == c.line);
    CHECK(e.location().column == c.column);
    CHECK(e.location().field == c.word);
    const std::string prefix = path + ":" + std::to_string(c.line) + ":" + std::to_string(c.column) + ": " + c.word + ": ";
    CHECK(std::string(e.what()).starts_with(prefix));
  }
}

TEST_CASE("gcode import: a radius mismatch reports both radii", "[gcode][import][errors]") {
  const LoadError e = file_error_of(data + "/error_arc_radius.ngc");
  // start (10,0), centre (0,0), end (0,10.03): radii 10 and 10.03 (0.03 mm: beyond LinuxCNC's 0.0283 mm and 0.1 %).
  CHECK_THAT(e.what(), Catch::Contains("start radius 10 mm, end radius 10.03 mm"));
  const LoadError zero = error_of("G2 X1 Y1 I0 J0\n");
  CHECK(zero.code() == Error::GcodeArcRadiusMismatch);
  CHECK_THAT(zero.what(), Catch::Contains("zero-radius arc"));
  // Under a work offset with absolute centres (G90.1) the radii are those of the arc that was
  // refused: start (10, 0) and centre (0, 0) of G54, shifted by 100 mm, radius 10 (not 110).
  const LoadError shifted = error_of("G21 G90 G10 L2 P1 X100\nG54 G0 X10 Y0\nG90.1 G2 X-10.03 Y0 I0 J0 F100\n");
  CHECK_THAT(shifted.what(), Catch::Contains("start radius 10 mm, end radius 10.0"));
  // In G18 the radii are measured in the Z-X plane: start (x 0, z 10) about (0, 0) and end (x 10.03, z 0).
  const LoadError zx = error_of("G21 G90 G18 G0 Z10\nG2 X10.03 Z0 I0 K-10 F100\n");
  CHECK_THAT(zx.what(), Catch::Contains("start radius 10 mm, end radius 10.0"));
}

TEST_CASE("gcode import: every G-code error code reaches the user with its word", "[gcode][import][errors]") {
  struct Case {
    const char* text;
    std::size_t line, column;
    const char* word;
    Error code;
  };
  const Case cases[] = {
      {"G1 X1 F100\nG1 A5\n", 2, 4, "A5", Error::GcodeUnsupportedWord},
      {"G1 X1 F100\nG2 X1 Y1 I1 E100\n", 2, 13, "E100", Error::GcodeUnsupportedWord},
      {"G95\n", 1, 1, "G95", Error::GcodeUnsupportedWord},
      {"G93 G1 X1\n", 1, 5, "G1", Error::GcodeMissingWord},
      {"G1 X12345678901234567.5\n", 1, 4, "X12345678901234567.5", Error::GcodeBadNumber},
      {"G1 X99999\n", 1, 4, "X99999", Error::GcodeBadNumber},
      {"G5 I1 J1 P1 X1 Y1\n", 1, 1, "G5", Error::GcodeMissingWord},
      {"X1\n", 1, 1, "X1", Error::GcodeMissingWord},
      {"G0 X1\nG3 X0 Y1.1 I-1\n", 2, 1, "G3", Error::GcodeArcRadiusMismatch},
      {"G2 X10 R2\n", 1, 8, "R2", Error::GcodeArcRadiusMismatch},
      {"G19\nG5.1 I1 X1\n", 2, 1, "G5.1", Error::GcodeSplineNotG17},
      {"G5.1 I1 X1 Y1\n", 1, 1, "G5.1", Error::GcodeMissingWord},  // LinuxCNC: both I and J
      {"G5 P0 Q-3 X2 Y2\n", 1, 1, "G5", Error::GcodeSplineNoTangent},
      {"G1 X1 $\n", 1, 7, "$", Error::GcodeSyntax},
      {"G1 X1 X2\n", 1, 7, "X2", Error::GcodeConflictingWords},
      {"G5 I0 J3 P0 Q-3 X1 Y1 Z1\n", 1, 23, "Z1", Error::GcodeConflictingWords},
      {"G5.2\nX1 Y1\nG5.3\n", 3, 1, "G5.3", Error::GcodeNurbsBlock},
      {"G5.2 L3\nX1 Y1\nX2 Y0 L2\n", 3, 7, "L2", Error::GcodeNurbsBlock},
  };
  for (const auto& c : cases) {
    INFO(c.text);
    const LoadError e = error_of(c.text);
    CHECK(e.code() == c.code);
    CHECK(e.location().line == c.line);
    CHECK(e.location().column == c.column);
    CHECK(e.location().field == c.word);
    const std::string prefix = "inline.ngc:" + std::to_string(c.line) + ":" + std::to_string(c.column) + ": " + c.word + ": ";
    CHECK(std::string(e.what()).starts_with(prefix));
  }
}

TEST_CASE("gcode import: feeds and NURBS weights are rounded to Q16.16 as the wire carries them", "[gcode][import]") {
  // F100 mm/min = 1.66667 mm/s: round(1.66667 · 65536 = 109226.67) = 109227.
  Job job = parse_gcode_job("G1 X1 F100\n", "feed.ngc");
  REQUIRE(job.segments.size() == 1);
  CHECK(job.segments[0].feed_mm_per_s() == 109227.0 / 65536.0);
  CHECK(job.sources[0].feed_mm_per_s == 109227.0 / 65536.0);
  // Weight P0.3: round(19660.8) = 19661. Clamped uniform knots 0 0 0 1 1 1 (three points, order 3):
  // one piece whose weights are the rounded file weights.
  job = parse_gcode_job("G5.2 P1 L3\nX1 Y1 P0.3\nX2 Y0\nG5.3\n", "weight.ngc");
  REQUIRE(job.sources.size() == 1);
  CHECK(job.sources[0].weights == std::vector<double>{1.0, 19661.0 / 65536.0, 1.0});
  REQUIRE(job.segments.size() == 1);
  CHECK(job.segments[0].rational().weight(1) == 19661.0 / 65536.0);
  // A feed too small for Q16.16 (0.0001 mm/min = 1.7e-6 mm/s) is an error at its F word.
  const LoadError e = error_of("G1 X1 F0.0001\n", "tiny.ngc");
  CHECK(e.location().line == 1);
  CHECK(e.location().column == 7);
  CHECK(std::string(e.what()).find("rounds to 0 in Q16.16") != std::string::npos);
}

TEST_CASE("gcode import: CRLF line ends and a missing file", "[gcode][import]") {
  const Job job = parse_gcode_job("G0 X1\r\nG1 Y1 F60\r\n", "crlf.ngc");
  REQUIRE(job.segments.size() == 2);
  CHECK(job.segments[1].end() == pt(1, 1));
  CHECK(job.segments[1].feed_mm_per_s() == 1.0);
  CHECK_THROWS_AS(import_gcode(data + "/does_not_exist.ngc"), std::runtime_error);
}

TEST_CASE("gcode import: random arcs with three-decimal coordinates all load and end where programmed", "[gcode][import][property]") {
  // Points on a circle rounded to 0.001 mm: radii differ by well under LinuxCNC's 0.028 mm, and
  // quantisation to Q16.16 must not turn an accepted arc into a rejected one.
  std::mt19937 random(curvestep::testing::test_seed());
  std::uniform_real_distribution<double> coordinate(-500.0, 500.0);
  std::uniform_real_distribution<double> radius(0.5, 300.0);
  std::uniform_real_distribution<double> angle(0.0, 2 * std::numbers::pi);
  auto three_decimals = [](double v) { return std::round(v * 1000.0) / 1000.0; };
  const int count = curvestep::testing::test_count(300);
  for (int n = 0; n < count; ++n) {
    const double cx = three_decimals(coordinate(random));
    const double cy = three_decimals(coordinate(random));
    const double r = radius(random);
    const double a0 = angle(random);
    const double a1 = angle(random);
    const double x0 = three_decimals(cx + r * std::cos(a0));
    const double y0 = three_decimals(cy + r * std::sin(a0));
    const double x1 = three_decimals(cx + r * std::cos(a1));
    const double y1 = three_decimals(cy + r * std::sin(a1));
    std::ostringstream program;
    program << std::fixed << std::setprecision(3);
    program << "G0 X" << x0 << " Y" << y0 << "\n"
            << (n % 2 == 0 ? "G2" : "G3") << " X" << x1 << " Y" << y1 << " I" << three_decimals(cx - x0) << " J"
            << three_decimals(cy - y0) << " F100\n";
    INFO(program.str());
    const Job job = parse_gcode_job(program.str(), "random.ngc");
    REQUIRE(job.segments.size() == 2);
    CHECK(job.segments[1].kind() == SegmentKind::Arc);
    CHECK(near(job.segments[1].end(), pt(x1, y1), grid_tolerance));
  }
}

TEST_CASE("gcode import: the example's path flattens within tolerance like any job", "[gcode][import]") {
  const Job job = import_gcode(std::string(CURVESTEP_GCODE_EXAMPLES) + "/cnc_pocket.ngc");
  const auto polyline = flatten_path(job.segments, 0.01);
  REQUIRE(polyline.size() > job.segments.size());
  CHECK(polyline.front() == job.segments.front().start());
  CHECK(polyline.back() == job.segments.back().end());
}
