// SPDX-License-Identifier: MIT
// Helpers for the curve property tests: random polygons, long double reference formulas that do
// not share code with the library (Bernstein sums, subset-sum blossom, convex hull), and error
// bounds derived from the scalar format.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <span>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core.hpp>
#include <curvestep/core/error_text.hpp>
#include <support/numeric.hpp>

namespace curvestep::testing {

using Real = long double;
template <std::size_t Dim>
using RealPoint = std::array<Real, Dim>;

template <Scalar S>
Real to_real(S value) {
  return static_cast<Real>(to_double(value));
}

template <Scalar S, std::size_t Dim>
RealPoint<Dim> to_real(const Vec<S, Dim>& v) {
  RealPoint<Dim> r{};
  for (std::size_t i = 0; i < Dim; ++i) r[i] = to_real(v[i]);
  return r;
}

template <Scalar S, std::size_t Dim>
std::vector<RealPoint<Dim>> to_real(std::span<const Vec<S, Dim>> points) {
  std::vector<RealPoint<Dim>> r;
  for (const auto& p : points) r.push_back(to_real(p));
  return r;
}

/// The value of a Result, failing the test with the error name and index otherwise.
template <class T>
T must(const Result<T>& r) {
  if (!r.has_value()) {
    FAIL_CHECK("unexpected failure " << error_name(r.error()) << " at index " << r.where());
  }
  REQUIRE(r.has_value());
  return r.value();
}

/// C(n, k) as a long double (independent of the library's detail::binomial).
inline Real binomial_real(std::size_t n, std::size_t k) {
  Real c = 1;
  for (std::size_t i = 1; i <= k; ++i) c = c * static_cast<Real>(n + 1 - i) / static_cast<Real>(i);
  return c;
}

inline Real power(Real base, std::size_t exponent) {
  Real r = 1;
  for (std::size_t i = 0; i < exponent; ++i) r *= base;
  return r;
}

/// Σ C(n,i) t^i (1-t)^(n-i) b_i: the Bernstein form, valid for any t (no de Casteljau).
template <std::size_t Dim>
RealPoint<Dim> bernstein_sum(const std::vector<RealPoint<Dim>>& b, Real t) {
  const std::size_t n = b.size() - 1;
  RealPoint<Dim> r{};
  for (std::size_t i = 0; i <= n; ++i) {
    const Real c = binomial_real(n, i) * power(t, i) * power(1 - t, n - i);
    for (std::size_t a = 0; a < Dim; ++a) r[a] += c * b[i][a];
  }
  return r;
}

/// The blossom as a sum over subsets: P(u) = Σ_{A ⊆ {1..n}} Π_{r∈A} u_r Π_{r∉A} (1-u_r) b_{|A|}.
/// Symmetric by construction (it is the multi-affine polar form of the Bernstein sum).
template <std::size_t Dim>
RealPoint<Dim> blossom_subset_sum(const std::vector<RealPoint<Dim>>& b, const std::vector<Real>& u) {
  const std::size_t n = u.size();
  RealPoint<Dim> r{};
  for (std::uint32_t mask = 0; mask < (1u << n); ++mask) {
    Real c = 1;
    std::size_t count = 0;
    for (std::size_t k = 0; k < n; ++k) {
      if ((mask >> k) & 1u) {
        c *= u[k];
        ++count;
      } else {
        c *= 1 - u[k];
      }
    }
    for (std::size_t a = 0; a < Dim; ++a) r[a] += c * b[count][a];
  }
  return r;
}

/// Eighth-order central differences of f (a long double curve) at t with step h: the first and
/// the second derivative. For a polynomial of degree <= 7 they are exact up to rounding (the
/// truncation error involves the 9th derivative).
template <std::size_t Dim, class F>
std::array<RealPoint<Dim>, 2> central_differences(F f, Real t, Real h) {
  constexpr std::array<Real, 4> first{4.0L / 5, -1.0L / 5, 4.0L / 105, -1.0L / 280};
  constexpr std::array<Real, 5> second{-205.0L / 72, 8.0L / 5, -1.0L / 5, 8.0L / 315, -1.0L / 560};
  std::array<RealPoint<Dim>, 2> d{};
  const RealPoint<Dim> centre = f(t);
  for (std::size_t a = 0; a < Dim; ++a) d[1][a] = second[0] * centre[a];
  for (std::size_t k = 1; k <= 4; ++k) {
    const RealPoint<Dim> plus = f(t + static_cast<Real>(k) * h);
    const RealPoint<Dim> minus = f(t - static_cast<Real>(k) * h);
    for (std::size_t a = 0; a < Dim; ++a) {
      d[0][a] += first[k - 1] * (plus[a] - minus[a]);
      d[1][a] += second[k] * (plus[a] + minus[a]);
    }
  }
  for (std::size_t a = 0; a < Dim; ++a) {
    d[0][a] /= h;
    d[1][a] /= h * h;
  }
  return d;
}

template <Scalar S, std::size_t Dim>
double max_error_real(const Vec<S, Dim>& actual, const RealPoint<Dim>& expected) {
  double m = 0;
  for (std::size_t i = 0; i < Dim; ++i) {
    m = std::fmax(m, static_cast<double>(std::fabs(to_real(actual[i]) - expected[i])));
  }
  return m;
}

template <std::size_t Dim>
Real max_norm_real(const RealPoint<Dim>& v) {
  Real m = 0;
  for (Real c : v) m = std::max(m, std::fabs(c));
  return m;
}

/// Largest |coordinate| of a polygon.
template <std::size_t Dim>
double polygon_scale(const std::vector<RealPoint<Dim>>& b) {
  Real m = 0;
  for (const auto& p : b) m = std::max(m, max_norm_real(p));
  return static_cast<double>(m);
}

/// The unit roundoff of S (Fixed: half a raw unit is the rounding error; we use one unit).
template <Scalar S>
double unit() {
  return to_double(resolution<S>());
}

/// Error bound for de Casteljau-type evaluation of degree n with coordinates of magnitude `scale`:
/// Fixed: each of the n levels rounds once by at most half a unit (plus input rounding slack);
/// floating point: each level adds about two roundings relative to the coordinate scale.
template <Scalar S>
double evaluation_tolerance(double scale, std::size_t degree) {
  const auto n = static_cast<double>(degree);
  if constexpr (FixedPoint<S>) {
    return (n + 1) * unit<S>();
  } else {
    return 4 * (n + 1) * unit<S>() * std::fmax(scale, 1.0);
  }
}

/// Deterministic random source seeded from test_seed() (CURVESTEP_TEST_SEED) and a per-test salt.
class Random {
 public:
  explicit Random(std::uint32_t salt) : engine_(test_seed() ^ (salt * 2654435761u)) {}

