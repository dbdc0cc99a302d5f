// SPDX-License-Identifier: MIT
// ArcLengthTable against the seed digests' arc lengths (TV-12, TV-A2) and the exact circle.
#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include <curvestep/core/curve/circular_arc.hpp>
#include <curvestep/core/sampling/arc_length_table.hpp>
#include <support/numeric.hpp>

using namespace curvestep;
using curvestep::testing::point;
using curvestep::testing::scalar;

namespace {
template <class S>
double length_tolerance() {
  if constexpr (FixedPoint<S>) {
    return 2e-3;  // a few raw units per interval
  } else if constexpr (std::is_same_v<S, float>) {
    return 2e-5;
  } else {
    return 1e-9;
  }
}
}  // namespace

TEMPLATE_TEST_CASE("arc_length_table: TV-12 and TV-A2 lengths and their inverses", "[core][sampling][arc_length]", double,
                   float, Q16_16) {
  using S = TestType;
  const double tolerance = length_tolerance<S>();
  using Curve = Bezier<S, 2, 7>;
  const auto tv04 = Curve::create({point<S>(0, 0), point<S>(1, 2), point<S>(3, 3), point<S>(4, 0)}).value();
  const auto table = ArcLengthTable<Curve, 64>::create(tv04, scalar<S>(tolerance / 4)).value();
  CHECK(to_double(table.total_length()) == Approx(5.829927224626644).margin(tolerance));
  CHECK(to_double(table.length_at(scalar<S>(0.5)).value()) == Approx(2.834662900232897).margin(tolerance));
  // The inverse: the parameter of the half-way length of [0, 1/2] is 1/2.
  const double t_half = to_double(table.parameter_at(scalar<S>(2.834662900232897)).value());
  // |Δt| <= |Δs| / speed; the speed at t = 1/2 is |(9/2, 3/4)| = 4.56.
  CHECK(t_half == Approx(0.5).margin(FixedPoint<S> ? 2e-4 : 10 * tolerance / 4.56));
  CHECK(to_double(table.parameter_at(S{}).value()) == 0.0);
  CHECK(to_double(table.parameter_at(table.total_length()).value()) == 1.0);

  const auto tva1 = Curve::create({point<S>(0, 0), point<S>(1, 2), point<S>(3, 2), point<S>(4, 0)}).value();
  const auto table2 = ArcLengthTable<Curve, 64>::create(tva1, scalar<S>(tolerance / 4)).value();
  CHECK(to_double(table2.total_length()) == Approx(5.268365543).margin(tolerance + 1e-9));

  using Quadratic = Bezier<S, 2, 2>;
  const auto tv11 = Quadratic::create({point<S>(0, 0), point<S>(1, 2), point<S>(2, 0)}).value();
  const auto table3 = ArcLengthTable<Quadratic, 32>::create(tv11, scalar<S>(tolerance / 4)).value();
  CHECK(to_double(table3.total_length()) == Approx(2.957885715089195).margin(tolerance));
}

TEMPLATE_TEST_CASE("arc_length_table: equal arc lengths on a circular arc are equal angles", "[core][sampling][arc_length]",
                   double, float, Q16_16) {
  using S = TestType;
  const double radius = FixedPoint<S> ? 20 : 50;  // Q16.16: |r'|² must stay below 32768
  const double tolerance = FixedPoint<S> ? 5e-3 : (std::is_same_v<S, float> ? 5e-4 : 1e-8);
  const auto arc = circular_arc<S>(point<S>(0, 0), point<S>(radius, 0), point<S>(-radius, 0), ArcDirection::CounterClockwise,
                                   scalar<S>(0.01))
                       .value();  // a half circle (the cubic rational form)
  const auto table = ArcLengthTable<std::remove_cvref_t<decltype(arc)>, 128>::create(arc, scalar<S>(tolerance)).value();
  const double pi = 3.14159265358979323846;
  CHECK(to_double(table.total_length()) == Approx(pi * radius).margin(3 * tolerance));
  for (int k = 0; k <= 10; ++k) {
    const double s = pi * radius * k / 10;
    const S t = table.parameter_at(k == 10 ? table.total_length() : scalar<S>(s)).value();
    const auto p = arc.evaluate(t).value();
    const double angle = std::atan2(to_double(p[1]), to_double(p[0]));
    INFO("k " << k << " t " << to_double(t));
    // s = R θ; the point's own rounding (Fixed: ~1e-4 mm) adds to the length tolerance.
    CHECK(angle * radius == Approx(s).margin(FixedPoint<S> ? 0.02 : 10 * tolerance + 1e-4));
  }
}

