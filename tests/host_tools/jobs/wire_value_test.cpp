// SPDX-License-Identifier: MIT
// round_for_wire, the one Q16.16 rounding of weights and feeds that the job loader, the G-code
// importer and the SVG importer share. Expected values are worked out by hand here: value · 65536
// rounded to the nearest integer (ties away from zero), divided by 65536; Q16.16 holds raw values
// from -2^31 to 2^31 - 1.
#include <cmath>
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/core/error.hpp>
#include <curvestep/host/wire_value.hpp>

using namespace curvestep;
using namespace curvestep::host;

TEST_CASE("wire value: weights and feeds round to the nearest Q16.16 value", "[host_tools][jobs][wire]") {
  for (const auto quantity : {WireQuantity::Weight, WireQuantity::Feed}) {
    // 0.1 · 65536 = 6553.6 -> 6554.
    auto r = round_for_wire(0.1, quantity);
    REQUIRE(r);
    CHECK(r.problem.empty());
    CHECK(r.value == 6554.0 / 65536.0);
    // 0.7071067811865476 · 65536 = 46340.95 -> 46341; 33.33333 · 65536 = 2184533.11 -> 2184533.
    CHECK(round_for_wire(0.7071067811865476, quantity).value == 46341.0 / 65536.0);
    CHECK(round_for_wire(33.33333, quantity).value == 2184533.0 / 65536.0);
    // Values on the grid stay as they are.
    CHECK(round_for_wire(1.0, quantity).value == 1.0);
    CHECK(round_for_wire(0x1p-16, quantity).value == 0x1p-16);
    // 2^-17 is half a step: the tie rounds away from zero to 2^-16.
    CHECK(round_for_wire(0x1p-17, quantity).value == 0x1p-16);
    // Zero and negative values are rounded without complaint (callers check signs): -6553.6 -> -6554.
    r = round_for_wire(0.0, quantity);
    REQUIRE(r);
    CHECK(r.value == 0.0);
    r = round_for_wire(-0.1, quantity);
    REQUIRE(r);
    CHECK(r.value == -6554.0 / 65536.0);
  }
}

TEST_CASE("wire value: the upper end of the Q16.16 range", "[host_tools][jobs][wire]") {
  // The largest Q16.16 value is (2^31 - 1) / 65536 = 32767.9999847412109375.
  const double largest = (0x1p31 - 1.0) / 65536.0;
  CHECK(round_for_wire(largest, WireQuantity::Weight).value == largest);
  // 32767.99998 · 65536 = 2147483647.3 -> 2^31 - 1.
  CHECK(round_for_wire(32767.99998, WireQuantity::Feed).value == largest);
  // Just below (2^31 - 0.5) / 65536 still rounds down to 2^31 - 1.
  const double half_above = (0x1p31 - 0.5) / 65536.0;
  CHECK(round_for_wire(std::nextafter(half_above, 0.0), WireQuantity::Weight).value == largest);
  // (2^31 - 0.5) / 65536 would round to 2^31: outside the range, as are 32768 and 40000.
  for (const double value : {half_above, 32768.0, 40000.0}) {
    INFO(value);
    const auto r = round_for_wire(value, WireQuantity::Weight);
    CHECK_FALSE(r);
    CHECK(r.code == Error::FixedOverflow);
    CHECK(r.problem.ends_with(" is outside the Q16.16 range (at most 32767.99998)"));
    CHECK(r.problem.starts_with("weight "));
  }
  const auto r = round_for_wire(40000.0, WireQuantity::Weight);
  CHECK(r.problem == "weight 40000 is outside the Q16.16 range (at most 32767.99998)");
  const auto feed = round_for_wire(-1e6, WireQuantity::Feed);
  CHECK(feed.code == Error::FixedOverflow);
  CHECK(feed.problem == "feed -1e+06 is outside the Q16.16 range (at most 32767.99998)");
}

TEST_CASE("wire value: a positive value that rounds to 0 is refused, naming what it is", "[host_tools][jobs][wire]") {
  // 7e-6 · 65536 = 0.459 -> 0; 1e-6 · 65536 = 0.066 -> 0.
  const auto weight = round_for_wire(7e-6, WireQuantity::Weight);
  CHECK_FALSE(weight);
  CHECK(weight.code == Error::NonPositiveWeight);
  CHECK(weight.problem == "weight 7e-06 rounds to 0 in Q16.16 (the smallest positive value is 2^-16 = 1.52588e-05)");
  const auto feed = round_for_wire(1e-6, WireQuantity::Feed);
  CHECK_FALSE(feed);
  CHECK(feed.code == Error::InvalidArgument);
  CHECK(feed.problem == "feed 1e-06 rounds to 0 in Q16.16 (the smallest positive value is 2^-16 = 1.52588e-05)");
  // A name given by the caller replaces "weight" / "feed"; the code still follows the quantity.
  const auto named = round_for_wire(1e-6, WireQuantity::Feed, "feed (mm/s)");
  CHECK(named.code == Error::InvalidArgument);
  CHECK(named.problem == "feed (mm/s) 1e-06 rounds to 0 in Q16.16 (the smallest positive value is 2^-16 = 1.52588e-05)");
  // The largest value below the tie 2^-17 rounds to 0.
  const auto below_half = round_for_wire(std::nextafter(0x1p-17, 0.0), WireQuantity::Weight);
  CHECK_FALSE(below_half);
  CHECK(below_half.code == Error::NonPositiveWeight);
}
