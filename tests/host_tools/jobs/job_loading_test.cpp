// SPDX-License-Identifier: MIT
// Job files: every segment type, units, Q16.16 quantisation, connectivity, B-spline extraction.
#include <cmath>
#include <numbers>
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/core/error.hpp>
#include <curvestep/host/job.hpp>

#include "jobs_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using curvestep::testing::distance;
using curvestep::testing::job_example;

namespace {

/// The Q16.16 grid value nearest x (ties away from zero), by definition of the format.
double on_grid(double x) { return std::round(x * 65536.0) / 65536.0; }

MachinePoint xyz(double x, double y, double z = 0) { return MachinePoint{{x, y, z}}; }

std::string one_segment_job(const std::string& segment, const std::string& units = "mm") {
  return R"({"version": 1, "units": ")" + units + R"(", "segments": [)" + segment + "]}";
}

}  // namespace

TEST_CASE("jobs: the example with every segment type loads and maps each segment to its pieces", "[host_tools][jobs]") {
  const Job job = load_job(job_example("every_type.json"));
  REQUIRE(job.sources.size() == 9);
  const std::array<SegmentType, 9> types{SegmentType::Rapid,  SegmentType::Line,           SegmentType::Arc,
                                         SegmentType::Arc,    SegmentType::Bezier,         SegmentType::RationalBezier,
                                         SegmentType::BSpline, SegmentType::Nurbs,         SegmentType::Rapid};
  for (std::size_t i = 0; i < types.size(); ++i) CHECK(job.sources[i].type == types[i]);
  // The first rapid goes to where the machine starts (0,0): zero length, dropped. The bspline has
  // interior knots 1 and 2 (3 pieces), the nurbs one interior knot (2 pieces).
  CHECK(job.sources[0].piece_count() == 0);
  CHECK(job.sources[6].piece_count() == 3);
  CHECK(job.sources[7].piece_count() == 2);
  REQUIRE(job.segments.size() == 1 + 2 + 1 + 1 + 3 + 2 + 1);
  REQUIRE(job.source_index.size() == job.segments.size());
  CHECK(job.source_index.front() == 1);
  CHECK(job.source_index.back() == 8);
  CHECK(job.segments.back().rapid());
  CHECK(job.segments.front().feed_mm_per_s() == 20);
  CHECK(job.segments.front().kind() == SegmentKind::Line);
  CHECK(job.segments[1].kind() == SegmentKind::Arc);
  CHECK(job.segments[3].kind() == SegmentKind::Bezier);
  CHECK(job.segments[4].kind() == SegmentKind::RationalBezier);
  for (std::size_t i = 1; i < job.segments.size(); ++i) {
    INFO("piece " << i);
    CHECK(distance(job.segments[i].start(), job.segments[i - 1].end()) <= 1.0 / 65536);
  }
  // The arc given by radius 5 from (10,10) to (0,10) clockwise is a half circle about (5,10);
  // clockwise from its east point it passes the south point (5,5).
  CHECK(job.segments[2].arc_center() == xyz(5, 10));
  CHECK(distance(evaluate_segment(job, 3, 0.5), xyz(5, 5)) < 1e-12);
  // The arc given by center (10,5) from (10,0) to (10,10) counter-clockwise bulges to x = 15.
  CHECK(distance(evaluate_segment(job, 2, 0.5), xyz(15, 5)) < 1e-12);
}

TEST_CASE("jobs: a helical arc rises linearly over all its turns", "[host_tools][jobs]") {
  const Job job = load_job(job_example("helix.json"));
  REQUIRE(job.segments.size() == 1);
  const PathSegment& helix = job.segments[0];
  CHECK(helix.kind() == SegmentKind::Arc);
  CHECK(helix.feed_mm_per_s() == 5);
  CHECK(helix.arc_sweep_rad() == Approx(4 * std::numbers::pi).epsilon(1e-15));
  // Two full turns about (0,0) from (10,0,0) to (10,0,5): u = k/8 is a quarter turn each.
  for (int k = 0; k <= 8; ++k) {
    const double u = k / 8.0;
    const double angle = u * 4 * std::numbers::pi;
    INFO("u = " << u);
    CHECK(distance(evaluate_segment(job, 0, u), xyz(10 * std::cos(angle), 10 * std::sin(angle), 5 * u)) < 1e-12);
  }
}

