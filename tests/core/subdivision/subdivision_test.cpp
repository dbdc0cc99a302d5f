// SPDX-License-Identifier: MIT
// Subdivision against seed 001 digest TV-14..TV-17 (closed square, open zigzag, polynomial
// reproduction, mask consistency), Chaikin's convergence to the quadratic B-spline (closed form
// of seed 001 §9, computed here independently), and every error of the engine.
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core.hpp>
#include <curvestep/core/subdivision/limit.hpp>
#include <curvestep/core/subdivision/refinable_polygon.hpp>
#include <curvestep/core/subdivision/refine.hpp>
#include <curvestep/core/subdivision/subdivision_mask.hpp>
#include <support/numeric.hpp>

using namespace curvestep;
using curvestep::testing::max_error;
using curvestep::testing::point;
using curvestep::testing::scalar;

namespace {
template <class S>
std::array<Vec2<S>, 4> square() {  // TV-14
  return {point<S>(0, 0), point<S>(8, 0), point<S>(8, 8), point<S>(0, 8)};
}
template <class S>
std::array<Vec2<S>, 5> zigzag() {  // TV-15
  return {point<S>(0, 0), point<S>(4, 8), point<S>(8, 0), point<S>(12, 8), point<S>(16, 0)};
}

/// Largest coordinate error of refined vertices against expected (x, y) pairs.
template <class S>
double worst(std::span<const Vec2<S>> actual, const std::vector<std::array<double, 2>>& expected) {
  REQUIRE(actual.size() >= expected.size());
  double w = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) w = std::fmax(w, max_error(actual[i], expected[i]));
  return w;
}

/// Ternary weights (1/3, 1/9) are not dyadic: one rounding per vertex and step in Q16.16.
template <class S>
double ternary_tolerance(int steps) {
  if constexpr (FixedPoint<S>) {
    return steps * to_double(resolution<S>());
  } else {
    return 8 * steps * static_cast<double>(std::numeric_limits<S>::epsilon()) * 8;
  }
}
}  // namespace

TEMPLATE_TEST_CASE("subdivision: TV-14 closed square, cubic B-spline and Chaikin steps are exact", "[core][subdivision][seed]",
                   double, float, Q16_16) {
  using S = TestType;
  const auto p = square<S>();
  RefinablePolygon<S, 2, 64> polygon = RefinablePolygon<S, 2, 64>::create(std::span<const Vec2<S>>(p), Boundary::Closed).value();
  SECTION("cubic B-spline") {
    REQUIRE(polygon.try_refine(cubic_bspline_mask()).has_value());
    REQUIRE(polygon.size() == 8);
    CHECK(worst<S>(polygon.vertices(), {{1, 1}, {4, 0}, {7, 1}, {8, 4}, {7, 7}, {4, 8}, {1, 7}, {0, 4}}) == 0);
    REQUIRE(polygon.try_refine(cubic_bspline_mask()).has_value());
    REQUIRE(polygon.size() == 16);
    CHECK(worst<S>(polygon.vertices(),
                   {{1.25, 1.25}, {2.5, 0.5}, {4, 0.25}, {5.5, 0.5}, {6.75, 1.25}, {7.5, 2.5}, {7.75, 4}, {7.5, 5.5}}) == 0);
  }
  SECTION("Chaikin") {
    REQUIRE(polygon.try_refine(chaikin_mask()).has_value());
    CHECK(worst<S>(polygon.vertices(), {{2, 0}, {6, 0}, {8, 2}, {8, 6}, {6, 8}, {2, 8}, {0, 6}, {0, 2}}) == 0);
    REQUIRE(polygon.try_refine(chaikin_mask()).has_value());
    CHECK(worst<S>(polygon.vertices(), {{3, 0}, {5, 0}, {6.5, 0.5}, {7.5, 1.5}, {8, 3}, {8, 5}, {7.5, 6.5}, {6.5, 7.5}}) == 0);
  }
  SECTION("four-point") {
    REQUIRE(polygon.try_refine(four_point_mask()).has_value());
    CHECK(worst<S>(polygon.vertices(), {{0, 0}, {4, -1}, {8, 0}, {9, 4}, {8, 8}, {4, 9}, {0, 8}, {-1, 4}}) == 0);
    REQUIRE(polygon.try_refine(four_point_mask()).has_value());
    CHECK(worst<S>(polygon.vertices(), {{0, 0},
                                        {29 / 16., -13 / 16.},
                                        {4, -1},
                                        {99 / 16., -13 / 16.},
                                        {8, 0},
                                        {141 / 16., 29 / 16.},
                                        {9, 4},
                                        {141 / 16., 99 / 16.}}) == 0);
  }
}

