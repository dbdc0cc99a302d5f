// SPDX-License-Identifier: MIT
// The G-code importer rounds feeds and NURBS weights with round_for_wire, so a value that cannot
// travel as Q16.16 is refused with the job loader's message and code. Expected roundings by hand:
// value · 65536 rounded to the nearest integer.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include <curvestep/core/error.hpp>
#include <curvestep/host/gcode_import.hpp>

using namespace curvestep;
using namespace curvestep::host;

TEST_CASE("gcode import: weights and feeds that cannot travel as Q16.16 get the job loader's message and code", "[gcode][import][wire]") {
  struct Case {
    std::string program;
    Error code;
    std::vector<std::string> parts;  ///< pieces of what()
  };
  const std::string rounds_to_zero = " rounds to 0 in Q16.16 (the smallest positive value is 2^-16 = 1.52588e-05)";
  const Case cases[] = {
      // P0.000001: 1e-6 · 65536 = 0.066 rounds to 0; a weight, as in the job loader.
      {"G5.2 P1 L3\nX1 Y1 P0.000001\nX2 Y0\nG5.3\n", Error::NonPositiveWeight, {"weight 1e-06" + rounds_to_zero}},
      // F0.0001 mm/min = 1.67e-6 mm/s: 1.67e-6 · 65536 = 0.109 rounds to 0; at the F word, in mm/s.
      {"G1 X1 F0.0001\n", Error::InvalidArgument, {": F0.0001: feed (mm/s) ", rounds_to_zero}},
      // F3000000 mm/min = 50000 mm/s, above the largest Q16.16 value 32767.99998.
      {"G1 X1 F3000000\n", Error::FixedOverflow, {"feed (mm/s) 50000 is outside the Q16.16 range (at most 32767.99998)"}},
  };
  for (const auto& c : cases) {
    INFO(c.program);
    try {
      (void)parse_gcode_job(c.program, "wire.ngc");
      FAIL("the program loaded");
    } catch (const LoadError& e) {
      const std::string what = e.what();
      INFO(what);
      CHECK(e.code() == c.code);
      for (const auto& part : c.parts) CHECK(what.find(part) != std::string::npos);
    }
  }
}
