// SPDX-License-Identifier: MIT
// Independent references for the sampling tests: de Casteljau and arc length in long double.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include <curvestep/core.hpp>

namespace curvestep::testing {

/// Control points as long doubles (exact copies of float, double and Q16.16 values).
template <std::size_t Dim>
using ReferencePolygon = std::vector<std::array<long double, Dim>>;

template <class Curve>
ReferencePolygon<Curve::dimension> reference_polygon(const Curve& curve) {
  ReferencePolygon<Curve::dimension> polygon;
  for (const auto& p : curve.control_points()) {
    std::array<long double, Curve::dimension> q{};
    for (std::size_t axis = 0; axis < Curve::dimension; ++axis) q[axis] = static_cast<long double>(to_double(p[axis]));
    polygon.push_back(q);
  }
  return polygon;
}

/// p(t) by de Casteljau in long double.
template <std::size_t Dim>
std::array<long double, Dim> reference_point(ReferencePolygon<Dim> work, long double t) {
  const std::size_t n = work.size() - 1;
  for (std::size_t r = 1; r <= n; ++r) {
    for (std::size_t i = 0; i + r <= n; ++i) {
      for (std::size_t axis = 0; axis < Dim; ++axis) work[i][axis] = (1 - t) * work[i][axis] + t * work[i + 1][axis];
    }
  }
  return work[0];
}

/// Rational r(t) in long double from control points and weights.
template <std::size_t Dim>
std::array<long double, Dim> reference_rational_point(const ReferencePolygon<Dim>& points, const std::vector<long double>& weights,
                                                      long double t) {
  ReferencePolygon<Dim + 1> h;
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::array<long double, Dim + 1> q{};
    for (std::size_t axis = 0; axis < Dim; ++axis) q[axis] = points[i][axis] * weights[i];
    q[Dim] = weights[i];
    h.push_back(q);
  }
  const auto r = reference_point<Dim + 1>(h, t);
  std::array<long double, Dim> p{};
  for (std::size_t axis = 0; axis < Dim; ++axis) p[axis] = r[axis] / r[Dim];
  return p;
}

/// Largest coordinate difference.
template <Scalar S, std::size_t Dim>
long double deviation(const Vec<S, Dim>& actual, const std::array<long double, Dim>& expected) {
  long double m = 0;
  for (std::size_t axis = 0; axis < Dim; ++axis) {
    m = std::fmax(m, std::fabs(static_cast<long double>(to_double(actual[axis])) - expected[axis]));
  }
  return m;
}

/// Euclidean distance from q to the segment [a, b] in long double.
template <std::size_t Dim>
long double distance_to_segment(const std::array<long double, Dim>& q, const std::array<long double, Dim>& a,
                                const std::array<long double, Dim>& b) {
  long double dd = 0, vd = 0;
  for (std::size_t axis = 0; axis < Dim; ++axis) {
    dd += (b[axis] - a[axis]) * (b[axis] - a[axis]);
    vd += (q[axis] - a[axis]) * (b[axis] - a[axis]);
  }
  long double s = dd > 0 ? vd / dd : 0;
  if (s < 0) s = 0;
  if (s > 1) s = 1;
  long double d2 = 0;
  for (std::size_t axis = 0; axis < Dim; ++axis) {
    const long double e = q[axis] - (a[axis] + s * (b[axis] - a[axis]));
    d2 += e * e;
  }
  return std::sqrt(d2);
}

}  // namespace curvestep::testing
