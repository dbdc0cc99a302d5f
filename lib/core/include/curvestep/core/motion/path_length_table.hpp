// SPDX-License-Identifier: MIT
// PathLengthTable: arc length s(u) of a path segment and its inverse u(s), so feed follows arc length.
//
// The segment's parameter range [0,1] is cut into Intervals equal pieces; the length of each piece
// is the 5-point Gauss–Legendre integral of |p'(u)| (exact for polynomial speed of degree 9; on
// 1/Intervals of a smooth curve its relative error is far below 1e-12). Inside a piece s(u) is the
// cubic Hermite interpolant through (u_k, s_k) with slopes |p'(u_k)| (error O(h^4), and well
// behaved where |p'| vanishes at a cusp, unlike the inverse u(s) whose slope is infinite there);
// u(s) inverts that cubic by Newton's method inside a bisection bracket (at most 40 steps);
// locate(s) also gives S'(u) and S''(u) of that cubic, for the interpolator's chain rule. The
// cubics meet with matching slopes but not curvatures: the path the table defines is C1 in s.
// Everything is +, -, *, /, sqrt in double: the same bits on every target.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

#include <curvestep/core/curve/arc_length.hpp>
#include <curvestep/core/motion/path_segment.hpp>

namespace curvestep {

/// Arc-length table of one segment with Intervals pieces.
template <std::size_t Intervals = 64>
class PathLengthTable {
  static_assert(Intervals >= 2, "an arc-length table needs at least two intervals");

 public:
  constexpr PathLengthTable() = default;

  /// Builds the table for `segment`. DegenerateCurve if the segment has zero length.
  [[nodiscard]] static Result<PathLengthTable> build(const PathSegment& segment) {
    Result<PathLengthTable> out(std::in_place);  // filled in place and returned by name: no 1 KiB copy
    PathLengthTable& table = out.value();
    double s = 0;
    table.length_[0] = 0;
    table.speed_[0] = norm(segment.derivative(0, 1));
    for (std::size_t k = 0; k < Intervals; ++k) {
      const double a = static_cast<double>(k) / Intervals;
      const double b = static_cast<double>(k + 1) / Intervals;
      const double half = (b - a) / 2;
      const double middle = a + half;
      double sum = 0;
      for (std::size_t g = 0; g < 5; ++g) {
        double u = middle + half * detail::gauss_legendre_5_nodes[g];
        if (u < 0) u = 0;
        if (u > 1) u = 1;
        sum += detail::gauss_legendre_5_weights[g] * norm(segment.derivative(u, 1));
      }
      s += sum * half;
      table.length_[k + 1] = s;
      table.speed_[k + 1] = norm(segment.derivative(b, 1));
    }
    if (!(s > 0) || !std::isfinite(s)) out = fail(Error::DegenerateCurve);
    return out;
  }

  /// Total arc length (mm).
  [[nodiscard]] constexpr double length() const noexcept { return length_[Intervals]; }

  /// u(s) and the derivatives of the table's s(u) there, for the chain rule of the interpolator.
  struct Located {
    double u = 0;        ///< parameter_at(s), bit for bit
    double ds_du = 0;    ///< dS/du of the table's piecewise cubic at u (|p'(u)| up to O(h^4))
    double d2s_du2 = 0;  ///< d²S/du² of that cubic on the piece holding u
  };

  /// The parameter u in [0,1] at arc length s (clamped to [0, length()]).
  [[nodiscard]] constexpr double parameter_at(double s) const noexcept {
    std::size_t piece = 0;
    double x = 0;
    return find(s, piece, x);
  }

