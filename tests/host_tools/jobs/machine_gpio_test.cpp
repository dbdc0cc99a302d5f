// SPDX-License-Identifier: MIT
// The machine file's optional "gpio" section (issue 6): parsed into GpioWiring, validated, with
// errors naming the file, line and key; unknown keys stay errors.
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/error.hpp>
#include <curvestep/host/machine_file.hpp>

#include "machine_error.hpp"

using namespace curvestep;
using namespace curvestep::host;

namespace {

/// A valid machine file (lines 1..6) followed by `extra` members of the root object (from line 7).
std::string machine_with(const std::string& extra) { return testing::machine_text(extra); }

}  // namespace

TEST_CASE("machine gpio: the section maps onto GpioWiring, the other keys are still read", "[host_tools][jobs][gpio]") {
  const MachineFile file = parse_machine_file(machine_with(R"("gpio": {"chip": "gpiochip0",
           "x": {"step": "GPIO17", "dir": "GPIO27"},
           "y": {"step": "GPIO22", "dir": "GPIO23", "invert_dir": true}})"),
                                              "m.json");
  REQUIRE(file.gpio.has_value());
  CHECK(file.gpio->chip == "gpiochip0");
  REQUIRE(file.gpio->axes[0].has_value());
  CHECK(file.gpio->axes[0]->step == "GPIO17");
  CHECK(file.gpio->axes[0]->dir == "GPIO27");
  CHECK_FALSE(file.gpio->axes[0]->invert_dir);
  REQUIRE(file.gpio->axes[1].has_value());
  CHECK(file.gpio->axes[1]->step == "GPIO22");
  CHECK(file.gpio->axes[1]->dir == "GPIO23");
  CHECK(file.gpio->axes[1]->invert_dir);
  CHECK_FALSE(file.gpio->axes[2].has_value());
  CHECK(file.limits.max_step_rate_hz == 40000);
  CHECK(file.limits.rapid_mm_per_s == 150);
  CHECK_FALSE(file.limits.jerk_limited);
  CHECK(file.limits.axes[0].steps_per_mm == 80);
  // load_machine / parse_machine accept (and validate) the section too; without it there is none.
  CHECK(parse_machine(machine_with(R"("gpio": {"chip": "0", "z": {"step": "a", "dir": "b"}})"), "m.json").v_max_mm_per_s == 200);
  CHECK_FALSE(parse_machine_file(machine_with(""), "m.json").gpio.has_value());
}

TEST_CASE("machine gpio: limit switch input lines per axis and their level", "[host_tools][jobs][gpio][limits]") {
  const MachineFile file = parse_machine_file(machine_with(R"("gpio": {"chip": "gpiochip0", "switches_active_low": true,
           "x": {"step": "GPIO17", "dir": "GPIO27", "min": "GPIO5", "max": "GPIO6"},
           "y": {"step": "GPIO22", "dir": "GPIO23", "max": "GPIO13"}})"),
                                              "m.json");
  REQUIRE(file.gpio.has_value());
  CHECK(file.gpio->switches_active_low);
  CHECK(file.gpio->axes[0]->min_switch == "GPIO5");
  CHECK(file.gpio->axes[0]->max_switch == "GPIO6");
  CHECK(file.gpio->axes[1]->min_switch.empty());
  CHECK(file.gpio->axes[1]->max_switch == "GPIO13");
  CHECK_FALSE(parse_machine_file(machine_with(R"("gpio": {"chip": "c", "x": {"step": "A", "dir": "B"}})"), "m.json")
                  .gpio->switches_active_low);
}

