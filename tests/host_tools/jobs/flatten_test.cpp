// SPDX-License-Identifier: MIT
// Flattening: the polyline stays within the tolerance of the exact path, checked densely.
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/host/flatten.hpp>
#include <curvestep/host/job.hpp>

#include "jobs_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using curvestep::testing::distance;
using curvestep::testing::distance_to_polyline;

namespace {

/// Largest distance from dense exact points of `segment` to its own flattened polyline.
double worst_deviation(const PathSegment& segment, double tolerance, std::size_t& point_count) {
  std::vector<MachinePoint> line{segment.start()};
  flatten_segment(segment, tolerance, line);
  point_count = line.size();
  double worst = 0;
  constexpr int samples = 3000;
  for (int k = 0; k <= samples; ++k) {
    worst = std::max(worst, distance_to_polyline(segment.point(static_cast<double>(k) / samples), line));
  }
  // The polyline's vertices are points of the curve: its far end is the curve's end.
  CHECK(line.back() == segment.end());
  return worst;
}

}  // namespace

TEST_CASE("jobs: flattened example jobs stay within the tolerance of every segment", "[host_tools][jobs]") {
  for (const char* name : {"every_type.json", "helix.json", "seed_cubic.json", "inch_square.json"}) {
    const Job job = load_job(curvestep::testing::job_example(name));
    for (const double tolerance : {0.1, 0.01, 0.001}) {
      for (std::size_t i = 0; i < job.segments.size(); ++i) {
        INFO(name << " piece " << i << " tolerance " << tolerance);
        std::size_t points = 0;
        const double worst = worst_deviation(job.segments[i], tolerance, points);
        CHECK(worst <= tolerance * (1 + 1e-9));
        CHECK(points >= 2);
      }
    }
  }
}

TEST_CASE("jobs: a tighter tolerance never gives fewer points, and lines stay two points", "[host_tools][jobs]") {
  const Job job = load_job(curvestep::testing::job_example("every_type.json"));
  std::size_t previous = 0;
  for (const double tolerance : {1.0, 0.1, 0.01, 0.001}) {
    const auto line = flatten_path(job.segments, tolerance);
    CHECK(line.size() >= previous);
    previous = line.size();
  }
  const Job square = load_job(curvestep::testing::job_example("inch_square.json"));
  CHECK(flatten_path(square.segments, 1e-6).size() == 5);
}

TEST_CASE("jobs: the flattened path is connected and starts at the first segment's start", "[host_tools][jobs]") {
  const Job job = load_job(curvestep::testing::job_example("every_type.json"));
  const auto line = flatten_path(job.segments, 0.01);
  CHECK(line.front() == job.segments.front().start());
  CHECK(line.back() == job.segments.back().end());
  // Every piece's start and end appear in the polyline.
  for (const auto& segment : job.segments) {
    CHECK(std::find(line.begin(), line.end(), segment.start()) != line.end());
    CHECK(std::find(line.begin(), line.end(), segment.end()) != line.end());
  }
}

TEST_CASE("jobs: a semicircle of radius 10 at tolerance 0.01 needs the sagitta count of chords", "[host_tools][jobs]") {
  const Job job = parse_job(R"({"version": 1, "segments": [
      {"type": "arc", "points": [[10, 0], [-10, 0]], "center": [0, 0], "direction": "ccw"}]})",
                            "semicircle.json");
  std::vector<MachinePoint> line;
  flatten_segment(job.segments[0], 0.01, line);
  // r(1 - cos(d/2)) <= 0.01 gives d <= 2 acos(0.999) = 0.0894 rad: pi / 0.0894 -> 36 chords.
  CHECK(line.size() == 36);
}

TEST_CASE("jobs: a tolerance that is not positive is refused", "[host_tools][jobs]") {
  const Job job = load_job(curvestep::testing::job_example("seed_cubic.json"));
  std::vector<MachinePoint> line;
  CHECK_THROWS_AS(flatten_segment(job.segments[0], 0, line), std::invalid_argument);
  CHECK_THROWS_AS(flatten_segment(job.segments[0], -1, line), std::invalid_argument);
  CHECK_THROWS_AS(flatten_segment(job.segments[0], NAN, line), std::invalid_argument);
}
