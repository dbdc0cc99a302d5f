// SPDX-License-Identifier: MIT
// Every B-spline validation error, with the index of the input at fault.
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/bspline/basis.hpp>
#include <curvestep/core/bspline/bezier_extraction.hpp>
#include <curvestep/core/bspline/bspline.hpp>
#include <curvestep/core/bspline/knot_vector.hpp>
#include <support/numeric.hpp>

#include "random_curves.hpp"

using namespace curvestep;
using namespace curvestep::testing;  // support/numeric.hpp and the folder's helpers

namespace {
template <class S>
using Small = BSpline<S, 2, 3, 6>;

template <class S>
Result<Small<S>> make(const std::vector<Vec2<S>>& control, const std::vector<S>& knots, std::size_t degree) {
  return Small<S>::create(std::span<const Vec2<S>>(control), std::span<const S>(knots), degree);
}
template <class S>
std::vector<Vec2<S>> four_points() {
  return points<S>({{0, 0}, {1, 2}, {3, 2}, {4, 0}});
}
}  // namespace

TEMPLATE_TEST_CASE("bspline: knots that decrease are rejected at the knot that drops", "[core][bspline][validation]",
                   double, float, Q16_16) {
  using S = TestType;
  const auto r = make(four_points<S>(), scalars<S>({0, 0, 0, 0.5, 0.4, 1, 1}), 2);
  CHECK(r.error() == Error::KnotsNotNondecreasing);
  CHECK(r.where() == 4);
  CHECK(validate_knots(std::span<const S>(scalars<S>({0, 0, 1, 0})), 1, 2).where() == 3);
}

TEMPLATE_TEST_CASE("bspline: the knot count must be control points plus degree plus one", "[core][bspline][validation]",
                   double, float, Q16_16) {
  using S = TestType;
  const auto r = make(four_points<S>(), scalars<S>({0, 0, 0, 1, 1, 1}), 2);
  CHECK(r.error() == Error::WrongKnotCount);
  CHECK(r.where() == 6);
  CHECK(make(four_points<S>(), scalars<S>({0, 0, 0, 0.5, 0.6, 1, 1, 1}), 2).error() == Error::WrongKnotCount);
}

TEMPLATE_TEST_CASE("bspline: interior multiplicity above the degree is rejected", "[core][bspline][validation]", double,
                   float, Q16_16) {
  using S = TestType;
  const auto points6 = points<S>({{0, 0}, {1, 2}, {3, 2}, {4, 0}, {5, 1}, {6, 0}});
  // Degree 2: 0.5 three times inside the domain.
  const auto r = make(points6, scalars<S>({0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1}), 2);
  CHECK(r.error() == Error::KnotMultiplicityTooHigh);
  CHECK(r.where() == 3);
  // Degree times is fine.
  CHECK(make(points<S>({{0, 0}, {1, 2}, {3, 2}, {4, 0}, {5, 1}}), scalars<S>({0, 0, 0, 0.5, 0.5, 1, 1, 1}), 2).has_value());
  // An end knot repeated more than degree + 1 times.
  const auto end = make(four_points<S>(), scalars<S>({0, 0, 0, 0, 1, 1, 1}), 2);
  CHECK(end.error() == Error::KnotMultiplicityTooHigh);
  CHECK(end.where() == 0);
}

TEMPLATE_TEST_CASE("bspline: an empty domain is rejected", "[core][bspline][validation]", double, Q16_16) {
  using S = TestType;
  CHECK(make(points<S>({{0, 0}, {1, 1}}), scalars<S>({0, 1, 1, 2}), 1).error() == Error::InvalidInterval);
}

