// SPDX-License-Identifier: MIT
// What a machine file sets up beyond the limits (issues 17.1 and 22.5): the tool table that G43 H
// and G41/G42 D read, the G28/G30 positions, and the travel (soft limits) every job is checked
// against before anything moves. Expected positions are worked out by hand.
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include <catch2/catch.hpp>

#include <curvestep/host/job_pipeline.hpp>
#include <curvestep/host/machine_file.hpp>

using namespace curvestep;
using namespace curvestep::host;

namespace {

const std::string limits = R"("version": 1, "v_max": 200, "a_max": 2000, "j_max": 50000, "feed": 50, "tolerance": 0.01, "rate_hz": 1000)";

std::filesystem::path write(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("curvestep_machine_setup_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(path) << text;
  return path;
}

std::string load_error_of(const std::string& machine_text) {
  try {
    (void)parse_machine_file(machine_text, "m.json");
  } catch (const LoadError& e) {
    return e.what();
  }
  FAIL("no LoadError for: " << machine_text);
  return {};
}

}  // namespace

TEST_CASE("machine setup: tools, G28/G30 positions and travel are read from the machine file", "[host][pipeline][machine]") {
  const MachineFile m = parse_machine_file(
      "{" + limits + R"(, "tools": [{"number": 1, "length": 12.5, "diameter": 6}, {"number": 2, "length": 3}],
         "g28": [10, 20, 30], "g30": [1, 2],
         "axes": {"x": {"travel": [0, 300]}, "z": {"travel": [-50, 5]}}})",
      "m.json");
  REQUIRE(m.tools.size() == 2);
  CHECK(m.tools.at(1).length_mm == 12.5);
  CHECK(m.tools.at(1).diameter_mm == 6.0);
  CHECK_FALSE(m.tools.at(2).diameter_mm.has_value());
  CHECK(*m.g28_position == MachinePoint{{10, 20, 30}});
  CHECK(*m.g30_position == MachinePoint{{1, 2, 0}});
  REQUIRE(m.travel[0].has_value());
  CHECK(m.travel[0]->high_mm == 300);
  CHECK_FALSE(m.travel[1].has_value());
  CHECK(m.travel[2]->low_mm == -50);
  CHECK(m.name == "m.json");
}

TEST_CASE("machine setup: a malformed table, position or travel names its field", "[host][pipeline][machine][errors]") {
  CHECK_THAT(load_error_of("{" + limits + R"(, "axes": {"x": {"travel": [300, 0]}}})"), Catch::Contains("low end must be below"));
  CHECK_THAT(load_error_of("{" + limits + R"(, "tools": [{"number": 1}, {"number": 1}]})"), Catch::Contains("tool 1 is listed twice"));
  CHECK_THAT(load_error_of("{" + limits + R"(, "tools": [{"number": 1, "diameter": -2}]})"), Catch::Contains("0 .. 1000 mm"));
  // Tool numbers as CAM posts use them (T102) are taken up to 99999, in a table of at most 100 tools.
  CHECK_THAT(load_error_of("{" + limits + R"(, "tools": [{"number": 100000}]})"), Catch::Contains("number"));
  CHECK(parse_machine_file("{" + limits + R"(, "tools": [{"number": 102, "length": 20}]})", "m.json").tools.at(102).length_mm == 20);
  std::string hundred_and_one;
  for (int tool = 1; tool <= 101; ++tool) hundred_and_one += (tool > 1 ? ", " : "") + std::string(R"({"number": )") + std::to_string(tool) + "}";
  CHECK_THAT(load_error_of("{" + limits + R"(, "tools": [)" + hundred_and_one + "]}"), Catch::Contains("tools"));
  CHECK_THAT(load_error_of("{" + limits + R"(, "g28": [1, 2, 99999]})"), Catch::Contains("-32767 .. 32767"));
  CHECK_THAT(load_error_of("{" + limits + R"(, "tools": [{"number": 1, "radius": 2}]})"), Catch::Contains("radius"));
}

TEST_CASE("machine setup: G43 H, G41 D and G28 use the machine file through the pipeline", "[host][pipeline][machine]") {
  const MachineFile m = parse_machine_file(
      "{" + limits + R"(, "tools": [{"number": 1, "length": 10, "diameter": 4}], "g28": [100, 50, 20]})", "m.json");
  // G43 H1: program Z0 is machine Z 10. G28 goes to (100, 50, 20).
  const auto program = write("tools.ngc", "G21 G90\nT1 M6\nG43 H1\nG0 X0 Y0 Z0\nG28\n");
  const PreparedJob prepared = prepare_job(program, m, m.limits, JobPipelineOptions{});
  REQUIRE(prepared.job.segments.size() >= 2);
  CHECK(prepared.job.segments[0].end()[2] == Approx(10));
  CHECK(prepared.job.segments.back().end() == MachinePoint{{100, 50, 20}});
  // G41 D1: the tool's radius 2 offsets a line along +X to the left (y + 2).
  const auto compensated = write("comp.ngc", "G21 G90 G0 X0 Y0\nG41 D1 G1 X10 Y0 F600\nG1 X30\nG40 G1 X40\n");
  const PreparedJob offset = prepare_job(compensated, m, m.limits, JobPipelineOptions{});
  bool found = false;
  for (const auto& s : offset.job.segments) found = found || (s.end()[1] == Approx(2) && s.end()[0] == Approx(30));
  CHECK(found);
}

TEST_CASE("machine setup: a job leaving the travel is refused before anything moves, arcs by their extremes", "[host][pipeline][machine]") {
  const MachineFile m = parse_machine_file("{" + limits + R"(, "axes": {"x": {"travel": [0, 300]}, "y": {"travel": [0, 200]}}})",
                                           "travel.json");
  // A half circle from (100, 10) to (100, 30) about (100, 20), counter-clockwise from -90 degrees:
  // through (110, 20): inside. Clockwise it passes (90, 20): inside too. Radius 15 from (100, 5):
  // the clockwise half circle reaches x = 85 and y = 5 .. 35: inside; radius 15 about (10, 20) reaches x = -5.
  const auto inside = write("inside.ngc", "G21 G90 G0 X100 Y10\nG3 X100 Y30 J10 F600\n");
  CHECK_NOTHROW(prepare_job(inside, m, m.limits, JobPipelineOptions{}));
  const auto outside = write("outside.ngc", "G21 G90 G0 X10 Y5\nG2 X10 Y35 J15 F600\n");
  try {
    (void)prepare_job(outside, m, m.limits, JobPipelineOptions{});
    FAIL("an arc reaching x = -5 was not refused");
  } catch (const LoadError& e) {
    const std::string text = e.what();
    INFO(text);
    CHECK(e.code() == Error::OutsideTravel);
    CHECK_THAT(text, Catch::Contains(":2") && Catch::Contains("x = -5 mm") && Catch::Contains("5 mm below") &&
                         Catch::Contains("0 .. 300 mm") && Catch::Contains("travel.json"));
  }
  // Without travel in the machine file nothing is checked.
  const MachineFile unlimited = parse_machine_file("{" + limits + "}", "free.json");
  CHECK_NOTHROW(prepare_job(outside, unlimited, unlimited.limits, JobPipelineOptions{}));
}