TEMPLATE_TEST_CASE("subdivision: TV-14 closed square, ternary quadratic steps", "[core][subdivision][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto p = square<S>();
  auto polygon = RefinablePolygon<S, 2, 64>::create(std::span<const Vec2<S>>(p), Boundary::Closed).value();
  REQUIRE(polygon.try_refine(ternary_quadratic_mask()).has_value());
  REQUIRE(polygon.size() == 12);
  CHECK(worst<S>(polygon.vertices(), {{8 / 9., 8 / 9.},
                                      {8 / 3., 0},
                                      {16 / 3., 0},
                                      {64 / 9., 8 / 9.},
                                      {8, 8 / 3.},
                                      {8, 16 / 3.},
                                      {64 / 9., 64 / 9.},
                                      {16 / 3., 8},
                                      {8 / 3., 8},
                                      {8 / 9., 64 / 9.},
                                      {0, 16 / 3.},
                                      {0, 8 / 3.}}) <= ternary_tolerance<S>(1));
  REQUIRE(polygon.try_refine(ternary_quadratic_mask()).has_value());
  REQUIRE(polygon.size() == 36);
  CHECK(worst<S>(polygon.vertices(), {{80 / 81., 80 / 81.},
                                      {40 / 27., 16 / 27.},
                                      {56 / 27., 8 / 27.},
                                      {224 / 81., 8 / 81.},
                                      {32 / 9., 0},
                                      {40 / 9., 0},
                                      {424 / 81., 8 / 81.},
                                      {160 / 27., 8 / 27.}}) <= ternary_tolerance<S>(2));
}

TEMPLATE_TEST_CASE("subdivision: TV-14 limit points and limit Bezier pieces", "[core][subdivision][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto p = square<S>();
  const std::span<const Vec2<S>> polygon(p);
  const double tol = FixedPoint<S> ? to_double(resolution<S>()) : 1e-6;
  CHECK(max_error(limit_point(SubdivisionScheme::CubicBSpline, polygon, 0, Boundary::Closed).value(), {4 / 3., 4 / 3.}) <= tol);
  const auto cubic = limit_bezier(SubdivisionScheme::CubicBSpline, polygon, 0, Boundary::Closed).value();
  REQUIRE(cubic.degree() == 3);
  CHECK(max_error(cubic[0], {4 / 3., 4 / 3.}) <= tol);
  CHECK(max_error(cubic[1], {8 / 3., 0}) <= tol);
  CHECK(max_error(cubic[2], {16 / 3., 0}) <= tol);
  CHECK(max_error(cubic[3], {20 / 3., 4 / 3.}) <= tol);
  // The edge middle's limit (4, 1/3) is the piece's midpoint.
  CHECK(max_error(cubic.point_at(scalar<S>(0.5)), {4, 1 / 3.}) <= 2 * tol);
  for (const auto scheme : {SubdivisionScheme::Chaikin, SubdivisionScheme::TernaryQuadratic}) {
    const auto corner = limit_bezier(scheme, polygon, 1, Boundary::Closed).value();
    REQUIRE(corner.degree() == 2);
    CHECK(max_error(corner[0], {4, 0}) == 0);
    CHECK(max_error(corner[1], {8, 0}) == 0);
    CHECK(max_error(corner[2], {8, 4}) == 0);
    CHECK(max_error(corner.point_at(scalar<S>(0.5)), {7, 1}) == 0);
    CHECK(max_error(limit_point(scheme, polygon, 1, Boundary::Closed).value(), {7, 1}) == 0);
    CHECK(max_error(limit_point(scheme, polygon, 0, Boundary::Closed).value(), {1, 1}) == 0);
  }
  for (std::size_t k = 0; k < 4; ++k) CHECK(limit_point(SubdivisionScheme::FourPoint, polygon, k, Boundary::Closed).value() == p[k]);
  CHECK(limit_bezier(SubdivisionScheme::FourPoint, polygon, 0, Boundary::Closed).error() == Error::InvalidArgument);
  CHECK(limit_point(SubdivisionScheme::CubicBSpline, polygon, 4, Boundary::Closed).error() == Error::InvalidArgument);
}

