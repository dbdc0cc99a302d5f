// SPDX-License-Identifier: MIT
// Fixed<Rep, F> against independent integer formulas: exhaustively for the 8-bit format Q3.4,
// widely for the 16-bit Q7.8, and at the range boundaries of the 32-bit formats.
// Rounding is to nearest with ties away from zero everywhere (docs/fixed_point.md).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/core/scalar.hpp>
#include <support/contract_violation.hpp>
#include <support/numeric.hpp>

using namespace curvestep;
using curvestep::testing::ContractViolation;

/// CHECK/REQUIRE that only reach Catch on failure: the loops below make millions of comparisons.
#define QUIET_CHECK(condition)       \
  do {                               \
    if (!(condition)) CHECK(condition); \
  } while (false)
#define QUIET_REQUIRE(condition)       \
  do {                                 \
    if (!(condition)) REQUIRE(condition); \
  } while (false)

namespace {

using Q3_4 = Fixed<std::int8_t, 4>;
using Q7_8 = Fixed<std::int16_t, 8>;

/// n / d rounded to nearest, ties away from zero (independent long division).
long long divide_rounded(long long n, long long d) {
  long long q = n / d;  // truncates toward zero
  const long long r = n % d;
  const long long twice = 2 * (r < 0 ? -r : r);
  const long long magnitude_d = d < 0 ? -d : d;
  if (twice >= magnitude_d) q += ((n < 0) != (d < 0)) ? -1 : 1;
  return q;
}

template <class F>
constexpr long long raw_max = std::numeric_limits<typename F::rep>::max();
template <class F>
constexpr long long raw_min = std::numeric_limits<typename F::rep>::min();

template <class F>
bool in_range(long long raw) {
  return raw >= raw_min<F> && raw <= raw_max<F>;
}

/// All raw values of an 8-bit format, or a deterministic sample of a 16-bit one (ends included).
template <class F>
std::vector<long long> raw_values(std::mt19937& engine, std::size_t sample, bool exhaustive = true) {
  std::vector<long long> values;
  if (exhaustive && sizeof(typename F::rep) == 1) {
    for (long long r = raw_min<F>; r <= raw_max<F>; ++r) values.push_back(r);
  } else {
    std::uniform_int_distribution<long long> pick(raw_min<F>, raw_max<F>);
    for (long long r : {raw_min<F>, raw_min<F> + 1, -1LL, 0LL, 1LL, raw_max<F> - 1, raw_max<F>}) values.push_back(r);
    while (values.size() < sample) values.push_back(pick(engine));
  }
  return values;
}

template <class F>
F make(long long raw) {
  return F::from_raw(static_cast<typename F::rep>(raw));
}

}  // namespace

TEST_CASE("fixed: from_double rejects the half unit just outside each end of the range", "[core][fixed]") {
  // lowest - 1/2 unit rounds (ties away from zero) to lowest - 1: out of range, never wrapped to max.
  const double q16_unit = 1.0 / 65536;
  CHECK(Q16_16::from_double(-32768.0 - q16_unit / 2).error() == Error::FixedOverflow);
  CHECK(Q16_16::from_double(-32768.0 - q16_unit * 0.49).value() == Q16_16::lowest());
  CHECK(Q16_16::from_double(32768.0 - q16_unit / 2).error() == Error::FixedOverflow);
  CHECK(Q16_16::from_double(32768.0 - q16_unit * 0.51).value() == Q16_16::max());
  const double q2_unit = std::ldexp(1.0, -30);
  CHECK(Q2_30::from_double(-2.0 - q2_unit / 2).error() == Error::FixedOverflow);
  CHECK(Q2_30::from_double(-2.0 - q2_unit * 0.49).value() == Q2_30::lowest());
  CHECK(Q2_30::from_double(2.0 - q2_unit / 2).error() == Error::FixedOverflow);
  CHECK(Q3_4::from_double(-8.0 - 1.0 / 32).error() == Error::FixedOverflow);
  CHECK(Q3_4::from_double(-8.0 - 0.49 / 16).value() == Q3_4::lowest());
  CHECK(Q7_8::from_double(-128.0 - 1.0 / 512).error() == Error::FixedOverflow);
}

