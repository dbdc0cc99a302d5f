// SPDX-License-Identifier: MIT
// Path smoothing: the smoothed path stays within the tolerance of the programmed polyline (distances
// computed here, from the programmed vertices and the smoothed segments' own evaluation), joints
// are passed at the segments' speed, and the issue's jobs run at feed within every limit.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/motion/path_length_table.hpp>
#include <curvestep/core/motion/segment_plan.hpp>
#include <curvestep/host/gcode_import.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/simulator.hpp>
#include <curvestep/host/smoothing/path_smoothing.hpp>
#include <curvestep/host/smoothing/smoothing_stream.hpp>

#include "polyline_jobs.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::testing;

namespace {

/// Distance from p to the segment [a, b] (written here, independent of the code under test).
double to_segment(const MachinePoint& p, const MachinePoint& a, const MachinePoint& b) {
  const MachinePoint d = b - a;
  const double l2 = dot(d, d);
  const double t = l2 > 0 ? std::clamp(dot(p - a, d) / l2, 0.0, 1.0) : 0.0;
  return norm(p - (a + d * t));
}

double to_polyline(const MachinePoint& p, const std::vector<MachinePoint>& line) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < line.size(); ++i) best = std::fmin(best, to_segment(p, line[i - 1], line[i]));
  return best;
}

/// The programmed polyline of a job of lines.
std::vector<MachinePoint> vertices_of(const Job& job) {
  std::vector<MachinePoint> v{job.segments.front().start()};
  for (const auto& s : job.segments) v.push_back(s.end());
  return v;
}

/// The smoothed path, each segment evaluated at `per_segment` + 1 points.
std::vector<MachinePoint> trace(const Job& job, std::size_t per_segment = 100) {
  std::vector<MachinePoint> points;
  for (const auto& s : job.segments) {
    for (std::size_t k = points.empty() ? 0 : 1; k <= per_segment; ++k) points.push_back(s.point(static_cast<double>(k) / static_cast<double>(per_segment)));
  }
  return points;
}

struct Deviation {
  double path_to_programmed = 0;  ///< largest distance of a smoothed point from the programmed polyline
  double programmed_to_path = 0;  ///< largest distance of a programmed vertex from the smoothed path
};

Deviation deviation(const Job& programmed, const Job& smoothed) {
  const auto programmed_line = vertices_of(programmed);
  const auto path = trace(smoothed);
  Deviation d;
  for (const auto& p : path) d.path_to_programmed = std::fmax(d.path_to_programmed, to_polyline(p, programmed_line));
  for (const auto& v : programmed_line) d.programmed_to_path = std::fmax(d.programmed_to_path, to_polyline(v, path));
  return d;
}

MachineLimits example_machine() {
  return load_machine_file(std::filesystem::path(CURVESTEP_SOURCE_DIR) / "examples" / "jobs" / "machine.json").limits;
}

/// Connected end to start, every coordinate on the Q16.16 grid at the joints.
void require_connected(const Job& job) {
  for (std::size_t i = 1; i < job.segments.size(); ++i) {
    INFO("joint " << i);
    REQUIRE(job.segments[i].start() == job.segments[i - 1].end());
    REQUIRE(grid(job.segments[i].start()) == job.segments[i].start());
  }
}


/// Checks the smoothed path against the programmed polyline, both ways, within `tolerance` (plus
/// the sampling's overstatement of a vertex's distance, below 0.05 um on these jobs).
void check_within(const Job& programmed, const Job& smoothed, double tolerance) {
  const Deviation d = deviation(programmed, smoothed);
  CHECK(d.path_to_programmed <= tolerance);
  CHECK(d.programmed_to_path <= tolerance + 5e-5);
}

/// Smooths `programmed` at 10 um and checks the smoothed job keeps every limit and takes no longer
/// than as programmed (within half a tick); returns what smoothing did.
smoothing::SmoothingReport smoothed_within_limits_and_no_slower(const Job& programmed, const MachineLimits& machine) {
  smoothing::SmoothingReport report;
  const Job smoothed = smoothing::smooth_for_machine(programmed, machine, 0.01, &report);
  const auto as_programmed = simulate(programmed, machine).summary;
  const auto with_smoothing = simulate(smoothed, machine).summary;
  CHECK(with_smoothing.violations.empty());
  CHECK(with_smoothing.duration_s <= as_programmed.duration_s + 0.5 / machine.rate_hz);
  return report;
}

}  // namespace

