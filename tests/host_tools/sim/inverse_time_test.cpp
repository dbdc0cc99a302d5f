// SPDX-License-Identifier: MIT
// G93 inverse-time feed in the simulated motion: on a machine whose acceleration and jerk are so
// high that speeding up and slowing down take well under a tick, each move takes 1/F minutes, so
// the job takes the sum of 1/F (hand-computed) to within a tick or two per move. A compensated
// inverse-time program runs on the example machine without a limit violation.
#include <cmath>
#include <filesystem>
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/host/gcode_import.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/simulator.hpp>

using namespace curvestep;
using namespace curvestep::host;

namespace {

/// 1 kHz, v_max 1000 mm/s, a 10^9 mm/s², j 10^12 mm/s³: reaching 10 mm/s takes about 0.2 ms.
MachineLimits stiff_machine() {
  MachineLimits m;
  m.v_max_mm_per_s = 1000;
  m.a_max_mm_per_s2 = 1e9;
  m.j_max_mm_per_s3 = 1e12;
  m.rapid_mm_per_s = 1000;
  m.rate_hz = 1000;
  REQUIRE(m.validate());
  return m;
}

double duration_s(const std::string& program) {
  SimulationOptions options;
  options.fixed_point = false;
  return simulate(parse_gcode_job(program, "inverse.ngc"), stiff_machine(), options).summary.duration_s;
}

}  // namespace

TEST_CASE("inverse time: a G93 square takes the sum of its moves' 1/F minutes", "[host_tools][sim][feed]") {
  // 10 mm sides at F6, F12, F3, F60: 10 s + 5 s + 20 s + 1 s = 36 s.
  const double square = duration_s("G21 G90 G0 X0 Y0\nG93 G1 X10 F6\nY10 F12\nX0 F3\nY0 F60\n");
  CHECK(square == Approx(36.0).margin(0.004));
  // The same lengths at other F: 10 s + 10 s + 10 s + 10 s.
  CHECK(duration_s("G93 G1 X10 F6\nY10 F6\nX0 F6\nY0 F6\n") == Approx(40.0).margin(0.004));
  // Inches: 1 in at F12 is 5 s whatever its length in mm.
  CHECK(duration_s("G20 G93 G1 X1 F12\n") == Approx(5.0).margin(0.002));
}

TEST_CASE("inverse time: a G93 arc and helix take 1/F minutes along their exact length", "[host_tools][sim][feed]") {
  // The rapid to the start, 10 mm at 1000 mm/s, takes 0.01 s. Then half a circle of radius 10
  // (10π mm) at F6: 10 s; a whole turn rising 5 mm at F4: 15 s.
  constexpr double rapid_s = 0.01;
  CHECK(duration_s("G0 X10 Y0\nG93 G3 X-10 Y0 I-10 J0 F6\n") == Approx(rapid_s + 10.0).margin(0.002));
  CHECK(duration_s("G0 X10 Y0\nG93 G2 X10 Y0 Z5 I-10 J0 F4\n") == Approx(rapid_s + 15.0).margin(0.002));
  // G94 afterwards: 10 mm at F60 (mm/min) takes 10 s, added to the arc's.
  CHECK(duration_s("G0 X10 Y0\nG93 G3 X-10 Y0 I-10 J0 F6\nG94 G1 X0 F60\n") == Approx(rapid_s + 20.0).margin(0.004));
}

TEST_CASE("inverse time: a compensated G93 program runs on the example machine without a limit violation",
          "[host_tools][sim][feed]") {
  // In the manner of LinuxCNC's inverse-time-with-comp test: cutter compensation on both sides and
  // none, inverse-time lines and an arc, back to G94 with the exit move.
  const std::string program =
      "G21 G90 G17\n"
      "o100 sub\n"
      "G0 X0 Y0 Z0\n"
      "G41.1 D#1\n"
      "G93 G1 X25 F30\n"
      "Y25 F20\n"
      "X-25 F15\n"
      "Y50 F10\n"
      "G94 X25 F600\n"
      "Y75\n"
      "X0\n"
      "Y100\n"
      "G93 G3 Y125 J12.5 F10\n"
      "G40 G94 G1 Y150 F500\n"
      "o100 endsub\n"
      "o100 call [0]\n"
      "o100 call [8]\n"
      "o100 call [-8]\n"
      "M2\n";
  const MachineLimits machine = load_machine(std::filesystem::path(CURVESTEP_SOURCE_DIR) / "examples" / "jobs" / "machine.json");
  const SimulationResult result = simulate(parse_gcode_job(program, "comp.ngc"), machine);
  CHECK(result.summary.violations.empty());
  CHECK(result.summary.duration_s > 3 * (2 + 3 + 4 + 6) * 1.0);  // at least the inverse-time lines' 2 s, 3 s, 4 s, 6 s
}
