// SPDX-License-Identifier: MIT
// Joining curves: checking C^r / G1 / G2 at a joint and constructing the next segment's first
// control points for a C^r or G2 join.
//
// Checks compare derivatives with respect to the global parameter (so interval lengths count):
// C^r holds when s^(k) from the left equals s^(k) from the right for k = 0..r. Geometric
// continuity ignores parametrisation: G1 needs unit tangents equal, G2 also equal curvature
// vectors κN = (r' × r'') × r' / |r'|^4 (in 2D the signed curvature).
// Construction of a C^r join for a segment on [b, c] after p on [a, b]: the k-th control point
// of the new segment is p's de Casteljau value of its last k+1 points at the extrapolation
// parameter µ = (c - a) / (b - a), i.e. its blossom P(1^{n-k}, µ^k) (seed 001, §2.1).
// The G2 join of two cubics (seed 000 §2.4) with α > 0, β: q1 = p3 + α(p3 - p2),
//   q2 = α² p1 - (2α² + 2α + β/2) p2 + (1 + α² + 2α + β/2) p3.
// Checks are analysis (not hot path) and are evaluated in double whatever the scalar type.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

#include <curvestep/core/curve/composite_bezier.hpp>

namespace curvestep {

/// The continuity found at a joint.
struct JointContinuity {
  int parametric = -1;  ///< largest r <= 2 with C^r (-1: not even C0)
  int geometric = -1;   ///< largest r <= 2 with G^r (-1: not even G0)
};

namespace detail {
template <std::size_t Dim>
[[nodiscard]] inline double max_difference(const std::array<double, Dim>& a, const std::array<double, Dim>& b) {
  double m = 0;
  for (std::size_t i = 0; i < Dim; ++i) m = std::fmax(m, std::fabs(a[i] - b[i]));
  return m;
}
template <std::size_t Dim>
[[nodiscard]] inline double length(const std::array<double, Dim>& a) {
  double s = 0;
  for (double c : a) s += c * c;
  return std::sqrt(s);
}
/// Curvature vector κN of a curve with derivatives d1, d2 (zero vector where d1 = 0).
template <std::size_t Dim>
[[nodiscard]] inline std::array<double, Dim> curvature_vector(const std::array<double, Dim>& d1,
                                                              const std::array<double, Dim>& d2) {
  double s2 = 0;
  double d12 = 0;
  for (std::size_t i = 0; i < Dim; ++i) {
    s2 += d1[i] * d1[i];
    d12 += d1[i] * d2[i];
  }
  std::array<double, Dim> k{};
  if (s2 == 0) return k;
  // (r' × r'') × r' / |r'|^4 = (r'' |r'|² - r' (r'·r'')) / |r'|^4, valid in any dimension.
  for (std::size_t i = 0; i < Dim; ++i) k[i] = (d2[i] * s2 - d1[i] * d12) / (s2 * s2);
  return k;
}
}  // namespace detail

/// Continuity of a composite curve at the joint between segments j-1 and j (1 <= j < size()),
/// each quantity compared with tolerance `tolerance` (absolute, in the curve's units per u^k).
template <Scalar S, std::size_t Dim, std::size_t MaxDegree, std::size_t MaxSegments>
[[nodiscard]] constexpr Result<JointContinuity> continuity(const CompositeBezier<S, Dim, MaxDegree, MaxSegments>& curve,
                                                           std::size_t j, double tolerance) {
  if (j == 0 || j >= curve.size()) return fail(Error::InvalidArgument, j);
  std::array<std::array<double, Dim>, 3> left{};
  std::array<std::array<double, Dim>, 3> right{};
  for (std::size_t k = 0; k <= 2; ++k) {
    CURVESTEP_TRY(const auto l, curve.segment_derivative(j - 1, from_int<S>(1), k));
    CURVESTEP_TRY(const auto r, curve.segment_derivative(j, S{}, k));
    left[k] = to_doubles(l);
    right[k] = to_doubles(r);
  }
  JointContinuity c;
  for (int k = 0; k <= 2; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    if (detail::max_difference(left[kk], right[kk]) > tolerance) break;
    c.parametric = k;
  }
  if (c.parametric < 0) return c;
  c.geometric = 0;
  const double left_speed = detail::length(left[1]);
  const double right_speed = detail::length(right[1]);
  if (left_speed == 0 || right_speed == 0) return c;
  std::array<double, Dim> left_tangent{};
  std::array<double, Dim> right_tangent{};
  for (std::size_t i = 0; i < Dim; ++i) {
    left_tangent[i] = left[1][i] / left_speed;
    right_tangent[i] = right[1][i] / right_speed;
  }
  if (detail::max_difference(left_tangent, right_tangent) > tolerance) return c;
  c.geometric = 1;
  if (detail::max_difference(detail::curvature_vector(left[1], left[2]), detail::curvature_vector(right[1], right[2])) >
      tolerance) {
    return c;
  }
  c.geometric = 2;
  return c;
}

/// The first r+1 control points d_0..d_r of a degree-n segment on [b, c] that joins `previous`
/// (on [a, b]) with C^r continuity; µ = (c - a)/(b - a) > 1. Contract: r <= degree.
/// The remaining n-r control points are free. FixedOverflow for large µ.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree>
[[nodiscard]] constexpr Result<std::array<Vec<S, Dim>, MaxDegree + 1>> continuation_points(const Bezier<S, Dim, MaxDegree>& previous,
                                                                                         S mu, std::size_t r) {
  CURVESTEP_EXPECTS(r <= previous.degree());
  std::array<Vec<S, Dim>, MaxDegree + 1> d{};
  std::array<S, MaxDegree> u{};
  const std::size_t n = previous.degree();
  for (std::size_t k = 0; k <= r; ++k) {
    for (std::size_t i = 0; i < n; ++i) u[i] = i < n - k ? from_int<S>(1) : mu;
    CURVESTEP_TRY(d[k], previous.blossom(std::span<const S>(u.data(), n)));
  }
  return d;
}

/// q1, q2 of a cubic that joins the cubic p0..p3 with G2 continuity for shape parameters
/// α > 0 and β (α = 1, β = 0 gives parametric C2). InvalidArgument for α <= 0 or a non-cubic.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree>
[[nodiscard]] constexpr Result<std::array<Vec<S, Dim>, 2>> g2_join_cubic(const Bezier<S, Dim, MaxDegree>& p, S alpha, S beta) {
  if (p.degree() != 3) return fail(Error::DegreeMismatch);
  if (!(S{} < alpha)) return fail(Error::InvalidArgument);
  using detail::Checked;
  std::array<Vec<S, Dim>, 2> q{};
  const Checked<S> a(alpha);
  const Checked<S> half_beta = Checked<S>(beta) / Checked<S>(from_int<S>(2));
  const Checked<S> one(from_int<S>(1));
  const Checked<S> two(from_int<S>(2));
  for (std::size_t i = 0; i < Dim; ++i) {
    const Checked<S> p1(p[1][i]);
    const Checked<S> p2(p[2][i]);
    const Checked<S> p3(p[3][i]);
    CURVESTEP_TRY(q[0][i], (p3 + a * (p3 - p2)).result());
    CURVESTEP_TRY(q[1][i], (a * a * p1 - (two * a * a + two * a + half_beta) * p2 + (one + a * a + two * a + half_beta) * p3).result());
  }
  return q;
}

}  // namespace curvestep