TEST_CASE("smoothing: the smoothed path stays within the tolerance of the programmed polyline, both ways", "[host][smoothing]") {
  constexpr double tolerance = 0.01;
  // Sampling the smoothed curves at 100 points each can overstate a vertex's distance by the
  // sagitta of a sample chord (below 0.05 um on these jobs).
  constexpr double sampling = 5e-5;
  const struct {
    const char* name;
    std::vector<MachinePoint> vertices;
  } jobs[] = {
      {"circle of 360 chords", circle_chords(360)},
      {"circle of 36 chords", circle_chords(36)},
      {"spiral of 2000 points", spiral(2000)},
      {"3-axis raster", raster(4)},
      {"walk turning 5..120 degrees", turning_walk({5, -20, 45, 120, -90, 10, 2, -60}, 40, 3)},
      {"walk of 0.2 mm lines turning 1..8 degrees", turning_walk({1, 3, -2, 8, 5, -4}, 300, 0.2)},
  };
  for (const auto& j : jobs) {
    INFO(j.name);
    const Job programmed = polyline_job(j.vertices);
    smoothing::SmoothingReport report;
    const Job smoothed = smoothing::smooth_for_machine(programmed, example_machine(), tolerance, &report);
    require_connected(smoothed);
    CHECK(smoothed.segments.front().start() == programmed.segments.front().start());
    CHECK(smoothed.segments.back().end() == programmed.segments.back().end());
    const Deviation d = deviation(programmed, smoothed);
    CHECK(d.path_to_programmed <= tolerance);
    CHECK(d.programmed_to_path <= tolerance + sampling);
    // The report's own figure is an upper bound of what was measured here.
    CHECK(report.max_deviation_mm <= tolerance);
    CHECK(std::fmax(d.path_to_programmed, d.programmed_to_path) <= report.max_deviation_mm + sampling);
  }
}

TEST_CASE("smoothing: runs of short lines become few curves, and the joints inside them are smooth", "[host][smoothing]") {
  const Job programmed = polyline_job(circle_chords(3600));
  smoothing::SmoothingReport report;
  const Job smoothed = smoothing::smooth_for_machine(programmed, example_machine(), 0.01, &report);
  CHECK(report.runs_fitted == 1);
  CHECK(report.lines_fitted == 3600);
  CHECK(smoothed.segments.size() <= 40);
  // The planner passes every joint at the speed the neighbouring curves allow (no corner).
  const MachineLimits machine = example_machine();
  for (std::size_t i = 1; i < smoothed.segments.size(); ++i) {
    const auto a_table = PathLengthTable<64>::build(smoothed.segments[i - 1]).value();
    const auto b_table = PathLengthTable<64>::build(smoothed.segments[i]).value();
    const auto a = plan_segment(smoothed.segments[i - 1], a_table, machine).value();
    const auto b = plan_segment(smoothed.segments[i], b_table, machine).value();
    INFO("joint " << i);
    CHECK(junction_speed(a, b, machine) >= 0.99 * std::fmin(a.limits.speed_cap_mm_per_s, b.limits.speed_cap_mm_per_s));
  }
}

TEST_CASE("smoothing: a run that cannot be fitted whole is fitted in its longest pieces that can", "[host][smoothing][sim]") {
  // A random walk of 0.2 mm lines turning up to 25 degrees each (every joint joins the run): as a
  // whole it needs a curve piece per line, so no fit of all of it is kept. Each line was emitted
  // alone and the rest fitted whole again (a fit of the run per line: 20 000 such lines took 25 min);
  // now the longest prefixes that fit are taken, the rest after them.
  constexpr double tolerance = 0.01;
  std::vector<MachinePoint> walk{MachinePoint{}};
  double heading = 0;
  std::uint32_t state = 12345;
  for (int i = 0; i < 400; ++i) {
    state = state * 1664525u + 1013904223u;  // a fixed LCG: the same walk everywhere
    heading += (static_cast<double>(state >> 8) / 16777216.0 - 0.5) * 50 * pi / 180;
    walk.push_back(walk.back() + MachinePoint{{0.2 * std::cos(heading), 0.2 * std::sin(heading), 0}});
  }
  const MachineLimits machine = example_machine();
  const Job programmed = polyline_job(walk);
  smoothing::SmoothingReport report;
  const Job smoothed = smoothing::smooth_for_machine(programmed, machine, tolerance, &report);
  require_connected(smoothed);
  CHECK(report.runs_fitted > 20);
  CHECK(report.lines_fitted > 100);
  check_within(programmed, smoothed, tolerance);
  const auto as_programmed = simulate(programmed, machine).summary;
  const auto with_smoothing = simulate(smoothed, machine).summary;
  CHECK(with_smoothing.violations.empty());
  CHECK(with_smoothing.duration_s < as_programmed.duration_s);
}

