// SPDX-License-Identifier: MIT
// `curvestep gpio`: the real program. Without GPIO hardware only its refusals and its dry run (the
// firmware on the host board with the edges counted instead of written) can be run; the dry run's
// net step counts are compared with the job's start and end points × steps/mm, computed here.
#include <cstdio>
#include <fstream>
#include <regex>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>

namespace {

struct Run {
  int status = -1;
  std::string out;
  std::string err;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string temporary(const std::string& name) { return "/tmp/curvestep_gpio_test_" + std::to_string(::getpid()) + "_" + name; }

Run run(const std::string& arguments) {
  const std::string out = temporary("stdout.txt");
  const std::string err = temporary("stderr.txt");
  // Standard input is /dev/null unless the arguments redirect it: never the runner's terminal,
  // which the program would read operator keys from.
  const std::string input = arguments.find('<') == std::string::npos ? " </dev/null" : "";
  const std::string command = std::string(CURVESTEP_BINARY) + " " + arguments + input + " >" + out + " 2>" + err;
  const int raw = std::system(command.c_str());
  Run r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

std::string source(const std::string& relative) { return std::string(CURVESTEP_SOURCE_DIR) + "/" + relative; }

std::string write(const std::string& name, const std::string& content) {
  const std::string path = temporary(name);
  std::ofstream(path) << content;
  return path;
}

/// The example machine (80, 80, 400 steps/mm; max_step_rate 40000) with `extra` members.
std::string machine(const std::string& name, const std::string& extra, double max_step_rate = 40000) {
  return write(name, R"({"version": 1, "v_max": 200, "a_max": 2000, "j_max": 50000, "feed": 50, "rapid": 150,
    "tolerance": 0.01, "rate_hz": 1000, "junction_deviation": 0.02, "max_step_rate": )" +
                         std::to_string(max_step_rate) + R"(, "profile": "scurve",
    "axes": {"x": {"steps_per_mm": 80, "v_max": 200, "a_max": 2000},
             "y": {"steps_per_mm": 80, "v_max": 200, "a_max": 2000},
             "z": {"steps_per_mm": 400, "v_max": 20, "a_max": 500}})" +
                         extra + "}");
}

const std::string gpio_section = R"(, "gpio": {"chip": "curvestep-no-such-chip", "x": {"step": "S0", "dir": "D0"},
    "y": {"step": "S1", "dir": "D1", "invert_dir": true}, "z": {"step": "S2", "dir": "D2"}})";

std::size_t lines_of(const std::string& text) {
  std::size_t n = 0;
  for (const char c : text) n += c == '\n' ? 1 : 0;
  return n;
}

/// "net steps:  x 1600  y 0  z 0 (planned ...)" -> the three counts.
std::array<long, 3> net_steps(const std::string& out) {
  const std::regex pattern(R"(net steps: +x (-?\d+) +y (-?\d+) +z (-?\d+))");
  std::smatch m;
  REQUIRE(std::regex_search(out, m, pattern));
  return {std::stol(m[1]), std::stol(m[2]), std::stol(m[3])};
}

}  // namespace

TEST_CASE("gpio: --help names the job, the machine and every option", "[host_tools][gpio]") {
  const Run r = run("gpio --help");
  INFO(r.out << r.err);
  CHECK(r.status == 0);
  for (const char* text : {"job", "--machine", "--rate", "--chip", "--dry-run", "\"gpio\" section", "Exit status"}) {
    CHECK(r.out.find(text) != std::string::npos);
  }
  const Run top = run("--help");
  CHECK(top.out.find("gpio") != std::string::npos);
}

TEST_CASE("gpio: a chip that does not exist fails with one line naming it, before anything runs", "[host_tools][gpio]") {
  const std::string m = machine("machine_gpio.json", gpio_section);
  Run r = run("gpio " + source("examples/jobs/every_type.json") + " --machine " + m);
  INFO(r.out << r.err);
  CHECK(r.status == 5);
  CHECK(r.out.empty());
  CHECK(lines_of(r.err) == 1);
  CHECK(r.err.find("GPIO chip \"curvestep-no-such-chip\" not found") != std::string::npos);
  // --chip overrides the machine file's chip, and the message names the one tried.
  r = run("gpio " + source("examples/jobs/every_type.json") + " --machine " + m + " --chip curvestep-chip-" +
          std::to_string(::getpid()));
  CHECK(r.status == 5);
  CHECK(lines_of(r.err) == 1);
  CHECK(r.err.find("GPIO chip \"curvestep-chip-" + std::to_string(::getpid()) + "\" not found") != std::string::npos);
}

TEST_CASE("gpio: a machine file without a gpio section is refused with its name", "[host_tools][gpio]") {
  const Run r = run("gpio " + source("examples/jobs/every_type.json") + " --machine " + source("examples/jobs/machine.json"));
  INFO(r.out << r.err);
  CHECK(r.status != 0);
  CHECK(r.err.find("machine.json: no \"gpio\" section") != std::string::npos);
}

