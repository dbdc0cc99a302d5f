// SPDX-License-Identifier: MIT
// Range safety of the fixed-point entry points: Fixed::from_double, from_double<S>, vec_from_doubles
// and the checked arithmetic, driven across the whole Q16.16 range and just beyond it.
// Expected values come from exact integer arithmetic (int64) on the raw values, not from the code.
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include <catch2/catch.hpp>

#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/core/geometry/vec.hpp>
#include <curvestep/core/scalar.hpp>

#include "support/numeric.hpp"

using namespace curvestep;
using curvestep::testing::test_count;
using curvestep::testing::test_seed;

namespace {

constexpr double nan_value = std::numeric_limits<double>::quiet_NaN();
constexpr double inf_value = std::numeric_limits<double>::infinity();

/// round(n / d) half away from zero, for d > 0, exactly.
std::int64_t round_half_away(std::int64_t n, std::int64_t d) {
  const bool negative = n < 0;
  const std::int64_t m = negative ? -n : n;
  const std::int64_t q = m / d + ((m % d) * 2 >= d ? 1 : 0);  // no overflow for |n| <= 2^62
  return negative ? -q : q;
}

bool fits_int32(std::int64_t v) { return v >= INT32_MIN && v <= INT32_MAX; }

}  // namespace

TEST_CASE("range: Q16.16 from_double accepts exactly the values that round into the range", "[core][range]") {
  // Largest and smallest values, and the half-step just outside them.
  CHECK(Q16_16::from_double(32767.0 + 65535.0 / 65536).value().raw() == INT32_MAX);
  CHECK(Q16_16::from_double(-32768.0).value().raw() == INT32_MIN);
  // 32767.99999 is 2^31 - 1 + 0.34 raw: rounds down to the largest value.
  CHECK(Q16_16::from_double(32767.99999).value().raw() == INT32_MAX);
  // (2^31 - 1/2) / 2^16 rounds half away to 2^31: out of range.
  CHECK(Q16_16::from_double((2147483647.5) / 65536).error() == Error::FixedOverflow);
  CHECK(Q16_16::from_double(32768.0).error() == Error::FixedOverflow);
  // -2^31 - 1/2 raw rounds half away to -2^31 - 1: out of range; a hair less negative is in.
  CHECK(Q16_16::from_double(-2147483648.5 / 65536).error() == Error::FixedOverflow);
  CHECK(Q16_16::from_double(-2147483648.25 / 65536).value().raw() == INT32_MIN);
  CHECK(Q16_16::from_double(1e300).error() == Error::FixedOverflow);
  CHECK(Q16_16::from_double(-1e300).error() == Error::FixedOverflow);
  CHECK(Q16_16::from_double(std::numeric_limits<double>::max()).error() == Error::FixedOverflow);
  CHECK(Q16_16::from_double(std::numeric_limits<double>::denorm_min()).value().raw() == 0);
}

TEST_CASE("range: NaN and infinity are rejected by every from_double", "[core][range]") {
  for (const double bad : {nan_value, -nan_value, inf_value, -inf_value}) {
    CHECK(Q16_16::from_double(bad).error() == Error::NotFinite);
    CHECK(from_double<Q16_16>(bad).error() == Error::NotFinite);
    CHECK(from_double<double>(bad).error() == Error::NotFinite);
    CHECK(from_double<float>(bad).error() == Error::NotFinite);
  }
  // A finite double beyond float's range would become infinity: refused, not wrapped to inf.
  CHECK(from_double<float>(1e39).error() == Error::NotFinite);
  CHECK(from_double<float>(-1e39).error() == Error::NotFinite);
  CHECK(from_double<float>(3.0e38).has_value());
}

TEST_CASE("range: vec_from_doubles names the first coordinate that does not fit", "[core][range]") {
  const auto nan_at_1 = vec_from_doubles<Q16_16, 3>({1.0, nan_value, 1e9});
  REQUIRE_FALSE(nan_at_1);
  CHECK(nan_at_1.error() == Error::NotFinite);
  CHECK(nan_at_1.where() == 1);
  const auto big_at_2 = vec_from_doubles<Q16_16, 3>({1.0, -2.0, 40000.0});
  REQUIRE_FALSE(big_at_2);
  CHECK(big_at_2.error() == Error::FixedOverflow);
  CHECK(big_at_2.where() == 2);
  const auto inf_at_0 = vec_from_doubles<double, 2>({-inf_value, 0.0});
  REQUIRE_FALSE(inf_at_0);
  CHECK(inf_at_0.error() == Error::NotFinite);
  CHECK(inf_at_0.where() == 0);
  CHECK(vec_from_doubles<float, 2>({0.5, 1e39}).error() == Error::NotFinite);
}