TEST_CASE("subdivision: TV-14 refined vertices converge to the limit points", "[core][subdivision][seed]") {
  const auto p = square<double>();
  // Vertex 0 keeps index 0 and the middle of edge 0 is at index 2^(L-1) after L binary steps.
  auto cubic = RefinablePolygon<double, 2, 4096>::create(std::span<const Vec2<double>>(p), Boundary::Closed).value();
  REQUIRE(cubic.try_refine(cubic_bspline_mask(), 10).has_value());
  CHECK(max_error(cubic.vertices()[0], {4 / 3., 4 / 3.}) < 1e-5);
  CHECK(max_error(cubic.vertices()[512], {4, 1 / 3.}) < 1e-5);
  auto ternary = RefinablePolygon<double, 2, 4096>::create(std::span<const Vec2<double>>(p), Boundary::Closed).value();
  REQUIRE(ternary.try_refine(ternary_quadratic_mask(), 6).has_value());
  CHECK(max_error(ternary.vertices()[0], {1, 1}) < 1e-5);
  auto four = RefinablePolygon<double, 2, 4096>::create(std::span<const Vec2<double>>(p), Boundary::Closed).value();
  REQUIRE(four.try_refine(four_point_mask(), 8).has_value());
  for (std::size_t k = 0; k < 4; ++k) CHECK(four.vertices()[k * 256] == p[k]);
}

TEMPLATE_TEST_CASE("subdivision: TV-15 open zigzag with the finite rule", "[core][subdivision][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto p = zigzag<S>();
  const std::span<const Vec2<S>> polygon(p);
  std::array<Vec2<S>, 16> out{};
  SECTION("cubic B-spline: 5 -> 7") {
    const auto r = refine(cubic_bspline_mask(), polygon, Boundary::Finite, std::span<Vec2<S>>(out)).value();
    CHECK(r.first_index == 1);
    REQUIRE(r.count == 7);
    CHECK(worst<S>(std::span<const Vec2<S>>(out), {{2, 4}, {4, 6}, {6, 4}, {8, 2}, {10, 4}, {12, 6}, {14, 4}}) == 0);
  }
  SECTION("Chaikin: 5 -> 8") {
    const auto r = refine(chaikin_mask(), polygon, Boundary::Finite, std::span<Vec2<S>>(out)).value();
    CHECK(r.first_index == 0);
    REQUIRE(r.count == 8);
    CHECK(worst<S>(std::span<const Vec2<S>>(out), {{1, 2}, {3, 6}, {5, 6}, {7, 2}, {9, 2}, {11, 6}, {13, 6}, {15, 2}}) == 0);
  }
  SECTION("ternary: 5 -> 11") {
    const auto r = refine(ternary_quadratic_mask(), polygon, Boundary::Finite, std::span<Vec2<S>>(out)).value();
    CHECK(r.first_index == 1);
    REQUIRE(r.count == 11);
    CHECK(worst<S>(std::span<const Vec2<S>>(out), {{4 / 3., 8 / 3.},
                                                   {8 / 3., 16 / 3.},
                                                   {4, 56 / 9.},
                                                   {16 / 3., 16 / 3.},
                                                   {20 / 3., 8 / 3.},
                                                   {8, 16 / 9.},
                                                   {28 / 3., 8 / 3.},
                                                   {32 / 3., 16 / 3.},
                                                   {12, 56 / 9.},
                                                   {40 / 3., 16 / 3.},
                                                   {44 / 3., 8 / 3.}}) <= ternary_tolerance<S>(1));
  }
  SECTION("four-point: the contiguous run p_2..p_6") {
    const auto r = refine(four_point_mask(), polygon, Boundary::Finite, std::span<Vec2<S>>(out)).value();
    CHECK(r.first_index == 2);
    REQUIRE(r.count == 5);
    CHECK(worst<S>(std::span<const Vec2<S>>(out), {{4, 8}, {6, 4}, {8, 0}, {10, 4}, {12, 8}}) == 0);
  }
}

