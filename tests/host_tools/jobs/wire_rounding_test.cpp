// SPDX-License-Identifier: MIT
// Weights and feeds are rounded to the nearest Q16.16 value on loading, as the wire carries them,
// so that the simulator sees the numbers a device receives (issue 6). Expected values are computed
// here by hand (value · 65536 rounded to the nearest integer).
#include <cmath>
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/core/error.hpp>
#include <curvestep/host/job.hpp>

#include "jobs_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using curvestep::testing::job_example;

namespace {

std::string job_with(const std::string& segment) { return R"({"version": 1, "segments": [)" + segment + "]}"; }

bool on_q16_grid(double value) { return std::isfinite(value) && value * 65536.0 == std::round(value * 65536.0); }

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// The LoadError of parsing `text` as "wire.json".
LoadError error_of(const std::string& text) {
  try {
    (void)parse_job(text, "wire.json");
  } catch (const LoadError& e) {
    return e;
  }
  FAIL("the job loaded: " << text);
  return LoadError({}, "", Error::InvalidArgument);
}

}  // namespace

TEST_CASE("jobs: weights are rounded to the nearest Q16.16 value", "[host_tools][jobs][wire]") {
  const Job job = parse_job(job_with(R"({"type": "rational_bezier", "points": [[10, 0], [10, 10], [0, 10]],
                                         "weights": [1, 0.7071067811865476, 3.00001]})"),
                            "w.json");
  // 0.7071067811865476 · 65536 = 46340.95 -> 46341; 3.00001 · 65536 = 196608.66 -> 196609.
  REQUIRE(job.sources[0].weights.size() == 3);
  CHECK(job.sources[0].weights[0] == 1.0);
  CHECK(job.sources[0].weights[1] == 46341.0 / 65536.0);
  CHECK(job.sources[0].weights[2] == 196609.0 / 65536.0);
  REQUIRE(job.segments.size() == 1);
  CHECK(job.segments[0].rational().weight(1) == 46341.0 / 65536.0);
  CHECK(job.segments[0].rational().weight(2) == 196609.0 / 65536.0);
}

TEST_CASE("jobs: feeds are rounded to the nearest Q16.16 value", "[host_tools][jobs][wire]") {
  // 0.1 · 65536 = 6553.6 -> 6554; 33.33333 · 65536 = 2184533.11 -> 2184533.
  const Job job = parse_job(R"({"version": 1, "segments": [
      {"type": "line", "points": [[0, 0], [1, 0]], "feed": 0.1},
      {"type": "line", "points": [[1, 0], [1, 1]], "feed": 33.33333}]})",
                            "f.json");
  REQUIRE(job.segments.size() == 2);
  CHECK(job.sources[0].feed_mm_per_s == 6554.0 / 65536.0);
  CHECK(job.segments[0].feed_mm_per_s() == 6554.0 / 65536.0);
  CHECK(job.sources[1].feed_mm_per_s == 2184533.0 / 65536.0);
  CHECK(job.segments[1].feed_mm_per_s() == 2184533.0 / 65536.0);
}

TEST_CASE("jobs: the weights of Bezier pieces extracted from a NURBS are on the Q16.16 grid", "[host_tools][jobs][wire]") {
  // Single interior knots: extraction inserts knots, so the pieces' weights are new numbers
  // (for knot 0.5 of this clamped quadratic, the middle weight pair becomes (0.3+2)/2 = 1.15).
  const Job job = parse_job(job_with(R"({"type": "nurbs", "degree": 2, "points": [[0, 0], [1, 2], [3, 2], [4, 0]],
                                         "weights": [1, 0.3, 2, 1], "knots": [0, 0, 0, 0.5, 1, 1, 1]})"),
                            "n.json");
  REQUIRE(job.segments.size() == 2);
  for (const auto& piece : job.segments) {
    REQUIRE(piece.kind() == SegmentKind::RationalBezier);
    for (std::size_t i = 0; i < piece.rational().control_points().size(); ++i) {
      INFO("weight " << i << " = " << piece.rational().weight(i));
      CHECK(on_q16_grid(piece.rational().weight(i)));
      CHECK(piece.rational().weight(i) > 0);
    }
  }
  // The shared end point of the two pieces (knot 0.5 inserted once, alpha = 1/2): weight (w1 + w2) / 2
  // of the rounded file weights w1 = round(0.3 · 65536) / 65536 = 19661 / 65536 and w2 = 2, i.e.
  // (19661 + 131072) / 131072 = 75366.5 / 65536, a tie that rounds away from zero to 75367 / 65536.
  CHECK(job.segments[0].rational().weight(2) == 75367.0 / 65536.0);
  CHECK(job.segments[1].rational().weight(0) == 75367.0 / 65536.0);
}