TEST_CASE("machine gpio: bad sections name the file, line and key", "[host_tools][jobs][gpio]") {
  const testing::BadSection cases[] = {
      {R"("gpio": {"x": {"step": "A", "dir": "B"}})", 7, "\"gpio\".\"chip\"", "missing required key"},
      {R"("gpio": {"chip": "", "x": {"step": "A", "dir": "B"}})", 7, "\"gpio\".\"chip\"", "must not be empty"},
      {R"("gpio": {"chip": 0, "x": {"step": "A", "dir": "B"}})", 7, "\"gpio\".\"chip\"", "expected a string, got a number"},
      {R"("gpio": {"chip": "c"})", 7, "\"gpio\"", "wires no axis"},
      {"\"gpio\": {\"chip\": \"c\",\n  \"x\": {\"dir\": \"B\"}}", 8, "\"gpio\".\"x\".\"step\"", "missing required key"},
      {"\"gpio\": {\"chip\": \"c\",\n  \"x\": {\"step\": \"A\", \"dir\": \"\"}}", 8, "\"gpio\".\"x\".\"dir\"", "must not be empty"},
      {"\"gpio\": {\"chip\": \"c\",\n  \"x\": {\"step\": \"A\", \"dir\": \"B\"},\n  \"y\": {\"step\": \"C\", \"dir\": \"A\"}}", 9,
       "\"gpio\".\"y\".\"dir\"", "line \"A\" is already used by \"gpio\".\"x\".\"step\""},
      {"\"gpio\": {\"chip\": \"c\",\n  \"x\": {\"step\": \"A\", \"dir\": \"B\", \"invert_dir\": 1}}", 8,
       "\"gpio\".\"x\".\"invert_dir\"", "expected true or false"},
      {"\"gpio\": {\"chip\": \"c\",\n  \"x\": {\"step\": \"A\", \"dir\": \"B\", \"pulse_us\": 5}}", 8,
       "\"gpio\".\"x\".\"pulse_us\"", "unknown key (expected one of: step, dir, invert_dir, min, max, comment)"},
      {"\"gpio\": {\"chip\": \"c\",\n  \"w\": {\"step\": \"A\", \"dir\": \"B\"}}", 8, "\"gpio\".\"w\"",
       "unknown key (expected one of: chip, x, y, z, switches_active_low, spindle, coolant, outputs, comment)"},
      {"\"gpio\": {\"chip\": \"c\", \"x\": {\"step\": \"A\", \"dir\": \"B\"},\n  \"outputs\": [\"C\", \"A\"]}", 8,
       "\"gpio\".\"outputs\"[1]", "line \"A\" is already used by \"gpio\".\"x\".\"step\""},
      {"\"gpio\": {\"chip\": \"c\", \"x\": {\"step\": \"A\", \"dir\": \"B\"},\n  \"outputs\": \"C\"}", 8,
       "\"gpio\".\"outputs\"", "expected an array"},
      {"\"gpio\": {\"chip\": \"c\", \"x\": {\"step\": \"A\", \"dir\": \"B\"},\n  \"outputs\": []}", 8,
       "\"gpio\".\"outputs\"", "expected 1 to 64 entries, got 0"},
      {"\"gpio\": {\"chip\": \"c\", \"x\": {\"step\": \"A\", \"dir\": \"B\"},\n  \"spindle\": {\"enable\": \"E\", \"pwm\": \"P\"}}", 8,
       "\"gpio\".\"spindle\".\"pwm\"", "unknown key (expected one of: enable, direction, comment)"},
      {"\"gpio\": {\"chip\": \"c\", \"x\": {\"step\": \"A\", \"dir\": \"B\"},\n  \"coolant\": {\"mist\": \"M\", \"flood\": \"M\"}}", 8,
       "\"gpio\".\"coolant\".\"flood\"", "line \"M\" is already used by \"gpio\".\"coolant\".\"mist\""},
      {"\"gpio\": {\"chip\": \"c\",\n  \"x\": {\"step\": \"A\", \"dir\": \"B\", \"min\": 5}}", 8, "\"gpio\".\"x\".\"min\"",
       "expected a string, got a number"},
      {"\"gpio\": {\"chip\": \"c\",\n  \"x\": {\"step\": \"A\", \"dir\": \"B\", \"max\": \"\"}}", 8, "\"gpio\".\"x\".\"max\"",
       "must not be empty"},
      {"\"gpio\": {\"chip\": \"c\",\n  \"x\": {\"step\": \"A\", \"dir\": \"B\", \"max\": \"B\"}}", 8, "\"gpio\".\"x\".\"max\"",
       "line \"B\" is already used by \"gpio\".\"x\".\"dir\""},
      {"\"gpio\": {\"chip\": \"c\", \"switches_active_low\": \"yes\",\n  \"x\": {\"step\": \"A\", \"dir\": \"B\"}}", 7,
       "\"gpio\".\"switches_active_low\"", "expected true or false"},
      {R"("gpio": "gpiochip0")", 7, "\"gpio\"", "expected an object"},
      {R"("gpoi": {"chip": "c"})", 7, "\"gpoi\"", "unknown key"},
  };
  testing::check_bad_sections(cases, "gpio_machine.json");
}

TEST_CASE("machine gpio: the machine outputs' lines map onto GpioWiring, and load_machine_wiring reads only gpio and pen",
          "[host_tools][jobs][gpio]") {
  const MachineFile file = parse_machine_file(machine_with(R"("gpio": {"chip": "gpiochip0", "x": {"step": "S", "dir": "D"},
           "spindle": {"enable": "EN", "direction": "CCW"}, "coolant": {"flood": "FL"}, "outputs": ["O0", "O1", "O2"]})"),
                                              "m.json");
  REQUIRE(file.gpio.has_value());
  CHECK(file.gpio->spindle_enable == "EN");
  CHECK(file.gpio->spindle_direction == "CCW");
  CHECK(file.gpio->coolant_mist.empty());  // not wired
  CHECK(file.gpio->coolant_flood == "FL");
  CHECK(file.gpio->outputs == std::vector<std::string>{"O0", "O1", "O2"});
  const auto path = std::filesystem::temp_directory_path() / ("wiring_" + std::to_string(getpid()) + ".json");
  std::ofstream(path) << R"({"gpio": {"chip": "c", "x": {"step": "S", "dir": "D"}, "outputs": ["O0"]},
  "pen": {"axis": "servo", "line": "SERVO", "up_pulse_us": 1000, "down_pulse_us": 2000, "settle": 0.1}})";
  const MachineWiring wiring = load_machine_wiring(path);  // no limits: not read
  std::filesystem::remove(path);
  REQUIRE(wiring.gpio.has_value());
  CHECK(wiring.gpio->outputs == std::vector<std::string>{"O0"});
  REQUIRE(wiring.pen.has_value());
  CHECK(wiring.pen->line == "SERVO");
}