TEST_CASE("arc_length_table: length_at and parameter_at are inverse on random cubics", "[core][sampling][arc_length]") {
  std::mt19937 rng(curvestep::testing::test_seed() + 3);
  std::uniform_real_distribution<double> coordinate(-100, 100);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int c = 0; c < curvestep::testing::test_count(6); ++c) {
    const auto curve = Bezier<double, 3, 3>::create({point<double>(coordinate(rng), coordinate(rng), coordinate(rng)),
                                                     point<double>(coordinate(rng), coordinate(rng), coordinate(rng)),
                                                     point<double>(coordinate(rng), coordinate(rng), coordinate(rng)),
                                                     point<double>(coordinate(rng), coordinate(rng), coordinate(rng))})
                           .value();
    const auto table = ArcLengthTable<Bezier<double, 3, 3>, 256>::create(curve, 1e-6).value();
    // Independent total: composite Simpson with 20000 panels on |r'| in long double.
    long double simpson = 0;
    const int panels = 4000;
    const auto speed = [&](long double t) {
      const auto d = curve.derivative_at(static_cast<double>(t), 1).value();
      return std::sqrt(static_cast<long double>(d[0]) * d[0] + static_cast<long double>(d[1]) * d[1] +
                       static_cast<long double>(d[2]) * d[2]);
    };
    for (int j = 0; j < panels; ++j) {
      const long double a = static_cast<long double>(j) / panels, b = static_cast<long double>(j + 1) / panels;
      simpson += (b - a) / 6 * (speed(a) + 4 * speed((a + b) / 2) + speed(b));
    }
    CHECK(table.total_length() == Approx(static_cast<double>(simpson)).margin(1e-5));
    for (int k = 0; k < 20; ++k) {
      const double t = unit(rng);
      const double s = table.length_at(t).value();
      CHECK(table.parameter_at(s).value() == Approx(t).margin(1e-6 / std::fmax(1e-3, static_cast<double>(speed(t))) + 1e-12));
    }
  }
}

TEST_CASE("arc_length_table: invalid tolerances, capacity and out-of-range queries are reported", "[core][sampling][arc_length][errors]") {
  const auto curve = Bezier<double, 2, 3>::create({point<double>(0, 0), point<double>(0, 40), point<double>(40, 40),
                                                   point<double>(40, 0)})
                         .value();
  CHECK(ArcLengthTable<Bezier<double, 2, 3>, 8>::create(curve, 0.0).error() == Error::InvalidTolerance);
  CHECK(ArcLengthTable<Bezier<double, 2, 3>, 8>::create(curve, 0.1, 0.5, 0.5).error() == Error::InvalidInterval);
  const auto looped = Bezier<double, 2, 3>::create({point<double>(0, 0), point<double>(60, 40), point<double>(-20, 40),
                                                    point<double>(40, 0)})
                          .value();  // a loop: the speed varies fast, two intervals cannot reach 1e-9
  CHECK(ArcLengthTable<Bezier<double, 2, 3>, 2>::create(looped, 1e-9).error() == Error::CapacityExceeded);
  const auto table = ArcLengthTable<Bezier<double, 2, 3>, 64>::create(curve, 1e-6).value();
  CHECK(table.parameter_at(-1.0).error() == Error::ParameterOutOfRange);
  CHECK(table.parameter_at(table.total_length() + 1).error() == Error::ParameterOutOfRange);
  CHECK(table.length_at(1.5).error() == Error::ParameterOutOfRange);
}
