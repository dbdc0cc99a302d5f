// SPDX-License-Identifier: MIT
// Exact circular arcs as rational Bézier curves.
//
// An arc of sweep θ about centre c from a = start - c to b = end - c (|a| = |b| = r) is the
// conic with end points start, end and, in homogeneous form, middle point
//     H1 = (cos(θ/2) c + r m, cos(θ/2)),   r m = cos(θ/2) a + sin(θ/2) J a
// where J turns a by +90° (counter-clockwise) or -90° (clockwise). cos(θ/2) and sin(θ/2) come
// from cos θ = a·b / r² by the half-angle formulas, so only square roots are needed.
//   * θ <= 90°: the quadratic form, weight cos(θ/2) >= √2/2, middle point c + r m / cos(θ/2).
//   * 90° < θ <= 180°: the same conic degree-elevated to a cubic, whose weights (1+2cos(θ/2))/3
//     stay positive and whose points stay finite even at θ = 180° (where the quadratic's middle
//     point would be at infinity).
// Larger sweeps need more segments: SweepTooLarge (full_circle builds four quarter arcs).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

#include <curvestep/core/curve/rational_bezier.hpp>
#include <curvestep/core/detail/checked.hpp>

namespace curvestep {

/// Direction of travel around the centre.
enum class ArcDirection : std::uint8_t {
  CounterClockwise,  ///< positive angles (G3)
  Clockwise,         ///< negative angles (G2)
};

/// The 2D arc about `center` from `start` to `end` in `direction`, sweep at most 180°.
/// Radii of start and end must agree within `radius_tolerance` (InvalidArgument otherwise);
/// DegenerateCurve for zero radius or coincident start and end; SweepTooLarge beyond 180°.
template <Scalar S, std::size_t MaxDegree = 7>
  requires(MaxDegree >= 3)
[[nodiscard]] constexpr Result<RationalBezier<S, 2, MaxDegree>> circular_arc(const Vec2<S>& center, const Vec2<S>& start,
                                                                             const Vec2<S>& end, ArcDirection direction,
                                                                             S radius_tolerance) {
  using detail::Checked;
  using Curve = RationalBezier<S, 2, MaxDegree>;
  CURVESTEP_TRY(const auto a, checked_sub(start, center));
  CURVESTEP_TRY(const auto b, checked_sub(end, center));
  // Work in units of r so Fixed products stay small: cos θ = (a/r)·(b/r).
  const Checked<S> r_squared = Checked<S>(a[0]) * Checked<S>(a[0]) + Checked<S>(a[1]) * Checked<S>(a[1]);
  const Checked<S> b_squared = Checked<S>(b[0]) * Checked<S>(b[0]) + Checked<S>(b[1]) * Checked<S>(b[1]);
  CURVESTEP_TRY(const S r, detail::checked_sqrt(r_squared).result());
  CURVESTEP_TRY(const S rb, detail::checked_sqrt(b_squared).result());
  if (r == S{}) return fail(Error::DegenerateCurve);
  if (radius_tolerance < abs(r - rb)) return fail(Error::InvalidArgument, 1);
  const Vec2<S> ua{{a[0] / r, a[1] / r}};
  const Vec2<S> ub{{b[0] / rb, b[1] / rb}};
  const S cos_sweep = dot(ua, ub);
  const S turn = cross(ua, ub);  // sin θ for counter-clockwise travel
  const bool ccw = direction == ArcDirection::CounterClockwise;
  const S signed_sin = ccw ? turn : -turn;
  const S one = from_int<S>(1);
  if (signed_sin < S{}) return fail(Error::SweepTooLarge);
  if (signed_sin == S{} && S{} < cos_sweep) return fail(Error::DegenerateCurve);
  S half_cos_squared = (one + cos_sweep) / from_int<S>(2);
  S half_sin_squared = (one - cos_sweep) / from_int<S>(2);
  if (half_cos_squared < S{}) half_cos_squared = S{};
  if (half_sin_squared < S{}) half_sin_squared = S{};
  const S half_cos = sqrt(half_cos_squared);  // cos(θ/2) = w1
  const S half_sin = sqrt(half_sin_squared);
  // r m = cos(θ/2) a + sin(θ/2) J a
  const Vec2<S> ja = ccw ? Vec2<S>{{-a[1], a[0]}} : Vec2<S>{{a[1], -a[0]}};
  const Vec2<S> rm = a * half_cos + ja * half_sin;
  if (!(cos_sweep < S{})) {
    // θ <= 90°: quadratic, middle point c + r m / cos(θ/2).
    const std::array<Vec2<S>, 3> points{start, center + rm / half_cos, end};
    const std::array<S, 3> weights{one, half_cos, one};
    return Curve::create(points, weights);
  }
  // 90° < θ <= 180°: the degree-elevated cubic.
  const S middle_weight = (one + from_int<S>(2) * half_cos) / from_int<S>(3);
  const Vec2<S> h1 = center * half_cos + rm;  // homogeneous middle point without its weight
  const S denominator = one + from_int<S>(2) * half_cos;
  const Vec2<S> q1 = (start + h1 * from_int<S>(2)) / denominator;
  const Vec2<S> q2 = (end + h1 * from_int<S>(2)) / denominator;
  const std::array<Vec2<S>, 4> points{start, q1, q2, end};
  const std::array<S, 4> weights{one, middle_weight, middle_weight, one};
  return Curve::create(points, weights);
}

/// The arc of `radius` about `center` from angle `start_rad` through `sweep_rad` (positive:
/// counter-clockwise), |sweep| <= π. Angles are doubles (host-side construction).
template <Scalar S, std::size_t MaxDegree = 7>
  requires(MaxDegree >= 3)
[[nodiscard]] Result<RationalBezier<S, 2, MaxDegree>> circular_arc_by_angle(const Vec2<S>& center, S radius,
                                                                            double start_rad, double sweep_rad) {
  if (!std::isfinite(start_rad) || !std::isfinite(sweep_rad)) return fail(Error::NotFinite);
  constexpr double pi = 3.14159265358979323846;
  if (std::fabs(sweep_rad) > pi * (1 + 1e-12)) return fail(Error::SweepTooLarge);
  if (sweep_rad == 0.0) return fail(Error::DegenerateCurve);
  const double r = to_double(radius);
  const double cx = to_double(center[0]);
  const double cy = to_double(center[1]);
  const double end_rad = start_rad + sweep_rad;
  CURVESTEP_TRY(const auto start, (vec_from_doubles<S, 2>({cx + r * std::cos(start_rad), cy + r * std::sin(start_rad)})));
  CURVESTEP_TRY(const auto end, (vec_from_doubles<S, 2>({cx + r * std::cos(end_rad), cy + r * std::sin(end_rad)})));
  const auto direction = sweep_rad > 0 ? ArcDirection::CounterClockwise : ArcDirection::Clockwise;
  S tolerance = resolution<S>() * from_int<S>(8);
  if constexpr (!FixedPoint<S>) tolerance = tolerance * (radius < S{1} ? S{1} : radius);
  return circular_arc<S, MaxDegree>(center, start, end, direction, tolerance);
}

/// A full circle as four quarter arcs (quadratic, weights 1, √2/2, 1), counter-clockwise from
/// angle 0. DegenerateCurve for radius <= 0.
template <Scalar S, std::size_t MaxDegree = 7>
[[nodiscard]] constexpr Result<std::array<RationalBezier<S, 2, MaxDegree>, 4>> full_circle(const Vec2<S>& center, S radius) {
  if (!(S{} < radius)) return fail(Error::DegenerateCurve);
  const S one = from_int<S>(1);
  const S w = sqrt(one / from_int<S>(2));
  std::array<RationalBezier<S, 2, MaxDegree>, 4> quarters{};
  const std::array<Vec2<S>, 4> axes{Vec2<S>{{radius, S{}}}, Vec2<S>{{S{}, radius}}, Vec2<S>{{-radius, S{}}},
                                    Vec2<S>{{S{}, -radius}}};
  for (std::size_t q = 0; q < 4; ++q) {
    const Vec2<S> from = axes[q];
    const Vec2<S> to = axes[(q + 1) % 4];
    CURVESTEP_TRY(const auto p0, checked_sub(center, -from));
    CURVESTEP_TRY(const auto p2, checked_sub(center, -to));
    CURVESTEP_TRY(const auto p1, checked_sub(p0, -to));
    const std::array<Vec2<S>, 3> points{p0, p1, p2};
    const std::array<S, 3> weights{one, w, one};
    CURVESTEP_TRY(quarters[q], (RationalBezier<S, 2, MaxDegree>::create(points, weights)));
  }
  return quarters;
}

}  // namespace curvestep
