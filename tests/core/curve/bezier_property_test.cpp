// SPDX-License-Identifier: MIT
// Bézier core properties on random curves (degrees 1..7, 2D and 3D, coordinates in [-100,100]),
// in double, float and Q16.16, against long double references that share no code with the library.
// Seed and count: CURVESTEP_TEST_SEED, CURVESTEP_TEST_COUNT.
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <vector>

#include "curve_test_support.hpp"

using namespace curvestep;
using namespace curvestep::testing;

namespace {

constexpr double coordinate_range = 100.0;

template <class S, std::size_t Dim>
using Curve = Bezier<S, Dim, 7>;

template <class S, std::size_t Dim>
Curve<S, Dim> make_curve(const std::vector<Vec<S, Dim>>& points) {
  auto c = Curve<S, Dim>::create(std::span<const Vec<S, Dim>>(points.data(), points.size()));
  REQUIRE(c.has_value());
  return c.value();
}

/// A random curve of random degree 1..7.
template <class S, std::size_t Dim>
std::vector<Vec<S, Dim>> random_polygon(Random& random, double range = coordinate_range) {
  return random.polygon<S, Dim>(random.integer(2, 8), range);
}

/// A random curve: its polygon, the curve and the polygon in long double.
template <class S, std::size_t Dim>
struct RandomCurve {
  std::vector<Vec<S, Dim>> points;
  Curve<S, Dim> curve;
  std::vector<RealPoint<Dim>> b;
};
template <class S, std::size_t Dim>
RandomCurve<S, Dim> random_curve(Random& random) {
  auto points = random_polygon<S, Dim>(random);
  const auto curve = make_curve(points);
  auto b = to_real<S, Dim>(points);
  return {std::move(points), curve, std::move(b)};
}

/// Runs a check in 2D and then in 3D with one Random(salt) and test_count(fallback) cases each:
/// `check(random, count, dim)` with dim a std::integral_constant.
template <class Check>
void in_2d_and_3d(std::uint32_t salt, int fallback, Check check) {
  Random random(salt);
  const int count = test_count(fallback);
  check(random, count, std::integral_constant<std::size_t, 2>{});
  check(random, count, std::integral_constant<std::size_t, 3>{});
}

template <class S, std::size_t Dim>
void check_end_points(Random& random, int count) {
  for (int c = 0; c < count; ++c) {
    const auto points = random_polygon<S, Dim>(random);
    const auto curve = make_curve(points);
    const std::size_t n = curve.degree();
    INFO("case " << c << " degree " << n << " dim " << Dim);
    // P-5: exact end points, and end tangents n (p1 - p0), n (pn - pn-1).
    CHECK(must(curve.evaluate(from_int<S>(0))) == points.front());
    CHECK(must(curve.evaluate(from_int<S>(1))) == points.back());
    const auto b = to_real<S, Dim>(points);
    RealPoint<Dim> start{};
    RealPoint<Dim> end{};
    for (std::size_t a = 0; a < Dim; ++a) {
      start[a] = static_cast<Real>(n) * (b[1][a] - b[0][a]);
      end[a] = static_cast<Real>(n) * (b[n][a] - b[n - 1][a]);
    }
    // Fixed: the hodograph is an exact integer combination; float: two roundings of n·p.
    const double tol = FixedPoint<S> ? 0.0 : 4 * unit<S>() * 2 * static_cast<double>(n) * coordinate_range;
    CHECK(max_error_real(must(curve.derivative_at(from_int<S>(0))), start) <= tol);
    CHECK(max_error_real(must(curve.derivative_at(from_int<S>(1))), end) <= tol);
  }
}

TEMPLATE_TEST_CASE("bezier: random curves interpolate their end points and end tangents", "[core][bezier][property]", double,
                   float, Q16_16) {
  in_2d_and_3d(1, 300, [](Random& random, int count, auto dim) { check_end_points<TestType, decltype(dim)::value>(random, count); });
}

template <class S, std::size_t Dim>
void check_convex_hull(Random& random, int count) {
  for (int c = 0; c < count; ++c) {
    const auto [points, curve, b] = random_curve<S, Dim>(random);
    const auto box = curve.bounding_box();
    // Independent hull of the (projected) control points: a convex combination projects to a
    // convex combination, so in 3D every coordinate plane must contain the projected point.
    constexpr std::array<std::array<std::size_t, 2>, 3> planes{{{0, 1}, {1, 2}, {0, 2}}};
    const std::size_t plane_count = Dim == 2 ? 1 : 3;
    std::vector<std::vector<RealPoint<2>>> hulls;
    for (std::size_t k = 0; k < plane_count; ++k) {
      std::vector<RealPoint<2>> projected;
      for (const auto& p : b) projected.push_back({p[planes[k][0]], p[planes[k][1]]});
      hulls.push_back(convex_hull(projected));
    }
    const double tol = evaluation_tolerance<S>(coordinate_range, curve.degree());
    double worst_box = 0;
    Real worst_hull = 0;
    double worst_reference = 0;
    for (int k = 0; k < 16; ++k) {
      const S t = random.parameter<S>();
      const auto p = must(curve.evaluate(t));
      for (std::size_t a = 0; a < Dim; ++a) {
        worst_box = std::fmax(worst_box, to_double(box.low[a]) - to_double(p[a]));
        worst_box = std::fmax(worst_box, to_double(p[a]) - to_double(box.high[a]));
      }
      const auto pr = to_real(p);
      for (std::size_t h = 0; h < plane_count; ++h) {
        worst_hull = std::max(worst_hull, distance_outside_hull(hulls[h], {pr[planes[h][0]], pr[planes[h][1]]}));
      }
      worst_reference = std::fmax(worst_reference, max_error_real(p, bernstein_sum(b, to_real(t))));
    }
    INFO("case " << c << " degree " << curve.degree() << " dim " << Dim);
    // The control-point box holds every evaluated point (the lerp of a convex combination is
    // documented to stay between its end points); the hull within rounding.
    CHECK(worst_box <= 0.0);
    CHECK(static_cast<double>(worst_hull) <= tol);
    // de Casteljau agrees with the Bernstein sum.
    CHECK(worst_reference <= tol);
  }
}

TEMPLATE_TEST_CASE("bezier: every point is a convex combination of the control points", "[core][bezier][property]", double, float,
                   Q16_16) {
  in_2d_and_3d(2, 300, [](Random& random, int count, auto dim) { check_convex_hull<TestType, decltype(dim)::value>(random, count); });
}

TEMPLATE_TEST_CASE("bezier: P-1 affine map of TV-04 commutes with evaluation exactly", "[core][bezier][property][seed]", double,
                   float, Q16_16) {
  using S = TestType;
  const auto map = [](const Vec<S, 2>& p) {
    return Vec<S, 2>{{p[0] * from_int<S>(2) + p[1] + from_int<S>(1), p[1] - from_int<S>(1)}};
  };
  const std::array<Vec<S, 2>, 4> polygon{point<S>(0, 0), point<S>(1, 2), point<S>(3, 3), point<S>(4, 0)};
  std::array<Vec<S, 2>, 4> mapped{};
  std::transform(polygon.begin(), polygon.end(), mapped.begin(), map);
  const auto original = Curve<S, 2>::create(polygon).value();
  const auto image = Curve<S, 2>::create(mapped).value();
  const S half = scalar<S>(0.5);
  CHECK(max_error(map(original.evaluate(half).value()), {55 / 8., 7 / 8.}) == 0.0);
  CHECK(max_error(must(image.evaluate(half)), {55 / 8., 7 / 8.}) == 0.0);
}

template <class S, std::size_t Dim>
void check_affine(Random& random, int count) {
  for (int c = 0; c < count; ++c) {
    const auto points = random_polygon<S, Dim>(random, 40.0);
    const auto curve = make_curve(points);
    // A random affine map with dyadic entries in [-2,2] (1/256 steps) and shift in [-10,10].
    std::array<std::array<S, Dim>, Dim> matrix{};
    Vec<S, Dim> shift{};
    for (std::size_t i = 0; i < Dim; ++i) {
      for (std::size_t j = 0; j < Dim; ++j) matrix[i][j] = random.quantize<S>(std::round(random.uniform(-2, 2) * 256) / 256);
      shift[i] = random.coordinate<S>(-10, 10);
    }
    const auto map = [&](const Vec<S, Dim>& p) {
      Vec<S, Dim> q = shift;
      for (std::size_t i = 0; i < Dim; ++i) {
        for (std::size_t j = 0; j < Dim; ++j) q[i] = q[i] + matrix[i][j] * p[j];
      }
      return q;
    };
    std::vector<Vec<S, Dim>> mapped;
    for (const auto& p : points) mapped.push_back(map(p));
    const auto image = make_curve(mapped);
    // Error: the map rounds Dim products (Fixed: Dim half units) and amplifies the evaluation
    // error of the original by at most the row sum 2·Dim; the image adds its own evaluation error.
    const auto n = curve.degree();
    const double scale = 2 * Dim * 40.0 + 10;
    const double tol = 2.0 * static_cast<double>(Dim) * evaluation_tolerance<S>(scale, n) + evaluation_tolerance<S>(scale, n) +
                       (static_cast<double>(Dim) + 1) * (FixedPoint<S> ? unit<S>() : 2 * unit<S>() * scale);
    double worst = 0;
    for (int k = 0; k < 8; ++k) {
      const S t = random.parameter<S>();
      const auto a = to_real(map(must(curve.evaluate(t))));
      worst = std::fmax(worst, max_error_real(must(image.evaluate(t)), a));
    }
    INFO("case " << c << " degree " << n << " dim " << Dim);
    CHECK(worst <= tol);
  }
}

TEMPLATE_TEST_CASE("bezier: random affine maps commute with evaluation", "[core][bezier][property]", double, float, Q16_16) {
  in_2d_and_3d(3, 200, [](Random& random, int count, auto dim) { check_affine<TestType, decltype(dim)::value>(random, count); });
}

template <class S, std::size_t Dim>
void check_split(Random& random, int count) {
  for (int c = 0; c < count; ++c) {
    const auto [points, curve, b] = random_curve<S, Dim>(random);
    const S t = random.parameter<S>();
    const auto halves = must(curve.split(t));
    const auto n = curve.degree();
    INFO("case " << c << " degree " << n << " dim " << Dim << " t " << to_double(t));
    REQUIRE(halves.left.degree() == n);
    REQUIRE(halves.right.degree() == n);
    CHECK(halves.left.front() == points.front());
    CHECK(halves.right.back() == points.back());
    CHECK(halves.left.back() == halves.right.front());
    // The halves' control points carry up to n roundings; evaluating them adds n more.
    const double tol = 2 * evaluation_tolerance<S>(coordinate_range, n);
    const Real tr = to_real(t);
    double worst = 0;
    for (int k = 0; k < 8; ++k) {
      const S s = random.parameter<S>();
      const Real sr = to_real(s);
      worst = std::fmax(worst, max_error_real(must(halves.left.evaluate(s)), bernstein_sum(b, tr * sr)));
      worst = std::fmax(worst, max_error_real(must(halves.right.evaluate(s)), bernstein_sum(b, tr + (1 - tr) * sr)));
    }
    CHECK(worst <= tol);
    // segment(t0, t1) is the same restriction by blossoming: p(t0 + (t1 - t0) s).
    S t0 = random.parameter<S>();
    S t1 = random.parameter<S>();
    if (t1 < t0) std::swap(t0, t1);
    const auto piece = must(curve.segment(t0, t1));
    double worst_piece = 0;
    for (int k = 0; k < 8; ++k) {
      const S s = random.parameter<S>();
      const Real u = to_real(t0) + (to_real(t1) - to_real(t0)) * to_real(s);
      worst_piece = std::fmax(worst_piece, max_error_real(must(piece.evaluate(s)), bernstein_sum(b, u)));
    }
    CHECK(worst_piece <= tol);
  }
}

TEMPLATE_TEST_CASE("bezier: split halves reproduce the curve", "[core][bezier][property]", double, float, Q16_16) {
  in_2d_and_3d(4, 300, [](Random& random, int count, auto dim) { check_split<TestType, decltype(dim)::value>(random, count); });
}

template <class S, std::size_t Dim>
void check_elevation(Random& random, int count) {
  for (int c = 0; c < count; ++c) {
    auto points = random_polygon<S, Dim>(random);
    if (points.size() > 7) points.resize(7);  // room for one elevation in MaxDegree 7
    const auto curve = make_curve(points);
    const auto elevated = must(curve.elevated());
    const auto b = to_real<S, Dim>(points);
    const auto n = curve.degree();
    INFO("case " << c << " degree " << n << " dim " << Dim);
    REQUIRE(elevated.degree() == n + 1);
    CHECK(elevated.front() == curve.front());
    CHECK(elevated.back() == curve.back());
    // Elevated control points are rounded once; evaluation of degree n+1 adds n+1 roundings.
    const double tol = evaluation_tolerance<S>(coordinate_range, n + 2);
    double worst = 0;
    for (int k = 0; k < 12; ++k) {
      const S t = random.parameter<S>();
      worst = std::fmax(worst, max_error_real(must(elevated.evaluate(t)), bernstein_sum(b, to_real(t))));
    }
    CHECK(worst <= tol);
  }
}

TEMPLATE_TEST_CASE("bezier: degree elevation leaves the curve unchanged", "[core][bezier][property]", double, float, Q16_16) {
  in_2d_and_3d(5, 300, [](Random& random, int count, auto dim) { check_elevation<TestType, decltype(dim)::value>(random, count); });
}

/// Eighth-order central differences of the Bernstein sum in long double, h = 1/16.
template <std::size_t Dim>
std::array<RealPoint<Dim>, 2> central_differences(const std::vector<RealPoint<Dim>>& b, Real t) {
  return curvestep::testing::central_differences<Dim>([&](Real u) { return bernstein_sum(b, u); }, t, 1.0L / 16);
}

template <class S, std::size_t Dim>
void check_derivatives(Random& random, int count) {
  for (int c = 0; c < count; ++c) {
    const auto [points, curve, b] = random_curve<S, Dim>(random);
    const auto n = curve.degree();
    const auto nd = static_cast<double>(n);
    INFO("case " << c << " degree " << n << " dim " << Dim);
    // Derivative control points are exact integer combinations (Fixed) of size <= n·2·range
    // (first) and n(n-1)·4·range (second); evaluation adds n roundings of that scale.
    const double scale1 = nd * 2 * coordinate_range;
    const double scale2 = nd * (nd - 1) * 4 * coordinate_range;
    const double fd_rounding = 1e-9;  // long double differences of values ~1e2 divided by h^2 = 1/256
    const double tol1 = evaluation_tolerance<S>(scale1, n) + (FixedPoint<S> ? 0.0 : 4 * unit<S>() * scale1) + fd_rounding;
    const double tol2 = evaluation_tolerance<S>(scale2, n) + (FixedPoint<S> ? 0.0 : 8 * unit<S>() * scale2) + fd_rounding;
    double worst1 = 0;
    double worst2 = 0;
    for (int k = 0; k < 6; ++k) {
      const S t = random.parameter<S>();
      const auto reference = central_differences(b, to_real(t));
      worst1 = std::fmax(worst1, max_error_real(must(curve.derivative_at(t, 1)), reference[0]));
      worst2 = std::fmax(worst2, max_error_real(must(curve.derivative_at(t, 2)), reference[1]));
    }
    CHECK(worst1 <= tol1);
    CHECK(worst2 <= tol2);
    // Order n+1: the zero curve (in Q16.16 the intermediate derivatives of high degree leave the
    // range, which is reported as FixedOverflow, so only low degrees there).
    if (!FixedPoint<S> || n <= 2) {
      const auto beyond = must(curve.derivative_at(random.parameter<S>(), n + 1));
      CHECK(beyond == Vec<S, Dim>{});
    }
  }
}

TEMPLATE_TEST_CASE("derivative: matches an eighth-order central finite difference", "[core][bezier][property]", double, float,
                   Q16_16) {
  in_2d_and_3d(6, 250, [](Random& random, int count, auto dim) { check_derivatives<TestType, decltype(dim)::value>(random, count); });
}

template <class S, std::size_t Dim>
void check_blossom(Random& random, int count) {
  for (int c = 0; c < count; ++c) {
    const auto [points, curve, b] = random_curve<S, Dim>(random);
    const auto n = curve.degree();
    INFO("case " << c << " degree " << n << " dim " << Dim);
    std::vector<S> u(n);
    for (auto& x : u) x = random.parameter<S>();
    std::vector<Real> ur;
    for (S x : u) ur.push_back(to_real(x));
    const auto expected = blossom_subset_sum(b, ur);
    const double tol = evaluation_tolerance<S>(coordinate_range, n);
    // Every permutation for degree <= 5; 24 random shuffles above.
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t{0});
    double worst = 0;
    int permutations = 0;
    const auto check_order = [&] {
      std::vector<S> arguments;
      for (std::size_t i : order) arguments.push_back(u[i]);
      worst = std::fmax(worst, max_error_real(must(curve.blossom(arguments)), expected));
      ++permutations;
    };
    if (n <= 5) {
      do check_order();
      while (std::next_permutation(order.begin(), order.end()));
    } else {
      for (int k = 0; k < 24; ++k) {
        std::shuffle(order.begin(), order.end(), random.engine());
        check_order();
      }
    }
    CHECK(permutations > 0);
    CHECK(worst <= tol);
    // Diagonal: P(t, ..., t) = p(t); P(0^{n-i}, 1^i) = b_i exactly.
    const S t = random.parameter<S>();
    const std::vector<S> diagonal(n, t);
    CHECK(max_error_real(must(curve.blossom(diagonal)), bernstein_sum(b, to_real(t))) <= tol);
    CHECK(max_error_real(must(curve.blossom(diagonal)), to_real(must(curve.evaluate(t)))) <= tol);
    for (std::size_t i = 0; i <= n; ++i) {
      std::vector<S> corner(n, from_int<S>(0));
      for (std::size_t k = n - i; k < n; ++k) corner[k] = from_int<S>(1);
      CHECK(must(curve.blossom(corner)) == points[i]);
    }
  }
}

