// SPDX-License-Identifier: MIT
// The machine file's optional "homing" section: per axis the switch side, speeds, pull-off, home
// position and seek distance, and the cycle's order; bad values name the file, line and key.
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/core/error.hpp>
#include <curvestep/host/machine_file.hpp>

#include "machine_error.hpp"

using namespace curvestep;
using namespace curvestep::host;

namespace {

/// A valid machine file (lines 1..8; x travels -10 .. 290 mm) followed by `extra` root members.
std::string machine_with(const std::string& extra) {
  return "{\n"
         "  \"version\": 1,\n"
         "  \"v_max\": 200, \"a_max\": 2000, \"j_max\": 50000,\n"
         "  \"feed\": 50, \"tolerance\": 0.01, \"rate_hz\": 1000,\n"
         "  \"max_step_rate\": 40000, \"rapid\": 150, \"profile\": \"trapezoid\",\n"
         "  \"axes\": {\"x\": {\"steps_per_mm\": 80, \"travel\": [-10, 290]}, \"y\": {\"steps_per_mm\": 80}, \"z\": {\"steps_per_mm\": 400}}" +
         std::string(extra.empty() ? "" : ",\n  " + extra) + "\n}\n";
}

LoadError error_of(const std::string& text) { return testing::machine_error_of(text, "homing_machine.json"); }

}  // namespace

TEST_CASE("machine homing: the section maps onto HomingCycle, z first by default", "[host_tools][jobs][homing]") {
  const MachineFile file = parse_machine_file(machine_with(R"("homing": {
    "x": {"switch": "min", "seek": 20, "locate": 2, "pull_off": 1.5, "position": -2},
    "z": {"switch": "max", "seek": 5, "locate": 1, "pull_off": 2, "distance": 60}})"),
                                              "m.json");
  REQUIRE(file.homing.has_value());
  const HomingCycle& cycle = *file.homing;
  CHECK(cycle.order == std::vector<std::size_t>{2, 0});
  REQUIRE(cycle.axes[0].has_value());
  CHECK_FALSE(cycle.axes[0]->max_side);
  CHECK(cycle.axes[0]->seek_mm_per_s == 20);
  CHECK(cycle.axes[0]->locate_mm_per_s == 2);
  CHECK(cycle.axes[0]->pull_off_mm == 1.5);
  CHECK(cycle.axes[0]->position_mm == -2);
  CHECK(cycle.axes[0]->distance_mm == 450);  // 1.5 x the travel's 300 mm
  CHECK_FALSE(cycle.axes[1].has_value());
  REQUIRE(cycle.axes[2].has_value());
  CHECK(cycle.axes[2]->max_side);
  CHECK(cycle.axes[2]->distance_mm == 60);
  CHECK(cycle.axes[2]->position_mm == 0);
  const MachineFile ordered = parse_machine_file(
      machine_with(R"("homing": {"order": ["x", "z"], "x": {"switch": "min", "seek": 20, "locate": 2, "pull_off": 1},
                                 "z": {"switch": "max", "seek": 5, "locate": 1, "pull_off": 2, "distance": 60}})"),
      "m.json");
  CHECK(ordered.homing->order == std::vector<std::size_t>{0, 2});
}

TEST_CASE("machine homing: bad sections name the file, line and key", "[host_tools][jobs][homing]") {
  struct Case {
    std::string homing;
    std::string field;
    std::string cause;
  };
  const std::string x = R"("x": {"switch": "min", "seek": 20, "locate": 2, "pull_off": 1})";
  const Case cases[] = {
      {R"("homing": {"x": {"switch": "left", "seek": 20, "locate": 2, "pull_off": 1}})", "\"homing\".\"x\".\"switch\"",
       "expected \"min\" or \"max\""},
      {R"("homing": {"x": {"switch": "min", "locate": 2, "pull_off": 1}})", "\"homing\".\"x\".\"seek\"", "missing required key"},
      {R"("homing": {"x": {"switch": "min", "seek": 0, "locate": 2, "pull_off": 1}})", "\"homing\".\"x\".\"seek\"", "positive"},
      {R"("homing": {"x": {"switch": "min", "seek": 2, "locate": 20, "pull_off": 1}})", "\"homing\".\"x\".\"locate\"",
       "is above \"seek\""},
      {R"("homing": {"x": {"switch": "min", "seek": 20, "locate": 2, "pull_off": -1}})", "\"homing\".\"x\".\"pull_off\"", "positive"},
      {R"("homing": {"y": {"switch": "min", "seek": 20, "locate": 2, "pull_off": 1}})", "\"homing\".\"y\"",
       "no \"distance\" (the longest seek, mm) and no \"axes\".\"y\".\"travel\""},
      {R"("homing": {"x": {"switch": "min", "seek": 20, "locate": 2, "pull_off": 1, "speed": 3}})", "\"homing\".\"x\".\"speed\"",
       "unknown key"},
      {R"("homing": {"order": ["x", "x"], )" + x + "}", "\"homing\".\"order\"[1]", "listed twice"},
      {R"("homing": {"order": ["z"], )" + x + "}", "\"homing\".\"order\"[0]", "\"z\" is no axis of the \"homing\" section"},
      {R"("homing": {"order": [], )" + x + "}", "\"homing\".\"order\"", ""},
      {R"("homing": {})", "\"homing\"", "homes no axis"},
  };
  for (const auto& c : cases) {
    const LoadError e = error_of(machine_with(c.homing));
    const std::string what = e.what();
    INFO(what);
    CHECK(e.code() == Error::InvalidMachine);
    CHECK(e.location().field == c.field);
    CHECK(what.find(c.cause) != std::string::npos);
  }
}
