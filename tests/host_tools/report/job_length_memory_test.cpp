// SPDX-License-Identifier: MIT
// Memory of a run (issue 19, item 7). `curvestep sim`, `sim --report`, `curvestep plot` and
// `curvestep gpio` hand each setpoint on as it is made and keep none. The same ten lines are run at two lengths,
// 15 000 and 150 000 setpoints; the largest resident size of the child process (getrusage through
// wait4) may grow by at most 4 MiB. A program that kept its setpoints (64-byte records, and 16 bytes
// more per point for the plot's strokes) would grow by more than 8 MiB. A G-code program is read
// as a stream and its smoothed job is not held (docs/robustness.md, "Memory of a run"): a program
// longer by many lines or many moves costs (almost) nothing more; the margins below are a few
// tens of bytes a line, where the whole-job load took about 0.8 KB a line.
#include <fstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "report_test_support.hpp"
#include "support/child_peak_memory.hpp"

namespace {

using namespace report_test;

/// Ten lines forth and back along x, `length_mm` each, at 20 mm/s (1000 setpoints a second at the
/// example machine's 1000 Hz): 10 · length / 20 · 1000 setpoints.
std::string write_zigzag_job(const std::string& name, double length_mm) {
  const std::string path = scratch(name);
  std::ofstream out(path);
  out << R"({"version": 1, "units": "mm", "segments": [)";
  for (int i = 0; i < 10; ++i) {
    const double y0 = i, y1 = i + 1;
    const double from = (i % 2 == 0) ? 0 : length_mm, to = (i % 2 == 0) ? length_mm : 0;
    out << (i == 0 ? "" : ",") << R"({"type": "line", "feed": 20, "points": [[)" << from << "," << y0 << "],[" << to << "," << y1 << "]]}";
  }
  out << "]}\n";
  return path;
}

/// Runs curvestep with `arguments` (output to /dev/null) and returns its largest resident size in KiB.
long peak_resident_kib(const std::vector<std::string>& arguments) {
  std::vector<std::string> words{CURVESTEP_BINARY};
  words.insert(words.end(), arguments.begin(), arguments.end());
  return curvestep::testing::peak_resident_kib(words);
}

/// `lines` G1 moves of 0.01 mm in rows of 10 mm (1000 moves, then a step of 0.01 mm in y to the
/// next row, which is run backwards) at 200 mm/s: every row is a run of short lines that smoothing
/// fits, as CAM output of a raster is.
std::string write_raster_program(const std::string& name, int lines) {
  const std::string path = scratch(name);
  std::ofstream out(path);
  out << "G21 G90 G17\nF12000\nG0 X0 Y0\n";
  int x_hundredths = 0;
  int y_hundredths = 0;
  int direction = 1;
  const auto move = [&out, &x_hundredths, &y_hundredths] {
    out << "G1 X" << x_hundredths / 100 << "." << (x_hundredths % 100 < 10 ? "0" : "") << x_hundredths % 100 << " Y" << y_hundredths / 100
        << "." << (y_hundredths % 100 < 10 ? "0" : "") << y_hundredths % 100 << "\n";
  };
  for (int written = 0; written < lines;) {
    for (int i = 0; i < 1000 && written < lines; ++i, ++written) {
      x_hundredths += direction;
      move();
    }
    ++y_hundredths;
    direction = -direction;
    if (written < lines) {
      move();
      ++written;
    }
  }
  return path;
}

/// `lines` moves of 0.5 mm along x (21 000 mm for 42 000) at 200 mm/s: with smoothing off
/// (--blend-tolerance 0) every line stays a segment of the smoothed job.
std::string write_long_moves_program(const std::string& name, int lines) {
  const std::string path = scratch(name);
  std::ofstream out(path);
  out << "G21 G90 G17\nF12000\nG0 X0 Y0\n";
  for (int i = 1; i <= lines; ++i) out << "G1 X" << i / 2 << (i % 2 == 1 ? ".5" : "") << "\n";
  return path;
}

}  // namespace