TEMPLATE_TEST_CASE("blossom: symmetric in its arguments and the curve on the diagonal", "[core][bezier][property]", double, float,
                   Q16_16) {
  in_2d_and_3d(7, 200, [](Random& random, int count, auto dim) { check_blossom<TestType, decltype(dim)::value>(random, count); });
}

TEMPLATE_TEST_CASE("bezier: P-2 reversed TV-04 at 1/4 equals the original at 3/4", "[core][bezier][property][seed]", double, float,
                   Q16_16) {
  using S = TestType;
  const auto curve = Curve<S, 2>::create({point<S>(0, 0), point<S>(1, 2), point<S>(3, 3), point<S>(4, 0)}).value();
  CHECK(max_error(curve.reversed().evaluate(scalar<S>(0.25)).value(), {99 / 32., 99 / 64.}) == 0.0);
  CHECK(max_error(must(curve.evaluate(scalar<S>(0.75))), {99 / 32., 99 / 64.}) == 0.0);
}

template <class S, std::size_t Dim>
void check_reversal(Random& random, int count) {
  for (int c = 0; c < count; ++c) {
    const auto points = random_polygon<S, Dim>(random);
    const auto curve = make_curve(points);
    const auto reversed = curve.reversed();
    const auto b = to_real<S, Dim>(points);
    INFO("case " << c << " degree " << curve.degree() << " dim " << Dim);
    CHECK(reversed.front() == curve.back());
    CHECK(reversed.back() == curve.front());
    double worst = 0;
    for (int k = 0; k < 8; ++k) {
      const S t = random.parameter<S>();
      const S s = from_int<S>(1) - t;  // exact in every format for t in [0,1]
      worst = std::fmax(worst, max_error_real(must(reversed.evaluate(s)), bernstein_sum(b, to_real(t))));
    }
    CHECK(worst <= evaluation_tolerance<S>(coordinate_range, curve.degree()));
  }
}

