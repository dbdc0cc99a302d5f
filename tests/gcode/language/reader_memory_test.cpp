// SPDX-License-Identifier: MIT
// Memory of a run (issue 19, item 7): the G-code reader holds neither the file's text nor a
// record per line. A child process (gcode_read_program) reads a raster program of 50 000 lines and
// one of 550 000 lines through ProgramReader; its largest resident size may grow by at most 8 bytes
// a line. A reader that held the text (about 17 bytes a line here) and a view of each line (16
// bytes) and a summary of it (24 bytes) grows by about 57 bytes a line, 27 MB: it fails this.
#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <string>
#include <unistd.h>

#include "support/child_peak_memory.hpp"

namespace {

/// `lines` G1 moves of a raster (rows of 1000 steps of 0.01 mm, each row a step in y), one a line.
std::string write_raster(const std::string& name, int lines) {
  const std::string path = "reader_memory_" + std::to_string(::getpid()) + "_" + name + ".ngc";
  std::ofstream out(path);
  for (int i = 0; i < lines; ++i) {
    const int step = i % 1000;
    const int x = (i / 1000) % 2 == 0 ? step : 1000 - step;
    out << "G1 X" << x / 100 << "." << x % 100 / 10 << x % 10 << " Y" << i / 1000 << "\n";
  }
  return path;
}

}  // namespace

TEST_CASE("memory: the G-code reader reading a file 500 000 lines longer grows by at most 8 bytes a line",
          "[gcode][language][file][memory]") {
  const std::string short_file = write_raster("short", 50'000);
  const std::string long_file = write_raster("long", 550'000);
  constexpr long bytes_per_line = 8;
  constexpr long margin_kib = 500'000 * bytes_per_line / 1024;

  const long short_kib = curvestep::testing::peak_resident_kib({GCODE_READ_PROGRAM, short_file});
  const long long_kib = curvestep::testing::peak_resident_kib({GCODE_READ_PROGRAM, long_file});
  INFO("reader: " << short_kib << " KiB for 50 000 lines, " << long_kib << " KiB for 550 000");
  CHECK(long_kib <= short_kib + margin_kib);

  std::remove(short_file.c_str());
  std::remove(long_file.c_str());
}
