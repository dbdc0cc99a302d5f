// SPDX-License-Identifier: MIT
// The simulator's summary against a second computation written here (finite differences of the
// double setpoints), its per-axis step-rate verdicts, and a progress fraction that follows the
// distance travelled.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/host/job.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/simulator.hpp>

using namespace curvestep;
using namespace curvestep::host;

namespace {

std::string source(const std::string& relative) { return std::string(CURVESTEP_SOURCE_DIR) + "/" + relative; }

bool mentions(const std::vector<std::string>& lines, const std::string& part) {
  return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(part) != std::string::npos; });
}

}  // namespace

TEST_CASE("sim summary: peaks and distance are the finite differences of the exact setpoints", "[host_tools][sim]") {
  const Job job = load_job(source("examples/jobs/every_type.json"));
  const MachineLimits machine = load_machine(source("examples/jobs/machine.json"));
  SimulationOptions options;
  options.fixed_point = false;  // the setpoints hold the exact positions the summary differences
  const SimulationResult r = simulate(job, machine, options);
  const auto& p = r.setpoints;
  const double dt = 1.0 / machine.rate_hz;
  double distance = 0, speed = 0, acceleration = 0, jerk = 0;
  std::array<double, 3> axis_speed{};
  for (std::size_t i = 1; i < p.size(); ++i) {
    double v = 0, a = 0, j = 0;
    for (std::size_t k = 0; k < 3; ++k) {
      const double d1 = p[i].position_mm[k] - p[i - 1].position_mm[k];
      v += d1 * d1;
      axis_speed[k] = std::max(axis_speed[k], std::fabs(d1) / dt);
      if (i >= 2) a += std::pow(p[i].position_mm[k] - 2 * p[i - 1].position_mm[k] + p[i - 2].position_mm[k], 2);
      if (i >= 3) {
        j += std::pow(p[i].position_mm[k] - 3 * p[i - 1].position_mm[k] + 3 * p[i - 2].position_mm[k] - p[i - 3].position_mm[k], 2);
      }
    }
    distance += std::sqrt(v);
    speed = std::max(speed, std::sqrt(v) / dt);
    acceleration = std::max(acceleration, std::sqrt(a) / (dt * dt));
    jerk = std::max(jerk, std::sqrt(j) / (dt * dt * dt));
  }
  const auto& s = r.summary;
  CHECK(s.distance_mm == Approx(distance).epsilon(1e-12));
  CHECK(s.peak_speed_mm_per_s == Approx(speed).epsilon(1e-12));
  CHECK(s.peak_acceleration_mm_per_s2 == Approx(acceleration).epsilon(1e-12));
  CHECK(s.peak_jerk_mm_per_s3 == Approx(jerk).epsilon(1e-12));
  for (std::size_t k = 0; k < 3; ++k) CHECK(s.peak_step_rate_hz[k] == Approx(axis_speed[k] * machine.axes[k].steps_per_mm).epsilon(1e-12));
  // The drawing moves at up to 150 mm/s (the rapid), so distance and peak speed are not trivial.
  CHECK(s.peak_speed_mm_per_s == Approx(150).epsilon(1e-3));
}

TEST_CASE("sim summary: every axis above max_step_rate is named, and only those", "[host_tools][sim]") {
  const Job job = load_job(source("examples/jobs/every_type.json"));
  MachineLimits machine = load_machine(source("examples/jobs/machine.json"));
  const SimulationResult fast = simulate(job, machine);
  const auto& peak = fast.summary.peak_step_rate_hz;
  REQUIRE(peak[0] > 0);
  REQUIRE(peak[1] > peak[0]);
  CHECK(peak[2] == 0);
  CHECK_FALSE(mentions(fast.summary.violations, "max_step_rate"));
  // A limit between the two peaks: y only. Below both: x and y.
  machine.max_step_rate_hz = (peak[0] + peak[1]) / 2;
  SimulationResult r = simulate(job, machine);
  CHECK(mentions(r.summary.violations, "axis y needs"));
  CHECK_FALSE(mentions(r.summary.violations, "axis x needs"));
  machine.max_step_rate_hz = peak[0] / 2;
  r = simulate(job, machine);
  CHECK(mentions(r.summary.violations, "axis x needs"));
  CHECK(mentions(r.summary.violations, "axis y needs"));
  CHECK_FALSE(mentions(r.summary.violations, "axis z needs"));
}

TEST_CASE("sim progress: the fraction follows the distance travelled, even for a one-segment job", "[host_tools][sim]") {
  // One 100 mm line at 1 mm/s: about 100 s, 100 000 setpoints at 1 kHz, reported every 20 000.
  // Segments queued over the total would say 1.0 at once; the distance says about 0.2, 0.4, ...
  const Job job = parse_job(R"({"version": 1, "segments": [{"type": "line", "points": [[0, 0], [100, 0]], "feed": 1}]})",
                            "slow.json");
  const MachineLimits machine = load_machine(source("examples/jobs/machine.json"));
  std::vector<double> fractions;
  SimulationOptions options;
  options.progress = [&](double f) { fractions.push_back(f); };
  const SimulationResult r = simulate(job, machine, options);
  REQUIRE(r.summary.duration_s == Approx(100).margin(0.5));
  REQUIRE(fractions.size() == 6);  // at 20 000, 40 000, ..., 100 000 setpoints, then 1.0 at the end
  for (std::size_t i = 0; i + 1 < fractions.size(); ++i) {
    INFO("report " << i);
    // After 20 000·(i+1) setpoints (20·(i+1) s at 1 mm/s; the ramp to 1 mm/s takes milliseconds).
    CHECK(fractions[i] == Approx(0.2 * static_cast<double>(i + 1)).margin(0.01));
    CHECK(fractions[i] <= 0.999);
  }
  CHECK(fractions.back() == 1.0);
}