TEMPLATE_TEST_CASE("bezier: the reversed polygon traces the curve backwards", "[core][bezier][property]", double, float, Q16_16) {
  in_2d_and_3d(8, 300, [](Random& random, int count, auto dim) { check_reversal<TestType, decltype(dim)::value>(random, count); });
}

template <class S, std::size_t Dim>
void check_power_basis(Random& random, int count) {
  for (int c = 0; c < count; ++c) {
    // |a_i| <= C(n,i) 2^i max|b| <= 672 max|b| for n <= 7: coordinates within 40 keep Q16.16 in range.
    const auto points = random_polygon<S, Dim>(random, 40.0);
    const auto curve = make_curve(points);
    const auto b = to_real<S, Dim>(points);
    const auto n = curve.degree();
    INFO("case " << c << " degree " << n << " dim " << Dim);
    const auto power = must(to_power_basis(curve));
    REQUIRE(power.degree == n);
    // Independent expansion: a_i = Σ_k C(n,k) b_k · [t^i] t^k (1-t)^(n-k).
    for (std::size_t i = 0; i <= n; ++i) {
      RealPoint<Dim> a{};
      for (std::size_t k = 0; k <= i; ++k) {
        const Real sign = (i - k) % 2 == 0 ? 1 : -1;
        const Real w = binomial_real(n, k) * binomial_real(n - k, i - k) * sign;
        for (std::size_t axis = 0; axis < Dim; ++axis) a[axis] += w * b[k][axis];
      }
      const double tol = FixedPoint<S> ? 0.0 : 2 * unit<S>() * 700 * 40 * static_cast<double>(n + 1);
      CHECK(max_error_real(power.coefficients[i], a) <= tol);
    }
    const auto back = must(from_power_basis(power));
    REQUIRE(back.degree() == n);
    for (std::size_t i = 0; i <= n; ++i) {
      // Fixed: both directions are exact integer combinations, so the round trip is exact.
      const double tol = FixedPoint<S> ? 0.0 : 4 * unit<S>() * 700 * 40 * static_cast<double>(n + 1);
      CHECK(max_error_real(back[i], b[i]) <= tol);
    }
    // Horner agrees with the Bernstein sum (Fixed: n products rounded, each error amplified by t <= 1).
    for (int k = 0; k < 4; ++k) {
      const S t = random.parameter<S>();
      const double tol = FixedPoint<S> ? static_cast<double>(n + 1) * unit<S>() : 4 * unit<S>() * 700 * 40 * static_cast<double>(n + 1);
      CHECK(max_error_real(power.evaluate(t), bernstein_sum(b, to_real(t))) <= tol);
    }
  }
}

