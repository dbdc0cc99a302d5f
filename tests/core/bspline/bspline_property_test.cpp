// SPDX-License-Identifier: MIT
// Cross-checks between independent algorithms on hundreds of random B-splines (fixed seeds):
// de Boor against the Cox–de Boor sum, derivatives against basis-derivative sums, knot
// insertion against the original curve, full insertion against Bézier extraction, and the
// binary span search against a linear scan.
#include <array>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/bspline/basis.hpp>
#include <curvestep/core/bspline/bezier_extraction.hpp>
#include <curvestep/core/bspline/bspline.hpp>
#include <support/numeric.hpp>

#include "random_curves.hpp"

using namespace curvestep;
using namespace curvestep::testing;  // support/numeric.hpp and the folder's helpers

namespace {
template <class S>
using Curve = BSpline<S, 2, 5, 64>;

/// Σ N^(order)_i(u) P_i with the basis in S (Cox–de Boor), summed in double.
template <class S>
std::array<double, 2> basis_sum(const Curve<S>& curve, S u, std::size_t order) {
  std::vector<S> n(curve.size());
  const auto r = basis_values(curve.knots(), curve.degree(), u, std::span<S>(n), order);
  REQUIRE(r.has_value());
  std::array<double, 2> sum{};
  for (std::size_t i = 0; i < curve.size(); ++i) {
    for (std::size_t axis = 0; axis < 2; ++axis) sum[axis] += to_double(n[i]) * to_double(curve.control_points()[i][axis]);
  }
  return sum;
}

template <class S>
Curve<S> random_curve(std::mt19937& random, int c, double range = 100) {
  const auto data = curvestep::testing::random_spline<S, 2>(random, 5, 12, c % 2 == 0, range);
  const auto made = Curve<S>::create(std::span<const Vec2<S>>(data.control), std::span<const S>(data.knots), data.degree);
  REQUIRE(made.has_value());
  return made.value();
}

Curve<Q16_16> make_spline_for_limits(const std::vector<std::array<double, 2>>& control, const std::vector<double>& knots,
                                     std::size_t degree) {
  std::vector<Vec2<Q16_16>> points;
  for (const auto& p : control) points.push_back(curvestep::testing::point<Q16_16>(p[0], p[1]));
  std::vector<Q16_16> scaled;
  for (const double k : knots) scaled.push_back(scalar<Q16_16>(k));
  return Curve<Q16_16>::create(std::span<const Vec2<Q16_16>>(points), std::span<const Q16_16>(scaled), degree).value();
}

/// Parameters on a 1/64 grid across the domain (exact in every type), knots included.
template <class S>
std::vector<S> sample_parameters(const Curve<S>& curve) {
  std::vector<S> out;
  const double start = to_double(curve.domain_start());
  const double end = to_double(curve.domain_end());
  for (double u = start; u <= end; u += 1 / 64.0) out.push_back(scalar<S>(u));
  return out;
}
}  // namespace

TEMPLATE_TEST_CASE("bspline: de Boor agrees with the Cox-de Boor sum on random curves", "[core][bspline][property]",
                   double, float, Q16_16) {
  using S = TestType;
  std::mt19937 random(curvestep::testing::test_seed() + 1);
  const int cases = curvestep::testing::test_count(300);
  for (int c = 0; c < cases; ++c) {
    const auto curve = random_curve<S>(random, c);
    const int p = static_cast<int>(curve.degree());
    for (const S u : sample_parameters(curve)) {
      // Fixed: p roundings in de Boor, p(p+1)/2 in the basis values times |P| <= 100, summed.
      const double bound = FixedPoint<S> ? (p + 100.0 * p * (p + 1)) * to_double(resolution<S>()) : tolerance<S>(100, 8 * p);
      CHECK(max_error(curve.evaluate(u).value(), basis_sum(curve, u, 0)) <= bound);
      // independent anchor: the Cox–de Boor recursion written in the test (long double)
      const auto reference = curvestep::testing::cox_de_boor_point<S, 2>(curve.control_points(), curve.knots(), curve.degree(), u);
      CHECK(curvestep::testing::max_error_long(curve.evaluate(u).value(), reference) <= bound);
    }
    // Partition of unity and the convex hull (bounding box) on the whole domain.
    const auto box = curve.bounding_box();
    for (const S u : sample_parameters(curve)) CHECK(box.contains(curve.evaluate(u).value()));
  }
}