TEMPLATE_TEST_CASE("subdivision: TV-15 open zigzag with replicated end points", "[core][subdivision][seed]", double, float, Q16_16) {
  using S = TestType;
  const auto p = zigzag<S>();
  const std::span<const Vec2<S>> polygon(p);
  std::array<Vec2<S>, 16> out{};
  SECTION("cubic B-spline adds p_0, p_8 and the fixed end points") {
    const auto r = refine(cubic_bspline_mask(), polygon, Boundary::PseudoFinite, std::span<Vec2<S>>(out)).value();
    CHECK(r.first_index == -1);
    REQUIRE(r.count == 11);
    CHECK(worst<S>(std::span<const Vec2<S>>(out), {{0, 0},
                                                   {0.5, 1},
                                                   {2, 4},
                                                   {4, 6},
                                                   {6, 4},
                                                   {8, 2},
                                                   {10, 4},
                                                   {12, 6},
                                                   {14, 4},
                                                   {15.5, 1},
                                                   {16, 0}}) == 0);
  }
  SECTION("Chaikin adds the end points") {
    const auto r = refine(chaikin_mask(), polygon, Boundary::PseudoFinite, std::span<Vec2<S>>(out)).value();
    CHECK(r.first_index == -1);
    REQUIRE(r.count == 10);
    CHECK(worst<S>(std::span<const Vec2<S>>(out), {{0, 0}, {1, 2}, {3, 6}, {5, 6}, {7, 2}, {9, 2}, {11, 6}, {13, 6}, {15, 2}, {16, 0}}) ==
          0);
  }
  SECTION("repeated refinement keeps the end points") {
    auto polygon_levels = RefinablePolygon<S, 2, 256>::create(polygon, Boundary::PseudoFinite).value();
    REQUIRE(polygon_levels.try_refine(cubic_bspline_mask(), 3).has_value());
    CHECK(polygon_levels.vertices().front() == p.front());
    CHECK(polygon_levels.vertices().back() == p.back());
  }
}

TEMPLATE_TEST_CASE("subdivision: limits of open polygons follow the boundary rule", "[core][subdivision]", double, float, Q16_16) {
  using S = TestType;
  const auto p = zigzag<S>();
  const std::span<const Vec2<S>> polygon(p);
  // Finite rule: no neighbour beyond the ends, so no limit at P_0 and no piece ending at P_K.
  CHECK(limit_point(SubdivisionScheme::CubicBSpline, polygon, 0, Boundary::Finite).error() == Error::InvalidArgument);
  CHECK(limit_bezier(SubdivisionScheme::Chaikin, polygon, 4, Boundary::Finite).error() == Error::InvalidArgument);
  CHECK(limit_bezier(SubdivisionScheme::CubicBSpline, polygon, 4, Boundary::PseudoFinite).error() == Error::InvalidArgument);
  CHECK(max_error(limit_point(SubdivisionScheme::CubicBSpline, polygon, 1, Boundary::Finite).value(), {4, 16 / 3.}) <=
        to_double(resolution<S>()) * (FixedPoint<S> ? 1 : 16));
  CHECK(limit_point(SubdivisionScheme::FourPoint, polygon, 0, Boundary::Finite).value() == p[0]);
  // Pseudo-finite: replicated ends, (5 P_0 + P_1)/6 and (7 P_0 + P_1)/8.
  CHECK(max_error(limit_point(SubdivisionScheme::CubicBSpline, polygon, 0, Boundary::PseudoFinite).value(), {2 / 3., 4 / 3.}) <=
        to_double(resolution<S>()) * (FixedPoint<S> ? 1 : 16));
  CHECK(max_error(limit_point(SubdivisionScheme::Chaikin, polygon, 0, Boundary::PseudoFinite).value(), {0.5, 1}) == 0);
}