TEMPLATE_TEST_CASE("power basis: round trip and Horner agree with the Bernstein form", "[core][bezier][property]", double, float,
                   Q16_16) {
  in_2d_and_3d(9, 250, [](Random& random, int count, auto dim) { check_power_basis<TestType, decltype(dim)::value>(random, count); });
}

TEMPLATE_TEST_CASE("bernstein: partition of unity, symmetry and the closed form", "[core][bezier][property]", double, float,
                   Q16_16) {
  using S = TestType;
  Random random(10);
  const int count = test_count(400);
  for (int c = 0; c < count; ++c) {
    const std::size_t n = random.integer(0, 7);
    const S t = random.parameter<S>();
    const S s = from_int<S>(1) - t;
    INFO("case " << c << " n " << n << " t " << to_double(t));
    const auto values = bernstein_all<7>(n, t);
    const auto mirrored = bernstein_all<7>(n, s);
    // Each triangular-scheme level rounds every entry once (Fixed: half a unit).
    const double tol = static_cast<double>(n + 1) * unit<S>() * (FixedPoint<S> ? 1.0 : 2.0);
    Real sum = 0;
    double worst = 0;
    for (std::size_t i = 0; i <= n; ++i) {
      sum += to_real(values[i]);
      const Real exact = binomial_real(n, i) * power(to_real(t), i) * power(1 - to_real(t), n - i);
      worst = std::fmax(worst, static_cast<double>(std::fabs(to_real(values[i]) - exact)));
      worst = std::fmax(worst, static_cast<double>(std::fabs(to_real(values[i]) - to_real(mirrored[n - i]))));
      CHECK(!(values[i] < S{}));
      CHECK(to_double(bernstein(n, i, t)) == to_double(values[i]));
    }
    CHECK(static_cast<double>(std::fabs(sum - 1)) <= tol);
    CHECK(worst <= 2 * tol);
    for (std::size_t i = n + 1; i <= 7; ++i) CHECK(values[i] == S{});
  }
}

