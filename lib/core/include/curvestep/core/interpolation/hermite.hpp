// SPDX-License-Identifier: MIT
// Cubic Hermite (Ferguson) segments: the Hermite basis, evaluation, Bézier and power forms.
//
// Given end points p0, p1 and end tangents v0, v1, the cubic with r(0) = p0, r(1) = p1,
// r'(0) = v0, r'(1) = v1 is (seed 000 §3.2, seed 003)
//   r(t) = G0(t)·p0 + G1(t)·p1 + H0(t)·v0 + H1(t)·v1,
//   G0 = 1 − 3t² + 2t³,  G1 = 3t² − 2t³,  H0 = t − 2t² + t³,  H1 = t³ − t²,
// and its Bézier control points are p0, p0 + v0/3, p1 − v1/3, p1. In the power form (Ferguson,
// seed 003) r(t) = A0 + A1 t + A2 t² + A3 t³ with A0 = p0, A1 = v0, A2 = 3(p1 − p0) − 2v0 − v1,
// A3 = 2(p0 − p1) + v0 + v1.
// On a global interval [a, b] the local parameter is s = (u − a)/(b − a); the tangents with
// respect to u must be multiplied by h = b − a before they enter the [0,1] formulas, so the
// inner Bézier points become p0 + h·v0/3 and p1 − h·v1/3.
//
// Error bounds: the basis values are polynomials in t ∈ [0,1] evaluated with checked operations
// (Fixed: at most 4 roundings of half a raw unit each, |G|,|H| <= 1). The Bézier points round
// once per product and once per division by 3. Tangents large enough to leave the Q range give
// FixedOverflow instead of a wrapped value.
#pragma once

#include <array>
#include <cstddef>
#include <span>

#include <curvestep/core/curve/bezier.hpp>
#include <curvestep/core/curve/power_basis.hpp>
#include <curvestep/core/detail/checked.hpp>

