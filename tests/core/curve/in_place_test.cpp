// SPDX-License-Identifier: MIT
// The in-place forms that keep large values off a microcontroller's stack give the numbers of
// the forms they replace: Bezier::derivative_at against derivative(k) then point_at (the
// hodograph curves built one by one), split(t, left, right) — also with a half written over the
// curve itself — against split(t), create_into against create, and Result's in-place value.
// Both forms are also held to expectations computed in the test: a de Casteljau written here
// (exact, bit for bit, where t is a short binary fraction), the closed form of a cubic halved at
// 1/2, and the k-th derivative as n!/(n-k)! times the Bernstein sum of the k-th differences.
#include <array>
#include <cstring>

#include <support/de_casteljau.hpp>

#include "curve_test_support.hpp"

using namespace curvestep;
using namespace curvestep::testing;

namespace {

template <class S>
S number(double value) {
  return from_double<S>(value).value();
}

template <class S, std::size_t Dim>
bool same_bits(const Vec<S, Dim>& a, const Vec<S, Dim>& b) {
  for (std::size_t i = 0; i < Dim; ++i) {
    if (std::memcmp(&a[i], &b[i], sizeof(S)) != 0) return false;
  }
  return true;
}

template <class Curve>
bool same_curve(const Curve& a, const Curve& b) {
  if (a.degree() != b.degree()) return false;
  for (std::size_t i = 0; i <= a.degree(); ++i) {
    if (!same_bits(a.control_points()[i], b.control_points()[i])) return false;
  }
  return true;
}

template <class S>
std::array<Vec<S, 3>, 6> six_points() {
  return {Vec<S, 3>{{number<S>(0.0), number<S>(0.0), number<S>(0.0)}},   Vec<S, 3>{{number<S>(3.25), number<S>(7.5), number<S>(-1.0)}},
          Vec<S, 3>{{number<S>(9.0), number<S>(-2.75), number<S>(4.5)}},  Vec<S, 3>{{number<S>(12.5), number<S>(6.0), number<S>(2.25)}},
          Vec<S, 3>{{number<S>(15.0), number<S>(11.5), number<S>(-3.5)}}, Vec<S, 3>{{number<S>(20.0), number<S>(1.25), number<S>(0.5)}}};
}

/// The k-th derivative at t of the curve with control points b: n!/(n-k)! Σ Δ^k b_i B_i^{n-k}(t)
/// (forward differences, then the Bernstein sum; no library code). Also the largest |coefficient|.
template <std::size_t Dim>
std::pair<RealPoint<Dim>, double> reference_derivative(std::vector<RealPoint<Dim>> b, Real t, std::size_t order) {
  if (order >= b.size()) return {RealPoint<Dim>{}, 0.0};
  Real factor = 1;
  for (std::size_t k = 0; k < order; ++k) {
    factor *= static_cast<Real>(b.size() - 1);
    for (std::size_t i = 0; i + 1 < b.size(); ++i) {
      for (std::size_t a = 0; a < Dim; ++a) b[i][a] = b[i + 1][a] - b[i][a];
    }
    b.pop_back();
  }
  for (auto& p : b) {
    for (auto& c : p) c *= factor;
  }
  return {bernstein_sum(b, t), polygon_scale(b)};
}

/// The curve's control points equal the reference points (bit for bit when `exact`, else within `tol`).
template <class S, std::size_t Dim>
void check_points(std::span<const Vec<S, Dim>> actual, const std::vector<RealPoint<Dim>>& expected, bool exact, double tol) {
  REQUIRE(actual.size() == expected.size());
  for (std::size_t i = 0; i < actual.size(); ++i) {
    if (exact) {
      Vec<S, Dim> e{};
      for (std::size_t a = 0; a < Dim; ++a) e[a] = number<S>(static_cast<double>(expected[i][a]));
      CHECK(same_bits(actual[i], e));
    } else {
      CHECK(max_error_real(actual[i], expected[i]) <= tol);
    }
  }
}

/// A de Casteljau step at t with these points is exact in S: t = 1/2 or 1/4 (the six points have
/// two fraction bits, |x| ≤ 20), or 1/8 in floating point (22 significant bits at most).
template <class S>
bool exact_split(double t) {
  return t == 0.5 || t == 0.25 || (t == 0.125 && !FixedPoint<S>);
}

template <class S>
void check_bezier_in_place() {
  const auto points = six_points<S>();
  for (std::size_t count = 1; count <= points.size(); ++count) {
    const auto curve = Bezier<S, 3, 7>::create(std::span<const Vec<S, 3>>(points.data(), count)).value();
    const auto real_points = to_real(curve.control_points());
    for (const double td : {0.0, 0.125, 0.25, 0.4, 0.5, 0.7, 1.0}) {
      const S t = number<S>(td);
      for (std::size_t order = 0; order <= 9; ++order) {
        const auto expected = curve.derivative(order);
        const auto actual = curve.derivative_at(t, order);
        REQUIRE(expected.has_value() == actual.has_value());
        if (!actual) continue;
        CHECK(same_bits(actual.value(), expected.value().point_at(t)));
        // independent anchor: the hodograph's coefficients are exact (integer multiples of
        // differences of exact values), so only the evaluation of degree n - order rounds
        const auto [reference, scale] = reference_derivative(real_points, to_real(t), order);
        const std::size_t degree = order < count ? count - 1 - order : 0;
        CHECK(max_error_real(actual.value(), reference) <= evaluation_tolerance<S>(scale, degree));
      }
      if (td == 0.0 || td == 1.0) continue;
      const auto halves = curve.split(t).value();
      Bezier<S, 3, 7> left;
      Bezier<S, 3, 7> right = curve;
      REQUIRE(right.split(t, left, right));  // the right half written over the curve itself
      CHECK(same_curve(left, halves.left));
      CHECK(same_curve(right, halves.right));
      // independent anchor: the de Casteljau written in the test
      const auto reference = de_casteljau_split(real_points, to_real(t));
      const double tol = evaluation_tolerance<S>(polygon_scale(real_points), count - 1);
      check_points(left.control_points(), reference.left, exact_split<S>(td), tol);
      check_points(right.control_points(), reference.right, exact_split<S>(td), tol);
    }
    Bezier<S, 3, 7> into;
    REQUIRE(Bezier<S, 3, 7>::create_into(into, curve.control_points()));
    CHECK(same_curve(into, curve));
  }
}

template <class S>
void check_rational_in_place() {
  const auto points = six_points<S>();
  const std::array<S, 6> weights{number<S>(1.0), number<S>(0.5), number<S>(2.0), number<S>(1.25), number<S>(0.75), number<S>(1.5)};
  using Curve = RationalBezier<S, 3, 7>;
  for (std::size_t count = 2; count <= points.size(); ++count) {
    const auto curve = Curve::create(std::span<const Vec<S, 3>>(points.data(), count), std::span<const S>(weights.data(), count)).value();
    for (const double td : {0.0, 0.3, 1.0}) {
      const S t = number<S>(td);
      for (std::size_t order = 0; order <= 3; ++order) {
        const auto general = curve.derivative_at(t, order);
        const auto bounded = curve.template derivative_at_most<3>(t, order);
        REQUIRE(general.has_value() == bounded.has_value());
        if (general) CHECK(same_bits(general.value(), bounded.value()));
      }
      CHECK(curve.template derivative_at_most<3>(t, 4).error() == Error::InvalidArgument);
    }
    Curve into;
    REQUIRE(Curve::create_into(into, curve.control_points(), std::span<const S>(weights.data(), count)));
    CHECK(same_curve(into, curve));
    CHECK(same_curve(into.homogeneous(), curve.homogeneous()));
    // the homogeneous points (w·P, w), computed here from the same numbers
    std::vector<RealPoint<4>> homogeneous(count);
    for (std::size_t i = 0; i < count; ++i) {
      const Real w = to_real(weights[i]);
      homogeneous[i] = {w * to_real(points[i][0]), w * to_real(points[i][1]), w * to_real(points[i][2]), w};
    }
    for (const double td : {0.125, 0.4, 0.5, 0.7}) {
      const S t = number<S>(td);
      const auto halves = curve.split(t).value();
      // independent anchor: the test's de Casteljau on the homogeneous points; exact at t = 1/2
      // (the w·P have four fraction bits at most), else within the evaluation error; the
      // projected points within that error divided by the smallest weight, plus one rounding
      const auto reference = de_casteljau_split(homogeneous, to_real(t));
      const double homogeneous_tol = evaluation_tolerance<S>(polygon_scale(homogeneous), count - 1);
      check_points(halves.left.homogeneous().control_points(), reference.left, td == 0.5, homogeneous_tol);
      check_points(halves.right.homogeneous().control_points(), reference.right, td == 0.5, homogeneous_tol);
      for (const auto* piece : {&reference.left, &reference.right}) {
        const auto& actual = piece == &reference.left ? halves.left : halves.right;
        for (std::size_t i = 0; i < count; ++i) {
          const auto& h = (*piece)[i];
          const RealPoint<3> projected{h[0] / h[3], h[1] / h[3], h[2] / h[3]};
          const double tol = homogeneous_tol * (1 + static_cast<double>(max_norm_real(projected))) / static_cast<double>(h[3]) + unit<S>();
          CHECK(max_error_real(actual.control_points()[i], projected) <= tol);
        }
      }
      // written over the curve itself, either half
      Curve left;
      Curve right = curve;
      REQUIRE(right.split(t, left, right));
      CHECK(same_curve(left, halves.left));
      CHECK(same_curve(right, halves.right));
      CHECK(same_curve(left.homogeneous(), halves.left.homogeneous()));
      CHECK(same_curve(right.homogeneous(), halves.right.homogeneous()));
      Curve other;
      left = curve;
      REQUIRE(left.split(t, left, other));
      CHECK(same_curve(left, halves.left));
      CHECK(same_curve(other, halves.right));
    }
  }
}

}  // namespace

