// SPDX-License-Identifier: MIT
// Tests of StepScale and position_in_steps: the rounding rule, exactness for Q16.16, range errors.
#include <cmath>
#include <cstdint>
#include <random>

#include <catch2/catch.hpp>

#include <curvestep/core/motion/step_position.hpp>

#include "step_test_support.hpp"
#include "support/numeric.hpp"

using namespace curvestep;
using curvestep::testing::expected_q16_steps;

namespace {
StepScale scale_of(double steps_per_mm) {
  const auto scale = StepScale::create(steps_per_mm);
  REQUIRE(scale.has_value());
  return scale.value();
}
}  // namespace

// The conversion is constexpr: these run in the compiler.
static_assert(position_in_steps(Q16_16::from_raw(2048), StepScale::create(80).value()).value() == 3);
static_assert(position_in_steps(Q16_16::from_raw(-2047), StepScale::create(80).value()).value() == -2);
static_assert(position_in_steps(0.03125, StepScale::create(80).value()).value() == 3);
static_assert(steps_of_fine_position(-(std::int64_t{5} << 15)) == -3);  // -2.5 steps

TEST_CASE("stepgen: a step scale stores steps per millimetre as a 32.32 integer", "[core][stepgen]") {
  CHECK(scale_of(80).raw() == std::uint64_t{80} << 32);
  CHECK(scale_of(0.5).raw() == std::uint64_t{1} << 31);
  CHECK(scale_of(78.125).steps_per_mm() == 78.125);
  CHECK(scale_of(0).is_zero());
  // 2000/25.4 is not dyadic: the quantised value is within 2^-33 of it.
  CHECK(std::fabs(scale_of(2000.0 / 25.4).steps_per_mm() - 2000.0 / 25.4) <= std::ldexp(1.0, -33));
}

TEST_CASE("stepgen: a step scale rejects negative, non-finite and too large values", "[core][stepgen]") {
  CHECK(StepScale::create(-1).error() == Error::InvalidLimit);
  CHECK(StepScale::create(std::nan("")).error() == Error::InvalidLimit);
  CHECK(StepScale::create(INFINITY).error() == Error::InvalidLimit);
  CHECK(StepScale::create(2097152.0).error() == Error::InvalidLimit);
  CHECK(StepScale::create(1048576.0).has_value());
}

TEST_CASE("stepgen: half steps round away from zero for Q16.16 and double", "[core][stepgen]") {
  const StepScale scale = scale_of(80);
  // raw 2048 is 2048/65536 mm = 0.03125 mm = 2.5 steps exactly.
  CHECK(position_in_steps(Q16_16::from_raw(2048), scale).value() == 3);
  CHECK(position_in_steps(Q16_16::from_raw(-2048), scale).value() == -3);
  CHECK(position_in_steps(Q16_16::from_raw(2047), scale).value() == 2);
  CHECK(position_in_steps(Q16_16::from_raw(-2047), scale).value() == -2);
  CHECK(position_in_steps(0.03125, scale).value() == 3);
  CHECK(position_in_steps(-0.03125, scale).value() == -3);
  CHECK(position_in_steps(0.03125f, scale).value() == 3);
  CHECK(position_in_steps(std::nextafter(0.03125, 0.0), scale).value() == 2);
}

TEST_CASE("stepgen: Q16.16 positions at 80 steps per mm give exact step counts", "[core][stepgen]") {
  const StepScale scale = scale_of(80);
  std::mt19937 random(curvestep::testing::test_seed());
  std::uniform_int_distribution<std::int32_t> raw_values(INT32_MIN, INT32_MAX);
  for (int i = 0; i < curvestep::testing::test_count(20000); ++i) {
    const std::int32_t raw = raw_values(random);
    INFO("raw " << raw);
    REQUIRE(position_in_steps(Q16_16::from_raw(raw), scale).value() == expected_q16_steps(raw, 80, 1));
  }
  // The extremes of the Q16.16 range.
  CHECK(position_in_steps(Q16_16::from_raw(INT32_MAX), scale).value() == expected_q16_steps(INT32_MAX, 80, 1));
  CHECK(position_in_steps(Q16_16::from_raw(INT32_MIN), scale).value() == expected_q16_steps(INT32_MIN, 80, 1));
}