TEMPLATE_TEST_CASE("bspline: capacity, degree and point-count limits", "[core][bspline][validation]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto seven = points<S>({{0, 0}, {1, 2}, {3, 2}, {4, 0}, {5, 1}, {6, 0}, {7, 1}});
  const auto r = make(seven, scalars<S>({0, 0, 0, 0.2, 0.4, 0.6, 0.8, 1, 1, 1}), 2);
  CHECK(r.error() == Error::CapacityExceeded);
  CHECK(r.where() == 7);
  const auto degree = make(four_points<S>(), scalars<S>({0, 0, 0, 0, 0, 1, 1, 1, 1}), 4);
  CHECK(degree.error() == Error::DegreeAboveCapacity);
  CHECK(degree.where() == 4);
  CHECK(make(four_points<S>(), scalars<S>({0, 1, 2, 3, 4}), 0).error() == Error::DegreeTooLow);
  CHECK(make(points<S>({{0, 0}, {1, 1}}), scalars<S>({0, 0, 0, 1, 1, 1}), 2).error() == Error::TooFewPoints);
  CHECK(make(std::vector<Vec2<S>>{}, scalars<S>({0, 1}), 1).error() == Error::EmptyControlPolygon);
  const auto closed = Small<S>::closed(std::span<const Vec2<S>>(four_points<S>()), 3);
  CHECK(closed.error() == Error::CapacityExceeded);
  CHECK(closed.where() == 7);
  CHECK(Small<S>::closed(std::span<const Vec2<S>>(points<S>({{0, 0}})), 1).error() == Error::TooFewPoints);
  // Knot insertion past the capacity.
  const auto full = make(points<S>({{0, 0}, {1, 2}, {3, 2}, {4, 0}, {5, 1}, {6, 0}}),
                         scalars<S>({0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1}), 2);
  REQUIRE(full.has_value());
  const auto inserted = full.value().insert_knot(scalar<S>(0.125));
  CHECK(inserted.error() == Error::CapacityExceeded);
  CHECK(inserted.where() == 7);
}

TEMPLATE_TEST_CASE("bspline: parameters outside the domain are rejected", "[core][bspline][validation]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto curve = make(four_points<S>(), scalars<S>({1, 1, 1, 2, 3, 3, 3}), 2).value();
  CHECK(curve.evaluate(scalar<S>(0.5)).error() == Error::ParameterOutOfRange);
  CHECK(curve.evaluate(scalar<S>(3.25)).error() == Error::ParameterOutOfRange);
  CHECK(curve.derivative_at(scalar<S>(4), 1).error() == Error::ParameterOutOfRange);
  CHECK(curve.find_span(scalar<S>(0)).error() == Error::ParameterOutOfRange);
  CHECK(curve.insert_knot(scalar<S>(5)).error() == Error::ParameterOutOfRange);
  CHECK(basis_function(curve.knots(), 2, 0, scalar<S>(0)).error() == Error::ParameterOutOfRange);
  CHECK(curve.evaluate(scalar<S>(3)).has_value());
  CHECK(Small<S>{}.evaluate(scalar<S>(0)).error() == Error::EmptyControlPolygon);
}

TEMPLATE_TEST_CASE("bspline: NaN and infinity are rejected with their index", "[core][bspline][validation]", double,
                   float) {
  using S = TestType;
  const S nan = std::numeric_limits<S>::quiet_NaN();
  const S infinity = std::numeric_limits<S>::infinity();
  auto control = four_points<S>();
  control[2][1] = nan;
  const auto bad_point = make(control, scalars<S>({0, 0, 0, 0.5, 1, 1, 1}), 2);
  CHECK(bad_point.error() == Error::NotFinite);
  CHECK(bad_point.where() == 2);
  auto knots = scalars<S>({0, 0, 0, 0.5, 1, 1, 1});
  knots[3] = infinity;
  const auto bad_knot = make(four_points<S>(), knots, 2);
  CHECK(bad_knot.error() == Error::NotFinite);
  CHECK(bad_knot.where() == 3);
  const auto curve = make(four_points<S>(), scalars<S>({0, 0, 0, 0.5, 1, 1, 1}), 2).value();
  CHECK(curve.evaluate(nan).error() == Error::NotFinite);
  CHECK(curve.derivative_at(infinity, 2).error() == Error::NotFinite);
  CHECK(curve.insert_knot(nan).error() == Error::NotFinite);
  CHECK(Small<S>::clamped(std::span<const Vec2<S>>(four_points<S>()), 2, S{}, infinity).error() == Error::NotFinite);
}

