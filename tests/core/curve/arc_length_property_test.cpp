// SPDX-License-Identifier: MIT
// Arc length of machine-sized curves (coordinates in [-100,100] mm) in double, float and Q16.16
// against a long double composite Simpson rule on the Bernstein-form speed.
#include <cmath>
#include <vector>

#include "curve_test_support.hpp"

using namespace curvestep;
using namespace curvestep::testing;

namespace {

template <std::size_t Dim>
Real reference_speed(const std::vector<RealPoint<Dim>>& b, Real t) {
  const std::size_t n = b.size() - 1;
  std::vector<RealPoint<Dim>> hodograph;
  for (std::size_t i = 0; i < n; ++i) {
    RealPoint<Dim> d{};
    for (std::size_t a = 0; a < Dim; ++a) d[a] = static_cast<Real>(n) * (b[i + 1][a] - b[i][a]);
    hodograph.push_back(d);
  }
  const auto v = bernstein_sum(hodograph, t);
  Real s = 0;
  for (Real c : v) s += c * c;
  return std::sqrt(s);
}

/// Composite Simpson with 4096 panels: the speed of these curves has no cusp (checked below), so
/// the error is far below the tolerances used.
template <std::size_t Dim>
Real reference_length(const std::vector<RealPoint<Dim>>& b, Real t0, Real t1) {
  constexpr int panels = 4096;
  const Real h = (t1 - t0) / panels;
  Real sum = reference_speed(b, t0) + reference_speed(b, t1);
  for (int k = 1; k < panels; ++k) sum += (k % 2 == 1 ? 4 : 2) * reference_speed(b, t0 + static_cast<Real>(k) * h);
  return sum * h / 3;
}

}  // namespace

TEMPLATE_TEST_CASE("arc length: machine-sized curves match a long double quadrature", "[core][bezier][property]", double, float,
                   Q16_16) {
  using S = TestType;
  Random random(51);
  const int count = test_count(40);
  int checked = 0;
  for (int c = 0; c < count; ++c) {
    const auto points = random.polygon<S, 2>(random.integer(2, 4), 100);
    const auto curve = must(Bezier<S, 2, 7>::create(std::span<const Vec<S, 2>>(points)));
    const auto b = to_real<S, 2>(points);
    // Skip curves with a (near) cusp: the quadrature reference would need more care there.
    Real slowest = 1e30L;
    for (int k = 0; k <= 64; ++k) slowest = std::min(slowest, reference_speed(b, static_cast<Real>(k) / 64));
    if (slowest < 1) continue;
    ++checked;
    const Real expected = reference_length(b, 0, 1);
    // Requested tolerance, plus the format's error on a sum of ~100 speed samples of size |r'|:
    // Fixed: each |r'| carries a few units; float: relative rounding of the length.
    const double requested = FixedPoint<S> ? 0.01 : 1e-6 * static_cast<double>(expected);
    const double format = FixedPoint<S> ? 64 * unit<S>() * static_cast<double>(expected) / 10 + 256 * unit<S>()
                                        : 64 * unit<S>() * static_cast<double>(expected);
    INFO("case " << c << " degree " << curve.degree() << " length " << static_cast<double>(expected));
    const auto length = arc_length(curve, S{}, from_int<S>(1), from_double<S>(requested).value());
    if (!length) FAIL_CHECK("arc_length failed: " << error_name(length.error()));
    if (length) CHECK(std::fabs(to_double(length.value()) - static_cast<double>(expected)) <= requested + format);
  }
  CHECK(checked > count / 3);
}