  double uniform(double low, double high) { return std::uniform_real_distribution<double>(low, high)(engine_); }
  std::size_t integer(std::size_t low, std::size_t high) {
    return std::uniform_int_distribution<std::size_t>(low, high)(engine_);
  }
  bool chance(double p) { return uniform(0, 1) < p; }

  /// A value of S close to `value` (exactly representable).
  template <Scalar S>
  S quantize(double value) {
    return from_double<S>(value).value();
  }
  template <Scalar S>
  S coordinate(double low, double high) {
    return quantize<S>(uniform(low, high));
  }

  /// A parameter in [0,1]; the ends are drawn on purpose now and then.
  template <Scalar S>
  S parameter() {
    if (chance(0.05)) return from_int<S>(0);
    if (chance(0.05)) return from_int<S>(1);
    if constexpr (FixedPoint<S>) {
      const auto one = static_cast<std::size_t>(S::one_raw);
      return S::from_raw(static_cast<typename S::rep>(integer(0, one)));
    } else {
      return static_cast<S>(uniform(0, 1));
    }
  }

  template <Scalar S, std::size_t Dim>
  std::vector<Vec<S, Dim>> polygon(std::size_t count, double range) {
    std::vector<Vec<S, Dim>> points(count);
    for (auto& p : points) {
      for (std::size_t a = 0; a < Dim; ++a) p[a] = coordinate<S>(-range, range);
    }
    return points;
  }

  std::mt19937& engine() { return engine_; }

 private:
  std::mt19937 engine_;
};

/// Andrew's monotone chain: the convex hull counter-clockwise, collinear points dropped.
inline std::vector<RealPoint<2>> convex_hull(std::vector<RealPoint<2>> points) {
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  const auto turn = [](const RealPoint<2>& o, const RealPoint<2>& a, const RealPoint<2>& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  };
  std::vector<RealPoint<2>> hull(2 * points.size());
  std::size_t k = 0;
  for (const auto& p : points) {
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], p) <= 0) --k;
    hull[k++] = p;
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && turn(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

inline Real distance_to_segment(const RealPoint<2>& p, const RealPoint<2>& a, const RealPoint<2>& b) {
  const Real dx = b[0] - a[0];
  const Real dy = b[1] - a[1];
  const Real length2 = dx * dx + dy * dy;
  Real s = length2 == 0 ? 0 : ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2;
  s = std::clamp<Real>(s, 0, 1);
  return std::hypot(p[0] - (a[0] + s * dx), p[1] - (a[1] + s * dy));
}

/// How far p lies outside the convex polygon `hull` (0 if inside or on the boundary).
inline Real distance_outside_hull(const std::vector<RealPoint<2>>& hull, const RealPoint<2>& p) {
  if (hull.size() == 1) return std::hypot(p[0] - hull[0][0], p[1] - hull[0][1]);
  if (hull.size() == 2) return distance_to_segment(p, hull[0], hull[1]);
  Real outside = 0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const auto& a = hull[i];
    const auto& b = hull[(i + 1) % hull.size()];
    const Real edge = std::hypot(b[0] - a[0], b[1] - a[1]);
    const Real signed_distance = ((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])) / edge;
    outside = std::max(outside, -signed_distance);
  }
  return outside;
}

}  // namespace curvestep::testing
