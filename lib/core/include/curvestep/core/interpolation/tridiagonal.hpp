// SPDX-License-Identifier: MIT
// O(n) solvers for tridiagonal and cyclic tridiagonal systems (Thomas, Sherman–Morrison), no inverse.
//
// Row i of the system reads  lower[i]·x[i-1] + diagonal[i]·x[i] + upper[i]·x[i+1] = d[i].
// In the open form lower[0] and upper[n-1] are ignored; in the cyclic form lower[0] multiplies
// x[n-1] and upper[n-1] multiplies x[0] (the corners of a periodic spline's matrix).
//
// Thomas algorithm (Gaussian elimination without pivoting on the band):
//   w_0 = b_0,  w_i = b_i − a_i·c'_{i−1},  c'_i = c_i / w_i,  d'_i = (d_i − a_i·d'_{i−1}) / w_i,
//   x_{n−1} = d'_{n−1},  x_i = d'_i − c'_i·x_{i+1}.
// For a strictly diagonally dominant matrix (|b_i| > |a_i| + |c_i|, which every spline system in
// this library is) all pivots satisfy |w_i| > |b_i| − |a_i| > 0, elimination is backward stable
// and the error growth is bounded by the dominance margin: with unit roundoff ε the computed x
// solves (A + E)x = d with |E| <= ~5ε|A| componentwise (Higham, §9.5). In Q16.16 every division
// and product rounds to half a raw unit; for the spline systems (diagonal 2 or 4, off-diagonal
// sums <= the diagonal / 2) the solution error stays within a few raw units times |x|.
//
// The cyclic system is solved with the Sherman–Morrison formula: write A = A' + u vᵀ with
// u = (γ, 0, …, 0, α), v = (1, 0, …, 0, β/γ), α = A[n−1][0], β = A[0][n−1], γ = −b_0; A' is
// tridiagonal (diagonal b_0 − γ and b_{n−1} − αβ/γ at the ends). Solve A'y = d and A'z = u, then
// x = y − ((y_0 + β·y_{n−1}/γ) / (1 + z_0 + β·z_{n−1}/γ))·z. Two Thomas sweeps, O(n).
//
// A pivot (or the Sherman–Morrison denominator) smaller than 16 units of the scalar's resolution
// times the row's magnitude |a_i| + |b_i| + |c_i| means the system is singular or too
// ill-conditioned for the scalar type: Error::SingularSystem with the row index.
// The matrix is shared by all coordinates, so vector right-hand sides are solved per coordinate
// in the same sweep: the pivots are computed once.
#pragma once

#include <cstddef>
#include <span>

#include <curvestep/core/detail/checked.hpp>
#include <curvestep/core/geometry/vec.hpp>
#include <curvestep/core/result.hpp>