TEMPLATE_TEST_CASE("bspline: derivatives agree with basis-derivative sums on random curves", "[core][bspline][property]",
                   double, float) {
  using S = TestType;
  std::mt19937 random(curvestep::testing::test_seed() + 2);
  const int cases = curvestep::testing::test_count(300);
  for (int c = 0; c < cases; ++c) {
    const auto curve = random_curve<S>(random, c);
    for (std::size_t order = 1; order <= curve.degree() + 1; ++order) {
      for (const S u : sample_parameters(curve)) {
        const auto expected = basis_sum(curve, u, order);
        const double scale = 100 * std::pow(8.0 * static_cast<double>(curve.degree()), static_cast<double>(order));
        CHECK(max_error(curve.derivative_at(u, order).value(), expected) <= tolerance<S>(scale, 64));
      }
    }
  }
}

TEST_CASE("bspline: Q16.16 derivatives stay close to the double derivatives", "[core][bspline][property]") {
  std::mt19937 random(curvestep::testing::test_seed() + 3);
  const int cases = curvestep::testing::test_count(200);
  for (int c = 0; c < cases; ++c) {
    // Same data in both types (coordinates and knots are drawn on grids exact in Q16.16).
    std::mt19937 copy = random;
    const auto fixed = random_curve<Q16_16>(random, c, 10);
    const auto exact = random_curve<double>(copy, c, 10);
    REQUIRE(fixed.size() == exact.size());
    for (std::size_t order = 1; order <= 2; ++order) {
      for (const auto u : sample_parameters(exact)) {
        const auto d = exact.derivative_at(u, order).value();
        const auto f = fixed.derivative_at(Q16_16::from_double(u).value(), order);
        if (!f) {
          CHECK(f.error() == Error::FixedOverflow);  // a second derivative can exceed ±32768
          continue;
        }
        const double scale = std::fmax(1, std::fabs(d[0]) + std::fabs(d[1]));
        CHECK(max_error(f.value(), to_doubles(d)) <= 2e-3 * scale);
      }
    }
  }
}

TEMPLATE_TEST_CASE("bspline: knot insertion leaves random curves unchanged", "[core][bspline][property]", double, float,
                   Q16_16) {
  using S = TestType;
  std::mt19937 random(curvestep::testing::test_seed() + 4);
  const int cases = curvestep::testing::test_count(300);
  for (int c = 0; c < cases; ++c) {
    const auto curve = random_curve<S>(random, c);
    const double start = to_double(curve.domain_start());
    const double end = to_double(curve.domain_end());
    const auto steps = static_cast<int>((end - start) * 64);
    const S u = scalar<S>(start + std::uniform_int_distribution<int>(0, steps)(random) / 64.0);
    const std::size_t times = std::uniform_int_distribution<std::size_t>(1, curve.degree())(random);
    const auto refined = curve.insert_knot(u, times);
    if (!refined) {
      const bool interior = curve.domain_start() < u && u < curve.domain_end();
      CHECK(refined.error() == Error::KnotMultiplicityTooHigh);
      CHECK(knot_multiplicity(curve.knots(), u) + times > curve.degree() + (interior ? 0 : 1));
      continue;
    }
    CHECK(refined.value().size() == curve.size() + times);
    CHECK(knot_multiplicity(refined.value().knots(), u) == knot_multiplicity(curve.knots(), u) + times);
    for (const S v : sample_parameters(curve)) {
      CHECK(max_error(refined.value().evaluate(v).value(), to_doubles(curve.evaluate(v).value())) <=
            tolerance<S>(100, 4 * static_cast<int>(curve.degree() + times)));
    }
  }
}