TEMPLATE_TEST_CASE("subdivision: TV-16 the four-point scheme reproduces cubics but not quartics", "[core][subdivision][seed]", double,
                   float, Q16_16) {
  using S = TestType;
  std::array<Vec2<S>, 7> cubic{};
  std::array<Vec2<S>, 7> quartic{};
  for (int x = -3; x <= 3; ++x) {
    cubic[static_cast<std::size_t>(x + 3)] = point<S>(x, x * x * x);
    quartic[static_cast<std::size_t>(x + 3)] = point<S>(x, x * x * x * x);
  }
  std::array<Vec2<S>, 16> out{};
  const auto r = refine(four_point_mask(), std::span<const Vec2<S>>(cubic), Boundary::Finite, std::span<Vec2<S>>(out)).value();
  REQUIRE(r.first_index == 2);
  REQUIRE(r.count == 9);
  // New (odd) vertices p_3, p_5, p_7, p_9 sit at x = -3/2, -1/2, 1/2, 3/2.
  CHECK(max_error(out[1], {-1.5, -27 / 8.}) == 0);
  CHECK(max_error(out[3], {-0.5, -1 / 8.}) == 0);
  CHECK(max_error(out[5], {0.5, 1 / 8.}) == 0);
  CHECK(max_error(out[7], {1.5, 27 / 8.}) == 0);
  REQUIRE(refine(four_point_mask(), std::span<const Vec2<S>>(quartic), Boundary::Finite, std::span<Vec2<S>>(out)).has_value());
  CHECK(max_error(out[5], {0.5, -0.5}) == 0);
}

namespace {
std::vector<std::int64_t> convolve(const std::vector<std::int64_t>& a, const std::vector<std::int64_t>& b) {
  std::vector<std::int64_t> c(a.size() + b.size() - 1, 0);
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  }
  return c;
}
void check_symbol(const SubdivisionMask& mask, const std::vector<std::int64_t>& symbol_numerators) {
  REQUIRE(symbol_numerators.size() == mask.length());
  for (std::size_t i = 0; i < mask.length(); ++i) {
    CHECK(mask.numerator(mask.first_index() + static_cast<std::int64_t>(i)) == symbol_numerators[i]);
  }
}
}  // namespace

TEST_CASE("subdivision: TV-17 stencils sum to one and the symbols factor as stated", "[core][subdivision][seed]") {
  const std::array<SubdivisionMask, 4> masks{cubic_bspline_mask(), chaikin_mask(), ternary_quadratic_mask(), four_point_mask()};
  const std::array<std::int64_t, 4> mask_sums{2, 2, 3, 2};
  for (std::size_t s = 0; s < 4; ++s) {
    std::int64_t total = 0;
    for (std::int64_t i = masks[s].first_index(); i <= masks[s].last_index(); ++i) total += masks[s].numerator(i);
    CHECK(total == mask_sums[s] * masks[s].denominator());
    for (std::size_t r = 0; r < masks[s].arity(); ++r) CHECK(masks[s].stencil_sum(r) == masks[s].denominator());
  }
  const std::vector<std::int64_t> one_plus_z{1, 1};
  const auto power4 = convolve(convolve(one_plus_z, one_plus_z), convolve(one_plus_z, one_plus_z));
  check_symbol(masks[0], power4);                                               // (1+z)^4 / 8
  check_symbol(masks[1], convolve(convolve(one_plus_z, one_plus_z), one_plus_z));  // (1+z)^3 / 4
  const std::vector<std::int64_t> ternary_base{1, 1, 1};
  check_symbol(masks[2], convolve(convolve(ternary_base, ternary_base), ternary_base));  // (1+z+z^2)^3 / 9
  check_symbol(masks[3], convolve(power4, {-1, 4, -1}));                                // (1+z)^4 (-1+4z-z^2) / 16
  CHECK(masks[0].denominator() == 8);
  CHECK(masks[1].denominator() == 4);
  CHECK(masks[2].denominator() == 9);
  CHECK(masks[3].denominator() == 16);
  CHECK(scheme_mask(SubdivisionScheme::TernaryQuadratic).arity() == 3);
}

