// SPDX-License-Identifier: MIT
// Bézier extraction against the seed digests (000 TV-19 spans, 004 TV-A6) and against de Boor.
#include <array>
#include <cstddef>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/bspline/bezier_extraction.hpp>
#include <support/numeric.hpp>

#include "random_curves.hpp"

using namespace curvestep;
using namespace curvestep::testing;  // support/numeric.hpp and the folder's helpers

namespace {
template <class S>
using Spline2 = BSpline<S, 2, 5, 16>;
template <class S>
using Piece2 = BezierSpan<S, 2, 5>;

template <class S>
Spline2<S> tv19_curve() {  // digest 000/002/003 TV-19: knots (0,0,0,0,1,2,2,2,2)
  const std::array<Vec2<S>, 5> control{point<S>(0, 0), point<S>(1, 2), point<S>(2, -1), point<S>(3, 2), point<S>(4, 0)};
  const std::array<S, 9> knots{scalar<S>(0), scalar<S>(0), scalar<S>(0), scalar<S>(0), scalar<S>(1),
                               scalar<S>(2), scalar<S>(2), scalar<S>(2), scalar<S>(2)};
  return Spline2<S>::create(std::span<const Vec2<S>>(control), std::span<const S>(knots), 3).value();
}

template <class S>
Spline2<S> tv13_curve() {  // digest 004 TV-13: knots [0,0,0,0,1,2,3,4,5,5,5,5]
  const std::array<Vec2<S>, 8> control{point<S>(-3, 7), point<S>(-1, 6), point<S>(0, 4), point<S>(0, 0),
                                       point<S>(4, 0),  point<S>(6, 1),  point<S>(7, 3), point<S>(9, 4)};
  std::array<S, 12> knots{};
  const std::array<double, 12> values{0, 0, 0, 0, 1, 2, 3, 4, 5, 5, 5, 5};
  for (std::size_t i = 0; i < knots.size(); ++i) knots[i] = scalar<S>(values[i]);
  return Spline2<S>::create(std::span<const Vec2<S>>(control), std::span<const S>(knots), 3).value();
}
}  // namespace

TEMPLATE_TEST_CASE("bspline: extraction of TV-19 gives the digest's two cubic spans exactly", "[core][bspline][seed]",
                   double, float, Q16_16) {
  using S = TestType;
  std::array<Piece2<S>, 4> pieces{};
  const auto count = extract_bezier(tv19_curve<S>(), std::span(pieces));  // static extent works too
  REQUIRE(count.has_value());
  REQUIRE(count.value() == 2);
  const std::array<std::array<std::array<double, 2>, 4>, 2> expected{
      {{{{0, 0}, {1, 2}, {1.5, 0.5}, {2, 0.5}}}, {{{2, 0.5}, {2.5, 0.5}, {3, 2}, {4, 0}}}}};
  for (std::size_t j = 0; j < 2; ++j) {
    REQUIRE(pieces[j].curve.degree() == 3);
    CHECK(to_double(pieces[j].start) == static_cast<double>(j));
    CHECK(to_double(pieces[j].end) == static_cast<double>(j + 1));
    CHECK(pieces[j].knot_span == 3 + j);
    for (std::size_t k = 0; k < 4; ++k) CHECK(max_error(pieces[j].curve[k], expected[j][k]) == 0.0);
  }
}

TEMPLATE_TEST_CASE("bspline: extraction of span [2,3] of 004 TV-13 matches TV-A6", "[core][bspline][seed]", double,
                   float, Q16_16) {
  using S = TestType;
  const auto curve = tv13_curve<S>();
  CHECK(curve.span_count() == 5);
  const auto piece = bezier_span(curve, 5);
  REQUIRE(piece.has_value());
  const std::array<std::array<double, 2>, 4> expected{{{2 / 3., 2 / 3.}, {4 / 3., 0}, {8 / 3., 0}, {11 / 3., 1 / 6.}}};
  for (std::size_t k = 0; k < 4; ++k) CHECK(max_error(piece.value().curve[k], expected[k]) <= tolerance<S>(4, 4));
  CHECK(piece.value().curve.front() == curve.evaluate(scalar<S>(2)).value());
  CHECK(piece.value().curve.back() == curve.evaluate(scalar<S>(3)).value());
  CHECK(bezier_span(curve, 2).error() == Error::InvalidArgument);   // below the domain
  CHECK(bezier_span(curve, 8).error() == Error::InvalidArgument);   // past the last span
}

TEMPLATE_TEST_CASE("bspline: extraction reports a too small buffer and supports early stop", "[core][bspline]", double,
                   Q16_16) {
  using S = TestType;
  const auto curve = tv13_curve<S>();
  std::array<Piece2<S>, 4> small{};
  const auto count = extract_bezier(curve, std::span<Piece2<S>>(small));
  CHECK(count.error() == Error::BufferTooSmall);
  CHECK(count.where() == 5);
  std::size_t seen = 0;
  CHECK(for_each_bezier(curve, [&](const Piece2<S>&) { return ++seen < 2; }).has_value());
  CHECK(seen == 2);
  const auto stopped = for_each_bezier(curve, [](const Piece2<S>&) -> Result<void> { return fail(Error::QueueFull, 7); });
  CHECK(stopped.error() == Error::QueueFull);
  CHECK(stopped.where() == 7);
}

TEMPLATE_TEST_CASE("bspline: extracted pieces by de Casteljau match de Boor on random curves", "[core][bspline][property]",
                   double, float, Q16_16) {
  using S = TestType;
  std::mt19937 random(curvestep::testing::test_seed());
  const int cases = curvestep::testing::test_count(300);
  for (int c = 0; c < cases; ++c) {
    const auto data = curvestep::testing::random_spline<S, 2>(random, 5, 10, c % 2 == 0);
    const auto made = Spline2<S>::create(std::span<const Vec2<S>>(data.control), std::span<const S>(data.knots), data.degree);
    INFO("case " << c << " error " << static_cast<int>(made.error()) << " at " << made.where());
    REQUIRE(made.has_value());
    const auto& curve = made.value();
    std::vector<Piece2<S>> pieces(curve.span_count());
    REQUIRE(extract_bezier(curve, std::span<Piece2<S>>(pieces)).has_value());
    for (std::size_t j = 0; j < pieces.size(); ++j) {
      const auto& piece = pieces[j];
      if (j > 0) CHECK(pieces[j - 1].curve.back() == piece.curve.front());  // joints are shared exactly
      for (int k = 0; k <= 8; ++k) {
        const S t = scalar<S>(k / 8.0);  // u on a 1/64 grid: exact in every type
        const S at = scalar<S>(to_double(piece.start) + k / 8.0 * (to_double(piece.end) - to_double(piece.start)));
        const auto expected = curve.evaluate(at).value();
        CHECK(max_error(piece.curve.point_at(t), to_doubles(expected)) <=
              tolerance<S>(100, 4 * static_cast<int>(data.degree) + 4));
        // independent anchor: the Cox–de Boor recursion written in the test (long double)
        const auto reference = curvestep::testing::cox_de_boor_point<S, 2>(curve.control_points(), curve.knots(), curve.degree(), at);
        CHECK(curvestep::testing::max_error_long(piece.curve.point_at(t), reference) <=
              tolerance<S>(100, 4 * static_cast<int>(data.degree) + 4));
      }
    }
  }
}
