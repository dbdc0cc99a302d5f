// SPDX-License-Identifier: MIT
// Runs G-code lines through the interpreter for the interpreter tests.
#pragma once

#include <catch2/catch.hpp>

#include <cstddef>
#include <initializer_list>
#include <string_view>

#include <curvestep/gcode.hpp>

namespace curvestep::gcode::testing {

using Machine = Interpreter<16>;

/// Runs `lines` (all must succeed) and returns the last line's motion.
inline Motion run(Machine& machine, std::initializer_list<std::string_view> lines) {
  Motion last;
  for (const auto line : lines) {
    INFO(line);
    const auto block = parse_line(line);
    REQUIRE(block);
    const auto motion = machine.execute(block.value());
    REQUIRE(motion);
    last = motion.value();
  }
  return last;
}

/// Runs `lines` on `machine`; all but the last must succeed; returns the last one's failure.
inline Failure run_failing(Machine& machine, std::initializer_list<std::string_view> lines) {
  std::size_t i = 0;
  for (const auto line : lines) {
    INFO(line);
    const auto block = parse_line(line);
    REQUIRE(block);
    const auto motion = machine.execute(block.value());
    if (++i < lines.size()) {
      REQUIRE(motion);
    } else {
      REQUIRE_FALSE(motion);
      return motion.failure();
    }
  }
  FAIL("no lines");
  return {};
}

/// Runs `lines` on a new machine; all but the last must succeed; returns the last one's failure.
inline Failure run_failing(std::initializer_list<std::string_view> lines) {
  Machine machine;
  return run_failing(machine, lines);
}

}  // namespace curvestep::gcode::testing
