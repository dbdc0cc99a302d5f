// SPDX-License-Identifier: MIT
// HermiteChunk: the setpoints of a run of ticks ("chunk") stepped by forward differencing between
// two exact evaluations of the path, within a documented bound (docs/motion.md, "Per-tick work").
// Only +, -, *, / in double, in the same order on every target: the stepped setpoints are
// bit-identical in the simulator and in a firmware.
//
// The exact setpoint at tick k is x(t_k) = p(u(s(t_k))): profile, arc-length table, curve. Inside
// one segment and one profile phase x(t) is smooth, so a chunk of N ticks (N a power of two,
// duration h = N Δt) is replaced by the quintic Hermite H(σ), σ = (t - t_0)/h in [0,1], that
// matches position, velocity and acceleration of the exact path at both ends:
//     Bézier control points  P0 = x0,  P1 = x0 + h v0/5,  P2 = x0 + 2h v0/5 + h² a0/20,
//                            P3 = x1 - 2h v1/5 + h² a1/20,  P4 = x1 - h v1/5,  P5 = x1
// (B'(0) = 5(P1-P0)/h, B''(0) = 20(P2-2P1+P0)/h², and mirrored at σ = 1). Consecutive chunks
// share end states, so the stream is C2: numerically differentiated acceleration stays continuous.
// The control points are taken relative to x0 and stepped at σ = k/N by a forward-difference table
// (Δ⁰..Δ⁵ per axis, 5 additions per step), seeded with the power coefficients and Stirling weights
// of sampling/detail/difference_seed.hpp as ForwardDifference seeds its chunks; N is a power of two,
// so the seed's divisions by N^i are exact. ForwardDifference itself is not used: its create()
// chooses a re-seed interval from a proven bound (hodograph differences, std::pow), about 9000
// instructions per chunk here, more than the exact evaluations a chunk saves. Without re-seeding,
// after k <= N <= 256 steps the seed's roundings ε_j have grown to Σ_j C(k,j) ε_j <= Σ_j |ε_j| N^j/j!,
// and ε_j <= a few u Σ_i |a_i| j!S(i,j)/N^i with u = 2^-53 and |a_i| <= 2⁵ C(5,i) max|P - x0|: the
// stepping error stays below 10⁻¹² of the chunk's extent, far below chunk_error_bound (the tests
// measure the total). The setpoint is x0 + Δ⁰.
//
// Error. For smooth x the Hermite error is e(σ) = x⁽⁶⁾(ξ)/720 h⁶ σ³(1-σ)³, largest at σ = 1/2.
// With E = max|e| (per axis) and e = 64 E σ³(1-σ)³:  |e'| <= 3.44 E/h, |e''| <= 24 E/h²,
// |e'''| <= 384 E/h³. chunk_error_bound(N) is the largest E for which the setpoints are within
// 10⁻³ of the path tolerance and their numerically differentiated speed, acceleration and jerk
// change by at most 10⁻³ of v_max, a_max and j_max:
//     ε(N) = min(10⁻³ tol, 10⁻³ v_max h/3.44, 10⁻³ a_max h²/24, 10⁻³ j_max h³/384).
// The controller accepts a chunk only if the Hermite at σ = 1/2 is within ε(N)/4 of an exact
// evaluation there (a factor 4 for the variation of x⁽⁶⁾ across the chunk), and at σ = 1/4 and 3/4
// too when the chunk crosses a knot of the arc-length table (where the exact path is only C1, so
// the error need not peak in the middle); otherwise it halves N (the exact middle state becomes
// the new end). N = 1 is the exact path.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/core/motion/path_segment.hpp>
#include <curvestep/core/contract.hpp>
#include <curvestep/core/result.hpp>
#include <curvestep/core/sampling/detail/difference_seed.hpp>

namespace curvestep {

/// The exact path at one tick: position and its time derivatives.
struct PathTickState {
  MachinePoint position{};      ///< p(u(s(t))) (mm)
  MachinePoint velocity{};      ///< dx/dt (mm/s); valid if `smooth`
  MachinePoint acceleration{};  ///< d²x/dt² (mm/s²); valid if `smooth`
  double speed_mm_per_s = 0;    ///< the profile's speed (reported in the setpoint)
  bool smooth = false;          ///< velocity and acceleration are known and finite
  double tau_s = 0;             ///< where it was evaluated: segment time,
  double u = 0;                 ///< curve parameter,
  double ds_du = 0;             ///< and slope and curvature of the arc-length table's s(u) there
  double d2s_du2 = 0;
};

/// ε(N): the per-axis bound of |stepped setpoint - exact setpoint| for a chunk of `ticks` ticks
/// (see the header comment). Uses only +, -, *, /.
[[nodiscard]] inline double chunk_error_bound(std::uint32_t ticks, const MachineLimits& machine) noexcept {
  const double h = static_cast<double>(ticks) / machine.rate_hz;
  double bound = 1e-3 * machine.tolerance_mm;
  bound = std::fmin(bound, 1e-3 * machine.v_max_mm_per_s * h / 3.44);
  bound = std::fmin(bound, 1e-3 * machine.a_max_mm_per_s2 * h * h / 24);
  bound = std::fmin(bound, 1e-3 * machine.j_max_mm_per_s3 * h * h * h / 384);
  return bound;
}

/// One chunk: the quintic Hermite between two exact states, stepped tick by tick.
class HermiteChunk {
 public:
  using Controls = std::array<MachinePoint, 6>;