TEST_CASE("in_place: Bezier derivative_at, split and create_into give the copying forms' numbers", "[core][curve]") {
  check_bezier_in_place<double>();
  check_bezier_in_place<float>();
  check_bezier_in_place<Q16_16>();
}

TEST_CASE("in_place: RationalBezier split (halves over the curve), create_into and derivative_at_most give the general forms' numbers", "[core][curve]") {
  check_rational_in_place<double>();
  check_rational_in_place<Q16_16>();
}

TEMPLATE_TEST_CASE("in_place: a cubic halved in place has the closed-form halves", "[core][curve]", double, float, Q16_16) {
  // left (P0, (P0+P1)/2, (P0+2P1+P2)/4, (P0+3P1+3P2+P3)/8), right the mirror image; the sums are
  // exact in double for these points and the results exact in every S
  using S = TestType;
  const auto points = six_points<double>();
  const auto& [p0, p1, p2, p3] = std::array<Vec<double, 3>, 4>{points[0], points[1], points[2], points[3]};
  const auto at = [](auto f) {
    Vec<S, 3> v{};
    for (std::size_t a = 0; a < 3; ++a) v[a] = number<S>(f(a));
    return v;
  };
  const std::array<Vec<S, 3>, 4> left_expected{
      at([&](std::size_t a) { return p0[a]; }), at([&](std::size_t a) { return (p0[a] + p1[a]) / 2; }),
      at([&](std::size_t a) { return (p0[a] + 2 * p1[a] + p2[a]) / 4; }),
      at([&](std::size_t a) { return (p0[a] + 3 * p1[a] + 3 * p2[a] + p3[a]) / 8; })};
  const std::array<Vec<S, 3>, 4> right_expected{
      left_expected[3], at([&](std::size_t a) { return (p1[a] + 2 * p2[a] + p3[a]) / 4; }),
      at([&](std::size_t a) { return (p2[a] + p3[a]) / 2; }), at([&](std::size_t a) { return p3[a]; })};
  const auto s_points = six_points<S>();
  Bezier<S, 3, 7> right = Bezier<S, 3, 7>::create(std::span<const Vec<S, 3>>(s_points.data(), 4)).value();
  Bezier<S, 3, 7> left;
  REQUIRE(right.split(number<S>(0.5), left, right));
  for (std::size_t i = 0; i < 4; ++i) {
    CHECK(same_bits(left.control_points()[i], left_expected[i]));
    CHECK(same_bits(right.control_points()[i], right_expected[i]));
  }
}

