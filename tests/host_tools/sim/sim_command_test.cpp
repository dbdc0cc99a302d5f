// SPDX-License-Identifier: MIT
// `curvestep sim`: the real program on the bundled jobs, its CSV, its summary and its failures.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include <curvestep/host/job.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/simulator.hpp>

namespace {

struct Run {
  int status = -1;
  std::string output;
};

Run run(const std::string& arguments) {
  const std::string command = std::string(CURVESTEP_BINARY) + " " + arguments + " 2>&1";
  Run r;
  FILE* pipe = popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) r.output += buffer;
  const int raw = pclose(pipe);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

std::string source(const std::string& relative) { return std::string(CURVESTEP_SOURCE_DIR) + "/" + relative; }

/// A scratch path unique to this process: CTest runs test cases in parallel.
std::string scratch(const std::string& name) { return "/tmp/curvestep_sim_test_" + std::to_string(::getpid()) + "_" + name; }

std::string temporary(const std::string& name, const std::string& content) {
  const std::string path = scratch(name);
  std::ofstream(path) << content;
  return path;
}

}  // namespace

TEST_CASE("sim: the bundled jobs run within the limits and write CSV", "[host_tools][sim]") {
  const std::string csv = scratch("out.csv");
  const Run r = run("sim " + source("examples/jobs/every_type.json") + " --machine " + source("examples/jobs/machine.json") + " -o " + csv);
  INFO(r.output);
  CHECK(r.status == 0);
  CHECK(r.output.find("limit violations:    none") != std::string::npos);
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  CHECK(header == "t,x,y,z,v,index");
  std::string line;
  std::size_t rows = 0;
  std::string last;
  while (std::getline(in, line)) {
    ++rows;
    last = line;
  }
  CHECK(rows > 100);
  // The last setpoint stands still (v = 0), and its index is the last tick (rows - 1).
  const std::string without_index = last.substr(0, last.rfind(','));
  CHECK(without_index.substr(without_index.rfind(',') + 1) == "0");
  CHECK(last.substr(last.rfind(',') + 1) == std::to_string(rows - 1));
}

TEST_CASE("sim: the CSV's last position is the job's end point", "[host_tools][sim]") {
  const auto job = curvestep::host::parse_job(
      R"({"version": 1, "units": "mm", "segments": [{"type": "bezier", "points": [[0,0],[1,2],[3,3],[4,0]]},
          {"type": "line", "points": [[4,0],[10,0.5]]}]})", "inline.json");
  const auto machine = curvestep::host::load_machine(source("examples/jobs/machine.json"));
  const auto result = curvestep::host::simulate(job, machine);
  CHECK(result.setpoints.back().position_mm[0] == 10.0);
  CHECK(result.setpoints.back().position_mm[1] == 0.5);
  CHECK(result.setpoints.back().raw_q16[1] == 32768);  // 0.5 in Q16.16
  CHECK(result.setpoints.front().position_mm[0] == 0.0);
  CHECK(result.summary.violations.empty());
  CHECK(result.summary.distance_mm == Approx(5.829927224626644 + std::hypot(6.0, 0.5)).epsilon(1e-4));  // seed TV-12 length + line
}

TEST_CASE("sim: a rate override changes the setpoint count", "[host_tools][sim]") {
  const Run slow = run("sim " + source("examples/jobs/seed_cubic.json") + " --machine " + source("examples/jobs/machine.json") + " --rate 500");
  const Run fast = run("sim " + source("examples/jobs/seed_cubic.json") + " --machine " + source("examples/jobs/machine.json") + " --rate 2000");
  CHECK(slow.status == 0);
  CHECK(fast.status == 0);
  CHECK(slow.output.find("at 500 Hz") != std::string::npos);
  CHECK(fast.output.find("at 2000 Hz") != std::string::npos);
  const Run bad = run("sim " + source("examples/jobs/seed_cubic.json") + " --machine " + source("examples/jobs/machine.json") + " --rate 50");
  CHECK(bad.status != 0);
  CHECK(bad.output.find("--rate") != std::string::npos);
  // NaN, 0 and negative rates are refused, not silently ignored (issue 19.8).
  for (const std::string nonsense : {"nan", "0", "-1000", "inf"}) {
    INFO(nonsense);
    const Run r = run("sim " + source("examples/jobs/seed_cubic.json") + " --machine " + source("examples/jobs/machine.json") +
                      " --rate " + nonsense);
    CHECK(r.status != 0);
    CHECK(r.output.find("--rate") != std::string::npos);
  }
}