TEST_CASE("smoothing: a jog smaller than the tolerance stays inside its run whatever its angle", "[host][smoothing][sim]") {
  // A circle of 0.1 mm chords with a 1 um step along x after every 20th vertex (what rounding leaves
  // in CAM output): each jog turns by up to 90 degrees, above the 30 degrees that end a run, and
  // each made a near-stop (4.17 s against 1.54 s for the circle without them).
  constexpr double tolerance = 0.01;
  const auto plain = circle_chords(628, 10);
  std::vector<MachinePoint> jogged;
  for (std::size_t i = 0; i < plain.size(); ++i) {
    jogged.push_back(plain[i]);
    if (i % 20 == 0 && i > 0 && i + 1 < plain.size()) jogged.push_back(plain[i] + MachinePoint{{0.001, 0, 0}});
  }
  const MachineLimits machine = example_machine();
  const Job programmed = polyline_job(jogged);
  smoothing::SmoothingReport report;
  const Job smoothed = smoothing::smooth_for_machine(programmed, machine, tolerance, &report);
  CHECK(report.runs_fitted == 1);
  CHECK(report.lines_fitted == programmed.segments.size());
  check_within(programmed, smoothed, tolerance);
  const auto with_jogs = simulate(smoothed, machine).summary;
  const auto without = simulate(smoothing::smooth_for_machine(polyline_job(plain), machine, tolerance), machine).summary;
  CHECK(with_jogs.violations.empty());
  CHECK(with_jogs.duration_s <= 1.01 * without.duration_s);
}