TEMPLATE_TEST_CASE("bspline: inserting every interior knot to full multiplicity gives the extracted Bezier points",
                   "[core][bspline][property]", double, float, Q16_16) {
  using S = TestType;
  std::mt19937 random(curvestep::testing::test_seed() + 5);
  const int cases = curvestep::testing::test_count(200);
  for (int c = 0; c < cases; ++c) {
    const auto data = curvestep::testing::random_spline<S, 2>(random, 4, 6, true);
    auto made = Curve<S>::create(std::span<const Vec2<S>>(data.control), std::span<const S>(data.knots), data.degree);
    REQUIRE(made.has_value());
    const auto original = made.value();
    Curve<S> refined = original;
    const std::size_t p = original.degree();
    for (std::size_t s = p + 1; s < original.size(); ++s) {
      const S u = original.knots()[s];
      if (original.knots()[s - 1] == u) continue;
      const std::size_t have = knot_multiplicity(original.knots(), u);
      if (have < p) refined = refined.insert_knot(u, p - have).value();
    }
    std::vector<BezierSpan<S, 2, 5>> pieces(original.span_count());
    REQUIRE(extract_bezier(original, std::span<BezierSpan<S, 2, 5>>(pieces)).has_value());
    REQUIRE(refined.size() == pieces.size() * p + 1);
    for (std::size_t j = 0; j < pieces.size(); ++j) {
      for (std::size_t k = 0; k <= p; ++k) {
        CHECK(max_error(pieces[j].curve[k], to_doubles(refined.control_points()[j * p + k])) <=
              tolerance<S>(100, 4 * static_cast<int>(p * p)));
      }
    }
  }
}

TEMPLATE_TEST_CASE("bspline: binary span search matches a linear scan", "[core][bspline][property]", double, Q16_16) {
  using S = TestType;
  std::mt19937 random(curvestep::testing::test_seed() + 6);
  const int cases = curvestep::testing::test_count(300);
  for (int c = 0; c < cases; ++c) {
    const auto curve = random_curve<S>(random, c);
    const auto knots = curve.knots();
    for (const S u : sample_parameters(curve)) {
      std::size_t expected = curve.degree();
      for (std::size_t s = curve.degree(); s < curve.size(); ++s) {
        if (!(u < knots[s]) && knots[s] < knots[s + 1]) expected = s;
      }
      const std::size_t found = curve.find_span(u).value();
      CHECK(found == expected);
      CHECK(knots[found] < knots[found + 1]);
    }
  }
}

TEMPLATE_TEST_CASE("bspline: the uniform clamped helper interpolates the end points", "[core][bspline]", double, float,
                   Q16_16) {
  using S = TestType;
  std::mt19937 random(curvestep::testing::test_seed() + 8);
  for (int c = 0; c < 50; ++c) {
    const auto data = curvestep::testing::random_spline<S, 2>(random, 5, 20, true);
    const auto curve = Curve<S>::clamped(std::span<const Vec2<S>>(data.control), data.degree, scalar<S>(-2), scalar<S>(3));
    REQUIRE(curve.has_value());
    CHECK(curve.value().layout() == KnotLayout::Clamped);
    CHECK(curve.value().span_count() == data.control.size() - data.degree);
    CHECK(curve.value().evaluate(scalar<S>(-2)).value() == data.control.front());
    CHECK(curve.value().evaluate(scalar<S>(3)).value() == data.control.back());
    const auto knots = curve.value().knots();
    const double width = 5.0 / static_cast<double>(data.control.size() - data.degree);
    for (std::size_t i = data.degree; i <= data.control.size(); ++i) {
      CHECK(to_double(knots[i]) ==
            Approx(-2 + width * static_cast<double>(i - data.degree)).margin(to_double(resolution<S>())));
    }
  }
}