TEST_CASE("range: Q16.16 from_double over the whole range and beyond, property", "[core][range]") {
  std::mt19937_64 rng(test_seed());
  std::uniform_int_distribution<std::int64_t> raw_in(INT32_MIN, INT32_MAX);
  std::uniform_real_distribution<double> fraction(-0.4999, 0.4999);
  std::uniform_real_distribution<double> exponent(15.0, 300.0);
  const int n = test_count(20000);
  for (int i = 0; i < n; ++i) {
    // In range: raw / 2^16 plus less than half a step converts to that raw value.
    const std::int64_t raw = raw_in(rng);
    const double value = (static_cast<double>(raw) + fraction(rng)) / 65536;
    const auto converted = Q16_16::from_double(value);
    REQUIRE(converted.has_value());
    REQUIRE(converted.value().raw() == raw);
    // Beyond: any magnitude from 2^15 up to 1e300 is refused (the sign chosen at random, and
    // -32768 itself excluded because it is representable).
    const double magnitude = std::pow(2.0, exponent(rng));
    const double outside = (rng() & 1) ? magnitude : -magnitude * 1.0000001;
    REQUIRE(Q16_16::from_double(outside).error() == Error::FixedOverflow);
  }
}

TEST_CASE("range: Q16.16 checked arithmetic is exact or FixedOverflow across the range, property", "[core][range]") {
  std::mt19937_64 rng(test_seed() + 1);
  std::uniform_int_distribution<std::int64_t> raw_in(INT32_MIN, INT32_MAX);
  // Raw values of every size: a random one shifted right by 0..31 bits.
  auto any_raw = [&] {
    const auto r = raw_in(rng);
    return static_cast<std::int32_t>(r >> (rng() % 32));
  };
  const int n = test_count(50000);
  for (int i = 0; i < n; ++i) {
    const std::int32_t ra = any_raw();
    const std::int32_t rb = any_raw();
    const auto a = Q16_16::from_raw(ra);
    const auto b = Q16_16::from_raw(rb);
    const std::int64_t sum = static_cast<std::int64_t>(ra) + rb;
    const auto s = checked_add(a, b);
    if (fits_int32(sum)) {
      REQUIRE(s.has_value());
      REQUIRE(s.value().raw() == sum);
    } else {
      REQUIRE(s.error() == Error::FixedOverflow);
    }
    const std::int64_t difference = static_cast<std::int64_t>(ra) - rb;
    const auto d = checked_sub(a, b);
    if (fits_int32(difference)) {
      REQUIRE(d.value().raw() == difference);
    } else {
      REQUIRE(d.error() == Error::FixedOverflow);
    }
    // Product: ra * rb / 2^16, rounded half away from zero (docs/fixed_point.md).
    const std::int64_t product = round_half_away(static_cast<std::int64_t>(ra) * rb, 65536);
    const auto p = checked_mul(a, b);
    if (fits_int32(product)) {
      REQUIRE(p.has_value());
      REQUIRE(p.value().raw() == product);
    } else {
      REQUIRE(p.error() == Error::FixedOverflow);
    }
    if (rb != 0) {
      // Quotient: ra * 2^16 / rb, rounded half away from zero.
      const std::int64_t numerator = static_cast<std::int64_t>(ra) * 65536;
      const std::int64_t quotient = rb > 0 ? round_half_away(numerator, rb) : round_half_away(-numerator, -static_cast<std::int64_t>(rb));
      const auto q = checked_div(a, b);
      if (fits_int32(quotient)) {
        REQUIRE(q.has_value());
        REQUIRE(q.value().raw() == quotient);
      } else {
        REQUIRE(q.error() == Error::FixedOverflow);
      }
    }
  }
}