TEST_CASE("sim: an invalid job fails with a one-line cause naming file and segment", "[host_tools][sim]") {
  const std::string job = temporary("bad_job.json",
                                    R"({"version": 1, "units": "mm", "segments": [{"type": "line", "points": [[0,0],[1,0]]},
                                        {"type": "line", "points": [[2,0],[3,0]]}]})");
  const Run r = run("sim " + job + " --machine " + source("examples/jobs/machine.json"));
  CHECK(r.status == 1);
  CHECK(r.output.find("bad_job.json") != std::string::npos);
  CHECK(r.output.find("segment 1") != std::string::npos);
  CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
}

TEST_CASE("sim: a job too fast for the drivers is planned slower, and with --strict-step-rate exits 3 naming the limit",
          "[host_tools][sim]") {
  std::ifstream in(source("examples/jobs/machine.json"));
  std::stringstream text;
  text << in.rdbuf();
  std::string machine = text.str();
  const auto at = machine.find("\"max_step_rate\": 40000");
  REQUIRE(at != std::string::npos);
  machine.replace(at, std::string("\"max_step_rate\": 40000").size(), "\"max_step_rate\": 1000");
  const std::string path = temporary("slow_machine.json", machine);
  const Run r = run("sim " + source("examples/jobs/every_type.json") + " --machine " + path + " --strict-step-rate");
  CHECK(r.status == 3);
  CHECK(r.output.find("steps/s") != std::string::npos);
  // Without --strict-step-rate: each axis at most 0.99 · 1000 / 80 = 12.375 mm/s, within the limit.
  const Run slower = run("sim " + source("examples/jobs/every_type.json") + " --machine " + path);
  INFO(slower.output);
  CHECK(slower.status == 0);
  CHECK(slower.output.find("axis x planned at most 12.375 mm/s") != std::string::npos);
  CHECK(slower.output.find("limit violations:    none") != std::string::npos);
}

TEST_CASE("sim: a dwell over a minute is noted with its line (G4 P in seconds, a post may mean milliseconds)", "[host_tools][sim]") {
  const std::string machine = source("examples/jobs/machine.json");
  const std::string long_dwells = temporary("long_dwell.ngc", "G21 G90\nG4 P75\nG1 X1 F600\nG4 P90\nG4 P0.5\nM2\n");
  const Run noted = run("sim " + long_dwells + " --machine " + machine);
  INFO(noted.output);
  CHECK(noted.status == 0);
  CHECK(noted.output.find("note: 2 dwells over 60 s, the longest 90 s (line 4): a dwell's P (G4, G82, G89) is in seconds") != std::string::npos);
  const std::string short_dwell = temporary("short_dwell.ngc", "G21 G90\nG4 P60\nG1 X1 F600\nM2\n");
  const Run quiet = run("sim " + short_dwell + " --machine " + machine);
  CHECK(quiet.status == 0);
  CHECK(quiet.output.find("over 60 s") == std::string::npos);
  std::remove(long_dwells.c_str());
  std::remove(short_dwell.c_str());
}

