// SPDX-License-Identifier: MIT
// `curvestep plot` and `sim --report` draw the setpoints as they are made (issue 19, item 7): the
// SVG and the HTML must be those the earlier implementation wrote while it held every setpoint in
// memory. The expected files in data/ were written by that implementation (curvestep plot and
// curvestep sim --report of commit 53bce29, before the change), run from data/ so the title is
// the bare file name.
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