namespace curvestep {

namespace detail {

/// Number of scalar components of a right-hand-side entry (a scalar or a Vec).
template <Scalar S>
[[nodiscard]] constexpr std::size_t rhs_component_count(const S&) noexcept {
  return 1;
}
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr std::size_t rhs_component_count(const Vec<S, Dim>&) noexcept {
  return Dim;
}
template <Scalar S>
[[nodiscard]] constexpr S& rhs_component(S& value, std::size_t) noexcept {
  return value;
}
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr S& rhs_component(Vec<S, Dim>& value, std::size_t axis) noexcept {
  return value[axis];
}

/// True when |pivot| is too small against the row magnitude to divide by safely.
template <Scalar S>
[[nodiscard]] constexpr bool negligible_pivot(S pivot, S row_magnitude) noexcept {
  // 16·resolution first: with Fixed, resolution·|row| alone would round to zero for |row| < ½.
  const Checked<S> threshold = Checked<S>(resolution<S>()) * Checked<S>(from_int<S>(16)) * Checked<S>(row_magnitude);
  if (!threshold.ok) return false;  // a huge row: the pivot test below is moot, overflow is caught later
  return !(threshold.value < abs(pivot)) || pivot == S{};
}

/// Thomas sweep over n rows given coefficient accessors; x holds d on entry and the solution on exit.
/// `scratch` receives c'_i (size >= n).
template <Scalar S, class Value, class Lower, class Diagonal, class Upper>
[[nodiscard]] constexpr Result<void> thomas_sweep(std::size_t n, Lower lower, Diagonal diagonal, Upper upper,
                                                  std::span<Value> x, std::span<S> scratch) noexcept {
  if (n == 0) return ok();
  for (std::size_t i = 0; i < n; ++i) {
    const S a = i == 0 ? S{} : lower(i);
    const S c = i + 1 == n ? S{} : upper(i);
    Checked<S> pivot = Checked<S>(diagonal(i));
    if (i > 0) pivot = pivot - Checked<S>(a) * Checked<S>(scratch[i - 1]);
    CURVESTEP_TRY(const S w, pivot.result());
    const Checked<S> magnitude = Checked<S>(abs(a)) + Checked<S>(abs(diagonal(i))) + Checked<S>(abs(c));
    CURVESTEP_TRY(const S row_magnitude, magnitude.result());
    if (negligible_pivot(w, row_magnitude)) return fail(Error::SingularSystem, i);
    CURVESTEP_TRY(scratch[i], (Checked<S>(c) / Checked<S>(w)).result());
    for (std::size_t axis = 0; axis < rhs_component_count(x[i]); ++axis) {
      Checked<S> d = Checked<S>(rhs_component(x[i], axis));
      if (i > 0) d = d - Checked<S>(a) * Checked<S>(rhs_component(x[i - 1], axis));
      CURVESTEP_TRY(rhs_component(x[i], axis), (d / Checked<S>(w)).result());
    }
  }
  for (std::size_t i = n - 1; i-- > 0;) {
    for (std::size_t axis = 0; axis < rhs_component_count(x[i]); ++axis) {
      const Checked<S> v = Checked<S>(rhs_component(x[i], axis)) - Checked<S>(scratch[i]) * Checked<S>(rhs_component(x[i + 1], axis));
      CURVESTEP_TRY(rhs_component(x[i], axis), v.result());
    }
  }
  return ok();
}

}  // namespace detail

/// Solves the tridiagonal system in place: `values` holds the right-hand sides d_i (scalars or
/// Vec, one solve per coordinate) and receives x. lower[0] and upper[n-1] are ignored.
/// `scratch` needs n scalars (BufferTooSmall otherwise). SingularSystem (index = row) for a zero
/// or negligible pivot; FixedOverflow/NotFinite if a result leaves the range.
/// Contract: lower, diagonal, upper and values have the same size.
template <Scalar S, class Value>
[[nodiscard]] constexpr Result<void> solve_tridiagonal(std::span<const S> lower, std::span<const S> diagonal,
                                                       std::span<const S> upper, std::span<Value> values,
                                                       std::span<S> scratch) noexcept {
  const std::size_t n = diagonal.size();
  CURVESTEP_EXPECTS(lower.size() == n && upper.size() == n && values.size() == n);
  if (scratch.size() < n) return fail(Error::BufferTooSmall, n);
  return detail::thomas_sweep<S>(
      n, [&](std::size_t i) { return lower[i]; }, [&](std::size_t i) { return diagonal[i]; },
      [&](std::size_t i) { return upper[i]; }, values, scratch);
}

/// Solves the cyclic tridiagonal system in place (lower[0] multiplies x[n-1], upper[n-1]
/// multiplies x[0]) by Sherman–Morrison. `scratch` needs 2n scalars (BufferTooSmall otherwise).
/// n = 1 and n = 2 are solved directly. SingularSystem (index = row) for a singular or
/// ill-conditioned matrix. Contract: all spans have the same size.
template <Scalar S, class Value>
[[nodiscard]] constexpr Result<void> solve_cyclic_tridiagonal(std::span<const S> lower, std::span<const S> diagonal,
                                                              std::span<const S> upper, std::span<Value> values,
                                                              std::span<S> scratch) noexcept {
  using detail::Checked;
  using detail::rhs_component;
  using detail::rhs_component_count;
  const std::size_t n = diagonal.size();
  CURVESTEP_EXPECTS(lower.size() == n && upper.size() == n && values.size() == n);
  if (scratch.size() < 2 * n) return fail(Error::BufferTooSmall, 2 * n);
  if (n == 0) return ok();
  if (n == 1) {
    CURVESTEP_TRY(const S b, (Checked<S>(diagonal[0]) + Checked<S>(lower[0]) + Checked<S>(upper[0])).result());
    const S magnitude = abs(diagonal[0]) + abs(lower[0]) + abs(upper[0]);
    if (detail::negligible_pivot(b, magnitude)) return fail(Error::SingularSystem, 0);
    for (std::size_t axis = 0; axis < rhs_component_count(values[0]); ++axis) {
      CURVESTEP_TRY(rhs_component(values[0], axis), (Checked<S>(rhs_component(values[0], axis)) / Checked<S>(b)).result());
    }
    return ok();
  }
  if (n == 2) {
    // [b0, a0 + c0; a1 + c1, b1] by Cramer's rule.
    const Checked<S> m00(diagonal[0]);
    const Checked<S> m01 = Checked<S>(lower[0]) + Checked<S>(upper[0]);
    const Checked<S> m10 = Checked<S>(lower[1]) + Checked<S>(upper[1]);
    const Checked<S> m11(diagonal[1]);
    CURVESTEP_TRY(const S determinant, (m00 * m11 - m01 * m10).result());
    CURVESTEP_TRY(const S scale, (Checked<S>(abs(m00.value)) * Checked<S>(abs(m11.value)) +
                                  Checked<S>(abs(m01.value)) * Checked<S>(abs(m10.value)))
                                     .result());
    if (detail::negligible_pivot(determinant, scale)) return fail(Error::SingularSystem, 1);
    for (std::size_t axis = 0; axis < rhs_component_count(values[0]); ++axis) {
      const Checked<S> d0(rhs_component(values[0], axis));
      const Checked<S> d1(rhs_component(values[1], axis));
      CURVESTEP_TRY(const S x0, ((d0 * m11 - m01 * d1) / Checked<S>(determinant)).result());
      CURVESTEP_TRY(const S x1, ((m00 * d1 - d0 * m10) / Checked<S>(determinant)).result());
      rhs_component(values[0], axis) = x0;
      rhs_component(values[1], axis) = x1;
    }
    return ok();
  }
  const S alpha = upper[n - 1];
  const S beta = lower[0];
  const S gamma = -diagonal[0];
  if (gamma == S{}) return fail(Error::SingularSystem, 0);
  CURVESTEP_TRY(const S first_diagonal, (Checked<S>(diagonal[0]) - Checked<S>(gamma)).result());
  CURVESTEP_TRY(const S last_diagonal,
                (Checked<S>(diagonal[n - 1]) - Checked<S>(alpha) * Checked<S>(beta) / Checked<S>(gamma)).result());
  const auto lower_of = [&](std::size_t i) { return lower[i]; };
  const auto upper_of = [&](std::size_t i) { return upper[i]; };
  const auto diagonal_of = [&](std::size_t i) {
    if (i == 0) return first_diagonal;
    if (i + 1 == n) return last_diagonal;
    return diagonal[i];
  };
  std::span<S> coefficients = scratch.first(n);
  std::span<S> z = scratch.subspan(n, n);
  CURVESTEP_CHECK(detail::thomas_sweep<S>(n, lower_of, diagonal_of, upper_of, values, coefficients));
  for (std::size_t i = 0; i < n; ++i) z[i] = S{};
  z[0] = gamma;
  z[n - 1] = alpha;
  CURVESTEP_CHECK(detail::thomas_sweep<S>(n, lower_of, diagonal_of, upper_of, z, coefficients));
  const Checked<S> denominator =
      Checked<S>(from_int<S>(1)) + Checked<S>(z[0]) + Checked<S>(beta) * Checked<S>(z[n - 1]) / Checked<S>(gamma);
  CURVESTEP_TRY(const S divisor, denominator.result());
  if (detail::negligible_pivot(divisor, from_int<S>(1))) return fail(Error::SingularSystem, n - 1);
  for (std::size_t axis = 0; axis < rhs_component_count(values[0]); ++axis) {
    const Checked<S> numerator = Checked<S>(rhs_component(values[0], axis)) +
                                 Checked<S>(beta) * Checked<S>(rhs_component(values[n - 1], axis)) / Checked<S>(gamma);
    CURVESTEP_TRY(const S factor, (numerator / Checked<S>(divisor)).result());
    for (std::size_t i = 0; i < n; ++i) {
      const Checked<S> corrected = Checked<S>(rhs_component(values[i], axis)) - Checked<S>(factor) * Checked<S>(z[i]);
      CURVESTEP_TRY(rhs_component(values[i], axis), corrected.result());
    }
  }
  return ok();
}

}  // namespace curvestep
