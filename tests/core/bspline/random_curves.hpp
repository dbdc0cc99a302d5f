// SPDX-License-Identifier: MIT
// Random B-spline data for the property tests: knots on a 1/8 grid (exact in double, float and
// Q16.16), clamped or unclamped, with random repeated knots up to the legal multiplicity.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <span>
#include <random>
#include <vector>

#include <curvestep/core/geometry/vec.hpp>
#include <support/numeric.hpp>

namespace curvestep::testing {

/// The curve's point at u by the Cox–de Boor recursion of the basis, written here in long double
/// (no library code): N_{i,0} is 1 on [U_i, U_{i+1}) — on (U_i, U_{i+1}] at the domain's end —
/// and N_{i,k} = (u − U_i)/(U_{i+k} − U_i) N_{i,k−1} + (U_{i+k+1} − u)/(U_{i+k+1} − U_{i+1}) N_{i+1,k−1}
/// with 0/0 = 0; the point is Σ N_{i,p}(u) P_i.
template <Scalar S, std::size_t Dim>
std::array<long double, Dim> cox_de_boor_point(std::span<const Vec<S, Dim>> control, std::span<const S> knot_values, std::size_t degree,
                                               S u_value) {
  std::vector<long double> knots;
  for (const S k : knot_values) knots.push_back(static_cast<long double>(to_double(k)));
  const auto u = static_cast<long double>(to_double(u_value));
  const bool at_end = u == knots[control.size()];
  std::vector<long double> n(knots.size() - 1);
  for (std::size_t i = 0; i + 1 < knots.size(); ++i) {
    n[i] = (at_end ? knots[i] < u && u <= knots[i + 1] : knots[i] <= u && u < knots[i + 1]) ? 1.0L : 0.0L;
  }
  const auto ratio = [](long double num, long double den) { return den == 0 ? 0.0L : num / den; };
  for (std::size_t k = 1; k <= degree; ++k) {
    for (std::size_t i = 0; i + k + 1 < knots.size(); ++i) {
      n[i] = ratio(u - knots[i], knots[i + k] - knots[i]) * n[i] + ratio(knots[i + k + 1] - u, knots[i + k + 1] - knots[i + 1]) * n[i + 1];
    }
  }
  std::array<long double, Dim> point{};
  for (std::size_t i = 0; i < control.size(); ++i) {
    for (std::size_t a = 0; a < Dim; ++a) point[a] += n[i] * static_cast<long double>(to_double(control[i][a]));
  }
  return point;
}

/// Largest coordinate difference between a point and a long double reference.
template <Scalar S, std::size_t Dim>
double max_error_long(const Vec<S, Dim>& actual, const std::array<long double, Dim>& expected) {
  double m = 0;
  for (std::size_t i = 0; i < Dim; ++i) m = std::fmax(m, static_cast<double>(std::fabs(static_cast<long double>(to_double(actual[i])) - expected[i])));
  return m;
}

/// Control points, knots and degree of one random curve.
template <Scalar S, std::size_t Dim>
struct RandomSplineData {
  std::vector<Vec<S, Dim>> control;
  std::vector<S> knots;
  std::size_t degree = 1;
};

/// A random valid B-spline: degree 1..max_degree, degree+1..degree+1+extra points with
/// coordinates in [-range, range]; clamped when `clamped`. Interior knots repeat at most `degree`
/// times, end knots at most degree+1 times.
template <Scalar S, std::size_t Dim>
RandomSplineData<S, Dim> random_spline(std::mt19937& random, std::size_t max_degree, std::size_t extra, bool clamped,
                                       double range = 100) {
  std::uniform_real_distribution<double> coordinate(-range, range);
  RandomSplineData<S, Dim> data;
  data.degree = std::uniform_int_distribution<std::size_t>(1, max_degree)(random);
  const std::size_t count = data.degree + 1 + std::uniform_int_distribution<std::size_t>(0, extra)(random);
  for (std::size_t i = 0; i < count; ++i) {
    Vec<S, Dim> p;
    for (std::size_t axis = 0; axis < Dim; ++axis) p[axis] = scalar<S>(coordinate(random));
    data.control.push_back(p);
  }
  // Distinct knot values with multiplicities; the total is count + degree + 1.
  const std::size_t total = count + data.degree + 1;
  std::vector<double> values;
  double u = std::uniform_int_distribution<int>(-8, 8)(random) / 8.0;
  std::uniform_int_distribution<int> gap(1, 3);
  std::uniform_int_distribution<std::size_t> repeat(1, data.degree);
  if (clamped) {
    for (std::size_t i = 0; i <= data.degree; ++i) values.push_back(u);
    const std::size_t interior = total - 2 * (data.degree + 1);
    while (values.size() < data.degree + 1 + interior) {
      u += gap(random) / 8.0;
      const std::size_t r = std::min(repeat(random), data.degree + 1 + interior - values.size());
      for (std::size_t k = 0; k < r; ++k) values.push_back(u);
    }
    u += gap(random) / 8.0;
    for (std::size_t i = 0; i <= data.degree; ++i) values.push_back(u);
  } else {
    while (values.size() < total) {
      // Keep the domain [u_p, u_{n+1}] non-empty: no run may cover both of its ends.
      std::size_t r = std::min(repeat(random), total - values.size());
      if (values.size() <= data.degree && values.size() + r > count) r = count - values.size();
      for (std::size_t k = 0; k < r; ++k) values.push_back(u);
      u += gap(random) / 8.0;
    }
  }
  for (const double v : values) data.knots.push_back(scalar<S>(v));
  return data;
}

/// Scalars from doubles (test data that must be representable).
template <Scalar S>
std::vector<S> scalars(std::initializer_list<double> values) {
  std::vector<S> out;
  for (const double v : values) out.push_back(scalar<S>(v));
  return out;
}

/// 2D points from {x, y} pairs.
template <Scalar S>
std::vector<Vec<S, 2>> points(std::initializer_list<std::array<double, 2>> values) {
  std::vector<Vec<S, 2>> out;
  for (const auto& v : values) out.push_back(point<S>(v[0], v[1]));
  return out;
}

/// A curve of type Curve from points, knots and degree; fails the test if create fails.
template <class Curve>
Curve make_spline(const std::vector<typename Curve::Point>& control, const std::vector<typename Curve::scalar_type>& knots,
                  std::size_t degree) {
  const auto made = Curve::create(std::span<const typename Curve::Point>(control),
                                  std::span<const typename Curve::scalar_type>(knots), degree);
  INFO("create failed with error " << static_cast<int>(made.error()) << " at " << made.where());
  REQUIRE(made.has_value());
  return made.value();
}

}  // namespace curvestep::testing
