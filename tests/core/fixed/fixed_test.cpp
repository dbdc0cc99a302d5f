// SPDX-License-Identifier: MIT
// Fixed<Rep, F>: conversions, documented rounding, range checks (nothing wraps).
#include <cmath>
#include <cstdint>
#include <limits>

#include <catch2/catch.hpp>

#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/core/scalar.hpp>
#include <support/contract_violation.hpp>
#include <support/numeric.hpp>

using curvestep::Error;
using curvestep::Q16_16;
using namespace curvestep::literals;

static_assert(Q16_16::constant(1.5).raw() == 0x18000, "1.5 in Q16.16 is 0x18000");
static_assert((1.25_q16 * 2.0_q16).raw() == Q16_16::constant(2.5).raw(), "exact products are exact");
static_assert((-0.5_q16).raw() == -0x8000, "negation");
static_assert(curvestep::sqrt(4.0_q16) == 2.0_q16, "sqrt of a perfect square is exact");

TEST_CASE("fixed: Q16.16 constants and conversions are exact for dyadic values", "[core][fixed]") {
  CHECK(Q16_16::from_double(0.90625).value().raw() == 59392);  // 29/32 * 65536
  CHECK(Q16_16::from_double(-1.265625).value().to_double() == -1.265625);
  CHECK(Q16_16::from_integer(32767).value().to_double() == 32767.0);
  CHECK(Q16_16::max().to_double() == 32768.0 - 1.0 / 65536.0);
  CHECK(Q16_16::lowest().to_double() == -32768.0);
  CHECK(Q16_16::resolution().to_double() == 1.0 / 65536.0);
}

TEST_CASE("fixed: from_double rounds to nearest with ties away from zero", "[core][fixed]") {
  const double ulp = 1.0 / 65536.0;
  CHECK(Q16_16::from_double(0.5 * ulp).value().raw() == 1);
  CHECK(Q16_16::from_double(-0.5 * ulp).value().raw() == -1);
  CHECK(Q16_16::from_double(0.49 * ulp).value().raw() == 0);
  CHECK(Q16_16::from_double(1.5 * ulp).value().raw() == 2);
  CHECK(Q16_16::from_double(-1.5 * ulp).value().raw() == -2);
}

TEST_CASE("fixed: out-of-range and non-finite input is an error, never a wrapped value", "[core][fixed]") {
  CHECK(Q16_16::from_double(32768.0).error() == Error::FixedOverflow);
  CHECK(Q16_16::from_double(-32768.00001).error() == Error::FixedOverflow);
  CHECK(Q16_16::from_double(1e300).error() == Error::FixedOverflow);
  CHECK(Q16_16::from_double(std::nan("")).error() == Error::NotFinite);
  CHECK(Q16_16::from_double(std::numeric_limits<double>::infinity()).error() == Error::NotFinite);
  CHECK(Q16_16::from_integer(32768).error() == Error::FixedOverflow);
  CHECK(Q16_16::from_integer(-32769).error() == Error::FixedOverflow);
  CHECK(Q16_16::from_integer(-32768).has_value());
  // Just inside the top: 32767.99999 rounds to max, 32767.999995 would round past it.
  CHECK(Q16_16::from_double(32767.0 + 65535.4 / 65536.0).value() == Q16_16::max());
  CHECK(Q16_16::from_double(32767.0 + 65535.6 / 65536.0).error() == Error::FixedOverflow);
}

TEST_CASE("fixed: checked arithmetic reports overflow and operators stop on it", "[core][fixed]") {
  const Q16_16 big = 30000.0_q16;
  CHECK(checked_add(big, big).error() == Error::FixedOverflow);
  CHECK(checked_sub(-big, big).error() == Error::FixedOverflow);
  CHECK(checked_mul(big, 2.0_q16).error() == Error::FixedOverflow);
  CHECK(checked_div(big, 0.5_q16).error() == Error::FixedOverflow);
  CHECK(checked_div(big, Q16_16{}).error() == Error::DivisionByZero);
  CHECK(checked_add(1.0_q16, 2.0_q16).value() == 3.0_q16);
  CHECK_THROWS_AS(big + big, curvestep::testing::ContractViolation);
  CHECK_THROWS_AS(big * big, curvestep::testing::ContractViolation);
  CHECK_THROWS_AS(-Q16_16::lowest(), curvestep::testing::ContractViolation);
  CHECK(saturating_add(big, big) == Q16_16::max());
  CHECK(saturating_mul(-big, big) == Q16_16::lowest());
}