namespace curvestep {

/// The four cubic Hermite basis values at one parameter.
template <Scalar S>
struct HermiteBasis {
  S start_point{};    ///< G0: weight of p0
  S end_point{};      ///< G1: weight of p1
  S start_tangent{};  ///< H0: weight of v0
  S end_tangent{};    ///< H1: weight of v1
};

/// G0, G1, H0, H1 at t ∈ [0,1]; ParameterOutOfRange otherwise.
template <Scalar S>
[[nodiscard]] constexpr Result<HermiteBasis<S>> hermite_basis(S t) noexcept {
  if (t < S{} || from_int<S>(1) < t) return fail(Error::ParameterOutOfRange);
  using detail::Checked;
  const Checked<S> x(t);
  const Checked<S> one(from_int<S>(1));
  const Checked<S> two(from_int<S>(2));
  const Checked<S> three(from_int<S>(3));
  const Checked<S> square = x * x;
  const Checked<S> cube = square * x;
  HermiteBasis<S> basis;
  CURVESTEP_TRY(basis.end_point, (three * square - two * cube).result());
  CURVESTEP_TRY(basis.start_point, (one - Checked<S>(basis.end_point)).result());
  CURVESTEP_TRY(basis.start_tangent, (x - two * square + cube).result());
  CURVESTEP_TRY(basis.end_tangent, (cube - square).result());
  return basis;
}

/// Second derivatives G0'', G1'', H0'', H1'' at t ∈ [0,1]: 12t − 6, 6 − 12t, 6t − 4, 6t − 2.
template <Scalar S>
[[nodiscard]] constexpr Result<HermiteBasis<S>> hermite_basis_second_derivative(S t) noexcept {
  if (t < S{} || from_int<S>(1) < t) return fail(Error::ParameterOutOfRange);
  using detail::Checked;
  const Checked<S> x(t);
  const Checked<S> six_t = Checked<S>(from_int<S>(6)) * x;
  HermiteBasis<S> basis;
  CURVESTEP_TRY(basis.start_point, (Checked<S>(from_int<S>(2)) * six_t - Checked<S>(from_int<S>(6))).result());
  CURVESTEP_TRY(basis.end_point, (Checked<S>(from_int<S>(6)) - Checked<S>(from_int<S>(2)) * six_t).result());
  CURVESTEP_TRY(basis.start_tangent, (six_t - Checked<S>(from_int<S>(4))).result());
  CURVESTEP_TRY(basis.end_tangent, (six_t - Checked<S>(from_int<S>(2))).result());
  return basis;
}

/// r(t) = G0 p0 + G1 p1 + H0 v0 + H1 v1 for t ∈ [0,1] (direct basis evaluation).
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr Result<Vec<S, Dim>> hermite_point(const Vec<S, Dim>& p0, const Vec<S, Dim>& p1, const Vec<S, Dim>& v0,
                                                          const Vec<S, Dim>& v1, S t) noexcept {
  using detail::Checked;
  CURVESTEP_TRY(const auto basis, hermite_basis(t));
  Vec<S, Dim> r;
  for (std::size_t i = 0; i < Dim; ++i) {
    const Checked<S> value = Checked<S>(basis.start_point) * Checked<S>(p0[i]) + Checked<S>(basis.end_point) * Checked<S>(p1[i]) +
                             Checked<S>(basis.start_tangent) * Checked<S>(v0[i]) + Checked<S>(basis.end_tangent) * Checked<S>(v1[i]);
    CURVESTEP_TRY(r[i], value.result());
  }
  return r;
}

/// The Bézier form (local parameter on [0,1]) of the Hermite segment on [a, b] whose tangents
/// v0, v1 are derivatives with respect to u: p0, p0 + h v0/3, p1 − h v1/3, p1 with h = b − a.
/// InvalidInterval if b <= a; FixedOverflow/NotFinite (index = control point).
template <Scalar S, std::size_t Dim, std::size_t MaxDegree = 3>
  requires(MaxDegree >= 3)
[[nodiscard]] constexpr Result<Bezier<S, Dim, MaxDegree>> hermite_to_bezier(const Vec<S, Dim>& p0, const Vec<S, Dim>& p1,
                                                                            const Vec<S, Dim>& v0, const Vec<S, Dim>& v1, S a,
                                                                            S b) noexcept {
  using detail::Checked;
  if (!(a < b)) return fail(Error::InvalidInterval);
  CURVESTEP_TRY(const S h, checked_sub(b, a));
  const Checked<S> three(from_int<S>(3));
  std::array<Vec<S, Dim>, 4> control{p0, {}, {}, p1};
  for (std::size_t i = 0; i < Dim; ++i) {
    const Checked<S> start = Checked<S>(v0[i]) * Checked<S>(h);
    const Checked<S> end = Checked<S>(v1[i]) * Checked<S>(h);
    const auto inner_start = (Checked<S>(p0[i]) + start / three).result();
    if (!inner_start) return fail(inner_start.error(), 1);
    control[1][i] = inner_start.value();
    const auto inner_end = (Checked<S>(p1[i]) - end / three).result();
    if (!inner_end) return fail(inner_end.error(), 2);
    control[2][i] = inner_end.value();
  }
  return Bezier<S, Dim, MaxDegree>::create(std::span<const Vec<S, Dim>>(control.data(), control.size()));
}

/// The Bézier form of the Hermite segment on [0,1]: p0, p0 + v0/3, p1 − v1/3, p1.
/// FixedOverflow/NotFinite (index = control point) if an inner point leaves the range.
template <Scalar S, std::size_t Dim, std::size_t MaxDegree = 3>
  requires(MaxDegree >= 3)
[[nodiscard]] constexpr Result<Bezier<S, Dim, MaxDegree>> hermite_to_bezier(const Vec<S, Dim>& p0, const Vec<S, Dim>& p1,
                                                                            const Vec<S, Dim>& v0, const Vec<S, Dim>& v1) noexcept {
  return hermite_to_bezier<S, Dim, MaxDegree>(p0, p1, v0, v1, S{}, from_int<S>(1));
}

/// The Ferguson power form A0 + A1 t + A2 t² + A3 t³ of the Hermite segment on [0,1] (seed 003).
template <Scalar S, std::size_t Dim, std::size_t MaxDegree = 3>
  requires(MaxDegree >= 3)
[[nodiscard]] constexpr Result<PowerBasis<S, Dim, MaxDegree>> ferguson_coefficients(const Vec<S, Dim>& p0, const Vec<S, Dim>& p1,
                                                                                    const Vec<S, Dim>& v0,
                                                                                    const Vec<S, Dim>& v1) noexcept {
  using detail::Checked;
  PowerBasis<S, Dim, MaxDegree> power;
  power.degree = 3;
  const Checked<S> two(from_int<S>(2));
  const Checked<S> three(from_int<S>(3));
  for (std::size_t i = 0; i < Dim; ++i) {
    const Checked<S> chord = Checked<S>(p1[i]) - Checked<S>(p0[i]);
    power.coefficients[0][i] = p0[i];
    power.coefficients[1][i] = v0[i];
    const auto a2 = (three * chord - two * Checked<S>(v0[i]) - Checked<S>(v1[i])).result();
    if (!a2) return fail(a2.error(), 2);
    power.coefficients[2][i] = a2.value();
    const auto a3 = (Checked<S>(v0[i]) + Checked<S>(v1[i]) - two * chord).result();
    if (!a3) return fail(a3.error(), 3);
    power.coefficients[3][i] = a3.value();
  }
  return power;
}

}  // namespace curvestep
