// SPDX-License-Identifier: MIT
// The in-place forms that keep large values off a microcontroller's stack give the numbers of
// the forms they replace: Bezier::derivative_at against derivative(k) then point_at (the
// hodograph curves built one by one), split(t, left, right) — also with a half written over the
// curve itself — against split(t), create_into against create, and Result's in-place value.
#include <array>
#include <cstring>

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

template <class S>
void check_bezier_in_place() {
  const auto points = six_points<S>();
  for (std::size_t count = 1; count <= points.size(); ++count) {
    const auto curve = Bezier<S, 3, 7>::create(std::span<const Vec<S, 3>>(points.data(), count)).value();
    for (const double td : {0.0, 0.125, 0.4, 0.7, 1.0}) {
      const S t = number<S>(td);
      for (std::size_t order = 0; order <= 9; ++order) {
        const auto expected = curve.derivative(order);
        const auto actual = curve.derivative_at(t, order);
        REQUIRE(expected.has_value() == actual.has_value());
        if (actual) CHECK(same_bits(actual.value(), expected.value().point_at(t)));
      }
      if (td == 0.0 || td == 1.0) continue;
      const auto halves = curve.split(t).value();
      Bezier<S, 3, 7> left;
      Bezier<S, 3, 7> right = curve;
      REQUIRE(right.split(t, left, right));  // the right half written over the curve itself
      CHECK(same_curve(left, halves.left));
      CHECK(same_curve(right, halves.right));
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
    for (const double td : {0.125, 0.4, 0.7}) {
      const S t = number<S>(td);
      const auto halves = curve.split(t).value();
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