// The smoothed job is not held (streamed_job.hpp: the file is read again for each pass): sim,
// plot, sim --report and gpio keep nothing per move (measured: flat in a release build, up to 1.4 MB
// under the sanitizers, whose allocator moves the peak). Holding the smoothed job cost about 930
// bytes a move here (472 per segment and the load's): 9 MB for 10 000 moves more, 37 MB for 40 000,
// which fails this (measured through the whole-job path, `--optimize`). Plot, report and gpio
// simulate the job more than once: 10 000 moves more for them.
TEST_CASE("memory: sim, plot, report and gpio of a G-code program of many more moves smoothing keeps grow by at most 3 MiB",
          "[host_tools][report][memory]") {
  const std::string machine = source("examples/jobs/machine.json");
  const std::string short_program = write_long_moves_program("short_moves.ngc", 2'000);
  const std::string long_program = write_long_moves_program("long_moves.ngc", 42'000);
  const std::string medium_program = write_long_moves_program("medium_moves.ngc", 12'000);
  constexpr long margin_kib = 3072;
  const auto peak = [&machine](const std::string& command, const std::string& program, const std::vector<std::string>& extra) {
    std::vector<std::string> arguments{command, program, "--machine", machine, "--blend-tolerance", "0"};
    arguments.insert(arguments.end(), extra.begin(), extra.end());
    return peak_resident_kib(arguments);
  };

  const long sim_short = peak("sim", short_program, {"--lookahead", "16"});
  const long sim_long = peak("sim", long_program, {"--lookahead", "16"});
  INFO("sim: " << sim_short << " KiB for 2 000 moves, " << sim_long << " KiB for 42 000");
  CHECK(sim_long <= sim_short + margin_kib);

  const std::string svg = scratch("moves.svg");
  const std::string html = scratch("moves.html");
  struct Command {
    const char* name;
    std::vector<std::string> arguments;
  };
  for (const Command& c : {Command{"plot", {"-o", svg}}, Command{"sim", {"--report", html}}, Command{"gpio", {"--dry-run"}}}) {
    const long short_kib = peak(c.name, short_program, c.arguments);
    const long medium_kib = peak(c.name, medium_program, c.arguments);
    INFO(c.name << " " << c.arguments.front() << ": " << short_kib << " KiB for 2 000 moves, " << medium_kib << " KiB for 12 000");
    CHECK(medium_kib <= short_kib + margin_kib);
  }

  for (const std::string& file : {short_program, medium_program, long_program, svg, html}) std::remove(file.c_str());
}

TEST_CASE("memory: sim of a G-code program 200 000 lines longer costs at most 20 bytes a line more", "[host_tools][report][memory]") {
  const std::string machine = source("examples/jobs/machine.json");
  const std::string short_program = write_raster_program("short.ngc", 20'000);
  const std::string long_program = write_raster_program("long.ngc", 220'000);
  constexpr long bytes_per_line = 20;
  constexpr long margin_kib = 200'000 * bytes_per_line / 1024;

  const long sim_short = peak_resident_kib({"sim", short_program, "--machine", machine});
  const long sim_long = peak_resident_kib({"sim", long_program, "--machine", machine});
  INFO("sim: " << sim_short << " KiB for 20 000 lines, " << sim_long << " KiB for 220 000");
  CHECK(sim_long <= sim_short + margin_kib);

  std::remove(short_program.c_str());
  std::remove(long_program.c_str());
}

TEST_CASE("memory: sim, its report, plot and gpio use the same memory for a job ten times longer", "[host_tools][report][memory]") {
  const std::string machine = source("examples/jobs/machine.json");
  const std::string short_job = write_zigzag_job("short.json", 30);  // 15 000 setpoints
  const std::string long_job = write_zigzag_job("long.json", 300);   // 150 000 setpoints
  const std::string svg = scratch("memory.svg");
  constexpr long margin_kib = 4096;

  const long sim_short = peak_resident_kib({"sim", short_job, "--machine", machine});
  const long sim_long = peak_resident_kib({"sim", long_job, "--machine", machine});
  INFO("sim: " << sim_short << " KiB for 15 000 setpoints, " << sim_long << " KiB for 150 000");
  CHECK(sim_long <= sim_short + margin_kib);

  const long plot_short = peak_resident_kib({"plot", short_job, "--machine", machine, "-o", svg});
  const long plot_long = peak_resident_kib({"plot", long_job, "--machine", machine, "-o", svg});
  INFO("plot: " << plot_short << " KiB for 15 000 setpoints, " << plot_long << " KiB for 150 000");
  CHECK(plot_long <= plot_short + margin_kib);

  const std::string html = scratch("memory.html");
  const long report_short = peak_resident_kib({"sim", short_job, "--machine", machine, "--report", html});
  const long report_long = peak_resident_kib({"sim", long_job, "--machine", machine, "--report", html});
  INFO("sim --report: " << report_short << " KiB for 15 000 setpoints, " << report_long << " KiB for 150 000");
  CHECK(report_long <= report_short + margin_kib);

  // gpio measures the step rate of the setpoints as the simulation makes them, and counts those the
  // controller streams back (--dry-run: the firmware runs as fast as it can, no line is driven).
  const long gpio_short = peak_resident_kib({"gpio", short_job, "--machine", machine, "--dry-run"});
  const long gpio_long = peak_resident_kib({"gpio", long_job, "--machine", machine, "--dry-run"});
  INFO("gpio --dry-run: " << gpio_short << " KiB for 15 000 setpoints, " << gpio_long << " KiB for 150 000");
  CHECK(gpio_long <= gpio_short + margin_kib);

  std::remove(html.c_str());
  std::remove(short_job.c_str());
  std::remove(long_job.c_str());
  std::remove(svg.c_str());
}