TEST_CASE("jobs: a rational quadratic with weights 1, sqrt(2)/2, 1 is a quarter circle", "[host_tools][jobs]") {
  const Job job = parse_job(one_segment_job(R"({"type": "rational_bezier", "points": [[10, 0], [10, 10], [0, 10]],
                                                "weights": [1, 0.7071067811865476, 1]})"),
                            "quarter.json");
  REQUIRE(job.segments.size() == 1);
  CHECK(job.segments[0].kind() == SegmentKind::RationalBezier);
  // The weight travels as Q16.16: round(√2/2 · 65536) = 46341 (√2/2 · 65536 = 46340.95).
  const double w = 46341.0 / 65536.0;
  for (int k = 0; k <= 64; ++k) {
    const double t = k / 64.0;
    const auto p = evaluate_segment(job, 0, t);
    // The rational quadratic with the rounded weight, summed directly (Bernstein basis).
    const double b0 = (1 - t) * (1 - t);
    const double b1 = 2 * t * (1 - t) * w;
    const double b2 = t * t;
    const double d = b0 + b1 + b2;
    CHECK(distance(p, xyz((10 * b0 + 10 * b1) / d, (10 * b1 + 10 * b2) / d)) < 1e-12);
    // Rounding √2/2 to 46341/65536 (by 7.6e-7) moves the conic off the circle by at most 1.9e-7 of the radius.
    CHECK(std::hypot(p[0], p[1]) == Approx(10).margin(2e-6));
    CHECK(p[0] >= 0);
    CHECK(p[1] >= 0);
  }
  const double half = 10 * std::numbers::sqrt2 / 2;
  CHECK(distance(evaluate_segment(job, 0, 0.5), xyz(half, half)) < 2e-6);
}

TEST_CASE("jobs: every coordinate is quantised to the Q16.16 grid, after inch conversion", "[host_tools][jobs]") {
  SECTION("millimetres") {
    const Job job = parse_job(one_segment_job(R"({"type": "line", "points": [[0.1, 0.3333333333], [-2.71828, 1e-6, 7.00001]]})"),
                              "grid.json");
    const auto& points = job.sources[0].points;
    CHECK(points[0] == xyz(on_grid(0.1), on_grid(0.3333333333)));
    CHECK(points[0][0] == 6554.0 / 65536.0);
    CHECK(points[0][1] == 21845.0 / 65536.0);
    CHECK(points[1] == xyz(on_grid(-2.71828), 0, on_grid(7.00001)));
    CHECK(job.segments[0].start() == points[0]);
    CHECK(job.segments[0].end() == points[1]);
  }
  SECTION("inches are 25.4 mm") {
    const Job job = parse_job(one_segment_job(R"({"type": "line", "points": [[0, 0], [1, 0.5]]})", "in"), "inch.json");
    CHECK(job.sources[0].points[1] == xyz(1664614.0 / 65536.0, on_grid(12.7)));
  }
  SECTION("the ends of the range") {
    const Job job = parse_job(one_segment_job(R"({"type": "line", "points": [[-32768, 0], [32767.99998, 0]]})"), "edge.json");
    CHECK(job.sources[0].points[0][0] == -32768.0);
    CHECK(job.sources[0].points[1][0] == 32767.0 + 65535.0 / 65536.0);
    try {
      (void)parse_job(one_segment_job(R"({"type": "line", "points": [[0, 0], [32768, 0]]})"), "over.json");
      FAIL("32768 mm must not load");
    } catch (const LoadError& e) {
      CHECK(e.code() == Error::FixedOverflow);
      CHECK(e.location().field == "\"points\"[1][0]");
      CHECK(std::string(e.what()).find("outside the Q16.16 range") != std::string::npos);
    }
  }
}

