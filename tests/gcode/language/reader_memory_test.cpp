// SPDX-License-Identifier: MIT
// Memory of a run (issue 19, item 7): the G-code reader holds neither the file's text nor a
// record per line. A child process (gcode_read_program) reads a raster program of 50 000 lines and
// one of 550 000 lines through ProgramReader; its largest resident size may grow by at most 8 bytes
// a line. A reader that held the text (about 17 bytes a line here) and a view of each line (16
// bytes) and a summary of it (24 bytes) grows by about 57 bytes a line (measured 98), which fails
// this. An O-word line keeps where it starts and its links (about 90 bytes): a program of 300 000
// more O-word lines may grow by at most 128 bytes each; keeping their parse trees took about 600.
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

/// `ifs` blocks "o<n> if [#1 GT 0]", "G1 X<k>", "o<n> endif": two O-word lines in three.
std::string write_branches(const std::string& name, int ifs) {
  const std::string path = "reader_memory_" + std::to_string(::getpid()) + "_" + name + ".ngc";
  std::ofstream out(path);
  out << "#1 = 1\n";
  for (int i = 0; i < ifs; ++i) out << "o" << i % 1000 << " if [#1 GT 0]\nG1 X" << i % 7 << "\no" << i % 1000 << " endif\n";
  return path;
}

/// How much more (KiB) the largest resident size of reading `long_file` is than of reading
/// `short_file` (both removed afterwards).
long growth_kib(const std::string& short_file, const std::string& long_file) {
  const long short_kib = curvestep::testing::peak_resident_kib({GCODE_READ_PROGRAM, short_file});
  const long long_kib = curvestep::testing::peak_resident_kib({GCODE_READ_PROGRAM, long_file});
  std::remove(short_file.c_str());
  std::remove(long_file.c_str());
  UNSCOPED_INFO("reader: " << short_kib << " KiB for " << short_file << ", " << long_kib << " KiB for " << long_file);
  return long_kib - short_kib;
}

}  // namespace

TEST_CASE("memory: the G-code reader reading a file 500 000 lines longer grows by at most 8 bytes a line",
          "[gcode][language][file][memory]") {
  constexpr long bytes_per_line = 8;
  CHECK(growth_kib(write_raster("short", 50'000), write_raster("long", 550'000)) <= 500'000 * bytes_per_line / 1024);
}

TEST_CASE("memory: the G-code reader keeps at most 128 bytes per O-word line", "[gcode][language][file][memory]") {
  constexpr long bytes_per_oword_line = 128;  // 25 000 and 175 000 ifs: 50 000 and 350 000 O-word lines
  CHECK(growth_kib(write_branches("short_branches", 25'000), write_branches("long_branches", 175'000)) <=
        300'000 * bytes_per_oword_line / 1024);
}