TEMPLATE_TEST_CASE("fixed: from_double of quarter units across the range matches round half away from zero", "[core][fixed]", Q3_4, Q7_8) {
  using F = TestType;
  const double unit = std::ldexp(1.0, -F::fraction_bits);
  // Every quarter unit within 64 units of both ends and of zero, every 7th elsewhere (all of Q3.4).
  const long long low = 4 * raw_min<F> - 12;
  const long long high = 4 * raw_max<F> + 12;
  for (long long q = low; q <= high;) {
    const double x = static_cast<double>(q) * unit / 4;
    const double expected = std::round(x / unit);  // std::round: ties away from zero
    const auto r = F::from_double(x);
    INFO("x = " << x);
    if (in_range<F>(static_cast<long long>(expected))) {
      QUIET_REQUIRE(r.has_value());
      QUIET_CHECK(static_cast<long long>(r.value().raw()) == static_cast<long long>(expected));
      QUIET_CHECK(r.value().to_double() == expected * unit);
    } else {
      REQUIRE_FALSE(r.has_value());
      QUIET_CHECK(r.error() == Error::FixedOverflow);
    }
    const bool near_special = q - low < 256 || high - q < 256 || (q > -256 && q < 256);
    q += (near_special || sizeof(typename F::rep) == 1) ? 1 : 7;
  }
}

TEMPLATE_TEST_CASE("fixed: sums products and quotients match exact integer rounding", "[core][fixed]", Q3_4, Q7_8) {
  using F = TestType;
  std::mt19937 engine(curvestep::testing::test_seed());
  const auto values = raw_values<F>(engine, 300);
  const long long one = 1LL << F::fraction_bits;
  for (long long a : values) {
    for (long long b : values) {
      const F fa = make<F>(a);
      const F fb = make<F>(b);
      // Sum and difference: exact or FixedOverflow.
      const long long sum = a + b;
      const auto s = checked_add(fa, fb);
      QUIET_REQUIRE(s.has_value() == in_range<F>(sum));
      if (s) QUIET_CHECK(static_cast<long long>(s.value().raw()) == sum);
      const long long difference = a - b;
      const auto d = checked_sub(fa, fb);
      QUIET_REQUIRE(d.has_value() == in_range<F>(difference));
      if (d) QUIET_CHECK(static_cast<long long>(d.value().raw()) == difference);
      // Product: a b / 2^F rounded once.
      const long long product = divide_rounded(a * b, one);
      const auto p = checked_mul(fa, fb);
      INFO("a = " << a << " b = " << b);
      QUIET_REQUIRE(p.has_value() == in_range<F>(product));
      if (p) {
        QUIET_CHECK(static_cast<long long>(p.value().raw()) == product);
        QUIET_CHECK(static_cast<long long>((fa * fb).raw()) == product);
      }
      QUIET_CHECK(static_cast<long long>(saturating_mul(fa, fb).raw()) == std::clamp(product, raw_min<F>, raw_max<F>));
      // Quotient: a 2^F / b rounded once; b = 0 is DivisionByZero.
      const auto q = checked_div(fa, fb);
      if (b == 0) {
        REQUIRE_FALSE(q.has_value());
        QUIET_CHECK(q.error() == Error::DivisionByZero);
        continue;
      }
      const long long quotient = divide_rounded(a * one, b);
      QUIET_REQUIRE(q.has_value() == in_range<F>(quotient));
      if (q) QUIET_CHECK(static_cast<long long>(q.value().raw()) == quotient);
    }
  }
}