TEST_CASE("jobs: a segment that does not start where the previous one ended names both points and the index", "[host_tools][jobs]") {
  const std::string text = R"({"version": 1, "segments": [
      {"type": "line", "points": [[0, 0], [5, 0]]},
      {"type": "line", "points": [[5, 0], [5, 2.5]]},
      {"type": "arc", "points": [[5, 3], [3, 5]], "center": [3, 3], "direction": "ccw"}]})";
  try {
    (void)parse_job(text, "gap.json");
    FAIL("a gap must not load");
  } catch (const LoadError& e) {
    CHECK(e.code() == Error::SegmentsNotConnected);
    CHECK(e.location().segment == std::size_t{2});
    CHECK(e.location().line == 4);
    const std::string what = e.what();
    CHECK(what == "gap.json:4: segment 2 (arc): \"points\"[0]: starts at (5, 3, 0), but segment 1 ended at (5, 2.5, 0)");
  }
}

TEST_CASE("jobs: a rapid may start anywhere and travels there from the previous end", "[host_tools][jobs]") {
  const Job job = parse_job(R"({"version": 1, "segments": [
      {"type": "line", "points": [[0, 0], [5, 0]]},
      {"type": "rapid", "points": [[20, 20], [30, 20]]},
      {"type": "rapid", "points": [[30, 30, 5]]},
      {"type": "line", "points": [[30, 30, 5], [30, 30, 0]], "feed": 2}]})",
                            "rapids.json");
  REQUIRE(job.segments.size() == 5);
  CHECK(job.segments[1].rapid());
  CHECK(job.segments[1].start() == xyz(5, 0));
  CHECK(job.segments[1].end() == xyz(20, 20));
  CHECK(job.segments[2].start() == xyz(20, 20));
  CHECK(job.segments[2].end() == xyz(30, 20));
  CHECK(job.segments[3].start() == xyz(30, 20));
  CHECK(job.segments[3].end() == xyz(30, 30, 5));
  CHECK_FALSE(job.segments[4].rapid());
  CHECK(job.source_index == std::vector<std::size_t>{0, 1, 1, 2, 3});
  // The rapid's own parameter runs over the move the file gives, not the connecting travel.
  CHECK(evaluate_segment(job, 1, 0.5) == xyz(25, 20));
  CHECK(evaluate_segment(job, 2, 0) == xyz(30, 20));
}

TEST_CASE("jobs: eval of the seed cubic at u = 1/4 gives (29/32, 81/64)", "[host_tools][jobs]") {
  const Job job = load_job(job_example("seed_cubic.json"));
  // Seed digest TV-04.
  CHECK(evaluate_segment(job, 0, 0.25) == xyz(0.90625, 1.265625));
  CHECK(evaluate_segment(job, 0, 0.5) == xyz(2, 1.875));
  CHECK(evaluate_segment(job, 0, 0.75) == xyz(3.09375, 1.546875));
  CHECK(evaluate_segment(job, 0, 1) == xyz(4, 0));
  CHECK_THROWS_AS(evaluate_segment(job, 0, 1.0000001), std::out_of_range);
  CHECK_THROWS_AS(evaluate_segment(job, 0, -0.5), std::out_of_range);
  CHECK_THROWS_AS(evaluate_segment(job, 1, 0.5), std::out_of_range);
}

