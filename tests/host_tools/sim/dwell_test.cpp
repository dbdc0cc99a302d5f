// SPDX-License-Identifier: MIT
// G4 dwells and exact stops in the simulated motion: a dwell of P seconds is round(P x rate) ticks
// at rest at the joint (halves up), inserted into the stream without changing anything else, and
// the events that need the machine at rest make their joint an exact stop.
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/host/gcode_import.hpp>
#include <curvestep/host/joint_stops.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/simulator.hpp>

using namespace curvestep;
using namespace curvestep::host;

namespace {

/// The example machine: 1 kHz, S-curve, feed 50 mm/s.
MachineLimits machine_1khz() {
  const MachineLimits m = load_machine(std::filesystem::path(CURVESTEP_SOURCE_DIR) / "examples" / "jobs" / "machine.json");
  REQUIRE(m.rate_hz == 1000);
  return m;
}

std::vector<SetpointRecord> run(const std::string& program) {
  return simulate(parse_gcode_job(program, "dwell.ngc"), machine_1khz()).setpoints;
}

/// Index of the first setpoint that differs from `a` in `b` (their common length if none); the
/// planned speed counts too (the first tick past a joint may round to the joint's position).
std::size_t first_difference(const std::vector<SetpointRecord>& a, const std::vector<SetpointRecord>& b) {
  std::size_t i = 0;
  while (i < a.size() && i < b.size() && a[i].raw_q16 == b[i].raw_q16 && a[i].index == b[i].index &&
         a[i].speed_mm_per_s == b[i].speed_mm_per_s) {
    ++i;
  }
  return i;
}

/// `with` is `without` with `rest` setpoints at x = `x` mm (speed 0) inserted at some index, the
/// rest of the stream bit for bit the same, `rest` ticks later.
void check_rest_inserted(const std::vector<SetpointRecord>& without, const std::vector<SetpointRecord>& with, std::uint64_t rest,
                         double x) {
  REQUIRE(with.size() == without.size() + rest);
  const std::size_t at = first_difference(without, with);
  REQUIRE(at + rest <= with.size());
  for (std::size_t i = at; i < at + rest; ++i) {
    REQUIRE(with[i].position_mm[0] == x);
    REQUIRE(with[i].position_mm[1] == 0.0);
    REQUIRE(with[i].speed_mm_per_s == 0.0);
  }
  for (std::size_t i = at; i < without.size(); ++i) {
    REQUIRE(with[i + rest].raw_q16 == without[i].raw_q16);
    REQUIRE(with[i + rest].index == without[i].index + rest);
  }
}

}  // namespace

TEST_CASE("dwell: G4 P0.5 at 1 kHz is exactly 500 ticks at rest at the joint", "[host_tools][sim][dwell]") {
  // Straight on: the dwell also makes the joint an exact stop, so compare with G4 P0 (a stop, no rest).
  const auto stop_only = run("G21 G90\nG1 X10 F600\nG4 P0\nG1 X20\n");
  const auto dwelled = run("G21 G90\nG1 X10 F600\nG4 P0.5\nG1 X20\n");
  check_rest_inserted(stop_only, dwelled, 500, 10.0);
  // The stop: two 10 mm moves from rest to rest, each as long as a lone one (within a tick).
  const auto lone = run("G21 G90\nG1 X10 F600\n");
  const auto passed = run("G21 G90\nG1 X10 F600\nG1 X20\n");
  CHECK(stop_only.size() + 1 >= 2 * lone.size() - 1);
  CHECK(stop_only.size() <= 2 * lone.size());
  CHECK(passed.size() < stop_only.size());
  // At a reversal the motion stops anyway: the dwell is all that differs from no dwell at all.
  check_rest_inserted(run("G21 G90\nG1 X10 F600\nG1 X0\n"), run("G21 G90\nG1 X10 F600\nG4 P0.5\nG1 X0\n"), 500, 10.0);
}

TEST_CASE("dwell: two dwells at one joint add up, M0 and M6 stop without a rest", "[host_tools][sim][dwell]") {
  const auto stop_only = run("G21 G90\nG1 X10 F600\nG4 P0\nG1 X20\n");
  check_rest_inserted(stop_only, run("G21 G90\nG1 X10 F600\nG4 P0.25\nG4 P0.125\nG1 X20\n"), 375, 10.0);
  CHECK(run("G21 G90\nG1 X10 F600\nM0\nG1 X20\n").size() == stop_only.size());
  CHECK(run("G21 G90\nG1 X10 F600\nT2 M6\nG1 X20\n").size() == stop_only.size());
  // Spindle and coolant words need no stop: the joint is passed at speed.
  CHECK(run("G21 G90\nG1 X10 F600\nM8\nG1 X20\n").size() == run("G21 G90\nG1 X10 F600\nG1 X20\n").size());
}

TEST_CASE("dwell: whole ticks at the control rate, halves rounded up", "[host_tools][sim][dwell]") {
  CHECK(dwell_ticks(0.5, 1000) == 500);
  CHECK(dwell_ticks(0.0015, 1000) == 2);   // 1.5 ticks
  CHECK(dwell_ticks(0.0014, 1000) == 1);   // 1.4 ticks
  CHECK(dwell_ticks(0.0004, 1000) == 0);   // below half a tick: a stop only
  CHECK(dwell_ticks(2.5, 40000) == 100000);
  CHECK(dwell_ticks(0, 1000) == 0);
  CHECK_THROWS_AS(dwell_ticks(-1, 1000), std::invalid_argument);
  CHECK_THROWS_AS(dwell_ticks(5e6, 1000), std::invalid_argument);  // 5e9 ticks > 2^32 - 1
}

TEST_CASE("dwell: joint stops come from the events before each segment", "[host_tools][sim][dwell]") {
  const Job job = parse_gcode_job("G21 G90\nG4 P0.01\nG1 X10 F600\nM3 S1000\nG1 X20\nG4 P0.002\nM0\nG1 X30\nG4 P9\n", "stops.ngc");
  REQUIRE(job.segments.size() == 3);
  const auto stops = joint_stops(job, 1000);
  REQUIRE(stops.size() == 4);  // one per segment, then the job's end
  CHECK(stops[0] == JointStop{true, 10});
  CHECK(stops[1] == JointStop{});  // M3 alone: passed at speed
  CHECK(stops[2] == JointStop{true, 2});
  CHECK(stops[3] == JointStop{true, 9000});  // G4 P9 after the last move: 9 s at 1 kHz at its end
}

TEST_CASE("dwell: a G4 after the last move rests at the end point and adds its time", "[host_tools][sim][dwell]") {
  // G4 P2 then M2: the motion to X10 is unchanged, then 2 s x 1 kHz = 2000 setpoints at X10 with
  // speed 0; the job (and sim's duration) ends exactly 2 s later.
  const auto plain = run("G21 G90\nG1 X10 F600\nM2\n");
  const auto dwelled = run("G21 G90\nG1 X10 F600\nG4 P2\nM2\n");
  check_rest_inserted(plain, dwelled, 2000, 10.0);
  CHECK(dwelled.size() == plain.size() + 2000);
  CHECK(dwelled.back().time_s == Approx(plain.back().time_s + 2.0).margin(1e-9));
  CHECK(dwelled.back().index == plain.back().index + 2000);
  const auto summary = simulate(parse_gcode_job("G21 G90\nG1 X10 F600\nG4 P2\nM2\n", "dwell.ngc"), machine_1khz()).summary;
  CHECK(summary.duration_s == Approx(plain.back().time_s + 2.0).margin(1e-9));
}
