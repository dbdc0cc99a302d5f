// SPDX-License-Identifier: MIT
// Random B-spline data for the property tests: knots on a 1/8 grid (exact in double, float and
// Q16.16), clamped or unclamped, with random repeated knots up to the legal multiplicity.
#pragma once

#include <cstddef>
#include <random>
#include <vector>

#include <curvestep/core/geometry/vec.hpp>
#include <support/numeric.hpp>

namespace curvestep::testing {

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

}  // namespace curvestep::testing