TEST_CASE("jobs: weights and feeds outside Q16.16, or rounding to 0, name file, segment and field", "[host_tools][jobs][wire]") {
  struct Case {
    std::string segments;
    std::string where;  ///< "segment 1 (rational_bezier)"
    std::string field;
    Error code;
    std::string cause;
  };
  const std::string line = R"({"type": "line", "points": [[0, 0], [1, 0]]}, )";
  const Case cases[] = {
      {line + R"({"type": "rational_bezier", "points": [[1, 0], [2, 1], [3, 0]], "weights": [1, 1e-6, 1]})",
       "segment 1 (rational_bezier)", "\"weights\"[1]", Error::NonPositiveWeight, "weight 1e-06 rounds to 0 in Q16.16"},
      {line + R"({"type": "rational_bezier", "points": [[1, 0], [2, 1], [3, 0]], "weights": [1, 1, 40000]})",
       "segment 1 (rational_bezier)", "\"weights\"[2]", Error::FixedOverflow, "weight 40000 is outside the Q16.16 range"},
      {line + R"({"type": "nurbs", "degree": 1, "points": [[1, 0], [2, 1]], "weights": [7e-6, 1], "knots": [0, 0, 1, 1]})",
       "segment 1 (nurbs)", "\"weights\"[0]", Error::NonPositiveWeight, "weight 7e-06 rounds to 0"},
      {line + R"({"type": "line", "points": [[1, 0], [2, 0]], "feed": 0.000007})", "segment 1 (line)", "\"feed\"",
       Error::InvalidArgument, "feed 7e-06 rounds to 0 in Q16.16"},
      {R"({"type": "arc", "points": [[0, 0], [2, 0]], "center": [1, 0], "direction": "cw", "feed": 1e6})", "segment 0 (arc)",
       "\"feed\"", Error::FixedOverflow, "feed 1e+06 is outside the Q16.16 range"},
  };
  for (const auto& c : cases) {
    const LoadError e = error_of(job_with(c.segments));
    const std::string what = e.what();
    INFO(what);
    CHECK(e.code() == c.code);
    CHECK(e.location().file == "wire.json");
    CHECK(e.location().field == c.field);
    CHECK(what.rfind("wire.json:", 0) == 0);
    CHECK(contains(what, ": " + c.where + ": " + c.field + ": "));
    CHECK(contains(what, c.cause));
  }
  // Just above half a step rounds up to 2^-16 and loads.
  const Job job = parse_job(job_with(R"({"type": "line", "points": [[0, 0], [1, 0]], "feed": 0.0000077})"), "small.json");
  CHECK(job.segments[0].feed_mm_per_s() == 1.0 / 65536.0);
}

TEST_CASE("jobs: every number of the example jobs travels exactly as Q16.16", "[host_tools][jobs][wire]") {
  // What the wire encoder (host_tools/src/link/wire.cpp) would otherwise round: coordinates, arc
  // centres, weights and feeds of every piece. On the grid, sim and a device see the same job.
  for (const char* name : {"every_type.json", "helix.json", "inch_square.json", "seed_cubic.json"}) {
    INFO(name);
    const Job job = load_job(job_example(name));
    for (std::size_t i = 0; i < job.segments.size(); ++i) {
      INFO("piece " << i);
      const PathSegment& s = job.segments[i];
      CHECK(on_q16_grid(s.feed_mm_per_s()));
      for (std::size_t a = 0; a < motion_axes; ++a) {
        CHECK(on_q16_grid(s.start()[a]));
        CHECK(on_q16_grid(s.end()[a]));
      }
      if (s.kind() == SegmentKind::RationalBezier) {
        for (std::size_t k = 0; k < s.rational().control_points().size(); ++k) {
          CHECK(on_q16_grid(s.rational().weight(k)));
          for (std::size_t a = 0; a < motion_axes; ++a) CHECK(on_q16_grid(s.rational().control_points()[k][a]));
        }
      }
      if (s.kind() == SegmentKind::Arc) {
        for (std::size_t a = 0; a < 2; ++a) CHECK(on_q16_grid(s.arc_center()[a]));
      }
    }
  }
}
