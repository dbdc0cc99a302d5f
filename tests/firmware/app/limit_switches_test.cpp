// SPDX-License-Identifier: MIT
// The hard-limit rule (firmware/limit_switches.hpp): a closed switch stops only motion toward it.
// Expected switch numbers are the documented bit layout (2 x axis, + 1 for max), written by hand.
#include <catch2/catch.hpp>

#include <cstdint>

#include <curvestep/firmware/limit_switches.hpp>

using namespace curvestep::firmware;
using curvestep::protocol::WirePoint;

TEST_CASE("limit switches: a closed switch faults motion toward it and names its bit", "[firmware][limits]") {
  const WirePoint at{0, 0, 0};
  CHECK(hard_limit_hit(0b000001, at, WirePoint{-1, 0, 0}, 3) == 0);  // x min, x going down
  CHECK(hard_limit_hit(0b000010, at, WirePoint{1, 0, 0}, 3) == 1);   // x max, x going up
  CHECK(hard_limit_hit(0b000100, at, WirePoint{0, -1, 0}, 3) == 2);  // y min
  CHECK(hard_limit_hit(0b100000, at, WirePoint{0, 0, 1}, 3) == 5);   // z max
}

TEST_CASE("limit switches: motion away from a closed switch, a standing axis and an open switch do not fault",
          "[firmware][limits]") {
  const WirePoint at{0, 0, 0};
  CHECK(hard_limit_hit(0b000001, at, WirePoint{1, 0, 0}, 3) == no_limit_switch);   // off the x min switch
  CHECK(hard_limit_hit(0b000010, at, WirePoint{-1, 0, 0}, 3) == no_limit_switch);  // off the x max switch
  CHECK(hard_limit_hit(0b000011, at, WirePoint{0, 5, 0}, 3) == no_limit_switch);   // x stands, y moves
  CHECK(hard_limit_hit(0, at, WirePoint{-9, 9, -9}, 3) == no_limit_switch);        // nothing closed
  CHECK(hard_limit_hit(0b010000, at, WirePoint{0, 0, -1}, 2) == no_limit_switch);  // z not driven (2 axes)
}
