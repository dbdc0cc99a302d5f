// SPDX-License-Identifier: MIT
// Arc length of machine-sized curves (coordinates in [-100,100] mm) in double, float and Q16.16
// against a long double composite Simpson rule on the Bernstein-form speed.
#include <cmath>
#include <vector>

#include "curve_test_support.hpp"

using namespace curvestep;
using namespace curvestep::testing;

namespace {

/// The hodograph control points n (b_{i+1} - b_i).
template <std::size_t Dim>
std::vector<RealPoint<Dim>> hodograph_of(const std::vector<RealPoint<Dim>>& b) {
  const std::size_t n = b.size() - 1;
  std::vector<RealPoint<Dim>> hodograph;
  for (std::size_t i = 0; i < n; ++i) {
    RealPoint<Dim> d{};
    for (std::size_t a = 0; a < Dim; ++a) d[a] = static_cast<Real>(n) * (b[i + 1][a] - b[i][a]);
    hodograph.push_back(d);
  }
  return hodograph;
}

/// |r'(t)| from the hodograph's Bernstein sum.
template <std::size_t Dim>
Real reference_speed(const std::vector<RealPoint<Dim>>& hodograph, Real t) {
  const auto v = bernstein_sum(hodograph, t);
  Real s = 0;
  for (Real c : v) s += c * c;
  return std::sqrt(s);
}

/// Composite Simpson with 2048 panels: the speed of these curves has no cusp (checked below), so
/// the error is far below the tolerances used.
template <std::size_t Dim>
Real reference_length(const std::vector<RealPoint<Dim>>& b, Real t0, Real t1) {
  constexpr int panels = 2048;
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
  const int count = test_count(30);
  int checked = 0;
  for (int c = 0; c < count; ++c) {
    const auto points = random.polygon<S, 2>(random.integer(2, 4), 100);
    const auto curve = must(Bezier<S, 2, 7>::create(std::span<const Vec<S, 2>>(points)));
    const auto b = hodograph_of(to_real<S, 2>(points));
    // Skip curves with a (near) cusp: near a speed minimum s the speed's fourth derivative grows
    // like |r''|^4 / s^3, and the Simpson reference needs s >= 10 to stay within 1e-5.
    Real slowest = 1e30L;
    for (int k = 0; k <= 256; ++k) slowest = std::min(slowest, reference_speed(b, static_cast<Real>(k) / 256));
    if (slowest < 10) continue;
    ++checked;
    const Real expected = reference_length(b, 0, 1);
    // Requested tolerance, plus the format's error on a sum of ~100 speed samples of size |r'|:
    // Fixed: each |r'| carries a few units; float: relative rounding of the length.
    // The documented absolute tolerance, the same for every format (a loose one exercises the
    // adaptive error estimate, which must not accept a coincidental agreement).
    const double requested = 0.01;
    const double format = FixedPoint<S> ? 64 * unit<S>() * static_cast<double>(expected) / 10 + 256 * unit<S>()
                                        : 64 * unit<S>() * static_cast<double>(expected);
    INFO("case " << c << " degree " << curve.degree() << " length " << static_cast<double>(expected));
    const auto length = arc_length(curve, S{}, from_int<S>(1), from_double<S>(requested).value());
    if (!length) FAIL_CHECK("arc_length failed: " << error_name(length.error()));
    if (length) CHECK(std::fabs(to_double(length.value()) - static_cast<double>(expected)) <= requested + format);
  }
  CHECK(checked > count / 3);
}

TEMPLATE_TEST_CASE("arc length: a 20 m line within the Q16.16 range", "[core][bezier]", double, float, Q16_16) {
  using S = TestType;
  // A straight cubic from x = 0 to x = 20000 mm whose speed reaches 20000 mm per unit t: the
  // length (20000) and every speed fit Q16.16, the sum of the quadrature weights times the
  // speeds (~40000) does not.
  const auto line = must(Bezier<S, 2, 7>::create({point<S>(0, 0), point<S>(6000, 0), point<S>(14000, 0), point<S>(20000, 0)}));
  const auto length = arc_length(line, S{}, from_int<S>(1), scalar<S>(0.01));
  if (!length) FAIL_CHECK("arc_length failed: " << error_name(length.error()));
  // Fixed: the quadrature nodes are Q16.16 parameters, rounded by half a unit, which moves each
  // speed sample by up to |r''| / 2 units (|r''| <= 12000 here) and the integral as much; float:
  // relative rounding of 20000.
  const double format = FixedPoint<S> ? 12000 * unit<S>() + 64 * unit<S>() : 64 * unit<S>() * 20000;
  if (length) CHECK(std::fabs(to_double(length.value()) - 20000) <= 0.01 + format);
}