TEMPLATE_TEST_CASE("bspline: inserting an unclamped domain end degree times makes the curve end at a control point",
                   "[core][bspline]", double, float, Q16_16) {
  using S = TestType;
  const auto control = curvestep::testing::points<S>({{0, 0}, {6, 0}, {6, 6}, {0, 6}, {-3, 3}});
  const auto curve = Curve<S>::create(std::span<const Vec2<S>>(control),
                                      std::span<const S>(curvestep::testing::scalars<S>({0, 1, 2, 3, 4, 5, 6, 7, 8})), 3)
                         .value();
  const auto start = curve.insert_knot(scalar<S>(3), 3);
  REQUIRE(start.has_value());
  const auto both = start.value().insert_knot(scalar<S>(5), 3);
  REQUIRE(both.has_value());
  const auto& clamped = both.value();
  CHECK(clamped.layout() == KnotLayout::Unclamped);  // u_0 = 0 still differs from u_p = 3
  CHECK(clamped.size() == 11);
  CHECK(to_double(clamped.domain_start()) == 3.0);
  CHECK(to_double(clamped.domain_end()) == 5.0);
  // The curve now starts at the new control point P_p and ends at P_{n−p}.
  CHECK(max_error(clamped.control_points()[3], to_doubles(curve.evaluate(scalar<S>(3)).value())) <= tolerance<S>(6, 8));
  CHECK(max_error(clamped.control_points()[7], to_doubles(curve.evaluate(scalar<S>(5)).value())) <= tolerance<S>(6, 8));
  CHECK(curve.insert_knot(scalar<S>(3), 4).error() == Error::KnotMultiplicityTooHigh);
}

TEST_CASE("bspline: Q16.16 evaluation keeps full resolution for points and knots near the format's limits",
          "[core][bspline][property]") {
  // Control points ±30000 apart and knot spans of up to 30000: the ratio step's product needs
  // all 64 bits and long spans drop their lowest bits first (detail/ratio.hpp).
  const auto line = make_spline_for_limits({{-30000, 0}, {30000, 20000}}, {0, 0, 30000, 30000}, 1);
  CHECK(line.evaluate(Q16_16::from_double(10000).value()).value() ==
        Vec2<Q16_16>{{Q16_16::from_double(-10000).value(), Q16_16::from_double(20000 / 3.0).value()}});
  std::mt19937 random(curvestep::testing::test_seed() + 9);
  std::uniform_real_distribution<double> coordinate(-30000, 30000);
  for (int c = 0; c < 100; ++c) {
    std::vector<std::array<double, 2>> control;
    for (int i = 0; i < 6; ++i) control.push_back({std::round(coordinate(random)), std::round(coordinate(random))});
    const auto curve = make_spline_for_limits(control, {0, 0, 0, 0, 7000, 25000, 32000, 32000, 32000, 32000}, 3);
    const auto exact = Curve<double>::create(
        std::span<const Vec2<double>>(curvestep::testing::points<double>({{control[0][0], control[0][1]}, {control[1][0], control[1][1]},
                                                                          {control[2][0], control[2][1]}, {control[3][0], control[3][1]},
                                                                          {control[4][0], control[4][1]}, {control[5][0], control[5][1]}})),
        std::span<const double>(curvestep::testing::scalars<double>({0, 0, 0, 0, 7000, 25000, 32000, 32000, 32000, 32000})), 3);
    for (int k = 0; k <= 64; ++k) {
      const double u = 500.0 * k;
      CHECK(max_error(curve.evaluate(Q16_16::from_double(u).value()).value(), to_doubles(exact.value().evaluate(u).value())) <=
            3 * to_double(resolution<Q16_16>()));
    }
  }
}