TEST_CASE("smoothing: a run longer than fit_max_run_lines is fitted as consecutive runs of that many lines", "[host][smoothing]") {
  smoothing::SmoothingOptions options = smoothing::options_for(example_machine(), 0.01);
  options.fit_max_run_lines = 1000;
  smoothing::SmoothingReport report;
  const Job smoothed = smoothing::smooth_job(polyline_job(circle_chords(3600)), options, &report);
  // 3600 = 1000 + 1000 + 1000 + 600 lines: four runs, their three joints inside the circle.
  CHECK(report.runs_fitted == 4);
  CHECK(report.lines_fitted == 3600);
  CHECK(smoothing::SmoothingOptions{}.fit_max_run_lines == 100'000);
  CHECK(smoothed.segments.front().start() == polyline_job(circle_chords(3600)).segments.front().start());
}

TEST_CASE("smoothing: a blended corner is curvature-continuous and passed at the blend's own speed", "[host][smoothing]") {
  // Two 10 mm lines meeting at 5 degrees: too few lines to fit, so a blend (at 20 degrees, at
  // 50 mm/s, a stop is faster: test below).
  const Job programmed = polyline_job({MachinePoint{{0, 0, 0}}, MachinePoint{{10, 0, 0}},
                                       MachinePoint{{10 + 10 * std::cos(pi / 36), 10 * std::sin(pi / 36), 0}}});
  const MachineLimits machine = example_machine();
  smoothing::SmoothingReport report;
  const Job smoothed = smoothing::smooth_for_machine(programmed, machine, 0.01, &report);
  REQUIRE(report.corners_blended == 1);
  REQUIRE(smoothed.segments.size() == 3);
  CHECK(smoothed.segments[1].kind() == SegmentKind::Bezier);
  for (std::size_t i = 1; i < 3; ++i) {
    const auto a = plan_segment(smoothed.segments[i - 1], PathLengthTable<64>::build(smoothed.segments[i - 1]).value(), machine).value();
    const auto b = plan_segment(smoothed.segments[i], PathLengthTable<64>::build(smoothed.segments[i]).value(), machine).value();
    INFO("joint " << i);
    CHECK(dot(a.end_tangent, b.start_tangent) > std::cos(2e-3));
    CHECK(junction_speed(a, b, machine) >= 0.99 * std::fmin(a.limits.speed_cap_mm_per_s, b.limits.speed_cap_mm_per_s));
  }
  // Unsmoothed, the corner's velocity jump allows a crawl only; smoothed, the blend's cap is far above.
  const auto line_a = plan_segment(programmed.segments[0], PathLengthTable<64>::build(programmed.segments[0]).value(), machine).value();
  const auto line_b = plan_segment(programmed.segments[1], PathLengthTable<64>::build(programmed.segments[1]).value(), machine).value();
  const auto blend = plan_segment(smoothed.segments[1], PathLengthTable<64>::build(smoothed.segments[1]).value(), machine).value();
  CHECK(blend.limits.speed_cap_mm_per_s > 10 * junction_speed(line_a, line_b, machine));
}

TEST_CASE("smoothing: rapids, exact stops, reversals and joints with events are kept as programmed", "[host][smoothing]") {
  const MachineLimits machine = example_machine();
  Job programmed = polyline_job({MachinePoint{{0, 0, 0}}, MachinePoint{{10, 0, 0}}, MachinePoint{{20, 0.5, 0}}, MachinePoint{{30, 0, 0}},
                                 MachinePoint{{40, 3, 0}}, MachinePoint{{30, 3, 0}}, MachinePoint{{20, 6, 0}}});
  // joints: 1 (10,0) blended (3 degrees); 2 (20,0.5) exact stop (G61); 3 (30,0) an event; 4 (40,3) a hairpin (free);
  programmed.segments[5].set_rapid(true);  // joint 5 rapid
  programmed.blend_tolerance_mm.assign(programmed.segments.size(), 0.0);
  programmed.blend_tolerance_mm[2] = -1;
  programmed.events.push_back(JobEvent{JobEventKind::Dwell, 3, 0.5, false, 4, "G4 P0.5"});
  smoothing::SmoothingReport report;
  const Job smoothed = smoothing::smooth_for_machine(programmed, machine, 0.01, &report);
  require_connected(smoothed);
  const auto starts_at = [&](const MachinePoint& p) {
    for (std::size_t i = 0; i < smoothed.segments.size(); ++i) {
      if (smoothed.segments[i].start() == p) return static_cast<long>(i);
    }
    return -1L;
  };
  CHECK(starts_at(programmed.segments[1].start()) == -1);  // blended: nobody starts at (10, 0)
  CHECK(starts_at(programmed.segments[2].start()) >= 0);   // exact stop
  const long event_joint = starts_at(programmed.segments[3].start());
  REQUIRE(event_joint >= 0);
  CHECK(smoothed.events.front().before_segment == static_cast<std::size_t>(event_joint));
  CHECK(starts_at(programmed.segments[5].start()) >= 0);   // rapid
  CHECK(smoothed.segments.back().rapid());
  CHECK(smoothed.segments.back().start() == programmed.segments.back().start());
  CHECK(smoothed.segments.back().end() == programmed.segments.back().end());
  CHECK(smoothed.blend_tolerance_mm.empty());
}

TEST_CASE("smoothing: the report accounts for every corner it kept, reversals among them", "[host][smoothing]") {
  // Joints: (10,0) a 3 degree corner, (20,0.5) an exact reversal (back along the same line),
  // (10,0) again a 90 degree corner, (10,10) a 45 degree corner.
  const Job programmed = polyline_job({MachinePoint{{0, 0, 0}}, MachinePoint{{10, 0, 0}}, MachinePoint{{20, 0.5, 0}},
                                       MachinePoint{{10, 0, 0}}, MachinePoint{{10, 10, 0}}, MachinePoint{{20, 20, 0}}});
  smoothing::SmoothingReport report;
  (void)smoothing::smooth_for_machine(programmed, example_machine(), 0.01, &report);
  CHECK(report.corners == 4);
  CHECK(report.corners_reversed == 1);
  CHECK(report.corners_blended + report.corners_stopped + report.corners_reversed + report.corners_unblendable == report.corners);
  const std::string text = smoothing::format_smoothing(report);
  CHECK(text.find("1 reversals: the planner stops there") != std::string::npos);
}

TEST_CASE("smoothing: a deviation allowed by G64 P is judged against that tolerance, not the machine's", "[host][smoothing]") {
  // Two 10 mm lines at 30 degrees; the move after the corner says G64 P0.5 (Job::blend_tolerance_mm),
  // the machine 0.01 mm. The blend may stray up to 0.5 mm: measured here, it goes beyond 0.01 mm.
  constexpr double program_tolerance = 0.5;
  constexpr double sampling = 5e-5;
  Job programmed = polyline_job({MachinePoint{{0, 0, 0}}, MachinePoint{{10, 0, 0}},
                                 MachinePoint{{10 + 10 * std::cos(pi / 6), 10 * std::sin(pi / 6), 0}}});
  programmed.blend_tolerance_mm = {0.0, program_tolerance};
  smoothing::SmoothingReport report;
  const Job smoothed = smoothing::smooth_for_machine(programmed, example_machine(), 0.01, &report);
  REQUIRE(report.corners_blended == 1);
  const Deviation d = deviation(programmed, smoothed);
  const double measured = std::fmax(d.path_to_programmed, d.programmed_to_path);
  CHECK(measured > 0.01);
  CHECK(measured <= program_tolerance + sampling);
  CHECK(report.largest_tolerance_mm == program_tolerance);
  CHECK(report.max_deviation_share == Approx(report.max_deviation_mm / program_tolerance));
  CHECK(report.max_deviation_share <= 1);
  const std::string text = smoothing::format_smoothing(report);
  INFO(text);
  CHECK(text.find("tolerance 10 um, up to 500 um set by G64 P; at most ") != std::string::npos);
}

TEST_CASE("smoothing: with smoothing off, a program's G64 P is reported as not applied", "[host][smoothing]") {
  // The machine file has no blend_tolerance (off); the program asks for G64 P0.05 at its corner.
  Job programmed = polyline_job({MachinePoint{{0, 0, 0}}, MachinePoint{{10, 0, 0}}, MachinePoint{{20, 1, 0}}});
  programmed.blend_tolerance_mm = {0.0, 0.05};
  smoothing::SmoothingReport whole;
  const Job smoothed = smoothing::smooth_for_machine(programmed, example_machine(), 0, &whole);
  CHECK(smoothed.segments.size() == 2);  // unchanged
  CHECK(whole.unapplied_tolerance_mm == 0.05);
  CHECK(smoothing::format_smoothing(whole).find("the program's G64 P (up to 50 um) is not applied") != std::string::npos);
  // The same through the stream a G-code program is loaded into line by line.
  smoothing::SmoothingStream stream(smoothing::options_for(example_machine(), 0), [](const PathSegment&, std::size_t) {});
  stream.segment(programmed.segments[0], 0, 0.0);
  stream.segment(programmed.segments[1], 1, 0.05);
  smoothing::SmoothingReport streamed;
  (void)stream.finish(Job{}, &streamed);
  CHECK(streamed.unapplied_tolerance_mm == 0.05);
  // Without G64 P nothing is said.
  smoothing::SmoothingReport plain;
  (void)smoothing::smooth_for_machine(polyline_job({MachinePoint{{0, 0, 0}}, MachinePoint{{10, 0, 0}}}), example_machine(), 0, &plain);
  CHECK(smoothing::format_smoothing(plain).find("G64") == std::string::npos);
}

TEST_CASE("smoothing: corners between two rapids are blended within the tolerance, the blends stay rapids", "[host][smoothing]") {
  // A G0 travel through shallow corners (as LinuxCNC blends G0 corners under G64): each corner is a
  // near-stop as programmed (a velocity jump within one tick allows < 1 mm/s), a blend passes it
  // (at 150 mm/s, corners of 5 degrees and more are faster stopped: test below).
  constexpr double tolerance = 0.01;
  constexpr double sampling = 5e-5;
  const MachineLimits machine = example_machine();
  Job programmed = polyline_job(turning_walk({2, -3, 2}, 4, 20));
  for (auto& s : programmed.segments) s.set_rapid(true);
  REQUIRE(programmed.segments.size() == 4);
  smoothing::SmoothingReport report;
  const Job smoothed = smoothing::smooth_for_machine(programmed, machine, tolerance, &report);
  require_connected(smoothed);
  CHECK(report.corners == 3);
  CHECK(report.corners_blended == 3);
  CHECK(smoothed.segments.size() == 7);
  for (const auto& s : smoothed.segments) CHECK(s.rapid());
  const Deviation d = deviation(programmed, smoothed);
  CHECK(d.path_to_programmed <= tolerance);
  CHECK(d.programmed_to_path <= tolerance + sampling);
  const auto as_programmed = simulate(programmed, machine).summary;
  const auto blended = simulate(smoothed, machine).summary;
  CHECK(blended.violations.empty());
  // Each blend saves at least a stop and a restart from the blend's speed (2 x 2 sqrt(v/j) > 20 ms
  // above 2.5 mm/s); the corners as programmed are passed below 1 mm/s.
  CHECK(blended.duration_s < as_programmed.duration_s - 3 * 0.02);
}

TEST_CASE("smoothing: a corner is blended only where the blend is faster than stopping", "[host][smoothing][sim]") {
  // Zig-zags of 10 mm lines at 50 mm/s and of 20 mm rapids at 150 mm/s, each simulated smoothed and
  // as programmed (stopping at every corner): smoothing never makes a job slower, and the shallow
  // corners, where a blend is far faster, are blended. (Deciding by the blend's length against a
  // stop from the blend's own speed blended the 20 and 30 degree feed corners: 1.667 and 1.712 s
  // against 1.58 s stopping; with the trapezoid profile the 10 to 30 degree ones, up to 1.506 s
  // against 1.35 s.)
  for (const bool jerk_limited : {true, false}) {
    MachineLimits machine = example_machine();
    machine.jerk_limited = jerk_limited;  // the S-curve and the trapezoid profile
    const double tick = 1.0 / machine.rate_hz;
    for (const bool rapid : {false, true}) {
      for (const double turn : {1.0, 2.0, 5.0, 10.0, 20.0, 30.0, 45.0}) {
        INFO((jerk_limited ? "S-curve, " : "trapezoid, ") << (rapid ? "rapids" : "feed lines") << ", corners of " << turn << " degrees");
        Job programmed = polyline_job(turning_walk({turn, -turn}, 6, rapid ? 20 : 10));
        for (auto& s : programmed.segments) s.set_rapid(rapid);
        smoothing::SmoothingReport report;
        const Job smoothed = smoothing::smooth_for_machine(programmed, machine, 0.01, &report);
        const auto stopping = simulate(programmed, machine).summary;
        const auto with_smoothing = simulate(smoothed, machine).summary;
        CHECK(with_smoothing.violations.empty());
        CHECK(with_smoothing.duration_s <= stopping.duration_s + tick / 2);
        if (turn <= 2) {
          CHECK(report.corners_blended == 5);
          CHECK(with_smoothing.duration_s < stopping.duration_s - 5 * 0.01);  // each blend saves > 10 ms
        }
      }
    }
  }
}

TEST_CASE("smoothing: a polyline of corners too sharp to blend runs segment by segment in the jerk-limited rest-to-rest minimum", "[host][smoothing][sim]") {
  // Plotter art of 60 degree corners every 1.2 mm (a Gosper curve's shape): a blend within 10 um is
  // slower than a stop there (docs/motion.md, "Tried on real programs"), so each corner is kept and
  // each line runs from rest to rest. With no acceleration or speed limit reached, the least time for
  // L mm is four jerk phases of T = (L / (2 j))^(1/3) (distance 2 j T^3): t = (32 L / j)^(1/3).
  constexpr std::size_t lines = 60;
  constexpr double length = 1.2;
  const MachineLimits machine = example_machine();
  const double t_phase = std::cbrt(length / (2 * machine.j_max_mm_per_s3));
  REQUIRE(machine.j_max_mm_per_s3 * t_phase < machine.a_max_mm_per_s2);  // a_max not reached
  REQUIRE(machine.j_max_mm_per_s3 * t_phase * t_phase < 50);            // nor the feed
  const double least = lines * 4 * t_phase;
  const Job programmed = polyline_job(turning_walk({60, -60}, lines, length));
  smoothing::SmoothingReport report;
  const Job smoothed = smoothing::smooth_for_machine(programmed, machine, 0.01, &report);
  CHECK(report.corners == lines - 1);
  CHECK(report.corners_stopped == lines - 1);
  const auto summary = simulate(smoothed, machine).summary;
  CHECK(summary.violations.empty());
  const double tick = 1.0 / machine.rate_hz;
  CHECK(summary.duration_s >= least - tick);              // nothing beats the optimum
  CHECK(summary.duration_s <= least + lines * tick);       // at most a tick per line above it
}

TEST_CASE("smoothing: a spiral of arcs joined nearly tangent is never slowed by blends", "[host][smoothing][sim]") {
  // Like LinuxCNC's arcspiral.ngc: clockwise arcs of 5.8 degrees whose radius shrinks by 0.05 mm
  // each, at 200 mm/s. Their joints are passed at speed as programmed; blends there (quintics
  // within 10 um, capped near 116 mm/s) made that file 51.4 s against 32.9 s unsmoothed.
  const MachineLimits machine = example_machine();
  Job programmed;
  programmed.name = "arc spiral";
  const auto at = [](std::size_t k) {
    const double radius = 50 - 0.05 * static_cast<double>(k);
    const double angle = -5.8 * pi / 180 * static_cast<double>(k);
    return grid(MachinePoint{{radius * std::cos(angle), radius * std::sin(angle), 0}});
  };
  for (std::size_t k = 0; k < 60; ++k) {
    const MachinePoint a = at(k);
    const MachinePoint b = at(k + 1);
    const double r = 50 - 0.05 * (static_cast<double>(k) + 0.5);
    const MachinePoint chord = b - a;
    const double half = norm(chord) / 2;
    const MachinePoint right{{chord[1] / (2 * half), -chord[0] / (2 * half), 0}};  // clockwise: centre on the right
    const MachinePoint centre = (a + b) * 0.5 + right * std::sqrt(r * r - half * half);
    auto arc = PathSegment::make_arc(a, b, centre, ArcDirection::Clockwise, 0, 1e-6).value();
    arc.set_feed_mm_per_s(200);
    programmed.segments.push_back(arc);
    programmed.source_index.push_back(k);
  }
  programmed.sources.resize(programmed.segments.size());
  CHECK(smoothed_within_limits_and_no_slower(programmed, machine).corners == 59);
}

TEST_CASE("smoothing: helices in G18 and G19, cut into pieces, are not slowed by blends between the pieces", "[host][smoothing][sim]") {
  // Arcs in Z-X and Y-Z with the third axis moving are cut into pieces (docs/gcode.md); their joints
  // are nearly tangent. Blends there, each lifting the speed ceiling by a few per cent for an
  // estimated gain of a few ms, made this program 1.240 s against 1.072 s as programmed (as
  // LinuxCNC's tort.ngc: 146 s against 136 s).
  const MachineLimits machine = example_machine();
  const Job programmed = parse_gcode_job(
      "G21 G90\nG0 X0 Y0 Z0\nF6000\nG18 G2 X6 Z0 I3 K0 Y2\nG19 G3 Y6 Z0 J2 K0 X8\nG17 G2 X12 Y6 I2 J-2 Z3\nM2\n", "helices");
  CHECK(smoothed_within_limits_and_no_slower(programmed, machine).corners > 20);
}

TEST_CASE("smoothing: blends at both ends of short arcs leave pieces whose joints the planner passes at speed",
          "[host][smoothing][sim]") {
  // LinuxCNC's arcspiral.ngc: 300 arcs of 5 mm (R 2 in, shrinking by 0.002 in each), in inches to
  // six places. Blended at both ends, each arc kept a piece of 0.1 mm between two grid points; its
  // tangent turned by 10^-4 rad against the blends', and the planner passed those joints at 44 mm/s
  // against 150 as programmed: 14.28 s smoothed against 11.94 s. The blend decision now judges the
  // joints with the pieces as they will be written.
  const MachineLimits machine = example_machine();
  std::string program = "G20\nG0 X0 Y0 Z0\nG1 X1.724638 Y-1.012731 F999\n";
  double angle = std::atan2(-1.012731, 1.724638);
  char line[96];
  for (int k = 1; k <= 300; ++k) {
    const double radius = 2.0 - 0.002 * k;
    angle -= 0.0995;
    std::snprintf(line, sizeof line, "G2 R%.6f X%.6f Y%.6f\n", radius, radius * std::cos(angle), radius * std::sin(angle));
    program += line;
  }
  const Job programmed = parse_gcode_job(program + "M2\n", "arc spiral");
  CHECK(smoothed_within_limits_and_no_slower(programmed, machine).corners_blended > 50);
}

TEST_CASE("smoothing: a blend never runs faster than the programmed feeds of the moves it joins", "[host][smoothing][sim]") {
  // A 10 mm line at 40 mm/s into one at 50 mm/s at 3 degrees: the blend takes up to half of each
  // (4.9 mm here). It ran at the outgoing feed, 50 mm/s, over the first line's last 4.9 mm.
  const MachineLimits machine = example_machine();
  Job programmed = polyline_job({MachinePoint{{0, 0, 0}}, MachinePoint{{10, 0, 0}},
                                 MachinePoint{{10 + 10 * std::cos(pi / 60), 10 * std::sin(pi / 60), 0}}});
  programmed.segments[0].set_feed_mm_per_s(40);
  smoothing::SmoothingReport report;
  const Job smoothed = smoothing::smooth_for_machine(programmed, machine, 0.01, &report);
  REQUIRE(report.corners_blended == 1);
  REQUIRE(smoothed.segments.size() == 3);
  CHECK(smoothed.segments[1].feed_mm_per_s() == 40);
  // Measured from the setpoints: the speed between consecutive setpoints whose positions lie on the
  // first line's stretch (x up to 10 mm) stays within its feed.
  const auto run = simulate(smoothed, machine);
  CHECK(run.summary.violations.empty());
  double fastest_on_first_line = 0;
  for (std::size_t i = 1; i < run.setpoints.size(); ++i) {
    const auto& p = run.setpoints[i - 1].position_mm;
    const auto& q = run.setpoints[i].position_mm;
    if (q[0] > 10) break;
    const double step = std::hypot(q[0] - p[0], q[1] - p[1], q[2] - p[2]);
    fastest_on_first_line = std::fmax(fastest_on_first_line, step * machine.rate_hz);
  }
  // Setpoints are on the Q16.16 grid: a step's length is exact to within two grid units.
  CHECK(fastest_on_first_line <= 40 + 2.0 / 65536 * machine.rate_hz);
  CHECK(fastest_on_first_line > 39.9);
}

TEST_CASE("smoothing: with the tolerance 0 the job is unchanged", "[host][smoothing]") {
  const Job programmed = polyline_job(circle_chords(36));
  smoothing::SmoothingReport report;
  const Job same = smoothing::smooth_for_machine(programmed, example_machine(), 0, &report);
  REQUIRE(same.segments.size() == programmed.segments.size());
  for (std::size_t i = 0; i < same.segments.size(); ++i) CHECK(same.segments[i].end() == programmed.segments[i].end());
  CHECK(report.corners_blended == 0);
  CHECK(report.runs_fitted == 0);
}

TEST_CASE("smoothing: the issue's jobs run at feed within every limit", "[host][smoothing][sim]") {
  const MachineLimits machine = example_machine();  // a 2000, j 50000, feed 50 mm/s
  const auto run = [&](const std::vector<MachinePoint>& vertices) {
    const Job smoothed = smoothing::smooth_for_machine(polyline_job(vertices), machine, 0.01);
    return simulate(smoothed, machine).summary;
  };
  // The same circle as one arc (full circle from (20, 0) about the origin).
  Job arc_job;
  arc_job.name = "arc";
  arc_job.segments.push_back(
      PathSegment::make_arc(MachinePoint{{20, 0, 0}}, MachinePoint{{20, 0, 0}}, MachinePoint{}, ArcDirection::CounterClockwise, 0, 1e-9).value());
  arc_job.segments.back().set_feed_mm_per_s(50);
  arc_job.source_index = {0};
  arc_job.sources.resize(1);
  const double arc_time = simulate(arc_job, machine).summary.duration_s;
  for (const std::size_t chords : {std::size_t{360}, std::size_t{3600}}) {
    INFO(chords << " chords");
    const auto s = run(circle_chords(chords));
    CHECK(s.violations.empty());
    CHECK(s.duration_s <= 1.15 * arc_time);
  }
  {
    INFO("spiral of 2000 points");
    const auto vertices = spiral(2000);
    double length = 0;
    for (std::size_t i = 1; i < vertices.size(); ++i) length += norm(vertices[i] - vertices[i - 1]);
    const auto s = run(vertices);
    CHECK(s.violations.empty());
    CHECK(s.duration_s <= 1.15 * length / 50);
  }
  {
    INFO("3-axis raster");
    const auto s = run(raster(6));
    CHECK(s.violations.empty());
  }
}

TEST_CASE("smoothing: the machine file's blend_tolerance is read and checked", "[host][smoothing]") {
  const std::string base = R"({"v_max": 100, "a_max": 1000, "j_max": 10000, "feed": 20, "tolerance": 0.01, "rate_hz": 1000)";
  CHECK(parse_machine_file(base + "}", "m.json").blend_tolerance_mm == 0);
  CHECK(parse_machine_file(base + R"(, "blend_tolerance": 0.05})", "m.json").blend_tolerance_mm == 0.05);
  try {
    (void)parse_machine_file(base + R"(, "blend_tolerance": -1})", "m.json");
    FAIL("a negative tolerance was accepted");
  } catch (const LoadError& e) {
    CHECK(std::string(e.what()).find("blend_tolerance") != std::string::npos);
  }
}
