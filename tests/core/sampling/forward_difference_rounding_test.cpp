// SPDX-License-Identifier: MIT
// ForwardDifference::point() in fixed point: the output is the wide accumulator rounded to the
// nearest raw unit, ties away from zero, for every fraction width G the stepper chooses
// (G >= 32 takes the high-word rounding, G = 31 the general shift). Reference: the same rounding
// computed independently on the accumulator's magnitude in unsigned arithmetic.
#include <array>
#include <cstdint>
#include <random>

#include <catch2/catch.hpp>

#include <curvestep/core/sampling/forward_difference.hpp>
#include <support/numeric.hpp>

using namespace curvestep;

namespace {

using Curve = Bezier<Q16_16, 3, 7>;

/// round(wide / 2^g), ties away from zero, by unsigned arithmetic on the magnitude (|wide| < 2^63,
/// so magnitude + 2^(g-1) < 2^64).
std::int64_t reference_round(std::int64_t wide, int g) {
  const bool negative = wide < 0;
  const std::uint64_t magnitude = negative ? std::uint64_t{0} - static_cast<std::uint64_t>(wide) : static_cast<std::uint64_t>(wide);
  const std::uint64_t half = std::uint64_t{1} << (g - 1);
  const auto q = static_cast<std::int64_t>((magnitude + half) >> g);
  return negative ? -q : q;
}

/// A random cubic whose coordinates stay within ±`extent` raw units.
Curve random_cubic(std::mt19937_64& rng, std::int64_t extent) {
  std::uniform_int_distribution<std::int64_t> coordinate(-extent, extent);
  std::array<Vec<Q16_16, 3>, 4> points{};
  for (auto& p : points) {
    for (std::size_t axis = 0; axis < 3; ++axis) p[axis] = Q16_16::from_raw(static_cast<std::int32_t>(coordinate(rng)));
  }
  return Curve::create(points).value();
}

}  // namespace

TEST_CASE("forward_difference: point() rounds the accumulator to nearest, ties away from zero, for every G", "[core][sampling]") {
  std::mt19937_64 rng(testing::test_seed());
  int seen_high_word = 0;
  int seen_general = 0;
  // extents from 2^3 to 2^31 - 1 raw: G runs from 48 down to 31
  for (int bits = 3; bits <= 31; ++bits) {
    const std::int64_t extent = bits == 31 ? 0x7fffffff : (std::int64_t{1} << bits);
    for (int trial = 0; trial < 8; ++trial) {
      const Curve curve = random_cubic(rng, extent);
      auto stepper = ForwardDifference<Q16_16, 3>::create(curve, 777).value();
      const int g = stepper.wide_fraction_bits();
      (g >= 32 ? seen_high_word : seen_general) += 1;
      for (;;) {
        const auto p = stepper.point();
        for (std::size_t axis = 0; axis < 3; ++axis) {
          const std::int64_t expected = reference_round(stepper.wide_coordinate(axis), g);
          REQUIRE(static_cast<std::int64_t>(p[axis].raw()) == expected);
          REQUIRE(static_cast<std::int64_t>(stepper.coordinate(axis).raw()) == expected);
        }
        if (stepper.finished()) break;
        stepper.step();
      }
    }
  }
  CHECK(seen_high_word > 0);
  CHECK(seen_general > 0);
}

TEST_CASE("forward_difference: ties of the accumulator round away from zero on both sides", "[core][sampling]") {
  // A line from -1 raw to +1 raw in 4 steps passes -0.5 and +0.5 raw exactly (N a power of two:
  // the seed is exact), which must round to -1 and +1.
  const std::array<Vec<Q16_16, 3>, 2> points{Vec<Q16_16, 3>{{Q16_16::from_raw(-1), Q16_16::from_raw(0), Q16_16::from_raw(0)}},
                                             Vec<Q16_16, 3>{{Q16_16::from_raw(1), Q16_16::from_raw(0), Q16_16::from_raw(0)}}};
  auto stepper = ForwardDifference<Q16_16, 3>::create(Curve::create(points).value(), 4).value();
  REQUIRE(stepper.wide_fraction_bits() >= 32);
  std::array<std::int32_t, 5> expected{-1, -1, 0, 1, 1};
  for (std::size_t k = 0; k <= 4; ++k) {
    CHECK(stepper.point()[0].raw() == expected[k]);
    if (k < 4) stepper.step();
  }
}
