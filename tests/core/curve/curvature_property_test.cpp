// SPDX-License-Identifier: MIT
// Curvature and osculating circles of machine-sized curves (coordinates in [-100,100] mm), in
// double, float and Q16.16, against a long double reference from the Bernstein-form derivatives.
#include <array>
#include <cmath>
#include <vector>

#include "curve_test_support.hpp"

using namespace curvestep;
using namespace curvestep::testing;

namespace {

/// First and second derivatives of the Bernstein form in long double: n Σ Δb_i B^{n-1}_i and
/// n(n-1) Σ Δ²b_i B^{n-2}_i.
template <std::size_t Dim>
std::array<RealPoint<Dim>, 2> reference_derivatives(const std::vector<RealPoint<Dim>>& b, Real t) {
  const std::size_t n = b.size() - 1;
  std::vector<RealPoint<Dim>> first;
  std::vector<RealPoint<Dim>> second;
  for (std::size_t i = 0; i + 1 <= n; ++i) {
    RealPoint<Dim> d{};
    for (std::size_t a = 0; a < Dim; ++a) d[a] = static_cast<Real>(n) * (b[i + 1][a] - b[i][a]);
    first.push_back(d);
  }
  for (std::size_t i = 0; i + 2 <= n; ++i) {
    RealPoint<Dim> d{};
    for (std::size_t a = 0; a < Dim; ++a) d[a] = static_cast<Real>(n * (n - 1)) * (b[i + 2][a] - 2 * b[i + 1][a] + b[i][a]);
    second.push_back(d);
  }
  std::array<RealPoint<Dim>, 2> r{};
  r[0] = bernstein_sum(first, t);
  if (!second.empty()) r[1] = bernstein_sum(second, t);
  return r;
}

template <class S, std::size_t Dim>
void check_curvature(Random& random, int count) {
  int checked = 0;
  for (int c = 0; c < count; ++c) {
    const auto points = random.polygon<S, Dim>(random.integer(3, 6), 100);
    const auto curve = must(Bezier<S, Dim, 7>::create(std::span<const Vec<S, Dim>>(points)));
    const auto b = to_real<S, Dim>(points);
    const S t = random.parameter<S>();
    const auto d = reference_derivatives(b, to_real(t));
    const Real speed = std::sqrt(d[0][0] * d[0][0] + d[0][1] * d[0][1] + (Dim == 3 ? d[0][Dim - 1] * d[0][Dim - 1] : 0));
    Real cross_norm = 0;
    Real signed_cross = 0;
    if constexpr (Dim == 2) {
      signed_cross = d[0][0] * d[1][1] - d[0][1] * d[1][0];
      cross_norm = signed_cross;
    } else {
      const Real x = d[0][1] * d[1][2] - d[0][2] * d[1][1];
      const Real y = d[0][2] * d[1][0] - d[0][0] * d[1][2];
      const Real z = d[0][0] * d[1][1] - d[0][1] * d[1][0];
      cross_norm = std::sqrt(x * x + y * y + z * z);
    }
    const Real kappa = cross_norm / (speed * speed * speed);
    // Skip near-cusps and near-inflections where κ or 1/κ leaves any fixed-point range.
    if (speed < 10 || std::fabs(kappa) > 10 || std::fabs(kappa) < 1e-4) continue;
    ++checked;
    const double n = static_cast<double>(curve.degree());
    // Error model: the derivatives carry an absolute error e (Fixed: n+1 units from de Casteljau
    // on exact hodograph points; floating point: ~4n roundings of their size), so r' × r'' is off
    // by about e (|r'| + |r''|) and |r'|³ by 3 e / |r'| relative; the Fixed divisions add a few
    // units of κ. Near an inflection the first term dominates: it is absolute, not relative to κ.
    const double second_size = static_cast<double>(std::sqrt(d[1][0] * d[1][0] + d[1][1] * d[1][1] +
                                                            (Dim == 3 ? d[1][Dim - 1] * d[1][Dim - 1] : 0)));
    const double speed_d = static_cast<double>(speed);
    const double kappa_d = std::fabs(static_cast<double>(kappa));
    const double e = FixedPoint<S> ? (n + 1) * unit<S>() : 4 * n * unit<S>() * std::fmax(speed_d, second_size);
    const double tol = 2 * e * (speed_d + second_size) / (speed_d * speed_d * speed_d) + 6 * kappa_d * e / speed_d +
                       (FixedPoint<S> ? 4 * unit<S>() : 16 * n * unit<S>() * kappa_d);
    const double relative = tol / kappa_d;
    INFO("case " << c << " degree " << curve.degree() << " dim " << Dim << " t " << to_double(t) << " speed "
                 << static_cast<double>(speed) << " kappa " << static_cast<double>(kappa));
    const auto value = curvature(curve, t);
    if (!value) FAIL_CHECK("curvature failed: " << error_name(value.error()));
    if (value) CHECK(std::fabs(to_double(value.value()) - static_cast<double>(kappa)) <= tol);
    if constexpr (Dim == 2) {
      // Centre = r + (|r'|² / (r' × r'')) (-y', x'); its distance from r is the radius 1/|κ| <= 10^4.
      const auto p = bernstein_sum(b, to_real(t));
      const Real k = speed * speed / signed_cross;
      const RealPoint<2> centre{p[0] - k * d[0][1], p[1] + k * d[0][0]};
      const Real radius = 1 / std::fabs(kappa);
      const auto actual = osculating_center(curve, t);
      if (!actual) FAIL_CHECK("osculating_center failed: " << error_name(actual.error()));
      // The centre moves by radius times the relative error of κ, plus the tangent direction error.
      const double centre_tol = static_cast<double>(radius) * (relative + 2 * e / speed_d) + evaluation_tolerance<S>(100, curve.degree());
      if (actual) CHECK(max_error_real(actual.value(), centre) <= centre_tol);
    }
  }
  CHECK(checked > count / 4);
}

}  // namespace

TEMPLATE_TEST_CASE("curvature: machine-sized random curves match the long double formula", "[core][bezier][property]", double,
                   float, Q16_16) {
  Random random(41);
  const int count = test_count(300);
  check_curvature<TestType, 2>(random, count);
  check_curvature<TestType, 3>(random, count);
}
