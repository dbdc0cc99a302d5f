// SPDX-License-Identifier: MIT
// Helpers for the language tests: run a program to its end, and catch the LoadError it throws.
#pragma once

#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include <curvestep/host/gcode/program_reader.hpp>
#include <curvestep/host/load_error.hpp>

namespace curvestep::testing {

/// Every block the program hands out.
inline std::vector<host::gcode::ProgramBlock> run_program(const std::string& text, host::gcode::ProgramOptions options = {}) {
  host::gcode::ProgramReader reader(text, "test.ngc", options);
  std::vector<host::gcode::ProgramBlock> blocks;
  while (auto block = reader.next()) blocks.push_back(std::move(*block));
  return blocks;
}

/// The value of `letter` in a block (fails the test if absent).
inline double word(const host::gcode::ProgramBlock& block, char letter) {
  const host::gcode::ProgramWord* w = block.find(letter);
  REQUIRE(w != nullptr);
  return w->value;
}

/// The X values of all blocks, in order.
inline std::vector<double> x_values(const std::vector<host::gcode::ProgramBlock>& blocks) {
  std::vector<double> xs;
  for (const auto& b : blocks) {
    if (const auto* w = b.find('X')) xs.push_back(w->value);
  }
  return xs;
}

/// The LoadError reading `text` to its end throws (construction included).
inline host::LoadError program_error(const std::string& text, host::gcode::ProgramOptions options = {}) {
  try {
    (void)run_program(text, options);
  } catch (const host::LoadError& error) {
    return error;
  }
  FAIL("no error for:\n" << text);
  return host::LoadError({}, "", Error::GcodeSyntax);
}

}  // namespace curvestep::testing