TEST_CASE("sim: a drawing outside its document's own page is noted unless --page lays it out", "[host_tools][sim][svg]") {
  // A 100 x 100 mm page (viewBox in mm) with a square from x 90 to 120 and y 40 to 60 (SVG y down):
  // 20 mm right of the page; the machine's y is up, so nothing is below or above.
  const std::string machine = source("examples/machines/plotter.json");
  const std::string off = temporary("off_page.svg",
                                    "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100mm\" height=\"100mm\" viewBox=\"0 0 100 100\">"
                                    "<rect x=\"90\" y=\"40\" width=\"30\" height=\"20\"/></svg>");
  const Run noted = run("sim " + off + " --machine " + machine);
  INFO(noted.output);
  CHECK(noted.status == 0);
  CHECK(noted.output.find("the drawing reaches 20 mm right of the page (the document's own page, 100 x 100 mm)") != std::string::npos);
  const Run laid_out = run("sim " + off + " --machine " + machine + " --page a4 --fit");
  CHECK(laid_out.status == 0);
  CHECK(laid_out.output.find("own page") == std::string::npos);
  const std::string inside = temporary("on_page.svg",
                                       "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100mm\" height=\"100mm\" viewBox=\"0 0 100 100\">"
                                       "<rect x=\"70\" y=\"40\" width=\"30\" height=\"20\"/></svg>");
  const Run quiet = run("sim " + inside + " --machine " + machine);
  CHECK(quiet.status == 0);
  CHECK(quiet.output.find("own page") == std::string::npos);
  std::remove(off.c_str());
  std::remove(inside.c_str());
}

TEST_CASE("sim: a missing machine option is a usage error", "[host_tools][sim]") {
  const Run r = run("sim " + source("examples/jobs/every_type.json"));
  CHECK(r.status != 0);
  CHECK(r.output.find("--machine") != std::string::npos);
}

