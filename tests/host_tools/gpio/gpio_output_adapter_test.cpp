// SPDX-License-Identifier: MIT
// CountingOutput (host_tools/src/gpio_command_output.hpp): signed step counts and edges passed on.
#include <cstdint>
#include <ctime>
#include <vector>

#include <catch2/catch.hpp>

#include "gpio_command_output.hpp"

using curvestep::host::CountingOutput;

namespace {

timespec now() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t;
}

/// Records what reaches the GPIO output.
struct FakeGpio {
  std::vector<timespec> epochs;
  std::vector<std::uint64_t> step_times;
  std::vector<bool> directions;
  int fault_stops = 0;
  void set_epoch(const timespec& e, bool) { epochs.push_back(e); }
  void set_step(std::uint64_t t, std::uint8_t, bool high) {
    if (high) step_times.push_back(t);
  }
  void set_direction(std::uint64_t, std::uint8_t, bool positive) { directions.push_back(positive); }
  void fault_stop() { ++fault_stops; }
};

}  // namespace

TEST_CASE("gpio output: steps are counted per axis and signed by the direction level", "[host_tools][gpio]") {
  FakeGpio gpio;
  CountingOutput<FakeGpio> out(&gpio);
  out.set_epoch(now(), true);
  out.set_step(10, 0, true);
  out.set_step(12, 0, false);
  out.set_direction(20, 0, false);
  for (const std::uint64_t t : {std::uint64_t{30}, std::uint64_t{40}, std::uint64_t{50}}) {
    out.set_step(t, 0, true);
    out.set_step(t + 2, 0, false);
  }
  out.set_direction(60, 2, false);
  out.set_step(70, 2, true);
  CHECK(out.steps()[0] == 4);
  CHECK(out.net_steps()[0] == 1 - 3);
  CHECK(out.steps()[1] == 0);
  CHECK(out.net_steps()[2] == -1);
  CHECK(gpio.step_times == std::vector<std::uint64_t>{10, 30, 40, 50, 70});
  CHECK(gpio.directions == std::vector<bool>{false, false});
  CHECK(gpio.epochs.size() == 1);  // passed on once, as run_device gives it
  out.fault_stop();
  CHECK(gpio.fault_stops == 1);
}

TEST_CASE("gpio output: a dry run (no inner output) only counts", "[host_tools][gpio]") {
  CountingOutput<FakeGpio> dry(nullptr);
  dry.set_epoch(now(), false);
  dry.set_direction(0, 1, false);
  dry.set_step(1, 1, true);
  dry.set_step(3, 1, false);
  CHECK(dry.steps()[1] == 1);
  CHECK(dry.net_steps()[1] == -1);
}