/// Control-polygon distance bound (seed 001 Theorem 4.1, §10 item 10):
/// max_i ||p(i/n) - b_i||_inf <= floor(n/2) ceil(n/2) / (2n) · max_i ||Δ² b_i||_inf.
template <std::size_t Dim>
Real flatness_bound(const std::vector<RealPoint<Dim>>& b) {
  const std::size_t n = b.size() - 1;
  if (n < 2) return 0;
  Real m = 0;
  for (std::size_t i = 0; i + 2 <= n; ++i) {
    for (std::size_t a = 0; a < Dim; ++a) m = std::max(m, std::fabs(b[i + 2][a] - 2 * b[i + 1][a] + b[i][a]));
  }
  const auto lower = static_cast<Real>(n / 2);
  const auto upper = static_cast<Real>((n + 1) / 2);
  return lower * upper / (2 * static_cast<Real>(n)) * m;
}

TEMPLATE_TEST_CASE("bezier: curve stays within the TV-10 control polygon bound and halving shrinks it",
                   "[core][bezier][property]", double, float, Q16_16) {
  using S = TestType;
  Random random(11);
  const int count = test_count(200);
  for (int c = 0; c < count; ++c) {
    const auto points = random_polygon<S, 2>(random);
    const auto curve = make_curve(points);
    const auto b = to_real<S, 2>(points);
    const auto n = curve.degree();
    INFO("case " << c << " degree " << n);
    const double tol = evaluation_tolerance<S>(coordinate_range, n);
    const Real bound = flatness_bound(b);
    for (std::size_t i = 0; i <= n; ++i) {
      // i/n is not representable in general: evaluate the reference at the quantized parameter.
      const S t = random.quantize<S>(static_cast<double>(i) / static_cast<double>(n));
      const auto p = must(curve.evaluate(t));
      RealPoint<2> d{};
      for (std::size_t a = 0; a < 2; ++a) d[a] = to_real(p[a]) - b[i][a];
      // The quantized parameter moves the point by at most |p'| · |Δt| <= n·200·unit.
      const double shift = static_cast<double>(n) * 200 * unit<S>();
      CHECK(static_cast<double>(max_norm_real(d) - bound) <= tol + shift);
    }
    // Each halving reduces the bound at least 4x (Δ² of a half is at most a quarter of the parent's).
    const auto halves = curve.split(scalar<S>(0.5)).value();
    const Real left = flatness_bound(to_real<S, 2>(halves.left.control_points()));
    const Real right = flatness_bound(to_real<S, 2>(halves.right.control_points()));
    const double slack = 4 * evaluation_tolerance<S>(coordinate_range, n);
    CHECK(static_cast<double>(left - bound / 4) <= slack);
    CHECK(static_cast<double>(right - bound / 4) <= slack);
  }
}

}  // namespace
