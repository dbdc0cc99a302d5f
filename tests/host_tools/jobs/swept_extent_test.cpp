// SPDX-License-Identifier: MIT
// The swept box of segments and the load-time Q16.16 check of the whole swept extent (issue 19 item 3).
#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/core/error.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/load_error.hpp>
#include <curvestep/host/swept_extent.hpp>

#include "jobs_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using curvestep::testing::job_example;
using curvestep::testing::run_curvestep;

namespace {

SweptBox box_of_first(const std::string& segments) {
  const Job job = parse_job(R"({"version": 1, "segments": [)" + segments + "]}", "box.json");
  REQUIRE_FALSE(job.segments.empty());
  return swept_box(job.segments.front());
}

std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("curvestep_swept_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST_CASE("swept extent: a half circle's box reaches the radius on the side it sweeps", "[host_tools][jobs][swept]") {
  // Centre (10, 5), radius 5, counter-clockwise from (10, 0) (angle -90°) to (10, 10) (+90°):
  // it passes 0°, the point (15, 5), and no other axis direction.
  const SweptBox box = box_of_first(R"({"type": "arc", "points": [[10, 0], [10, 10]], "center": [10, 5], "direction": "ccw"})");
  CHECK(box.low[0] == Approx(10).margin(1e-9));
  CHECK(box.high[0] == Approx(15).margin(1e-4));
  CHECK(box.low[1] == Approx(0).margin(1e-9));
  CHECK(box.high[1] == Approx(10).margin(1e-9));
  // The same ends clockwise: the other half, through (5, 5).
  const SweptBox cw = box_of_first(R"({"type": "arc", "points": [[10, 0], [10, 10]], "center": [10, 5], "direction": "cw"})");
  CHECK(cw.low[0] == Approx(5).margin(1e-4));
  CHECK(cw.high[0] == Approx(10).margin(1e-9));
}

TEST_CASE("swept extent: a Bezier's box is its control hull", "[host_tools][jobs][swept]") {
  const SweptBox box = box_of_first(R"({"type": "bezier", "points": [[0, 0], [3, 9], [7, -4], [10, 1]]})");
  CHECK(box.low[0] == 0);
  CHECK(box.high[0] == 10);
  CHECK(box.low[1] == Approx(-4).margin(1e-4));
  CHECK(box.high[1] == Approx(9).margin(1e-4));
}

TEST_CASE("swept extent: a JSON arc whose circle passes 32768 mm is refused naming line and segment", "[host_tools][jobs][swept]") {
  // Ends (32000, -1000), (32000, 1000) and centre (32000, 0) are all in range; the counter-clockwise
  // half circle passes (33000, 0).
  const std::string text = "{\"version\": 1, \"segments\": [\n"
                           "  {\"type\": \"line\", \"points\": [[0, 0], [32000, -1000]]},\n"
                           "  {\"type\": \"arc\", \"points\": [[32000, -1000], [32000, 1000]], \"center\": [32000, 0], \"direction\": \"ccw\"}\n"
                           "]}\n";
  const Job job = parse_job(text, "far_arc.json");
  try {
    check_swept_extent(job);
    FAIL("the job passed the check");
  } catch (const LoadError& e) {
    CHECK(e.code() == Error::FixedOverflow);
    CHECK(e.location().file == "far_arc.json");
    CHECK(e.location().line == 3);
    CHECK(e.location().segment == std::optional<std::size_t>{1});
    CHECK_THAT(e.message(), Catch::Contains("x = 33000 mm") && Catch::Contains("Q16.16"));
  }
  // The clockwise half stays inside x <= 32000.
  const std::string inside = "{\"version\": 1, \"segments\": [\n"
                             "  {\"type\": \"arc\", \"points\": [[32000, -1000], [32000, 1000]], \"center\": [32000, 0], \"direction\": \"cw\"}\n"
                             "]}\n";
  CHECK_NOTHROW(check_swept_extent(parse_job(inside, "near_arc.json")));
}

TEST_CASE("swept extent: every example job passes the check", "[host_tools][jobs][swept]") {
  for (const char* name : {"every_type.json", "helix.json", "inch_square.json", "seed_cubic.json"}) {
    INFO(name);
    CHECK_NOTHROW(check_swept_extent(load_job(job_example(name))));
  }
}

TEST_CASE("swept extent: sim refuses G3 I29991 at load with file:line", "[host_tools][jobs][swept][cli]") {
  // A full circle about (29991, 0) through the origin reaches x = 59982 mm.
  const auto gcode = write_temp("far_circle.ngc", "G21 G90 F600\nG1 X0 Y0\nG3 I29991\n");
  const auto machine = "'" + job_example("machine.json").string() + "'";
  const auto result = run_curvestep("sim '" + gcode.string() + "' --machine " + machine);
  CHECK(result.exit_code != 0);
  CHECK_THAT(result.err, Catch::Contains(gcode.filename().string() + ":3") && Catch::Contains("x = 59982 mm"));
  const auto json = write_temp("far_arc.json",
                               "{\"version\": 1, \"segments\": [\n"
                               "  {\"type\": \"arc\", \"points\": [[32000, -1000], [32000, 1000]], \"center\": [32000, 0], \"direction\": \"ccw\"}\n"
                               "]}\n");
  const auto json_result = run_curvestep("sim '" + json.string() + "' --machine " + machine);
  CHECK(json_result.exit_code != 0);
  CHECK_THAT(json_result.err, Catch::Contains("far_arc.json:2") && Catch::Contains("x = 33000 mm"));
  std::filesystem::remove(gcode);
  std::filesystem::remove(json);
}