  /// parameter_at(s) with the slope and curvature of the table's s(u) there: the exact path
  /// u(t) of the interpolator satisfies S(u(t)) = s(t), so du/dt = v / S'(u) and
  /// d²u/dt² = (a - S''(u) (du/dt)²) / S'(u). s <= 0 and s >= length() use the first and last
  /// piece; a piece of zero length gives zero rates.
  [[nodiscard]] constexpr Located locate(double s) const noexcept {
    std::size_t piece = 0;
    double x = 0;
    const double u = find(s, piece, x);
    // S(u) = s_k + H(x), x = (u - u_k) Intervals: S' = H'(x) Intervals, S'' = H''(x) Intervals².
    const double h = length_[piece + 1] - length_[piece];
    if (!(h > 0)) return Located{u, 0, 0};
    const double m0 = speed_[piece] * (1.0 / Intervals);
    const double m1 = speed_[piece + 1] * (1.0 / Intervals);
    const double x2 = x * x;
    const double slope = (3 * x2 - 4 * x + 1) * m0 + (-6 * x2 + 6 * x) * h + (3 * x2 - 2 * x) * m1;
    const double bend = (6 * x - 4) * m0 + (-12 * x + 6) * h + (6 * x - 2) * m1;
    constexpr double intervals = static_cast<double>(Intervals);
    return Located{u, slope * intervals, bend * intervals * intervals};
  }

  /// The arc length at parameter u in [0,1] (linear between the table's knots is not used:
  /// the piece containing u is integrated again with Gauss–Legendre).
  [[nodiscard]] double length_at(const PathSegment& segment, double u) const {
    if (!(u > 0)) return 0;
    if (u >= 1) return length();
    const auto k = static_cast<std::size_t>(u * Intervals);
    const double a = static_cast<double>(k) / Intervals;
    const double half = (u - a) / 2;
    double sum = 0;
    for (std::size_t g = 0; g < 5; ++g) {
      sum += detail::gauss_legendre_5_weights[g] * norm(segment.derivative(a + half + half * detail::gauss_legendre_5_nodes[g], 1));
    }
    return length_[k] + sum * half;
  }

 private:
  /// u(s) (clamped), and the piece and local x in [0,1] it lies at.
  [[nodiscard]] constexpr double find(double s, std::size_t& piece, double& x) const noexcept {
    if (!(s > 0)) {
      piece = 0;
      x = 0;
      return 0;
    }
    if (s >= length()) {
      piece = Intervals - 1;
      x = 1;
      return 1;
    }
    std::size_t low = 0;
    std::size_t high = Intervals;
    while (high - low > 1) {
      const std::size_t middle = (low + high) / 2;
      if (length_[middle] <= s) {
        low = middle;
      } else {
        high = middle;
      }
    }
    piece = low;
    const double h = length_[low + 1] - length_[low];
    const double du = 1.0 / Intervals;
    const double u0 = static_cast<double>(low) * du;
    x = 0;
    if (!(h > 0)) return u0;
    x = solve_piece(low, s - length_[low]);
    return u0 + x * du;
  }

  /// x in [0,1] with H(x) = target on piece `low` (h > 0): s(u) on the piece as the cubic Hermite
  /// H(x), x = (u - u0)/du, through (0, 0) and (1, h) with slopes |p'| du; Newton's method kept
  /// inside a bisection bracket.
  [[nodiscard]] constexpr double solve_piece(std::size_t low, double target) const noexcept {
    const double h = length_[low + 1] - length_[low];
    const double du = 1.0 / Intervals;
    const double m0 = speed_[low] * du;
    const double m1 = speed_[low + 1] * du;
    auto value = [&](double x) {
      const double x2 = x * x;
      const double x3 = x2 * x;
      return (x3 - 2 * x2 + x) * m0 + (-2 * x3 + 3 * x2) * h + (x3 - x2) * m1;
    };
    auto slope = [&](double x) {
      const double x2 = x * x;
      return (3 * x2 - 4 * x + 1) * m0 + (-6 * x2 + 6 * x) * h + (3 * x2 - 2 * x) * m1;
    };
    double low_x = 0;
    double high_x = 1;
    double x = target / h;
    for (int i = 0; i < 40; ++i) {
      const double f = value(x) - target;
      if (f > 0) {
        high_x = x;
      } else {
        low_x = x;
      }
      if (std::fabs(f) <= 1e-13 * h) break;
      const double d = slope(x);
      double next = d > 0 ? x - f / d : (low_x + high_x) / 2;
      if (!(next > low_x && next < high_x)) next = (low_x + high_x) / 2;
      x = next;
    }
    return x;
  }

  std::array<double, Intervals + 1> length_{};  ///< s at u = k / Intervals
  std::array<double, Intervals + 1> speed_{};   ///< |p'(u)| at u = k / Intervals
};

}  // namespace curvestep