TEMPLATE_TEST_CASE("bspline: knot insertion refuses too high a multiplicity", "[core][bspline][validation]", double,
                   Q16_16) {
  using S = TestType;
  const auto curve = BSpline<S, 2, 3, 12>::create(std::span<const Vec2<S>>(four_points<S>()),
                                                  std::span<const S>(scalars<S>({0, 0, 0, 0.5, 1, 1, 1})), 2)
                         .value();
  CHECK(curve.insert_knot(scalar<S>(0.5), 1).has_value());               // multiplicity 2 = degree
  CHECK(curve.insert_knot(scalar<S>(0.5), 2).error() == Error::KnotMultiplicityTooHigh);
  CHECK(curve.insert_knot(scalar<S>(0.25), 3).error() == Error::KnotMultiplicityTooHigh);
  CHECK(curve.insert_knot(scalar<S>(0)).error() == Error::KnotMultiplicityTooHigh);  // clamped end is full
  CHECK(curve.insert_knot(scalar<S>(1)).error() == Error::KnotMultiplicityTooHigh);
}

TEMPLATE_TEST_CASE("bspline: knot-vector helpers check their inputs", "[core][bspline][validation]", double, Q16_16) {
  using S = TestType;
  std::array<S, 16> out{};
  CHECK(uniform_clamped_knots(4, 0, S{}, scalar<S>(1), std::span<S>(out)).error() == Error::DegreeTooLow);
  CHECK(uniform_clamped_knots(2, 2, S{}, scalar<S>(1), std::span<S>(out)).error() == Error::TooFewPoints);
  CHECK(uniform_clamped_knots(4, 2, scalar<S>(1), scalar<S>(1), std::span<S>(out)).error() == Error::InvalidInterval);
  const auto small = uniform_clamped_knots(10, 3, S{}, scalar<S>(1), std::span<S>(out.data(), 8));
  CHECK(small.error() == Error::BufferTooSmall);
  CHECK(small.where() == 14);
  CHECK(uniform_periodic_knots(1, 2, S{}, scalar<S>(1), std::span<S>(out)).error() == Error::TooFewPoints);
  CHECK(uniform_periodic_knots(4, 2, S{}, S{}, std::span<S>(out)).error() == Error::InvalidInterval);
  const auto spacing = periodic_knots(std::span<const S>(scalars<S>({1, 0, 1})), 2, S{}, std::span<S>(out));
  CHECK(spacing.error() == Error::InvalidInterval);
  CHECK(spacing.where() == 1);
  if constexpr (FixedPoint<S>) {
    const auto wide = make(four_points<S>(), scalars<S>({-20000, -20000, -20000, 0, 20000, 20000, 20000}), 2);
    CHECK(wide.error() == Error::FixedOverflow);
    CHECK(wide.where() == 6);
    // The same knots' differences would not fit the format: caught before any arithmetic.
    CHECK(uniform_periodic_knots(4, 2, scalar<S>(30000), scalar<S>(1000), std::span<S>(out)).error() ==
          Error::FixedOverflow);
  }
}

TEMPLATE_TEST_CASE("bspline: basis functions check their inputs", "[core][bspline][validation]", double, Q16_16) {
  using S = TestType;
  const auto knots = scalars<S>({0, 0, 0, 1, 2, 2, 2});
  const std::span<const S> k(knots);
  CHECK(basis_function(k, 2, 4, scalar<S>(1)).error() == Error::InvalidArgument);
  CHECK(basis_function(k, 3, 0, scalar<S>(1)).error() == Error::WrongKnotCount);
  CHECK(basis_function<2>(std::span<const S>(scalars<S>({0, 0, 0, 0, 1, 1, 1, 1})), 3, 0, scalar<S>(1)).error() ==
        Error::DegreeAboveCapacity);
  CHECK(basis_function(std::span<const S>(scalars<S>({0, 0, 1, 0.5, 2, 2})), 1, 0, scalar<S>(1)).error() ==
        Error::KnotsNotNondecreasing);
  std::array<S, 2> few{};
  CHECK(basis_values(k, 2, scalar<S>(1), std::span<S>(few)).error() == Error::BufferTooSmall);
}
