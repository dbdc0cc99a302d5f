// SPDX-License-Identifier: MIT
// CountingOutput (host_tools/src/gpio_command_output.hpp): signed step counts, edges passed on, and
// the inner output's edge clock re-based when the step generator's time lies in the past.
#include <cstdint>
#include <ctime>
#include <vector>

#include <catch2/catch.hpp>

#include "gpio_command_output.hpp"

using curvestep::host::CountingOutput;

namespace {

std::int64_t ns(const timespec& t) { return std::int64_t{t.tv_sec} * 1000000000 + t.tv_nsec; }

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
  CountingOutput<FakeGpio> out(&gpio, 1000000, 1000);
  out.set_epoch(now(), true);  // fast: no clock keeping
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
  CHECK(gpio.epochs.size() == 1);  // only run_device's
  out.fault_stop();
  CHECK(gpio.fault_stops == 1);
}

TEST_CASE("gpio output: an edge more than a control period late re-bases the inner clock to now", "[host_tools][gpio]") {
  FakeGpio gpio;
  CountingOutput<FakeGpio> out(&gpio, 1000000, 1000);  // 1 us timer ticks, 1 ms control period
  timespec start = now();
  start.tv_sec -= 5;  // the device started 5 s ago; the job's step time 0 is now
  out.set_epoch(start, false);
  REQUIRE(gpio.epochs.size() == 1);
  const std::int64_t before = ns(now());
  out.set_step(3000, 0, true);  // step-timer time 3 ms: 4.997 s late
  const std::int64_t after = ns(now());
  REQUIRE(gpio.epochs.size() == 2);
  CHECK(out.rebases() == 1);
  // The new epoch maps time 3000 us to the moment of the call: epoch = now - 3 ms.
  CHECK(ns(gpio.epochs[1]) >= before - 3000000);
  CHECK(ns(gpio.epochs[1]) <= after - 3000000);
  // Edges on time (or early) after that leave the clock alone.
  out.set_step(3002, 0, false);
  out.set_step(3500, 0, true);
  CHECK(out.rebases() == 1);
  CHECK(gpio.epochs.size() == 2);
  // Without an inner output nothing is re-based (dry run).
  CountingOutput<FakeGpio> dry(nullptr, 1000000, 1000);
  dry.set_epoch(start, false);
  dry.set_step(0, 1, true);
  CHECK(dry.rebases() == 0);
  CHECK(dry.net_steps()[1] == 1);
}
