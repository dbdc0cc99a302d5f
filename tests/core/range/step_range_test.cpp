// SPDX-License-Identifier: MIT
// Range safety of step counts (step_position.hpp): counts are int32 on every target, so a position
// whose count passes 2^31 - 1 in magnitude is StepCountOverflow, never a wrapped count.
// The expected count is computed independently: round(raw * scale / 2^48) half away from zero in
// __int128 for Q16.16, and by exact integer reasoning at chosen points for double.
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include <catch2/catch.hpp>

#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/core/motion/step_position.hpp>

#include "support/numeric.hpp"

using namespace curvestep;
using curvestep::testing::test_count;
using curvestep::testing::test_seed;

namespace {
__extension__ typedef unsigned __int128 Wide;  // exact products of up to 31 x 53 bits
}  // namespace

TEST_CASE("range: Q16.16 step counts at the int32 edge", "[core][range]") {
  // 65536 steps/mm: the count of a Q16.16 position is exactly its raw value.
  const auto scale = StepScale::create(65536.0).value();
  CHECK(position_in_steps(Q16_16::from_raw(INT32_MAX), scale).value() == INT32_MAX);
  CHECK(position_in_steps(Q16_16::from_raw(-INT32_MAX), scale).value() == -INT32_MAX);
  // -2^31 steps does not fit the symmetric range |count| <= 2^31 - 1.
  CHECK(position_in_steps(Q16_16::from_raw(INT32_MIN), scale).error() == Error::StepCountOverflow);
  // The largest scale at the largest position: about 3.4e10 steps.
  const auto largest = StepScale::create(max_steps_per_mm).value();
  CHECK(position_in_steps(Q16_16::max(), largest).error() == Error::StepCountOverflow);
  CHECK(position_in_steps(Q16_16::lowest(), largest).error() == Error::StepCountOverflow);
  CHECK(position_in_steps(Q16_16::from_raw(1), largest).value() == 16);
}

TEST_CASE("range: double step counts at the int32 edge, NaN and infinity", "[core][range]") {
  const auto one = StepScale::create(1.0).value();
  CHECK(position_in_steps(2147483647.0, one).value() == INT32_MAX);
  CHECK(position_in_steps(2147483647.25, one).value() == INT32_MAX);
  // 2^31 - 1/2 rounds half away to 2^31: overflow. So does everything beyond, up to the largest double.
  CHECK(position_in_steps(2147483647.5, one).error() == Error::StepCountOverflow);
  CHECK(position_in_steps(-2147483647.5, one).error() == Error::StepCountOverflow);
  CHECK(position_in_steps(1e300, one).error() == Error::StepCountOverflow);
  CHECK(position_in_steps(-std::numeric_limits<double>::max(), one).error() == Error::StepCountOverflow);
  CHECK(position_in_steps(std::numeric_limits<double>::quiet_NaN(), one).error() == Error::NotFinite);
  CHECK(position_in_steps(std::numeric_limits<double>::infinity(), one).error() == Error::NotFinite);
  CHECK(position_in_steps(-std::numeric_limits<float>::infinity(), one).error() == Error::NotFinite);
  CHECK(position_in_steps(3.0e38f, one).error() == Error::StepCountOverflow);
}

TEST_CASE("range: StepScale refuses scales it cannot hold exactly", "[core][range]") {
  CHECK(StepScale::create(max_steps_per_mm).has_value());
  CHECK(StepScale::create(std::nextafter(max_steps_per_mm, 2e6)).error() == Error::InvalidLimit);
  CHECK(StepScale::create(-1e-300).error() == Error::InvalidLimit);
  CHECK(StepScale::create(std::numeric_limits<double>::quiet_NaN()).error() == Error::InvalidLimit);
  CHECK(StepScale::create(std::numeric_limits<double>::infinity()).error() == Error::InvalidLimit);
}

TEST_CASE("range: Q16.16 step counts over the whole position and scale range, property", "[core][range]") {
  std::mt19937_64 rng(test_seed() + 2);
  std::uniform_int_distribution<std::int64_t> raw_in(INT32_MIN, INT32_MAX);
  std::uniform_real_distribution<double> log_scale(-4.0, 20.0);
  const int n = test_count(50000);
  int overflows = 0;
  for (int i = 0; i < n; ++i) {
    const std::int32_t raw = static_cast<std::int32_t>(raw_in(rng) >> (rng() % 8));
    const auto scale = StepScale::create(std::pow(2.0, log_scale(rng))).value();
    // Expected: round(|raw| * scale.raw() / 2^48) half away from zero, with the sign of raw.
    const bool negative = raw < 0;
    const Wide magnitude = static_cast<Wide>(negative ? -static_cast<std::int64_t>(raw) : raw);
    const Wide count = (magnitude * scale.raw() + (static_cast<Wide>(1) << 47)) >> 48;
    const auto got = position_in_steps(Q16_16::from_raw(raw), scale);
    if (count > static_cast<Wide>(INT32_MAX)) {
      ++overflows;
      REQUIRE(got.error() == Error::StepCountOverflow);
    } else {
      REQUIRE(got.has_value());
      const auto expected = static_cast<std::int64_t>(count);
      REQUIRE(got.value() == (negative ? -expected : expected));
    }
  }
  CHECK(overflows > n / 50);  // the edge is really exercised
}
