// SPDX-License-Identifier: MIT
// The real curvestep binary: eval and sample, success and failure paths.
#include <filesystem>
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/host/job.hpp>

#include "jobs_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using curvestep::testing::job_data;
using curvestep::testing::job_example;
using curvestep::testing::run_curvestep;

namespace {

std::string quoted(const std::filesystem::path& path) { return "'" + path.string() + "'"; }

std::size_t line_count(const std::string& text) { return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')); }

}  // namespace

TEST_CASE("cli: eval prints the seed cubic at u = 0.25 as 0.90625,1.265625,0", "[host_tools][jobs]") {
  const auto result = run_curvestep("eval " + quoted(job_example("seed_cubic.json")) + " --segment 0 --u 0.25");
  CHECK(result.exit_code == 0);
  CHECK(result.out == "x,y,z\n0.90625,1.265625,0\n");
  CHECK(result.err.empty());
}

TEST_CASE("cli: eval writes several parameters to a file with -o", "[host_tools][jobs]") {
  const auto out = std::filesystem::temp_directory_path() / ("curvestep_eval_" + std::to_string(::getpid()) + ".csv");
  const auto result = run_curvestep("eval " + quoted(job_example("seed_cubic.json")) + " --segment 0 --u 0,0.5,0.75,1 -o " + quoted(out));
  CHECK(result.exit_code == 0);
  CHECK(result.out.empty());
  CHECK(curvestep::testing::read_file(out) == "x,y,z\n0,0,0\n2,1.875,0\n3.09375,1.546875,0\n4,0,0\n");
  std::filesystem::remove(out);
}

TEST_CASE("cli: eval outside the domain fails with a one-line cause", "[host_tools][jobs]") {
  const auto result = run_curvestep("eval " + quoted(job_example("seed_cubic.json")) + " --segment 0 --u 0.5,1.5");
  CHECK(result.exit_code != 0);
  CHECK(line_count(result.err) == 1);
  CHECK(result.err.find("u = 1.5 is outside the domain [0, 1] of segment 0 (bezier)") != std::string::npos);
  CHECK(result.out.empty());  // nothing is written when any parameter is bad
  const auto negative = run_curvestep("eval " + quoted(job_example("seed_cubic.json")) + " --segment 0 --u=-0.5");
  CHECK(negative.exit_code != 0);
  CHECK(negative.err.find("u = -0.5 is outside the domain [0, 1]") != std::string::npos);
}

TEST_CASE("cli: eval of a missing segment index fails with a one-line cause", "[host_tools][jobs]") {
  const auto result = run_curvestep("eval " + quoted(job_example("seed_cubic.json")) + " --segment 4 --u 0.5");
  CHECK(result.exit_code != 0);
  CHECK(line_count(result.err) == 1);
  CHECK(result.err.find("segment 4 does not exist") != std::string::npos);
  const auto negative = run_curvestep("eval " + quoted(job_example("seed_cubic.json")) + " --segment -1 --u 0.5");
  CHECK(negative.exit_code != 0);
  CHECK(negative.err.find("--segment") != std::string::npos);
}

TEST_CASE("cli: eval of a B-spline takes u in its knot domain", "[host_tools][jobs]") {
  const auto inside = run_curvestep("eval " + quoted(job_example("every_type.json")) + " --segment 6 --u 3");
  CHECK(inside.exit_code == 0);
  CHECK(inside.out == "x,y,z\n4,45,0\n");  // a clamped spline ends at its last control point
  const auto outside = run_curvestep("eval " + quoted(job_example("every_type.json")) + " --segment 6 --u 3.5");
  CHECK(outside.exit_code != 0);
  CHECK(outside.err.find("outside the domain [0, 3]") != std::string::npos);
}

TEST_CASE("cli: eval and sample of a bad file name the file, segment and field", "[host_tools][jobs]") {
  const auto path = job_data("bad_out_of_range.json");
  for (const std::string& command : {"eval " + quoted(path) + " --segment 0 --u 0", "sample " + quoted(path) + " --tolerance 0.1"}) {
    const auto result = run_curvestep(command);
    CHECK(result.exit_code != 0);
    CHECK(line_count(result.err) == 1);
    CHECK(result.err.find(path.string() + ":9: segment 3 (bezier): \"points\"[2][1]: value 1e+09 is outside the Q16.16 range") !=
          std::string::npos);
  }
}

TEST_CASE("cli: sample writes a polyline within the tolerance of the exact path", "[host_tools][jobs]") {
  const auto out = std::filesystem::temp_directory_path() / ("curvestep_sample_" + std::to_string(::getpid()) + ".csv");
  const double tolerance = 0.005;
  const auto result = run_curvestep("sample " + quoted(job_example("every_type.json")) + " --tolerance 0.005 -o " + quoted(out));
  REQUIRE(result.exit_code == 0);
  const auto line = curvestep::testing::parse_points_csv(curvestep::testing::read_file(out));
  std::filesystem::remove(out);
  REQUIRE(line.size() > 10);
  const Job job = load_job(job_example("every_type.json"));
  CHECK(line.front() == job.segments.front().start());
  CHECK(line.back() == job.segments.back().end());
  // Densely along every source segment, by its own parameter: the exact point is near the polyline.
  for (std::size_t i = 0; i < job.sources.size(); ++i) {
    const auto [low, high] = job.sources[i].domain();
    for (int k = 0; k <= 1000; ++k) {
      const double u = low + (high - low) * k / 1000.0;
      INFO("segment " << i << " u " << u);
      CHECK(curvestep::testing::distance_to_polyline(evaluate_segment(job, i, u), line) <= tolerance * (1 + 1e-9));
    }
  }
}

TEST_CASE("cli: sample without a usable tolerance fails", "[host_tools][jobs]") {
  const auto missing = run_curvestep("sample " + quoted(job_example("seed_cubic.json")));
  CHECK(missing.exit_code != 0);
  const auto zero = run_curvestep("sample " + quoted(job_example("seed_cubic.json")) + " --tolerance 0");
  CHECK(zero.exit_code != 0);
  CHECK(line_count(zero.err) == 1);
  CHECK(zero.err.find("--tolerance") != std::string::npos);
  const auto absent_file = run_curvestep("sample " + quoted(job_data("no_such_job.json")) + " --tolerance 0.1");
  CHECK(absent_file.exit_code != 0);
  CHECK(absent_file.err.find("no_such_job.json: cannot open the file") != std::string::npos);
}

TEST_CASE("cli: G-code loads under the extensions senders and laser tools give it, others are named", "[host_tools][jobs]") {
  const auto base = std::filesystem::temp_directory_path() / ("curvestep_ext_" + std::to_string(::getpid()));
  for (const char* extension : {".gco", ".gc", ".g", ".cnc", ".TAP"}) {
    INFO(extension);
    const auto path = std::filesystem::path(base.string() + extension);
    curvestep::testing::write_file(path, "G21 G90\nG1 X10 Y2 F600\n");
    const auto result = run_curvestep("eval " + quoted(path) + " --segment 0 --u 1");
    CHECK(result.exit_code == 0);
    CHECK(result.out == "x,y,z\n10,2,0\n");
    std::filesystem::remove(path);
  }
  const auto unknown = std::filesystem::path(base.string() + ".xyz");
  curvestep::testing::write_file(unknown, "G1 X1\n");
  const auto result = run_curvestep("eval " + quoted(unknown) + " --segment 0 --u 1");
  CHECK(result.exit_code != 0);
  CHECK(result.err.find("unknown job format '.xyz'") != std::string::npos);
  CHECK(result.err.find(".gcode, .tap, .gc, .gco, .g, .cnc, .svg") != std::string::npos);
  std::filesystem::remove(unknown);
}