TEST_CASE("stepgen: Q16.16 positions are exact for any dyadic steps per mm", "[core][stepgen]") {
  const StepScale scale = scale_of(78.125);  // 625/8
  std::mt19937 random(curvestep::testing::test_seed() + 1);
  std::uniform_int_distribution<std::int32_t> raw_values(-2000000000, 2000000000);
  for (int i = 0; i < curvestep::testing::test_count(20000); ++i) {
    const std::int32_t raw = raw_values(random);
    INFO("raw " << raw);
    REQUIRE(position_in_steps(Q16_16::from_raw(raw), scale).value() == expected_q16_steps(raw, 625, 8));
  }
}

TEST_CASE("stepgen: a non-dyadic steps per mm rounds like the exact product away from half steps",
          "[core][stepgen]") {
  const long double steps_per_mm = 2000.0L / 25.4L;
  const StepScale scale = scale_of(static_cast<double>(steps_per_mm));
  std::mt19937 random(curvestep::testing::test_seed() + 2);
  std::uniform_int_distribution<std::int32_t> raw_values(-65536000, 65536000);  // +-1000 mm
  int compared = 0;
  for (int i = 0; i < curvestep::testing::test_count(20000); ++i) {
    const std::int32_t raw = raw_values(random);
    const long double exact = static_cast<long double>(raw) / 65536.0L * steps_per_mm;
    const long double fraction = std::fabs(exact - std::trunc(exact));
    if (std::fabs(fraction - 0.5L) < 1e-6L) continue;  // within the documented quantisation error
    ++compared;
    INFO("raw " << raw);
    REQUIRE(position_in_steps(Q16_16::from_raw(raw), scale).value() == std::llroundl(exact));
    const double millimetres = static_cast<double>(raw) / 65536.0;
    REQUIRE(position_in_steps(millimetres, scale).value() == std::llroundl(exact));
  }
  CHECK(compared > curvestep::testing::test_count(20000) * 9 / 10);
}

TEST_CASE("stepgen: a zero steps per mm axis is always at step zero", "[core][stepgen]") {
  const StepScale zero;
  CHECK(position_in_steps(Q16_16::from_raw(INT32_MAX), zero).value() == 0);
  CHECK(position_in_steps(-1.0e12, zero).value() == 0);
  CHECK(position_in_steps(3.5f, zero).value() == 0);
}

TEST_CASE("stepgen: step counts beyond 32 bits are StepCountOverflow", "[core][stepgen]") {
  SECTION("Q16.16 at 100000 steps per mm") {
    const StepScale scale = scale_of(100000);
    CHECK(position_in_steps(Q16_16::from_double(30000.0).value(), scale).error() == Error::StepCountOverflow);
    CHECK(position_in_steps(Q16_16::from_double(-30000.0).value(), scale).error() == Error::StepCountOverflow);
    CHECK(position_in_steps(Q16_16::from_double(20000.0).value(), scale).value() == 2000000000);
  }
  SECTION("double at one step per mm: the last count that fits is 2^31 - 1") {
    const StepScale scale = scale_of(1);
    CHECK(position_in_steps(2147483647.0, scale).value() == 2147483647);
    CHECK(position_in_steps(2147483647.4, scale).value() == 2147483647);
    CHECK(position_in_steps(2147483647.5, scale).error() == Error::StepCountOverflow);
    CHECK(position_in_steps(-2147483647.4, scale).value() == -2147483647);
    CHECK(position_in_steps(-2147483647.5, scale).error() == Error::StepCountOverflow);
    CHECK(position_in_steps(1.0e300, scale).error() == Error::StepCountOverflow);
  }
  SECTION("NaN and infinity are NotFinite") {
    const StepScale scale = scale_of(80);
    CHECK(position_in_steps(std::nan(""), scale).error() == Error::NotFinite);
    CHECK(position_in_steps(-INFINITY, scale).error() == Error::NotFinite);
  }
}