TEST_CASE("subdivision: masks whose stencils do not sum to one are rejected", "[core][subdivision]") {
  const auto wrong_denominator = SubdivisionMask::create(2, {1, 4, 6, 4, 1}, 16);
  CHECK(wrong_denominator.error() == Error::InvalidMask);
  const auto bad_stencil = SubdivisionMask::create(2, {2, 3, 3, 0}, 4);  // stencils 2+3 = 5 and 3+0 = 3
  REQUIRE(!bad_stencil.has_value());
  CHECK(bad_stencil.error() == Error::InvalidMask);
  CHECK(SubdivisionMask::create(3, {1, 3, 3, 1}, 4).error() == Error::InvalidMask);
  CHECK(SubdivisionMask::create(2, {1, 2, 1}, 0).error() == Error::InvalidMask);
  CHECK(SubdivisionMask::create(2, std::span<const std::int32_t>(), 1).error() == Error::InvalidMask);
  CHECK(SubdivisionMask::create(1, {1}, 1).error() == Error::InvalidArgument);
  const std::array<std::int32_t, 16> long_mask{};
  CHECK(SubdivisionMask::create(2, std::span<const std::int32_t>(long_mask), 1).error() == Error::CapacityExceeded);
  // Linear interpolation [1,2,1]/2 is valid: it keeps the vertices and inserts edge midpoints.
  const auto linear = SubdivisionMask::create(2, {1, 2, 1}, 2).value();
  const auto p = square<double>();
  std::array<Vec2<double>, 8> out{};
  REQUIRE(refine(linear, std::span<const Vec2<double>>(p), Boundary::Closed, std::span<Vec2<double>>(out)).has_value());
  CHECK(max_error(out[0], {0, 0}) == 0);
  CHECK(max_error(out[1], {4, 0}) == 0);
}

TEMPLATE_TEST_CASE("subdivision: output buffers and polygon capacities are checked", "[core][subdivision]", double, float, Q16_16) {
  using S = TestType;
  const auto p = square<S>();
  std::array<Vec2<S>, 7> small{};
  const auto r = refine(chaikin_mask(), std::span<const Vec2<S>>(p), Boundary::Closed, std::span<Vec2<S>>(small));
  CHECK(r.error() == Error::BufferTooSmall);
  CHECK(r.where() == 8);
  auto polygon = RefinablePolygon<S, 2, 8>::create(std::span<const Vec2<S>>(p), Boundary::Closed).value();
  const auto grown = polygon.try_refine(chaikin_mask(), 2);
  CHECK(grown.error() == Error::CapacityExceeded);
  CHECK(grown.where() == 16);
  CHECK(polygon.size() == 8);  // the level that fitted is kept
  CHECK(RefinablePolygon<S, 2, 3>::create(std::span<const Vec2<S>>(p), Boundary::Closed).error() == Error::CapacityExceeded);
  const std::array<Vec2<S>, 1> single{point<S>(1, 1)};
  CHECK(refine(chaikin_mask(), std::span<const Vec2<S>>(single), Boundary::Finite, std::span<Vec2<S>>(small)).error() ==
        Error::TooFewPoints);
  CHECK(refine(chaikin_mask(), std::span<const Vec2<S>>(), Boundary::Closed, std::span<Vec2<S>>(small)).error() == Error::TooFewPoints);
}

TEST_CASE("subdivision: the four-point scheme leaving the Q16.16 range reports FixedOverflow", "[core][subdivision]") {
  using S = Q16_16;
  const std::array<Vec2<S>, 4> p{point<S>(-32000, 0), point<S>(32000, 0), point<S>(32000, 0), point<S>(-32000, 0)};
  std::array<Vec2<S>, 8> out{};
  const auto r = refine(four_point_mask(), std::span<const Vec2<S>>(p), Boundary::Closed, std::span<Vec2<S>>(out));
  REQUIRE(!r.has_value());
  CHECK(r.error() == Error::FixedOverflow);
}