TEST_CASE("gpio: with --strict-step-rate a job faster than max_step_rate is refused before anything moves", "[host_tools][gpio]") {
  // v_max 200 mm/s at 80 steps/mm would be 16000 steps/s; every_type.json's feed 20 mm/s line alone
  // needs 1600. With max_step_rate 1000 some axis must exceed it.
  const std::string m = machine("machine_slow_driver.json", gpio_section, 1000);
  const Run r = run("gpio " + source("examples/jobs/every_type.json") + " --machine " + m + " --dry-run --strict-step-rate");
  INFO(r.out << r.err);
  CHECK(r.status == 3);
  CHECK(r.err.find("more than max_step_rate 1000") != std::string::npos);
  CHECK(r.err.find("nothing moved") != std::string::npos);
  CHECK(r.out.find("steps taken") == std::string::npos);
  // Without it the job is planned slower (each axis at most 0.99 · 1000 / 80 = 12.375 mm/s) and runs.
  const Run slower = run("gpio " + source("examples/jobs/every_type.json") + " --machine " + m + " --dry-run");
  INFO(slower.out << slower.err);
  CHECK(slower.status == 0);
  CHECK(slower.err.find("planned at most 12.375 mm/s") != std::string::npos);
}

TEST_CASE("gpio: --rate must give whole microseconds per tick on the host board's 1 MHz step timer", "[host_tools][gpio]") {
  const std::string m = machine("machine_rate.json", gpio_section);
  // 1 MHz / 300 Hz = 3333.3 us per tick: refused; 1 MHz / 2000 Hz = 500 us: runs.
  Run r = run("gpio " + source("examples/jobs/seed_cubic.json") + " --machine " + m + " --dry-run --rate 300");
  INFO(r.out << r.err);
  CHECK(r.status != 0);
  CHECK(r.err.find("rate 300 Hz") != std::string::npos);
  CHECK(r.err.find("whole number of microseconds") != std::string::npos);
  r = run("gpio " + source("examples/jobs/seed_cubic.json") + " --machine " + m + " --dry-run --rate 2000");
  CHECK(r.status == 0);
  CHECK(r.out.find("at 2000 Hz") != std::string::npos);
  CHECK(net_steps(r.out) == std::array<long, 3>{4 * 80, 0, 0});
}

TEST_CASE("gpio: a dry run takes the steps from the job's start to its end on every axis", "[host_tools][gpio]") {
  const std::string m = machine("machine_dry.json", gpio_section);
  SECTION("every_type.json: from (0, 0, 0) to the final rapid's (20, 0, 0)") {
    const Run r = run("gpio " + source("examples/jobs/every_type.json") + " --machine " + m + " --dry-run");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK(net_steps(r.out) == std::array<long, 3>{20 * 80, 0, 0});
  }
  SECTION("seed_cubic.json: from (0, 0) to (4, 0)") {
    const Run r = run("gpio " + source("examples/jobs/seed_cubic.json") + " --machine " + m + " --dry-run");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK(net_steps(r.out) == std::array<long, 3>{4 * 80, 0, 0});
  }
  SECTION("negative x, positive y and z: from (0, 0, 0) to (-3.3, 2.0125, 1)") {
    // On the Q16.16 grid -3.3 is -216269/65536 (x 80 = -264.0002 steps) and 2.0125 is 131891/65536
    // (x 80 = 160.9998 steps); z 1 mm x 400. The step count is the nearest integer.
    const std::string job = write("negative.json", R"({"version": 1, "segments": [
        {"type": "line", "points": [[0, 0, 0], [-3.3, 2.0125, 1]], "feed": 5}]})");
    const Run r = run("gpio " + job + " --machine " + m + " --dry-run");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK(net_steps(r.out) == std::array<long, 3>{-264, 161, 400});
  }
}

TEST_CASE("gpio: with --keys, Esc from a non-terminal stdin aborts through the protocol before anything moves, without it stdin is not read",
          "[host_tools][gpio][operator]") {
  const std::string m = machine("machine_keys.json", gpio_section);
  const std::string escape = write("escape.txt", "\x1b");
  const std::string job = source("examples/jobs/every_type.json");
  const Run aborted = run("gpio " + job + " --machine " + m + " --dry-run --keys <" + escape);
  INFO(aborted.out << aborted.err);
  CHECK(aborted.status == 6);
  CHECK_THAT(aborted.out, Catch::Contains("aborted:             by the operator at setpoint 0"));
  CHECK_THAT(aborted.err, Catch::Contains("aborted by the operator"));
  CHECK(net_steps(aborted.out) == std::array<long, 3>{0, 0, 0});
  const Run ignored = run("gpio " + job + " --machine " + m + " --dry-run <" + escape);
  INFO(ignored.out << ignored.err);
  CHECK(ignored.status == 0);
  CHECK(net_steps(ignored.out) == std::array<long, 3>{20 * 80, 0, 0});
}