TEST_CASE("in_place: errors of the in-place forms", "[core][curve]") {
  const auto points = six_points<double>();
  auto curve = Bezier<double, 3, 7>::create(std::span<const Vec<double, 3>>(points.data(), 4)).value();
  const auto before = curve;
  Bezier<double, 3, 7> left;
  CHECK(curve.split(1.5, left, curve).error() == Error::ParameterOutOfRange);
  CHECK(same_curve(curve, before));  // unchanged
  std::array<Vec<double, 3>, 2> bad{points[0], Vec<double, 3>{{1.0, std::nan(""), 0.0}}};
  CHECK(Bezier<double, 3, 7>::create_into(curve, bad).where() == 1);
  CHECK(same_curve(curve, before));  // unchanged
  // hodograph overflow: 1e308 - (-1e308) times the degree is not finite
  std::array<Vec<double, 3>, 2> huge{Vec<double, 3>{{-1e308, 0.0, 0.0}}, Vec<double, 3>{{1e308, 0.0, 0.0}}};
  const auto wide = Bezier<double, 3, 7>::create(huge).value();
  CHECK(wide.derivative(1).error() == Error::NotFinite);
  CHECK(wide.derivative_at(0.5, 1).error() == Error::NotFinite);
  CHECK(wide.derivative_at(0.5, 1).where() == wide.derivative(1).where());
}

TEST_CASE("in_place: Result built in place, then failed", "[core]") {
  Result<std::array<int, 4>> r(std::in_place);
  REQUIRE(r.has_value());
  CHECK(r.value() == std::array<int, 4>{});
  r.value()[2] = 7;
  CHECK(r.value()[2] == 7);
  r = fail(Error::DegenerateCurve, 3);
  CHECK(!r);
  CHECK(r.error() == Error::DegenerateCurve);
  CHECK(r.where() == 3);
}
