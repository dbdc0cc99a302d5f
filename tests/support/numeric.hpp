// SPDX-License-Identifier: MIT
// Test helpers: scalar construction from exact rationals, per-type tolerances, readable Fixed.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/core/geometry/vec.hpp>
#include <curvestep/core/scalar.hpp>

namespace curvestep::testing {

/// A scalar from a double that must be representable (test data): fails the test otherwise.
template <Scalar S>
S scalar(double value) {
  const auto r = from_double<S>(value);
  REQUIRE(r.has_value());
  return r.value();
}

/// A 2D or 3D point from doubles.
template <Scalar S, class... D>
Vec<S, sizeof...(D)> point(D... values) {
  return Vec<S, sizeof...(D)>{{scalar<S>(static_cast<double>(values))...}};
}

/// Tolerance for a result of magnitude ~`scale` computed with `operations` roundings.
template <Scalar S>
double tolerance(double scale = 1.0, int operations = 8) {
  if constexpr (FixedPoint<S>) {
    return operations * to_double(resolution<S>());
  } else {
    return operations * static_cast<double>(std::numeric_limits<S>::epsilon()) * (scale < 1 ? 1 : scale);
  }
}

/// Largest coordinate difference between a point and expected doubles.
template <Scalar S, std::size_t Dim>
double max_error(const Vec<S, Dim>& actual, const std::array<double, Dim>& expected) {
  double m = 0;
  for (std::size_t i = 0; i < Dim; ++i) m = std::fmax(m, std::fabs(to_double(actual[i]) - expected[i]));
  return m;
}

/// Seed for randomized property tests: CURVESTEP_TEST_SEED or a fixed default.
inline std::uint32_t test_seed() {
  if (const char* s = std::getenv("CURVESTEP_TEST_SEED")) return static_cast<std::uint32_t>(std::stoul(s));
  return 20261121u;
}
/// Number of random cases: CURVESTEP_TEST_COUNT or `fallback`.
inline int test_count(int fallback) {
  if (const char* s = std::getenv("CURVESTEP_TEST_COUNT")) return std::stoi(s);
  return fallback;
}

}  // namespace curvestep::testing

namespace Catch {
/// Prints Fixed as its value and raw hex, e.g. 1.5 (raw 0x00018000).
template <std::signed_integral Rep, int F>
struct StringMaker<curvestep::Fixed<Rep, F>> {
  static std::string convert(const curvestep::Fixed<Rep, F>& v) {
    std::ostringstream s;
    s.precision(10);
    s << v.to_double() << " (raw 0x" << std::hex << static_cast<std::uint32_t>(v.raw()) << ")";
    return s.str();
  }
};
template <curvestep::Scalar S, std::size_t Dim>
struct StringMaker<curvestep::Vec<S, Dim>> {
  static std::string convert(const curvestep::Vec<S, Dim>& v) {
    std::ostringstream s;
    s.precision(12);
    s << "(";
    for (std::size_t i = 0; i < Dim; ++i) s << (i ? ", " : "") << curvestep::to_double(v[i]);
    s << ")";
    return s.str();
  }
};
}  // namespace Catch
