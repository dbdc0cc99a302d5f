// SPDX-License-Identifier: MIT
// The G-code importer rounds feeds and NURBS weights with round_for_wire, so a positive value that
// rounds to 0 in Q16.16 is refused with the job loader's message and code.
#include <catch2/catch.hpp>

#include <string>

#include <curvestep/core/error.hpp>
#include <curvestep/host/gcode_import.hpp>

using namespace curvestep;
using namespace curvestep::host;

namespace {

LoadError gcode_error(const std::string& text) {
  try {
    (void)parse_gcode_job(text, "wire.ngc");
  } catch (const LoadError& e) {
    return e;
  }
  FAIL("the program loaded: " << text);
  return LoadError({}, "", Error::InvalidArgument);
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("gcode import: a NURBS weight that rounds to 0 in Q16.16 is a non-positive weight", "[gcode][import][wire]") {
  // P0.000001: 1e-6 · 65536 = 0.066 rounds to 0.
  const LoadError e = gcode_error("G5.2 P1 L3\nX1 Y1 P0.000001\nX2 Y0\nG5.3\n");
  INFO(e.what());
  CHECK(e.code() == Error::NonPositiveWeight);
  CHECK(contains(e.what(), "weight 1e-06 rounds to 0 in Q16.16 (the smallest positive value is 2^-16 = 1.52588e-05)"));
}

TEST_CASE("gcode import: a feed that rounds to 0 in Q16.16 names the feed in mm/s", "[gcode][import][wire]") {
  // F0.0001 mm/min = 1.67e-6 mm/s: 1.67e-6 · 65536 = 0.109 rounds to 0.
  const LoadError e = gcode_error("G1 X1 F0.0001\n");
  INFO(e.what());
  CHECK(e.code() == Error::InvalidArgument);
  CHECK(contains(e.what(), ": F0.0001: feed (mm/s) "));
  CHECK(contains(e.what(), " rounds to 0 in Q16.16 (the smallest positive value is 2^-16 = 1.52588e-05)"));
}

TEST_CASE("gcode import: a feed outside Q16.16 names the range", "[gcode][import][wire]") {
  // F3000000 mm/min = 50000 mm/s, above the largest Q16.16 value 32767.99998.
  const LoadError e = gcode_error("G1 X1 F3000000\n");
  INFO(e.what());
  CHECK(e.code() == Error::FixedOverflow);
  CHECK(contains(e.what(), "feed (mm/s) 50000 is outside the Q16.16 range (at most 32767.99998)"));
}
