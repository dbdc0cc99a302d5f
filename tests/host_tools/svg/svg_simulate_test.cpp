// SPDX-License-Identifier: MIT
// An imported drawing runs through the host simulator within the machine's limits.
#include <catch2/catch.hpp>

#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/simulator.hpp>
#include <curvestep/host/svg_import.hpp>

#include "svg_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::testing;

TEST_CASE("svg: an imported circle and wave simulate without limit violations", "[host_tools][svg]") {
  const Job job = parse_svg_job(page("<circle cx=\"20\" cy=\"30\" r=\"10\"/><path d=\"M 40 50 C 50 30 60 70 70 50 A 10 5 30 1 1 90 60\"/>"),
                                "sim.svg", {});
  const MachineLimits machine = load_machine(std::filesystem::path(CURVESTEP_JOBS_EXAMPLES) / "machine.json");
  const auto result = simulate(job, machine);
  INFO(format_summary(result.summary, machine));
  CHECK(result.summary.violations.empty());
  REQUIRE(!result.setpoints.empty());
  // It ends where the last arc ends: user (90, 60) = machine (90, 40).
  const auto& last = result.setpoints.back().position_mm;
  CHECK(near(MachinePoint{{last[0], last[1], last[2]}}, on_page(90, 60), 1e-3));
  // Every setpoint of the circle's segments lies on the circle (within Q16.16 and the planner's sagitta).
  for (const auto& setpoint : result.setpoints) {
    if (setpoint.segment >= 1 && setpoint.segment <= 4) {
      CHECK(std::hypot(setpoint.position_mm[0] - 20, setpoint.position_mm[1] - 70) == Approx(10).margin(1e-3));
    }
  }
}
