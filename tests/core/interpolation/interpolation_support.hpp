// SPDX-License-Identifier: MIT
// Helpers shared by the interpolation tests: point lists, exact-rational expectations, checks of
// interpolation and continuity from both sides of every joint.
#pragma once

#include <array>
#include <cstddef>
#include <cmath>
#include <limits>
#include <span>

#include <catch2/catch.hpp>

#include <curvestep/core.hpp>
#include <curvestep/core/interpolation/cubic_spline.hpp>
#include <curvestep/core/interpolation/hermite.hpp>
#include <support/numeric.hpp>

namespace curvestep::testing {

/// Tolerance for values computed through a linear solve: Q16.16 rounds every product and quotient
/// to half a raw unit and the spline systems are strictly diagonally dominant (bounded error
/// growth), so 8 raw units per unit of magnitude `scale`; float/double: 8 epsilons times scale.
template <Scalar S>
double solve_tolerance(double scale = 1.0) {
  const double magnitude = scale < 1 ? 1 : scale;
  if constexpr (FixedPoint<S>) {
    return 8 * to_double(resolution<S>()) * magnitude;
  } else {
    return 8 * static_cast<double>(std::numeric_limits<S>::epsilon()) * magnitude;
  }
}

/// Points from doubles (2D).
template <Scalar S, std::size_t N>
std::array<Vec2<S>, N> points2(const std::array<std::array<double, 2>, N>& xy) {
  std::array<Vec2<S>, N> p{};
  for (std::size_t i = 0; i < N; ++i) p[i] = point<S>(xy[i][0], xy[i][1]);
  return p;
}

/// Scalars from doubles.
template <Scalar S, std::size_t N>
std::array<S, N> scalars(const std::array<double, N>& values) {
  std::array<S, N> s{};
  for (std::size_t i = 0; i < N; ++i) s[i] = scalar<S>(values[i]);
  return s;
}

/// Spans over the test's arrays (the interpolation functions take spans).
template <Scalar S, std::size_t N>
std::span<const Vec2<S>> view(const std::array<Vec2<S>, N>& a) {
  return std::span<const Vec2<S>>(a);
}
template <Scalar S, std::size_t N>
std::span<const S> view(const std::array<S, N>& a) {
  return std::span<const S>(a);
}

/// The curve passes through points[i] at breakpoint i (both the segment before and after).
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxSegments, std::size_t N>
void check_passes_through(const CompositeBezier<S, Dim, MaxDegree, MaxSegments>& curve, const std::array<Vec<S, Dim>, N>& points,
                          bool closed) {
  const std::size_t segments = curve.size();
  REQUIRE(segments == (closed ? N : N - 1));
  for (std::size_t j = 0; j < segments; ++j) {
    CHECK(curve.segment(j).front() == points[j]);
    CHECK(curve.segment(j).back() == points[(j + 1) % N]);
  }
}

/// Largest |left − right| of the order-th derivative (in u) at every joint (and at the wrap).
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxSegments>
double joint_jump(const CompositeBezier<S, Dim, MaxDegree, MaxSegments>& curve, std::size_t order, bool closed) {
  double worst = 0;
  const std::size_t segments = curve.size();
  for (std::size_t j = closed ? 0 : 1; j < segments; ++j) {
    const std::size_t before = j == 0 ? segments - 1 : j - 1;
    const auto left = curve.segment_derivative(before, from_int<S>(1), order);
    const auto right = curve.segment_derivative(j, S{}, order);
    REQUIRE(left.has_value());
    REQUIRE(right.has_value());
    worst = std::fmax(worst, max_error(left.value(), to_doubles(right.value())));
  }
  return worst;
}

}  // namespace curvestep::testing