TEMPLATE_TEST_CASE("fixed: operators stop on overflow instead of wrapping", "[core][fixed]", Q3_4, Q7_8, Q16_16) {
  using F = TestType;
  const F top = F::max();
  const F bottom = F::lowest();
  CHECK_THROWS_AS(top + F::resolution(), ContractViolation);
  CHECK_THROWS_AS(bottom - F::resolution(), ContractViolation);
  CHECK_THROWS_AS(-bottom, ContractViolation);
  CHECK_THROWS_AS(top * from_int<F>(2), ContractViolation);
  CHECK_THROWS_AS(top / F{}, ContractViolation);
  // Integer factors and divisors that do not fit the wide type must not be truncated first.
  CHECK_THROWS_AS(top * 65537, ContractViolation);
  CHECK_THROWS_AS(from_int<F>(2) * 2'000'000'000, ContractViolation);
  CHECK(static_cast<long long>((top / 65537).raw()) == divide_rounded(raw_max<F>, 65537));
  CHECK(static_cast<long long>((top / -3).raw()) == divide_rounded(raw_max<F>, -3));
  CHECK(static_cast<long long>((F::resolution() * 3).raw()) == 3);
  // Integer construction: exact inside, a contract violation outside (also far outside).
  const long long largest = raw_max<F> >> F::fraction_bits;
  CHECK(static_cast<long long>(F{static_cast<int>(largest)}.raw()) == largest << F::fraction_bits);
  CHECK_THROWS_AS(F{static_cast<int>(largest + 1)}, ContractViolation);
  CHECK_THROWS_AS(F{100000}, ContractViolation);
  CHECK_THROWS_AS(F{-100000}, ContractViolation);
}

TEMPLATE_TEST_CASE("fixed: sqrt is correctly rounded for every raw value", "[core][fixed]", Q3_4, Q7_8) {
  using F = TestType;
  const long double one = std::ldexp(1.0L, F::fraction_bits);
  for (long long r = 0; r <= raw_max<F>; ++r) {
    // sqrt(r / 2^F) in units: sqrt(r 2^F), never exactly halfway for an integer r 2^F.
    const long double exact = std::sqrt(static_cast<long double>(r) * one);
    const auto expected = static_cast<long long>(std::floor(exact + 0.5L));
    INFO("raw = " << r);
    QUIET_CHECK(static_cast<long long>(curvestep::sqrt(make<F>(r)).raw()) == expected);
  }
  CHECK_THROWS_AS(curvestep::sqrt(make<F>(-1)), ContractViolation);
}

TEMPLATE_TEST_CASE("fixed: checked_lerp is one rounding of the exact affine combination", "[core][fixed]", Q3_4, Q7_8) {
  using F = TestType;
  std::mt19937 engine(curvestep::testing::test_seed() + 1);
  const auto values = raw_values<F>(engine, 32, false);
  const long long one = 1LL << F::fraction_bits;
  for (long long a : values) {
    for (long long b : values) {
      for (long long t : values) {
        // a + (b - a) t / 2^F, rounded once.
        const long long expected = a + divide_rounded((b - a) * t, one);
        const auto r = checked_lerp(make<F>(a), make<F>(b), make<F>(t));
        INFO("a = " << a << " b = " << b << " t = " << t);
        QUIET_REQUIRE(r.has_value() == in_range<F>(expected));
        if (r) QUIET_CHECK(static_cast<long long>(r.value().raw()) == expected);
      }
    }
  }
}

TEST_CASE("fixed: Q16.16 integer multiples and divisions against exact integers", "[core][fixed]") {
  std::mt19937 engine(curvestep::testing::test_seed() + 2);
  std::uniform_int_distribution<long long> raw(raw_min<Q16_16>, raw_max<Q16_16>);
  std::uniform_int_distribution<int> divisor(-100000, 100000);
  std::uniform_int_distribution<int> factor(-40, 40);
  for (int k = 0; k < curvestep::testing::test_count(5000); ++k) {
    const long long a = raw(engine);
    const int d = divisor(engine);
    const int m = factor(engine);
    const Q16_16 fa = make<Q16_16>(a);
    INFO("a = " << a << " d = " << d << " m = " << m);
    if (d != 0) CHECK(static_cast<long long>((fa / d).raw()) == divide_rounded(a, d));
    if (in_range<Q16_16>(a * m)) {
      CHECK(static_cast<long long>((fa * m).raw()) == a * m);
    } else {
      CHECK_THROWS_AS(fa * m, ContractViolation);
    }
  }
}
