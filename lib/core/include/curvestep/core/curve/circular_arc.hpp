// SPDX-License-Identifier: MIT
// Exact circular arcs as rational Bézier curves.
//
// An arc of sweep θ about centre c from a = start - c to b = end - c (|a| = |b| = r) is the
// conic with end points start, end and, in homogeneous form, middle point
//     H1 = (cos(θ/2) c + r m, cos(θ/2)),   r m = cos(θ/2) a + sin(θ/2) J a
// where J turns a by +90° (counter-clockwise) or -90° (clockwise). With unit vectors u_a, u_b,
// cos(θ/2) = |u_a + u_b| / 2 and sin(θ/2) = |u_a - u_b| / 2: only square roots are needed, and
// unlike sqrt((1 + cos θ)/2) these stay accurate near 180° (where 1 + cos θ cancels and the
// square root would magnify a rounding of 2^-16 to 2^-8.5). Fixed lengths are the rounded integer
// square root of the exact sum of squared raw values, so r² never has to fit the format (Q16.16:
// radii up to the range); the cubic's points are formed relative to the centre for the same reason.
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

namespace detail {
/// |v| without overflow. Fixed: the exact sum of the squared raw values (< 2^63 for 32-bit
/// reps) and a rounded integer square root, so the length is correct to half a unit at any size.
/// Floating point: m sqrt((x/m)² + (y/m)²) with m the larger coordinate.
template <Scalar S>
[[nodiscard]] constexpr Result<S> scaled_length(const Vec2<S>& v) noexcept {
  if constexpr (FixedPoint<S>) {
    static_assert(sizeof(typename S::rep) <= 4, "squares of the raw values must fit 64 bits");
    const auto magnitude = [](typename S::rep raw) {
      const auto wide = static_cast<std::int64_t>(raw);
      return static_cast<std::uint64_t>(wide < 0 ? -wide : wide);
    };
    const std::uint64_t x = magnitude(v[0].raw());
    const std::uint64_t y = magnitude(v[1].raw());
    const std::uint64_t sum = x * x + y * y;
    std::uint64_t root = integer_sqrt(sum);
    if (sum - root * root > root) ++root;  // sum >= (root + 1/2)^2: round up
    return S::from_wide(static_cast<typename S::wide>(root));
  }
  const S ax = abs(v[0]);
  const S ay = abs(v[1]);
  const S m = ax < ay ? ay : ax;
  if (m == S{}) return S{};
  const S x = ax / m;
  const S y = ay / m;
  return checked_mul(m, sqrt(x * x + y * y));
}
}  // namespace detail

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
  using Curve = RationalBezier<S, 2, MaxDegree>;
  CURVESTEP_TRY(const auto a, checked_sub(start, center));
  CURVESTEP_TRY(const auto b, checked_sub(end, center));
  // Work in units of r so Fixed products stay small: cos θ = (a/r)·(b/r).
  CURVESTEP_TRY(const S r, detail::scaled_length(a));
  CURVESTEP_TRY(const S rb, detail::scaled_length(b));
  if (r == S{} || rb == S{}) return fail(Error::DegenerateCurve);
  if (radius_tolerance < abs(r - rb)) return fail(Error::InvalidArgument, 1);
  const Vec2<S> ua{{a[0] / r, a[1] / r}};
  const Vec2<S> ub{{b[0] / rb, b[1] / rb}};
  const S cos_sweep = dot(ua, ub);
  const S turn = cross(ua, ub);  // sin θ for counter-clockwise travel
  const bool ccw = direction == ArcDirection::CounterClockwise;
  S signed_sin = ccw ? turn : -turn;
  const S one = from_int<S>(1);
  if (signed_sin < S{}) {
    // A half circle whose end points were rounded may turn a hair the wrong way: accept a turn
    // within the end points' own angular uncertainty (radius tolerance / r) as exactly 180°.
    const S slack = radius_tolerance / r + resolution<S>() * from_int<S>(8);
    if (!(cos_sweep < S{}) || slack < -signed_sin) return fail(Error::SweepTooLarge);
    signed_sin = S{};
  }
  if (signed_sin == S{} && S{} < cos_sweep) return fail(Error::DegenerateCurve);
  CURVESTEP_TRY(const S sum_length, detail::scaled_length(ua + ub));
  CURVESTEP_TRY(const S difference_length, detail::scaled_length(ua - ub));
  const S half_cos = sum_length / from_int<S>(2);  // cos(θ/2) = w1
  const S half_sin = difference_length / from_int<S>(2);
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
  // With the homogeneous middle point h1 = cos(θ/2) c + r m: q1 = (start + 2 h1) / (1 + 2 cos(θ/2)),
  // taken relative to the centre, c + (a + 2 r m) / (1 + 2 cos(θ/2)), so that no intermediate
  // sum of absolute coordinates can leave the Fixed range far from the origin.
  const S middle_weight = (one + from_int<S>(2) * half_cos) / from_int<S>(3);
  const S denominator = one + from_int<S>(2) * half_cos;
  const Vec2<S> q1 = center + (a + rm * from_int<S>(2)) / denominator;
  const Vec2<S> q2 = center + (b + rm * from_int<S>(2)) / denominator;
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
  if constexpr (!FixedPoint<S>) {
    // Floating-point start and end carry rounding relative to their coordinates, not the radius.
    const S magnitude = abs(center[0]) + abs(center[1]) + radius;
    tolerance = tolerance * (magnitude < S{1} ? S{1} : magnitude);
  }
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
