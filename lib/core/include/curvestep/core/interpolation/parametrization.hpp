// SPDX-License-Identifier: MIT
// Parameter values (knots) for interpolation: uniform, chord-length and centripetal.
//
// An interpolating spline passes through p_i at parameter u_i; the choice of u_i shapes it
// (seed 000 §3.3). With u_0 = 0 and d_i = |p_{i+1} − p_i|:
//   uniform      u_{i+1} = u_i + 1          good only when the points are evenly spaced;
//   chord length u_{i+1} = u_i + d_i        u approximates arc length, so the speed stays near 1
//                                           and the feed along the curve is near the parameter rate;
//   centripetal  u_{i+1} = u_i + sqrt(d_i)  (Lee 1989) between the two: avoids the loops and
//                                           cusps uniform knots make around sharp turns.
// Coincident consecutive points give an empty interval: DegenerateCurve (index = the later point),
// except with uniform knots. For a closed curve the closing chord p_{m-1} -> p_0 adds one more knot.
//
// Distances in Fixed are exact to half a raw unit: the squared raw differences are summed in a
// 64-bit integer and rooted with an integer square root (pre-scaled by a power of two only when a
// difference exceeds 2^30 raw units, costing that many low bits). float/double use the plain norm.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>

#include <curvestep/core/detail/checked.hpp>
#include <curvestep/core/geometry/vec.hpp>
#include <curvestep/core/result.hpp>

namespace curvestep {

/// How interpolation parameters are spaced.
enum class Parametrization : std::uint8_t {
  Uniform,      ///< u_{i+1} − u_i = 1
  ChordLength,  ///< u_{i+1} − u_i = |p_{i+1} − p_i|
  Centripetal,  ///< u_{i+1} − u_i = sqrt(|p_{i+1} − p_i|)
};

/// Whether a point sequence is an open curve or a closed loop (the last point joins the first).
enum class Closure : std::uint8_t {
  Open,    ///< n points, n knots
  Closed,  ///< n points, n + 1 knots (the last for the closing chord p_{n-1} -> p_0)
};

/// |a − b| without intermediate overflow. FixedOverflow if the distance itself is out of range.
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr Result<S> checked_distance(const Vec<S, Dim>& a, const Vec<S, Dim>& b) noexcept {
  if constexpr (FixedPoint<S>) {
    static_assert(Dim <= 8, "checked_distance sums at most 8 squares of 60 bits in 64 bits");
    std::array<std::uint64_t, Dim> magnitude{};
    std::uint64_t largest = 0;
    for (std::size_t i = 0; i < Dim; ++i) {
      const std::int64_t difference = std::int64_t{a[i].raw()} - std::int64_t{b[i].raw()};
      magnitude[i] = static_cast<std::uint64_t>(difference < 0 ? -difference : difference);
      if (magnitude[i] > largest) largest = magnitude[i];
    }
    int shift = 0;
    while ((largest >> shift) >= (std::uint64_t{1} << 30)) ++shift;
    std::uint64_t sum = 0;
    for (std::size_t i = 0; i < Dim; ++i) {
      const std::uint64_t m = magnitude[i] >> shift;
      sum += m * m;
    }
    // Round to nearest: root of 4·sum is twice the root; add one and halve.
    std::uint64_t root = 0;
    if (sum < (std::uint64_t{1} << 62)) {
      root = (detail::integer_sqrt(sum << 2) + 1) >> 1;
    } else {
      root = detail::integer_sqrt(sum);
    }
    const std::uint64_t scaled = root << shift;
    if (scaled > static_cast<std::uint64_t>(std::numeric_limits<typename S::rep>::max())) return fail(Error::FixedOverflow);
    return S::from_raw(static_cast<typename S::rep>(scaled));
  } else {
    S largest{};
    for (std::size_t i = 0; i < Dim; ++i) {
      const S c = abs(a[i] - b[i]);
      if (c > largest) largest = c;
    }
    if (largest == S{}) return S{};
    S sum{};
    for (std::size_t i = 0; i < Dim; ++i) {
      const S c = (a[i] - b[i]) / largest;
      sum += c * c;
    }
    const S d = largest * sqrt(sum);
    if (!is_finite(d)) return fail(Error::NotFinite);
    return d;
  }
}

/// The parameter step from p to q for a parametrization (uniform: 1). DegenerateCurve if p == q
/// for chord-length or centripetal spacing (index = `index`).
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr Result<S> parameter_step(const Vec<S, Dim>& p, const Vec<S, Dim>& q, Parametrization kind,
                                                 std::size_t index) noexcept {
  if (kind == Parametrization::Uniform) return from_int<S>(1);
  CURVESTEP_TRY(const S d, checked_distance(p, q));
  if (d == S{}) return fail(Error::DegenerateCurve, index);
  if (kind == Parametrization::ChordLength) return d;
  return sqrt(d);
}

/// Writes u_0 = 0, u_1, …, u_{n-1} for the n points into `knots` (open curve); Closure::Closed
/// also writes u_n for the closing chord back to points[0] (n + 1 knots). Returns the number written.
/// TooFewPoints for fewer than 2 points, BufferTooSmall if `knots` is short, DegenerateCurve for
/// coincident consecutive points (non-uniform), FixedOverflow/NotFinite if the sum leaves the range.
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr Result<std::size_t> parametrize(std::span<const Vec<S, Dim>> points, Parametrization kind,
                                                        std::span<S> knots, Closure closure = Closure::Open) noexcept {
  const std::size_t n = points.size();
  if (n < 2) return fail(Error::TooFewPoints, n);
  const std::size_t count = closure == Closure::Closed ? n + 1 : n;
  if (knots.size() < count) return fail(Error::BufferTooSmall, count);
  knots[0] = S{};
  for (std::size_t i = 1; i < count; ++i) {
    const std::size_t to = i == n ? 0 : i;
    CURVESTEP_TRY(const S step, parameter_step(points[i - 1], points[to], kind, i));
    const auto next = checked_add(knots[i - 1], step);
    if (!next) return fail(next.error(), i);
    knots[i] = next.value();
  }
  return count;
}

namespace detail {
/// For the interpolators that take a Parametrization: the knots of `points` from `kind` (at most
/// MaxSegments + 1, on the stack), handed to `interpolate` as a span; parametrize's errors.
template <std::size_t MaxSegments, Scalar S, std::size_t Dim, class Interpolate>
[[nodiscard]] constexpr Result<void> with_parametrized_knots(std::span<const Vec<S, Dim>> points, Parametrization kind,
                                                             Closure closure, const Interpolate& interpolate) noexcept {
  std::array<S, MaxSegments + 1> knots{};
  CURVESTEP_TRY(const std::size_t count, parametrize(points, kind, std::span<S>(knots), closure));
  return interpolate(std::span<const S>(knots.data(), count));
}
}  // namespace detail

}  // namespace curvestep
