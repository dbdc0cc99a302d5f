// SPDX-License-Identifier: MIT
// `curvestep sim --report`: the HTML report's content, its warnings, the motion profile behind its
// charts, and the progress line.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <curvestep/host/job.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/report.hpp>
#include <curvestep/host/simulator.hpp>

#include "report_test_support.hpp"

namespace {

using report_test::count;
using report_test::run_curvestep;
using report_test::scratch;
using report_test::source;

double peak(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

}  // namespace

TEST_CASE("report: sim --report writes one self-contained page with the plot, three charts and the summary", "[host_tools][report]") {
  const std::string html = scratch("report.html");
  std::remove(html.c_str());
  const auto r = run_curvestep("sim " + source("examples/jobs/every_type.json") + " --machine " + source("examples/jobs/machine.json") +
                           " --report " + html);
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(r.output.find("limit violations:    none") != std::string::npos);  // sim's own output is unchanged
  CHECK(r.output.find("wrote " + html) != std::string::npos);
  const std::string text = report_test::read_file(html);
  REQUIRE(text.rfind("<!DOCTYPE html>", 0) == 0);
  CHECK(text.find("</html>") != std::string::npos);
  // Nothing is fetched: no links, no sources, no imports, no remote addresses.
  for (const char* external : {"<link", " src=", "href=", "@import"}) {
    INFO(external);
    CHECK(text.find(external) == std::string::npos);
  }
  CHECK(count(text, "url(") == count(text, "url(#"));  // references inside the page only
  // The only address is the SVG namespace name (an identifier, never fetched).
  CHECK(count(text, "http") == count(text, "xmlns=\"http://www.w3.org/2000/svg\""));
  CHECK(count(text, "<svg") == 4);  // path + speed, acceleration, jerk
  for (const char* part : {"class=\"path-plot\"", "chart-speed", "chart-acceleration", "chart-jerk", "class=\"start-marker\"",
                           "class=\"end-marker\"", "class=\"rapid\"", "id=\"render-check\""}) {
    INFO(part);
    CHECK(text.find(part) != std::string::npos);
  }
  CHECK(count(text, "class=\"limit\"") == 3);  // v_max, a_max, j_max drawn
  CHECK(text.find("No limit exceeded.") != std::string::npos);
  CHECK(text.find("<th>peak speed</th><td>150 mm/s</td><td>200 mm/s</td><td class=\"good\">ok</td>") != std::string::npos);
}

TEST_CASE("report: limits exceeded appear as warnings and sim keeps exit status 3", "[host_tools][report]") {
  // machine.json with a step-rate ceiling the job's y axis exceeds (150 mm/s rapid × 80 steps/mm > 5000).
  std::string machine = report_test::read_file(source("examples/jobs/machine.json"));
  const auto at = machine.find("\"max_step_rate\": 40000");
  REQUIRE(at != std::string::npos);
  machine.replace(at, std::string("\"max_step_rate\": 40000").size(), "\"max_step_rate\": 5000");
  const std::string machine_file = scratch("slow_steppers.json");
  std::ofstream(machine_file) << machine;
  const std::string html = scratch("report_warnings.html");
  std::remove(html.c_str());
  // --strict-step-rate: refuse instead of planning the axis slower (the default).
  const auto r = run_curvestep("sim " + source("examples/jobs/every_type.json") + " --machine " + machine_file + " --report " + html +
                               " --strict-step-rate");
  INFO(r.output);
  CHECK(r.status == 3);
  CHECK(r.output.find("LIMIT VIOLATION:     axis y needs") != std::string::npos);
  const std::string text = report_test::read_file(html);
  CHECK(text.find("<ul class=\"warnings\" id=\"warnings\">\n<li>axis y needs") != std::string::npos);
  CHECK(text.find("No limit exceeded.") == std::string::npos);
  CHECK(text.find("<td class=\"bad\">exceeds</td>") != std::string::npos);
}

TEST_CASE("report: an unwritable report fails with exit status 1 and the file named", "[host_tools][report]") {
  const auto r = run_curvestep("sim " + source("examples/jobs/every_type.json") + " --machine " + source("examples/jobs/machine.json") +
                           " --report /nonexistent_directory/r.html");
  CHECK(r.status == 1);
  CHECK(r.output.find("curvestep: cannot write /nonexistent_directory/r.html\n") != std::string::npos);
}

TEST_CASE("report: sim and plot print no progress bar when stderr is not a terminal", "[host_tools][report]") {
  const auto r = run_curvestep("sim " + source("examples/jobs/helix.json") + " --machine " + source("examples/jobs/machine.json"));
  CHECK(r.output.find('\r') == std::string::npos);
  CHECK(r.output.find("ETA") == std::string::npos);
  CHECK(r.output.find('#') == std::string::npos);
  const auto p = run_curvestep("plot " + source("examples/jobs/helix.json") + " --machine " + source("examples/jobs/machine.json") + " -o " +
                           scratch("helix.svg"));
  CHECK(p.output == "  wrote " + scratch("helix.svg") + "\n");
}

TEST_CASE("report: the motion profile of exact setpoints has the summary's peaks", "[host_tools][report]") {
  const auto job = curvestep::host::load_job(source("examples/jobs/every_type.json"));
  const auto machine = curvestep::host::load_machine(source("examples/jobs/machine.json"));
  curvestep::host::SimulationOptions options;
  options.fixed_point = false;
  const auto result = curvestep::host::simulate(job, machine, options);
  const auto profile = curvestep::host::motion_profile(result.setpoints, machine, false);
  CHECK(profile.stride == 1);
  REQUIRE(profile.time_s.size() == result.setpoints.size());
  // Same differences as the summary, taken from the same exact positions.
  CHECK(peak(profile.acceleration_mm_per_s2) == Approx(result.summary.peak_acceleration_mm_per_s2).epsilon(1e-12));
  CHECK(peak(profile.jerk_mm_per_s3) == Approx(result.summary.peak_jerk_mm_per_s3).epsilon(1e-12));
  // The planned speed: up to the rapid's 150 mm/s, ending at rest.
  CHECK(peak(profile.speed_mm_per_s) == Approx(150).epsilon(1e-9));
  CHECK(profile.speed_mm_per_s.back() == 0.0);
  CHECK(profile.acceleration_mm_per_s2[0] == 0.0);
  CHECK(profile.jerk_mm_per_s3[2] == 0.0);
}

TEST_CASE("report: Q16.16 setpoints are differenced over a stride that keeps rounding below 1% of the limits", "[host_tools][report]") {
  const auto job = curvestep::host::load_job(source("examples/jobs/every_type.json"));
  const auto machine = curvestep::host::load_machine(source("examples/jobs/machine.json"));
  const auto result = curvestep::host::simulate(job, machine);
  const auto profile = curvestep::host::motion_profile(result.setpoints, machine, true);
  // By hand: e = sqrt(3)·2^-17 = 1.3215e-5 mm. Jerk: 8e/h³ <= 1% of 50000 needs h >= 5.955 ms, so 6
  // setpoints at 1 kHz; acceleration: 4e/h² <= 1% of 2000 needs only h >= 1.63 ms.
  CHECK(profile.stride == 6);
  // Smoothing over 6 ms may lower a peak a little and rounding may add up to 1% of the limit.
  CHECK(peak(profile.acceleration_mm_per_s2) <= result.summary.peak_acceleration_mm_per_s2 + 0.01 * machine.a_max_mm_per_s2);
  CHECK(peak(profile.acceleration_mm_per_s2) >= 0.9 * result.summary.peak_acceleration_mm_per_s2);
  CHECK(peak(profile.jerk_mm_per_s3) <= result.summary.peak_jerk_mm_per_s3 + 0.01 * machine.j_max_mm_per_s3);
  CHECK(peak(profile.jerk_mm_per_s3) >= 0.7 * result.summary.peak_jerk_mm_per_s3);
}

TEST_CASE("report: html_report refuses missing inputs", "[host_tools][report]") {
  curvestep::host::ReportInput input;
  CHECK_THROWS_AS(curvestep::host::html_report(input), std::invalid_argument);
  const auto job = curvestep::host::load_job(source("examples/jobs/every_type.json"));
  const auto machine = curvestep::host::load_machine(source("examples/jobs/machine.json"));
  const curvestep::host::SimulationResult empty;
  input.job = &job;
  input.machine = &machine;
  input.result = &empty;
  CHECK_THROWS_AS(curvestep::host::html_report(input), std::invalid_argument);
}

TEST_CASE("report: the progress line shows the bar, the percentage and an ETA from the elapsed time", "[host_tools][report]") {
  using curvestep::host::format_progress_line;
  // Half done after 10 s: 10 s to go.
  CHECK(format_progress_line(0.5, 10.0) == "  [" + std::string(20, '#') + std::string(20, ' ') + "] 50%  ETA 10 s");
  // A quarter done after 60 s: 180 s to go.
  CHECK(format_progress_line(0.25, 60.0) == "  [" + std::string(10, '#') + std::string(30, ' ') + "] 25%  ETA 3 min 00 s");
  // Too early to tell, and done.
  CHECK(format_progress_line(0.005, 1.0) == "  [" + std::string(40, ' ') + "] 0%");
  CHECK(format_progress_line(1.0, 5.0) == "  [" + std::string(40, '#') + "] 100%");
}