namespace {
/// Closed-form uniform quadratic B-spline of a closed polygon (seed 001 §9 notes), in double:
/// the piece around d_j is the Bézier (d_{j-1}+d_j)/2, d_j, (d_j+d_{j+1})/2 on [j - 1/2, j + 1/2].
std::array<double, 2> quadratic_bspline(const std::vector<std::array<double, 2>>& d, double u) {
  const auto n = static_cast<long>(d.size());
  const long j = static_cast<long>(std::floor(u + 0.5));
  const double t = u - (static_cast<double>(j) - 0.5);
  const auto& previous = d[static_cast<std::size_t>(((j - 1) % n + n) % n)];
  const auto& middle = d[static_cast<std::size_t>((j % n + n) % n)];
  const auto& next = d[static_cast<std::size_t>(((j + 1) % n + n) % n)];
  std::array<double, 2> r{};
  for (std::size_t a = 0; a < 2; ++a) {
    const double b0 = (previous[a] + middle[a]) / 2;
    const double b2 = (middle[a] + next[a]) / 2;
    r[a] = (1 - t) * (1 - t) * b0 + 2 * t * (1 - t) * middle[a] + t * t * b2;
  }
  return r;
}
}  // namespace

TEMPLATE_TEST_CASE("subdivision: Chaikin converges to the quadratic B-spline of the original polygon", "[core][subdivision][seed]",
                   double, float, Q16_16) {
  using S = TestType;
  const std::vector<std::array<double, 2>> d{{0, 0}, {8, -2}, {12, 6}, {4, 10}, {-2, 5}};
  std::array<Vec2<S>, 5> original{};
  for (std::size_t i = 0; i < 5; ++i) original[i] = point<S>(d[i][0], d[i][1]);
  auto polygon = RefinablePolygon<S, 2, 512>::create(std::span<const Vec2<S>>(original), Boundary::Closed).value();
  // Largest second difference of the data, for the distance bound |Q_i − S(c_i)| = |Δ²Q|/8.
  double second_difference = 0;
  for (std::size_t i = 0; i < 5; ++i) {
    for (std::size_t a = 0; a < 2; ++a) {
      second_difference = std::fmax(second_difference, std::fabs(d[(i + 4) % 5][a] - 2 * d[i][a] + d[(i + 1) % 5][a]));
    }
  }
  const double rounding = (FixedPoint<S> ? 2 : 1024) * to_double(resolution<S>());
  for (int level = 1; level <= 6; ++level) {
    REQUIRE(polygon.try_refine(chaikin_mask()).has_value());
    const auto q = polygon.vertices();
    const double spacing = std::ldexp(1.0, -level);
    const double offset = (1 - spacing) / 2;  // vertex i of level L belongs to u = i·2^-L + (1 − 2^-L)/2
    double vertex_distance = 0;
    double midpoint_error = 0;
    for (std::size_t i = 0; i < q.size(); ++i) {
      const double u = static_cast<double>(i) * spacing + offset;
      vertex_distance = std::fmax(vertex_distance, max_error(q[i], quadratic_bspline(d, u)));
      // Edge midpoints of every level lie exactly on the limit curve (knot insertion).
      const auto& next = q[(i + 1) % q.size()];
      const std::array<double, 2> midpoint{(to_double(q[i][0]) + to_double(next[0])) / 2, (to_double(q[i][1]) + to_double(next[1])) / 2};
      const auto expected = quadratic_bspline(d, u + spacing / 2);
      midpoint_error = std::fmax(midpoint_error, std::fmax(std::fabs(midpoint[0] - expected[0]), std::fabs(midpoint[1] - expected[1])));
    }
    CHECK(midpoint_error <= rounding);
    CHECK(vertex_distance <= second_difference / 8 * std::ldexp(1.0, -2 * level) + rounding);
  }
}
