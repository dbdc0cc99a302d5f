// SPDX-License-Identifier: MIT
// Rational curves whose parameter speed the controller's arc-length table cannot follow are
// refused at load time (issue 19 item 1); ordinary curves are followed at the planned speed.
#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/core/error.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/load_error.hpp>
#include <curvestep/host/parameter_speed.hpp>

#include "jobs_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using curvestep::testing::job_example;
using curvestep::testing::run_curvestep;

namespace {

Job job_of(const std::string& segment) {
  return parse_job("{\"version\": 1, \"segments\": [\n  " + segment + "\n]}\n", "rational.json");
}

/// The largest distance between consecutive setpoints of `sim -o` CSV (t,x,y,z,v), in mm.
double largest_step(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  double previous[3] = {NAN, NAN, NAN};
  double largest = 0;
  while (std::getline(in, line)) {
    double t = 0;
    double p[3] = {};
    if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &t, &p[0], &p[1], &p[2]) != 4) continue;
    if (!std::isnan(previous[0])) {
      largest = std::max(largest, std::hypot(p[0] - previous[0], p[1] - previous[1], p[2] - previous[2]));
    }
    std::copy(p, p + 3, previous);
  }
  return largest;
}

}  // namespace

TEST_CASE("parameter speed: the issue's quadratic with weights 1, 100, 1 is refused with its line", "[host_tools][jobs][speed]") {
  const Job job = job_of(R"({"type": "rational_bezier", "points": [[0, 0], [5, 5], [10, 0]], "weights": [1, 100, 1]})");
  CHECK(table_speed_factor(job.segments.front()) > 2);
  try {
    check_parameter_speed(job);
    FAIL("the curve was accepted");
  } catch (const LoadError& e) {
    CHECK(e.code() == Error::InvalidJob);
    CHECK(e.location().file == "rational.json");
    CHECK(e.location().line == 2);
    CHECK(e.location().segment == std::optional<std::size_t>{0});
    CHECK_THAT(e.message(), Catch::Contains("weights vary too strongly"));
  }
}

TEST_CASE("parameter speed: a cubic with weights 1, 60, 60, 1 is refused", "[host_tools][jobs][speed]") {
  const Job job = job_of(R"({"type": "rational_bezier", "points": [[0, 0], [3, 5], [7, 5], [10, 0]], "weights": [1, 60, 60, 1]})");
  CHECK_THROWS_AS(check_parameter_speed(job), LoadError);
}

TEST_CASE("parameter speed: weights 2^-16, 1, 1 (a speed spike thinner than every sample) are refused", "[host_tools][jobs][speed]") {
  // With w0 = 2^-16 the curve covers its first ~5 mm for u < 1e-4: the table's cubic on its first
  // piece cannot follow, and sim moved 6.8 mm in one tick (v_max 200 mm/s at 1000 Hz allows 0.2),
  // while the slopes compared at the table's own u agreed (a fuzz find of the planner harness's
  // step check). Exact weights on the Q16.16 grid: the loaders accept them.
  const Job job = job_of(R"({"type": "rational_bezier", "points": [[0, 0], [5, 5], [10, 0]], "weights": [0.0000152587890625, 1, 1]})");
  CHECK(table_speed_factor(job.segments.front()) > 10);
  CHECK_THROWS_AS(check_parameter_speed(job), LoadError);
}

TEST_CASE("parameter speed: a circle quarter and a mild rational curve are followed within 5 %", "[host_tools][jobs][speed]") {
  // The exact quarter circle (weights 1, cos 45°, 1) and a weight ratio of 3.
  const Job quarter = job_of(R"({"type": "rational_bezier", "points": [[10, 0], [10, 10], [0, 10]], "weights": [1, 0.7071067811865476, 1]})");
  CHECK(table_speed_factor(quarter.segments.front()) < 1.001);
  CHECK_NOTHROW(check_parameter_speed(quarter));
  const Job mild = job_of(R"({"type": "rational_bezier", "points": [[0, 0], [5, 5], [10, 0]], "weights": [1, 3, 1]})");
  CHECK_NOTHROW(check_parameter_speed(mild));
  for (const char* name : {"every_type.json", "helix.json", "inch_square.json", "seed_cubic.json"}) {
    INFO(name);
    CHECK_NOTHROW(check_parameter_speed(load_job(job_example(name))));
  }
}

TEST_CASE("parameter speed: sim refuses the weights 1, 100, 1 job and a G5.2 P100 NURBS at load", "[host_tools][jobs][speed][cli]") {
  const auto dir = std::filesystem::temp_directory_path();
  const auto json = dir / ("curvestep_speed_" + std::to_string(::getpid()) + ".json");
  std::ofstream(json) << R"({"version":1,"segments":[{"type":"rational_bezier","points":[[0,0],[5,5],[10,0]],"weights":[1,100,1]}]})";
  const auto gcode = dir / ("curvestep_speed_" + std::to_string(::getpid()) + ".ngc");
  std::ofstream(gcode) << "G21 G90 G17 F600\nG1 X0 Y0\nG5.2 P1 L3\nX5 Y5 P100\nX10 Y0 P1\nG5.3\n";
  const auto machine = "'" + job_example("machine.json").string() + "'";
  const auto refused = run_curvestep("sim '" + json.string() + "' --machine " + machine);
  CHECK(refused.exit_code != 0);
  CHECK_THAT(refused.err, Catch::Contains(json.filename().string() + ":1") && Catch::Contains("weights vary too strongly"));
  const auto nurbs = run_curvestep("sim '" + gcode.string() + "' --machine " + machine);
  CHECK(nurbs.exit_code != 0);
  CHECK_THAT(nurbs.err, Catch::Contains("weights vary too strongly"));
  std::filesystem::remove(json);
  std::filesystem::remove(gcode);
}

TEST_CASE("parameter speed: an accepted rational curve moves at most v_max / rate per tick", "[host_tools][jobs][speed][cli]") {
  // Weights 1, 3, 1 pass the check; at v_max 200 mm/s and 1000 Hz no tick may move more than
  // 0.2 mm (2 % margin for Q16.16 rounding).
  const auto dir = std::filesystem::temp_directory_path();
  const auto json = dir / ("curvestep_speed_ok_" + std::to_string(::getpid()) + ".json");
  const auto csv = dir / ("curvestep_speed_ok_" + std::to_string(::getpid()) + ".csv");
  std::ofstream(json) << R"({"version":1,"segments":[{"type":"rational_bezier","points":[[0,0],[5,5],[10,0]],"weights":[1,3,1],"feed":200}]})";
  const auto machine = "'" + job_example("machine.json").string() + "'";
  const auto result = run_curvestep("sim '" + json.string() + "' --machine " + machine + " -o '" + csv.string() + "'");
  REQUIRE(result.exit_code == 0);
  CHECK(largest_step(curvestep::testing::read_file(csv)) <= 0.2 * 1.02);
  std::filesystem::remove(json);
  std::filesystem::remove(csv);
}