  /// Largest chunk (ticks) the controller may use.
  static constexpr std::uint32_t max_ticks = 256;

  /// Control points, relative to a.position, of the quintic Hermite from state a to state b over
  /// `duration_s` (both states smooth).
  [[nodiscard]] static Controls controls(const PathTickState& a, const PathTickState& b, double duration_s) noexcept {
    const double h = duration_s;
    const double h2 = h * h;
    Controls q{};
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      const double end = b.position[axis] - a.position[axis];
      q[0][axis] = 0;
      q[1][axis] = h * a.velocity[axis] / 5;
      q[2][axis] = 2 * h * a.velocity[axis] / 5 + h2 * a.acceleration[axis] / 20;
      q[3][axis] = end - 2 * h * b.velocity[axis] / 5 + h2 * b.acceleration[axis] / 20;
      q[4][axis] = end - h * b.velocity[axis] / 5;
      q[5][axis] = end;
    }
    return q;
  }

  /// The quintic at σ = 1/2, 1/4 and 3/4 (relative to the start): the Bernstein weights of degree 5
  /// there, (1 5 10 10 5 1)/32 and (243 405 270 90 15 1)/1024 (reversed for 3/4), are exact in double.
  [[nodiscard]] static MachinePoint at_half(const Controls& q) noexcept { return weighted(q, {1, 5, 10, 10, 5, 1}, 32); }
  [[nodiscard]] static MachinePoint at_quarter(const Controls& q) noexcept { return weighted(q, {243, 405, 270, 90, 15, 1}, 1024); }
  [[nodiscard]] static MachinePoint at_three_quarters(const Controls& q) noexcept {
    return weighted(q, {1, 15, 90, 270, 405, 243}, 1024);
  }

  /// Starts stepping the quintic `q` (relative to `origin`) in `ticks` steps, ticks a power of two
  /// <= max_ticks (contract). NotFinite if a control point or a difference is not finite.
  [[nodiscard]] Result<void> start(const MachinePoint& origin, const Controls& q, std::uint32_t ticks) noexcept {
    CURVESTEP_EXPECTS(ticks >= 1 && ticks <= max_ticks && (ticks & (ticks - 1)) == 0);
    // Δʲ(0) = Σ_{i>=j} a_i j! S(i,j) / N^i with a_i the power coefficients (difference_seed.hpp);
    // N is a power of two, so 1/N^i is exact.
    const double step = 1.0 / static_cast<double>(ticks);
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      std::array<double, 6> control{};
      for (std::size_t i = 0; i < 6; ++i) control[i] = q[i][axis];
      const auto a = detail::power_coefficients(control, 5);
      std::array<double, 6> scaled{};  // a_i / N^i
      double power = 1;
      for (std::size_t i = 0; i < 6; ++i) {
        scaled[i] = a[i] * power;
        power *= step;
      }
      table_[axis][0] = scaled[0];
      for (std::size_t j = 1; j < 6; ++j) {
        double sum = 0;
        for (std::size_t i = j; i < 6; ++i) sum += scaled[i] * static_cast<double>(detail::stirling_difference_weights[i][j]);
        if (!std::isfinite(sum)) return fail(Error::NotFinite);
        table_[axis][j] = sum;
      }
    }
    origin_ = origin;
    return ok();
  }

  /// The next tick's setpoint position: origin + the quintic at the next step, by 5 additions per
  /// axis (and one to add the origin). Contract: fewer than `ticks` steps taken since start().
  [[nodiscard]] MachinePoint next() noexcept {
    MachinePoint p;
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      auto& d = table_[axis];
      d[0] += d[1];
      d[1] += d[2];
      d[2] += d[3];
      d[3] += d[4];
      d[4] += d[5];
      p[axis] = origin_[axis] + d[0];
    }
    return p;
  }

 private:
  [[nodiscard]] static MachinePoint weighted(const Controls& q, const std::array<double, 6>& w, double total) noexcept {
    MachinePoint m{};
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      double sum = 0;
      for (std::size_t i = 0; i < 6; ++i) sum += w[i] * q[i][axis];
      m[axis] = sum / total;
    }
    return m;
  }

  std::array<std::array<double, 6>, motion_axes> table_{};  ///< per axis: Δ⁰..Δ⁵ of the offset from origin_
  MachinePoint origin_{};
};

}  // namespace curvestep