namespace {

/// 100 collinear lines of 0.04 mm: at the machine's feed the braking distance spans more than 9
/// of them, so the look-ahead window changes the setpoints.
std::string short_lines_job() {
  std::string segments;
  for (int k = 0; k < 100; ++k) {
    if (k > 0) segments += ",";
    segments += R"({"type": "line", "points": [[)" + std::to_string(0.04 * k) + ",0],[" + std::to_string(0.04 * (k + 1)) + ",0]]}";
  }
  return temporary("short_lines.json", R"({"version": 1, "units": "mm", "segments": [)" + segments + "]}");
}

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

TEST_CASE("sim: --lookahead replays a shorter window, and the default is 16 extended by distance", "[host_tools][sim][lookahead]") {
  // Path smoothing off (it would merge the collinear lines into one): the window alone matters.
  const std::string job = short_lines_job();
  const std::string machine = source("examples/jobs/machine.json") + " --blend-tolerance 0";
  const Run nine = run("sim " + job + " --machine " + machine + " --lookahead 9 -o " + scratch("la9.csv"));
  const Run sixteen = run("sim " + job + " --machine " + machine + " --lookahead 16 -o " + scratch("la16.csv"));
  const Run by_default = run("sim " + job + " --machine " + machine + " -o " + scratch("la_default.csv"));
  INFO(nine.output);
  REQUIRE(nine.status == 0);
  REQUIRE(sixteen.status == 0);
  REQUIRE(by_default.status == 0);
  CHECK(nine.output.find("look-ahead 9") != std::string::npos);
  CHECK(by_default.output.find("look-ahead") == std::string::npos);
  const std::string csv9 = file_text(scratch("la9.csv"));
  const std::string csv16 = file_text(scratch("la16.csv"));
  const std::string csv_default = file_text(scratch("la_default.csv"));
  CHECK(csv9 != csv16);
  // 100 lines of 0.04 mm: 16 of them (0.64 mm) hide the braking distance, the default does not.
  CHECK(csv_default != csv16);
  CHECK(std::count(csv_default.begin(), csv_default.end(), '\n') < std::count(csv16.begin(), csv16.end(), '\n'));
  // The command writes what the library gives with the same window.
  const auto job_file = curvestep::host::parse_job(file_text(job), "short_lines.json");
  const auto machine_limits = curvestep::host::load_machine(source("examples/jobs/machine.json"));
  curvestep::host::SimulationOptions options;
  options.lookahead = 9;
  std::ostringstream expected;
  curvestep::host::write_setpoints_csv(expected, curvestep::host::simulate(job_file, machine_limits, options).setpoints);
  CHECK(csv9 == expected.str());
  curvestep::host::SimulationOptions by_distance;
  by_distance.lookahead_distance_mm = curvestep::host::lookahead_distance_for(machine_limits);
  std::ostringstream expected_default;
  curvestep::host::write_setpoints_csv(expected_default, curvestep::host::simulate(job_file, machine_limits, by_distance).setpoints);
  CHECK(csv_default == expected_default.str());
}

TEST_CASE("sim: an out-of-range --lookahead fails with a one-line cause", "[host_tools][sim][lookahead]") {
  for (const std::string bad : {"0", "17", "-3", "nine"}) {
    const Run r = run("sim " + source("examples/jobs/seed_cubic.json") + " --machine " + source("examples/jobs/machine.json") +
                      " --lookahead " + bad);
    INFO(bad << ": " << r.output);
    CHECK(r.status != 0);
    CHECK(r.output.find("--lookahead") != std::string::npos);
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
  }
}

TEST_CASE("sim: --help documents --lookahead", "[host_tools][sim][lookahead]") {
  const Run r = run("sim --help");
  CHECK(r.status == 0);
  CHECK(r.output.find("--lookahead") != std::string::npos);
  CHECK(r.output.find("1..16") != std::string::npos);
}

TEST_CASE("sim: --override-at sets the override of the simulation, and a bad one fails with a one-line cause",
          "[host_tools][sim][override]") {
  const std::string base = "sim " + source("examples/jobs/seed_cubic.json") + " --machine " + source("examples/jobs/machine.json") +
                           " --lookahead 16";
  const Run plain = run(base + " -o " + scratch("plain.csv"));
  REQUIRE(plain.status == 0);
  // 10 % from the start, comma-separated with a later event, and the same as two options.
  const Run listed = run(base + " --override-at 0:10:100,0.05:20 -o " + scratch("listed.csv"));
  INFO(listed.output);
  REQUIRE(listed.status == 0);
  CHECK(listed.output.find("override:            before setpoint 0, feed 10 %, rapid 100 %") != std::string::npos);
  CHECK(listed.output.find("override:            before setpoint 50, feed 20 %, rapid 100 %") != std::string::npos);
  const Run repeated = run(base + " --override-at 0:10:100 --override-at 0.05:20:100 -o " + scratch("repeated.csv"));
  REQUIRE(repeated.status == 0);
  std::ifstream a(scratch("listed.csv"));
  std::ifstream b(scratch("repeated.csv"));
  std::ifstream c(scratch("plain.csv"));
  const std::string listed_csv((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>());
  const std::string repeated_csv((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>());
  const std::string plain_csv((std::istreambuf_iterator<char>(c)), std::istreambuf_iterator<char>());
  CHECK(listed_csv == repeated_csv);
  CHECK(listed_csv.size() > plain_csv.size());  // slower: more setpoints
  for (const std::string bad : {"1:201", "1:9", "1:100:101", "x:100", "1", "1:50.5"}) {
    const Run r = run(base + " --override-at " + bad);
    INFO(bad << ": " << r.output);
    CHECK(r.status != 0);
    CHECK(r.output.find("--override-at") != std::string::npos);
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
  }
  for (const char* name : {"plain.csv", "listed.csv", "repeated.csv"}) std::filesystem::remove(scratch(name));
}

TEST_CASE("sim: every example G-code program (CAM-style, parametric) runs within the limits", "[host_tools][sim][gcode]") {
  std::size_t programs = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(source("examples/gcode"))) {
    const auto extension = entry.path().extension();
    if (!entry.is_regular_file() || (extension != ".ngc" && extension != ".nc" && extension != ".gcode")) continue;
    ++programs;
    const Run r = run("sim " + entry.path().string() + " --machine " + source("examples/jobs/machine.json"));
    INFO(entry.path().string() << "\n" << r.output);
    CHECK(r.status == 0);
    CHECK(r.output.find("limit violations:    none") != std::string::npos);
  }
  CHECK(programs >= 13);  // examples/gcode/*.ngc and every file of examples/gcode/cam
}