TEST_CASE("fixed: multiply and divide round to nearest, symmetric about zero", "[core][fixed]") {
  const Q16_16 ulp = Q16_16::resolution();
  const Q16_16 half = 0.5_q16;
  CHECK((ulp * half).raw() == 1);      // 0.5 ulp -> 1 (away from zero)
  CHECK(((-ulp) * half).raw() == -1);  // -0.5 ulp -> -1
  CHECK((Q16_16::from_raw(3) * 0.25_q16).raw() == 1);  // 0.75 -> 1
  CHECK((Q16_16::from_raw(-3) * 0.25_q16).raw() == -1);
  CHECK((1.0_q16 / 3.0_q16).raw() == 21845);  // 0.333333 * 65536 = 21845.33
  CHECK((2.0_q16 / 3.0_q16).raw() == 43691);  // 43690.67
  CHECK(((-2.0_q16) / 3.0_q16).raw() == -43691);
  CHECK((1.0_q16 / 3) == 1.0_q16 / 3.0_q16);
}

TEST_CASE("fixed: random products and quotients are within half a unit of the exact value", "[core][fixed]") {
  std::mt19937 rng(curvestep::testing::test_seed());
  std::uniform_int_distribution<std::int32_t> raw(-(1 << 23), 1 << 23);
  for (int i = 0; i < curvestep::testing::test_count(20000); ++i) {
    const Q16_16 a = Q16_16::from_raw(raw(rng));
    const Q16_16 b = Q16_16::from_raw(raw(rng));
    const long double exact_product = static_cast<long double>(a.to_double()) * b.to_double();
    if (std::fabs(static_cast<double>(exact_product)) < 30000) {
      CHECK(std::fabs(static_cast<double>(exact_product) - (a * b).to_double()) <= 0.5 / 65536.0);
    }
    if (b.raw() != 0) {
      const long double exact_quotient = static_cast<long double>(a.to_double()) / b.to_double();
      if (std::fabs(static_cast<double>(exact_quotient)) < 30000) {
        CHECK(std::fabs(static_cast<double>(exact_quotient) - (a / b).to_double()) <= 0.5 / 65536.0 + 1e-12);
      }
    }
  }
}

TEST_CASE("fixed: sqrt is correctly rounded", "[core][fixed]") {
  std::mt19937 rng(curvestep::testing::test_seed());
  std::uniform_int_distribution<std::int32_t> raw(0, std::numeric_limits<std::int32_t>::max());
  for (int i = 0; i < curvestep::testing::test_count(20000); ++i) {
    const Q16_16 a = Q16_16::from_raw(raw(rng));
    const double exact = std::sqrt(a.to_double());
    CHECK(std::fabs(curvestep::sqrt(a).to_double() - exact) <= 0.5 / 65536.0 + 1e-12);
  }
  CHECK(curvestep::sqrt(Q16_16{}) == Q16_16{});
  CHECK_THROWS_AS(curvestep::sqrt(-1.0_q16), curvestep::testing::ContractViolation);
}

TEST_CASE("fixed: lerp is exact at the ends and checked when extrapolating", "[core][fixed]") {
  const Q16_16 a = Q16_16::lowest();
  const Q16_16 b = Q16_16::max();
  CHECK(curvestep::lerp(a, b, Q16_16{}) == a);
  CHECK(curvestep::lerp(a, b, 1.0_q16) == b);
  CHECK(curvestep::lerp(a, b, 0.5_q16).raw() == 0);  // -2^31 + (2^32-1)/2 rounded away: 0
  CHECK(curvestep::checked_lerp(a, b, 2.0_q16).error() == Error::FixedOverflow);
  CHECK(curvestep::checked_lerp(1.0_q16, 2.0_q16, 3.0_q16).value() == 4.0_q16);
  CHECK(curvestep::checked_lerp(-30000.0_q16, 30000.0_q16, 30000.0_q16).error() == Error::FixedOverflow);
}
