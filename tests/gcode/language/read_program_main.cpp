// SPDX-License-Identifier: MIT
// gcode_read_program FILE: reads a G-code program to its end through the language layer alone
// (ProgramReader::open_file, next()) and prints the number of blocks. The memory test runs it in a
// child process to measure what the reader holds.
#include <cstdio>
#include <exception>

#include <curvestep/host/gcode/program_reader.hpp>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: gcode_read_program FILE\n");
    return 2;
  }
  try {
    auto reader = curvestep::host::gcode::ProgramReader::open_file(argv[1], argv[1]);
    unsigned long blocks = 0;
    while (reader.next()) ++blocks;
    std::printf("%lu blocks\n", blocks);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return 1;
  }
  return 0;
}