TEST_CASE("jobs: a clamped cubic B-spline is extracted into Bezier pieces that follow the spline", "[host_tools][jobs]") {
  // Seed 004 TV-13 and TV-A6.
  const Job job = parse_job(one_segment_job(R"({"type": "bspline", "degree": 3,
      "points": [[-3, 7], [-1, 6], [0, 4], [0, 0], [4, 0], [6, 1], [7, 3], [9, 4]],
      "knots": [0, 0, 0, 0, 1, 2, 3, 4, 5, 5, 5, 5]})"),
                            "tv13.json");
  REQUIRE(job.segments.size() == 5);
  CHECK(job.sources[0].domain() == std::pair<double, double>{0.0, 5.0});
  // Each piece's control points are quantised again: one Q16.16 rounding (2^-17) per coordinate.
  const double grid = 1.0 / 131072.0 * std::sqrt(2.0) + 1e-12;
  const std::array<std::pair<double, MachinePoint>, 8> expected{{{0, xyz(-3, 7)},
                                                                 {0.5, xyz(-31.0 / 32, 263.0 / 48)},
                                                                 {1, xyz(-0.25, 23.0 / 6)},
                                                                 {2, xyz(2.0 / 3, 2.0 / 3)},
                                                                 {2.5, xyz(49.0 / 24, 5.0 / 48)},
                                                                 {3, xyz(11.0 / 3, 1.0 / 6)},
                                                                 {4, xyz(71.0 / 12, 4.0 / 3)},
                                                                 {5, xyz(9, 4)}}};
  for (const auto& [u, point] : expected) {
    INFO("u = " << u);
    CHECK(distance(evaluate_segment(job, 0, u), point) <= grid);
  }
  const auto piece = job.segments[2].polynomial().control_points();  // span [2,3]
  const std::array<MachinePoint, 4> tv_a6{xyz(2.0 / 3, 2.0 / 3), xyz(4.0 / 3, 0), xyz(8.0 / 3, 0), xyz(11.0 / 3, 1.0 / 6)};
  REQUIRE(piece.size() == 4);
  for (std::size_t i = 0; i < 4; ++i) CHECK(distance(piece[i], tv_a6[i]) <= grid);
  CHECK_THROWS_AS(evaluate_segment(job, 0, 5.5), std::out_of_range);
}

TEST_CASE("jobs: a nine-point NURBS circle becomes four rational pieces on the circle", "[host_tools][jobs]") {
  const Job job = parse_job(one_segment_job(R"({"type": "nurbs", "degree": 2,
      "points": [[10, 0], [10, 10], [0, 10], [-10, 10], [-10, 0], [-10, -10], [0, -10], [10, -10], [10, 0]],
      "weights": [1, 0.7071067811865476, 1, 0.7071067811865476, 1, 0.7071067811865476, 1, 0.7071067811865476, 1],
      "knots": [0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1]})"),
                            "circle.json");
  REQUIRE(job.segments.size() == 4);
  for (const auto& piece : job.segments) CHECK(piece.kind() == SegmentKind::RationalBezier);
  for (int k = 0; k <= 400; ++k) {
    const auto p = evaluate_segment(job, 0, k / 400.0);
    CHECK(std::hypot(p[0], p[1]) == Approx(10).margin(1e-4));
  }
  CHECK(distance(evaluate_segment(job, 0, 0.5), xyz(-10, 0)) < 1e-4);
}

TEST_CASE("jobs: an arc given by a negative radius takes the long way round", "[host_tools][jobs]") {
  const Job job = parse_job(one_segment_job(R"({"type": "arc", "points": [[10, 0], [0, 10]], "radius": -10, "direction": "ccw"})"),
                            "long.json");
  // Counter-clockwise from (10,0) to (0,10) the long way is about (10,10), sweeping 3/2 pi.
  CHECK(job.segments[0].arc_center() == xyz(10, 10));
  CHECK(job.segments[0].arc_sweep_rad() == Approx(1.5 * std::numbers::pi));
  // Halfway: a quarter turn and a half past the start's angle -pi/2, i.e. at angle pi/4.
  const double offset = 10 * std::numbers::sqrt2 / 2;
  CHECK(distance(evaluate_segment(job, 0, 0.5), xyz(10 + offset, 10 + offset)) < 1e-12);
}

TEST_CASE("jobs: zero-length lines are dropped but keep their place in the numbering", "[host_tools][jobs]") {
  const Job job = parse_job(R"({"version": 1, "segments": [
      {"type": "line", "points": [[0, 0], [1, 0]]},
      {"type": "line", "points": [[1, 0], [1, 0]]},
      {"type": "line", "points": [[1, 0], [1, 1]]}]})",
                            "zero.json");
  CHECK(job.segments.size() == 2);
  CHECK(job.source_index == std::vector<std::size_t>{0, 2});
  CHECK(evaluate_segment(job, 1, 0.5) == xyz(1, 0));
  CHECK(evaluate_segment(job, 2, 0.5) == xyz(1, 0.5));
}
