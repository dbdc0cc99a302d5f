// SPDX-License-Identifier: MIT
// `curvestep plot` and `sim --report` draw the setpoints as they are made (issue 19, item 7): the
// SVG and the HTML must be those the earlier implementation wrote while it held every setpoint in
// memory. The expected files in data/ were written by that implementation (curvestep plot and
// curvestep sim --report of commit 53bce29, before the change), run from data/ so the title is
// the bare file name; since blends are weighed by the planner's speeds and run at the slower feed,
// by 53bce29 with that smoothing rule ported onto it (its setpoints of the job equal this tree's).
// When the jerk cap from curvature rose (docs/motion.md, "Jerk from curvature": the job takes
// 2.281 s, 2.284 s before) the full-memory writer could no longer be ported onto this tree's
// smoothing, so by_speed.svg and report.html are now this tree's streamed output: from here on they
// guard against change, and the equality with the full-memory writer rests on the earlier files.
// Written again when a curve's profile took the jerk its curvature leaves (curve_profile_jerk): 2.275 s.
#include <cstdio>
#include <string>

#include <catch2/catch.hpp>

#include "report_test_support.hpp"

namespace {

using namespace report_test;

/// Runs `curvestep <command> streamed_plot_job.json <options> <output_option> FILE` from the data
/// folder (the job's name is then its bare file name) and returns what it wrote to FILE.
std::string run_in_data_folder(const std::string& command, const std::string& options, const std::string& output_option,
                               const std::string& name) {
  const std::string output = scratch(name);
  const Run r = run_command("cd " + source("tests/host_tools/report/data") + " && " + CURVESTEP_BINARY + " " + command +
                            " streamed_plot_job.json " + options + " " + output_option + " " + output);
  INFO(r.output);
  REQUIRE(r.status == 0);
  const std::string text = read_file(output);
  std::remove(output.c_str());
  return text;
}

std::string plot_in_data_folder(const std::string& machine_option, const std::string& name) {
  return run_in_data_folder("plot", machine_option, "-o", name);
}

}  // namespace

TEST_CASE("plot: the streamed plot of a simulation is the SVG the full-memory plot wrote", "[host_tools][report][plot]") {
  const std::string svg = plot_in_data_folder("--machine " + source("examples/jobs/machine.json"), "by_speed.svg");
  const std::string expected = read_file(source("tests/host_tools/report/data/streamed_plot_job.by_speed.svg"));
  REQUIRE(expected.size() > 10000);
  CHECK(count(svg, "<polyline") == count(expected, "<polyline"));
  CHECK(svg == expected);
}

TEST_CASE("plot: the plot by segment is unchanged by the streamed writer", "[host_tools][report][plot]") {
  const std::string svg = plot_in_data_folder("", "by_segment.svg");
  const std::string expected = read_file(source("tests/host_tools/report/data/streamed_plot_job.by_segment.svg"));
  REQUIRE(!expected.empty());
  CHECK(svg == expected);
}

TEST_CASE("report: the streamed HTML report is the one the full-memory report wrote", "[host_tools][report][plot]") {
  const std::string html = run_in_data_folder("sim", "--machine " + source("examples/jobs/machine.json"), "--report", "report.html");
  const std::string expected = read_file(source("tests/host_tools/report/data/streamed_plot_job.report.html"));
  REQUIRE(expected.size() > 10000);
  CHECK(count(html, "<polyline") == count(expected, "<polyline"));
  CHECK(html == expected);
}

namespace {

/// Runs `curvestep <command> <job> --machine <example machine> <extra> <output_option> FILE` and
/// returns what it wrote to FILE.
std::string written_by(const std::string& command, const std::string& job, const std::string& extra, const std::string& output_option,
                       const std::string& name) {
  const std::string output = scratch(name);
  const Run r = run_curvestep(command + " " + job + " --machine " + source("examples/jobs/machine.json") + " " + extra + " " +
                              output_option + " " + output);
  INFO(r.output);
  REQUIRE(r.status == 0);
  const std::string text = read_file(output);
  std::remove(output.c_str());
  return text;
}

}  // namespace

// A G-code job is not held by plot and sim --report: each pass reads the file again, and rapids are
// known by the ranges of file segments the first pass found. --optimize (a no-op on G-code) takes
// the path that holds the job whole: the drawings must be the same, rapids included.
TEST_CASE("plot and report: a G-code job read again for each pass draws what the job held whole draws", "[host_tools][report][plot]") {
  for (const char* program : {"examples/gcode/cam/fusion_style_drill.nc", "examples/gcode/cnc_pocket.ngc"}) {
    INFO(program);
    const std::string job = source(program);
    const std::string streamed_svg = written_by("plot", job, "", "-o", "streamed.svg");
    const std::string whole_svg = written_by("plot", job, "--optimize", "-o", "whole.svg");
    CHECK(count(whole_svg, "stroke-dasharray") > 0);  // rapids drawn dashed
    CHECK(count(streamed_svg, "stroke-dasharray") == count(whole_svg, "stroke-dasharray"));
    CHECK(streamed_svg == whole_svg);
    const std::string streamed_html = written_by("sim", job, "", "--report", "streamed.html");
    const std::string whole_html = written_by("sim", job, "--optimize", "--report", "whole.html");
    CHECK(count(streamed_html, "<polyline") == count(whole_html, "<polyline"));
    CHECK(streamed_html == whole_html);
  }
}
