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

/// The axes of these tests: x travels -10 .. 290 mm (the default seek distance's base).
const std::string homing_axes = R"({"x": {"steps_per_mm": 80, "travel": [-10, 290]}, "y": {"steps_per_mm": 80}, "z": {"steps_per_mm": 400}})";

/// A valid machine file (lines 1..6) followed by `extra` root members (from line 7).
std::string machine_with(const std::string& extra) { return testing::machine_text(extra, homing_axes); }

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
  const std::string x = R"("x": {"switch": "min", "seek": 20, "locate": 2, "pull_off": 1})";
  const testing::BadSection cases[] = {
      {R"("homing": {"x": {"switch": "left", "seek": 20, "locate": 2, "pull_off": 1}})", 7, "\"homing\".\"x\".\"switch\"",
       "expected \"min\" or \"max\""},
      {R"("homing": {"x": {"switch": "min", "locate": 2, "pull_off": 1}})", 7, "\"homing\".\"x\".\"seek\"", "missing required key"},
      {R"("homing": {"x": {"switch": "min", "seek": 0, "locate": 2, "pull_off": 1}})", 7, "\"homing\".\"x\".\"seek\"", "positive"},
      {R"("homing": {"x": {"switch": "min", "seek": 2, "locate": 20, "pull_off": 1}})", 7, "\"homing\".\"x\".\"locate\"",
       "is above \"seek\""},
      {R"("homing": {"x": {"switch": "min", "seek": 20, "locate": 2, "pull_off": -1}})", 7, "\"homing\".\"x\".\"pull_off\"", "positive"},
      {R"("homing": {"y": {"switch": "min", "seek": 20, "locate": 2, "pull_off": 1}})", 7, "\"homing\".\"y\"",
       "no \"distance\" (the longest seek, mm) and no \"axes\".\"y\".\"travel\""},
      {R"("homing": {"x": {"switch": "min", "seek": 20, "locate": 2, "pull_off": 1, "speed": 3}})", 7, "\"homing\".\"x\".\"speed\"",
       "unknown key"},
      {R"("homing": {"order": ["x", "x"], )" + x + "}", 7, "\"homing\".\"order\"[1]", "listed twice"},
      {R"("homing": {"order": ["z"], )" + x + "}", 7, "\"homing\".\"order\"[0]", "\"z\" is no axis of the \"homing\" section"},
      {R"("homing": {"order": [], )" + x + "}", 7, "\"homing\".\"order\"", ""},
      {R"("homing": {})", 7, "\"homing\"", "homes no axis"},
  };
  testing::check_bad_sections(cases, "homing_machine.json", homing_axes);
}
