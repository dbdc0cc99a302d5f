// SPDX-License-Identifier: MIT
// Rational Bézier curves and circular arcs: seed vectors TV-15/TV-16 and properties on random
// curves in double, float and Q16.16 against long double references.
#include <array>
#include <cmath>
#include <vector>

#include "curve_test_support.hpp"

using namespace curvestep;
using namespace curvestep::testing;

namespace {

template <class S, std::size_t Dim = 2>
using Rational = RationalBezier<S, Dim, 7>;

constexpr long double pi = 3.141592653589793238462643383279502884L;

/// Σ w_i b_i B_i / Σ w_i B_i in long double (Bernstein sums, no de Casteljau).
template <std::size_t Dim>
RealPoint<Dim> rational_reference(const std::vector<RealPoint<Dim>>& b, const std::vector<Real>& w, Real t) {
  const std::size_t n = b.size() - 1;
  RealPoint<Dim> numerator{};
  Real denominator = 0;
  for (std::size_t i = 0; i <= n; ++i) {
    const Real c = binomial_real(n, i) * power(t, i) * power(1 - t, n - i) * w[i];
    denominator += c;
    for (std::size_t a = 0; a < Dim; ++a) numerator[a] += c * b[i][a];
  }
  for (auto& x : numerator) x /= denominator;
  return numerator;
}

/// Error bound of rational evaluation in the format of S: n + 2 roundings (homogeneous points,
/// n de Casteljau levels, the division), amplified by the ratio of the weights. Floating point: the
/// weight coordinate's relative error is multiplied by the distance from the first control point
/// (at most the polygon's extent) over the smallest weight. Fixed: the same holds with the weight
/// coordinate's resolution 2^-16 relative to the largest homogeneous value, which the evaluation
/// may raise to 2^13 by scaling the weights; only a curve whose extent times weights exceeds that
/// pays in proportion to its size.
template <Scalar S>
double rational_tolerance(double extent, double smallest_weight, double largest_weight, double scale, std::size_t degree) {
  const auto n = static_cast<double>(degree);
  if constexpr (FixedPoint<S>) {
    return 2 * (n + 2) * unit<S>() * (1 + largest_weight / smallest_weight) * (1 + extent * largest_weight / 8192);
  } else {
    return 8 * (n + 2) * unit<S>() * (scale + extent / smallest_weight);
  }
}

/// A rational curve on `points` with random weights in [low, high], and both in long double.
template <class S>
struct WeightedCurve {
  std::vector<Vec<S, 2>> points;
  std::vector<S> weights;
  Rational<S> curve;
  std::vector<RealPoint<2>> b;
  std::vector<Real> wr;
};
template <class S>
WeightedCurve<S> random_weights(Random& random, const std::vector<Vec<S, 2>>& points, double low, double high) {
  WeightedCurve<S> out;
  out.points = points;
  out.weights.resize(points.size());
  for (auto& w : out.weights) w = random.coordinate<S>(low, high);
  out.curve = must(Rational<S>::create(points, out.weights));
  out.b = to_real<S, 2>(points);
  for (S w : out.weights) out.wr.push_back(to_real(w));
  return out;
}
/// The same on a random polygon of `point_count` points with coordinates in [-range, range].
template <class S>
WeightedCurve<S> random_rational(Random& random, std::size_t point_count, double range, double low, double high) {
  return random_weights<S>(random, random.polygon<S, 2>(point_count, range), low, high);
}

}  // namespace

TEMPLATE_TEST_CASE("rational bezier: TV-15 quartic with weights 1 1 3 5 1", "[core][rational][seed]", double, float, Q16_16) {
  using S = TestType;
  const std::array<Vec<S, 2>, 5> points{point<S>(0, 0), point<S>(1, 2), point<S>(2, 3), point<S>(3, 2), point<S>(4, 0)};
  const std::array<S, 5> weights{scalar<S>(1), scalar<S>(1), scalar<S>(3), scalar<S>(5), scalar<S>(1)};
  const auto curve = must(Rational<S>::create(points, weights));
  const auto plain = must(Bezier<S, 2, 7>::create(points));
  struct Row {
    double t, weight_sum, x, y, plain_x, plain_y;
  };
  const std::array<Row, 3> rows{{{0.25, 103 / 64., 154 / 103., 411 / 206., 1, 201 / 128.},
                                 {0.5, 11 / 4., 26 / 11., 51 / 22., 2, 17 / 8.},
                                 {0.75, 199 / 64., 570 / 199., 795 / 398., 3, 201 / 128.}}};
  for (const auto& row : rows) {
    INFO("t = " << row.t);
    const S t = scalar<S>(row.t);
    // Integer weights and points at dyadic t: the homogeneous curve is exact in every format.
    const auto h = curve.homogeneous().point_at(t);
    CHECK(to_double(h[2]) == row.weight_sum);
    CHECK(max_error(plain.evaluate(t).value(), {row.plain_x, row.plain_y}) == 0.0);
    // One division: half a unit (Fixed) or a few roundings of values ~3.
    CHECK(max_error(must(curve.evaluate(t)), {row.x, row.y}) <= tolerance<S>(3, 4));
  }
  // Pulled toward p3 (w = 5) and p2 (w = 3): at t = 1/2 the rational point is right of and above
  // the polynomial one.
  const auto r = must(curve.evaluate(scalar<S>(0.5)));
  CHECK(to_double(r[0]) > 2.0);
  CHECK(to_double(r[1]) > 17 / 8.);
}

TEMPLATE_TEST_CASE("rational bezier: TV-16 quarter circle has radius one at every t", "[core][rational][seed]", double, float,
                   Q16_16) {
  using S = TestType;
  const S w = sqrt(scalar<S>(0.5));
  const std::array<Vec<S, 2>, 3> points{point<S>(1, 0), point<S>(1, 1), point<S>(0, 1)};
  const std::array<S, 3> weights{scalar<S>(1), w, scalar<S>(1)};
  const auto curve = must(Rational<S>::create(points, weights));
  // Error budget in units of the format: the weight √2/2 is rounded (radius sensitivity 0.25),
  // the homogeneous middle point is rounded, two de Casteljau levels and one division round.
  const double tol = FixedPoint<S> ? 4 * unit<S>() : 16 * unit<S>();
  const double h = std::sqrt(0.5);
  CHECK(max_error(must(curve.evaluate(scalar<S>(0.5))), {h, h}) <= tol);
  CHECK(max_error(must(curve.evaluate(scalar<S>(0.25))), {0.929788301062430, 0.368094709561873}) <= tol);
  CHECK(max_error(must(curve.evaluate(scalar<S>(0.75))), {0.368094709561873, 0.929788301062430}) <= tol);
  double worst_radius = 0;
  double worst_curvature = 0;
  for (int k = 0; k <= 256; ++k) {
    const S t = scalar<S>(k / 256.0);
    const auto p = to_real(must(curve.evaluate(t)));
    worst_radius = std::fmax(worst_radius, static_cast<double>(std::fabs(std::hypot(p[0], p[1]) - 1)));
    // Curvature divides by |r'|^3 ~ 2.8: the derivative errors are amplified a little.
    worst_curvature = std::fmax(worst_curvature, std::fabs(to_double(must(curvature(curve, t))) - 1));
  }
  CHECK(worst_radius <= tol);
  CHECK(worst_curvature <= (FixedPoint<S> ? 64 : 256) * unit<S>());
}

TEMPLATE_TEST_CASE("rational bezier: equal weights give the polynomial curve", "[core][rational][property]", double, float, Q16_16) {
  using S = TestType;
  Random random(21);
  const int count = test_count(300);
  for (int c = 0; c < count; ++c) {
    const auto points = random.polygon<S, 3>(random.integer(2, 8), 100);
    const S weight = random.coordinate<S>(0.5, 2);
    const std::vector<S> weights(points.size(), weight);
    const auto curve = must(Rational<S, 3>::create(points, weights));
    const auto plain = must(Bezier<S, 3, 7>::create(points));
    const auto ones = must(Rational<S, 3>::from_polynomial(plain));
    const auto n = plain.degree();
    INFO("case " << c << " degree " << n << " weight " << to_double(weight));
    const double tol = rational_tolerance<S>(200 * std::sqrt(3.0), to_double(weight), to_double(weight), 100, n);
    const auto b = to_real<S, 3>(points);
    double worst = 0;
    for (int k = 0; k < 8; ++k) {
      const S t = random.parameter<S>();
      // The polynomial curve itself (long double Bernstein sum), and the library's polynomial
      // evaluation within its own bound of it.
      const auto expected = bernstein_sum(b, to_real(t));
      CHECK(max_error_real(must(plain.evaluate(t)), expected) <= evaluation_tolerance<S>(100, n));
      worst = std::fmax(worst, max_error_real(must(curve.evaluate(t)), expected));
      worst = std::fmax(worst, max_error_real(must(ones.evaluate(t)), expected));
    }
    CHECK(worst <= tol);
  }
}

/// Eighth-order central differences of the long double rational curve, h = 1/1024.
template <std::size_t Dim>
std::array<RealPoint<Dim>, 2> rational_differences(const std::vector<RealPoint<Dim>>& b, const std::vector<Real>& w, Real t) {
  return central_differences<Dim>([&](Real u) { return rational_reference(b, w, u); }, t, 1.0L / 1024);
}

TEMPLATE_TEST_CASE("rational bezier: derivatives match a central finite difference", "[core][rational][property]", double, float,
                   Q16_16) {
  using S = TestType;
  Random random(22);
  const int count = test_count(250);
  for (int c = 0; c < count; ++c) {
    // Q16.16: coordinates within 10 keep r'' and the Leibniz products 2 w' r' in range.
    const double range = FixedPoint<S> ? 10 : 50;
    const auto [points, weights, curve, b, wr] = random_rational<S>(random, random.integer(2, 6), range, 0.5, 2);
    const auto n = curve.degree();
    const auto nd = static_cast<double>(n);
    INFO("case " << c << " degree " << n);
    // Scales: |r'| <= n (w_max/w_min)^2 · 2 range = 8 range n, |r''| <= ~ n² · 4^3 · 2 range.
    // Fixed error propagation of w r' = A' - w' r with A', w' rounded n times, divided by w >= 1/2,
    // and r'' adds 2 w' r' + w'' r: a few units times the ratio of the scales to w_min.
    const double scale1 = 8 * range * nd;
    const double scale2 = 128 * range * nd * nd;
    const double fd1 = 1e-10 * scale1;
    const double fd2 = 1e-7 * scale2;
    const double tol1 = (FixedPoint<S> ? (nd + 2) * 16 * unit<S>() * (1 + 4 * nd) : 64 * (nd + 1) * unit<S>() * scale1) + fd1;
    const double tol2 = (FixedPoint<S> ? (nd + 2) * 64 * unit<S>() * (1 + 16 * nd * nd) : 256 * (nd + 1) * unit<S>() * scale2) + fd2;
    double worst1 = 0;
    double worst2 = 0;
    for (int k = 0; k < 6; ++k) {
      const S t = random.parameter<S>();
      const auto reference = rational_differences(b, wr, to_real(t));
      worst1 = std::fmax(worst1, max_error_real(must(curve.derivative_at(t, 1)), reference[0]));
      worst2 = std::fmax(worst2, max_error_real(must(curve.derivative_at(t, 2)), reference[1]));
      CHECK(max_error_real(must(curve.derivative_at(t, 0)), rational_reference(b, wr, to_real(t))) <=
            rational_tolerance<S>(2 * range * std::sqrt(2.0), 0.5, 2, range, n));
    }
    CHECK(worst1 <= tol1);
    CHECK(worst2 <= tol2);
  }
}

TEMPLATE_TEST_CASE("rational bezier: random curves stay in the control box and split into halves", "[core][rational][property]",
                   double, float, Q16_16) {
  using S = TestType;
  Random random(23);
  const int count = test_count(300);
  for (int c = 0; c < count; ++c) {
    const auto [points, weights, curve, b, wr] = random_rational<S>(random, random.integer(2, 8), 100, 0.25, 4);
    const auto n = curve.degree();
    INFO("case " << c << " degree " << n);
    const auto box = curve.bounding_box();
    const auto hull = convex_hull(b);
    const double tol = rational_tolerance<S>(200 * std::sqrt(2.0), 0.25, 4, 100, n);
    const S split_at = random.parameter<S>();
    const auto halves = must(curve.split(split_at));
    CHECK(halves.left.front() == points.front());
    CHECK(halves.right.back() == points.back());
    double worst = 0;
    double worst_box = 0;
    Real worst_hull = 0;
    for (int k = 0; k < 8; ++k) {
      const S t = random.parameter<S>();
      const auto p = must(curve.evaluate(t));
      worst = std::fmax(worst, max_error_real(p, rational_reference(b, wr, to_real(t))));
      for (std::size_t a = 0; a < 2; ++a) {
        worst_box = std::fmax(worst_box, to_double(box.low[a]) - to_double(p[a]));
        worst_box = std::fmax(worst_box, to_double(p[a]) - to_double(box.high[a]));
      }
      worst_hull = std::max(worst_hull, distance_outside_hull(hull, to_real(p)));
      const Real ts = to_real(split_at);
      const Real s = to_real(t);
      worst = std::fmax(worst, max_error_real(must(halves.left.evaluate(t)), rational_reference(b, wr, ts * s)));
      worst = std::fmax(worst, max_error_real(must(halves.right.evaluate(t)), rational_reference(b, wr, ts + (1 - ts) * s)));
    }
    CHECK(worst <= 2 * tol);
    CHECK(worst_box <= tol);
    CHECK(static_cast<double>(worst_hull) <= tol);
  }
}

namespace {

/// Checks an arc about `center` from start through `sweep` radians (sign = direction).
template <class S>
void check_arc(const RationalBezier<S, 2, 7>& arc, const Vec2<S>& center, const Vec2<S>& start, const Vec2<S>& end, long double sweep,
               double radius_tolerance) {
  CHECK(arc.front() == start);
  CHECK(arc.back() == end);
  CHECK(must(arc.evaluate(from_int<S>(0))) == start);
  CHECK(must(arc.evaluate(from_int<S>(1))) == end);
  const auto c = to_real(center);
  const auto s = to_real(start);
  const Real radius = std::hypot(s[0] - c[0], s[1] - c[1]);
  const Real start_angle = std::atan2(s[1] - c[1], s[0] - c[0]);
  double worst_radius = 0;
  double worst_angle = 0;
  Real previous = 0;
  bool monotone = true;
  for (int k = 0; k <= 64; ++k) {
    const auto p = to_real(must(arc.evaluate(from_double<S>(k / 64.0).value())));
    worst_radius = std::fmax(worst_radius, static_cast<double>(std::fabs(std::hypot(p[0] - c[0], p[1] - c[1]) - radius)));
    // Angle travelled from the start in the arc's direction, in [0, |sweep|].
    Real angle = std::atan2(p[1] - c[1], p[0] - c[0]) - start_angle;
    if (sweep < 0) angle = -angle;
    while (angle < -pi / 2) angle += 2 * pi;
    while (angle > 2 * pi - pi / 2) angle -= 2 * pi;
    const Real excess = std::max<Real>(-angle, angle - std::fabs(sweep));
    worst_angle = std::fmax(worst_angle, static_cast<double>(std::max<Real>(excess, 0)));
    if (angle < previous - static_cast<Real>(radius_tolerance) / radius) monotone = false;
    previous = angle;
  }
  CHECK(worst_radius <= radius_tolerance);
  CHECK(worst_angle <= 4 * radius_tolerance / static_cast<double>(radius));
  CHECK(monotone);
}

}  // namespace

TEMPLATE_TEST_CASE("circular arc: random sweeps up to 180 degrees stay on the circle", "[core][rational][arc][property]", double,
                   float, Q16_16) {
  using S = TestType;
  Random random(24);
  const int count = test_count(200);
  for (int c = 0; c < count; ++c) {
    const double radius = random.uniform(0.5, 100);
    const auto center = random.polygon<S, 2>(1, 100)[0];
    const double start_angle = random.uniform(-3.2, 3.2);
    double sweep = random.uniform(0.001, std::acos(-1.0));
    if (random.chance(0.1)) sweep = std::acos(-1.0);        // exactly half a circle
    if (random.chance(0.1)) sweep = std::acos(-1.0) / 2;    // exactly the quadratic/cubic boundary
    if (random.chance(0.5)) sweep = -sweep;                 // clockwise
    const double cx = to_double(center[0]);
    const double cy = to_double(center[1]);
    const auto start = must(vec_from_doubles<S, 2>({cx + radius * std::cos(start_angle), cy + radius * std::sin(start_angle)}));
    const auto end = must(vec_from_doubles<S, 2>(
        {cx + radius * std::cos(start_angle + sweep), cy + radius * std::sin(start_angle + sweep)}));
    INFO("case " << c << " radius " << radius << " start " << start_angle << " sweep " << sweep);
    // Quantizing start and end moves them by half a unit: the radii differ by about one unit.
    const double input = FixedPoint<S> ? 2 * unit<S>() : 4 * unit<S>() * (radius + 200);
    // On the circle within a few units of the format relative to the radius (the unit vectors and
    // the half-angle cosine carry the format's relative resolution) plus the coordinate rounding.
    const double on_circle = FixedPoint<S> ? 8 * unit<S>() * (1 + radius) : 8 * unit<S>() * (radius + 200);
    const auto direction = sweep > 0 ? ArcDirection::CounterClockwise : ArcDirection::Clockwise;
    const auto arc = circular_arc<S, 7>(center, start, end, direction, from_double<S>(input).value());
    INFO("error " << error_name(arc.error()) << " at " << arc.where());
    REQUIRE(arc.has_value());
    // Quadratic up to 90°, cubic beyond (at exactly 90° rounding may pick either form).
    if (std::fabs(std::fabs(sweep) - std::acos(-1.0) / 2) > 1e-3) {
      CHECK(arc.value().degree() == (std::fabs(sweep) < std::acos(-1.0) / 2 ? 2u : 3u));
    }
    check_arc(arc.value(), center, start, end, sweep, on_circle);
    // The same arc from angles.
    const auto by_angle = circular_arc_by_angle<S, 7>(center, from_double<S>(radius).value(), start_angle, sweep);
    REQUIRE(by_angle.has_value());
    check_arc(by_angle.value(), center, by_angle.value().front(), by_angle.value().back(), sweep, on_circle);
  }
}

TEMPLATE_TEST_CASE("circular arc: full circle of four quarters stays on the circle and closes", "[core][rational][arc][property]",
                   double, float, Q16_16) {
  using S = TestType;
  Random random(25);
  const int count = test_count(60);
  for (int c = 0; c < count; ++c) {
    const S radius = random.coordinate<S>(0.5, 100);
    const auto center = random.polygon<S, 2>(1, 100)[0];
    INFO("case " << c << " radius " << to_double(radius));
    const auto circle = must(full_circle<S, 7>(center, radius));
    const double on_circle = FixedPoint<S> ? 4 * unit<S>() * (1 + to_double(radius)) : 8 * unit<S>() * (to_double(radius) + 200);
    const std::array<std::array<double, 2>, 4> directions{{{1, 0}, {0, 1}, {-1, 0}, {0, -1}}};
    for (std::size_t q = 0; q < 4; ++q) {
      const auto& d = directions[q];
      const auto& next = directions[(q + 1) % 4];
      const Vec2<S> start{{center[0] + radius * from_int<S>(static_cast<int>(d[0])), center[1] + radius * from_int<S>(static_cast<int>(d[1]))}};
      const Vec2<S> end{{center[0] + radius * from_int<S>(static_cast<int>(next[0])),
                         center[1] + radius * from_int<S>(static_cast<int>(next[1]))}};
      CHECK(circle[q].back() == circle[(q + 1) % 4].front());
      check_arc(circle[q], center, start, end, pi / 2, on_circle);
    }
  }
}

TEMPLATE_TEST_CASE("circular arc: large radii within the Q16.16 range", "[core][rational][arc]", double, float, Q16_16) {
  using S = TestType;
  // A 1 m radius and a 10 m radius arc about the origin: coordinates fit Q16.16 (±32767 mm).
  for (const double radius : {1000.0, 10000.0}) {
    INFO("radius " << radius);
    const auto center = point<S>(0, 0);
    const auto start = point<S>(radius, 0);
    const auto end = point<S>(0, radius);
    const double input = FixedPoint<S> ? 2 * unit<S>() : 4 * unit<S>() * radius;
    const auto arc = circular_arc<S, 7>(center, start, end, ArcDirection::CounterClockwise, from_double<S>(input).value());
    REQUIRE(arc.has_value());
    check_arc(arc.value(), center, start, end, pi / 2, 8 * unit<S>() * (1 + radius));
    const auto circle = full_circle<S, 7>(center, from_double<S>(radius).value());
    REQUIRE(circle.has_value());
  }
}

TEMPLATE_TEST_CASE("rational bezier: evaluation error does not grow with the distance from the origin",
                   "[core][rational][property]", double, float, Q16_16) {
  using S = TestType;
  Random random(26);
  const int count = test_count(200);
  for (int c = 0; c < count; ++c) {
    // A small curve (extent <= 2√2 mm) placed anywhere in the Q16.16 range.
    const double ox = random.uniform(-30000, 30000);
    const double oy = random.uniform(-30000, 30000);
    std::vector<Vec<S, 2>> points(random.integer(2, 6));
    for (auto& p : points) {
      p = must(vec_from_doubles<S, 2>({ox + random.uniform(-1, 1), oy + random.uniform(-1, 1)}));
    }
    // Weights <= 1: create() documents FixedOverflow when w b leaves the range.
    const auto [polygon, weights, curve, b, wr] = random_weights<S>(random, points, 0.5, 1);
    INFO("case " << c << " offset " << ox << ", " << oy << " degree " << curve.degree());
    // The bound depends on the extent (2√2) and the coordinate scale (floats: 30000), not on the
    // offset itself for Fixed, whose units are absolute.
    const double tol = rational_tolerance<S>(2 * std::sqrt(2.0), 0.5, 1, 30000, curve.degree());
    double worst = 0;
    double worst_split = 0;
    const S split_at = random.parameter<S>();
    const auto halves = must(curve.split(split_at));
    for (int k = 0; k < 8; ++k) {
      const S t = random.parameter<S>();
      worst = std::fmax(worst, max_error_real(must(curve.evaluate(t)), rational_reference(b, wr, to_real(t))));
      worst = std::fmax(worst, max_error_real(must(curve.derivative_at(t, 0)), rational_reference(b, wr, to_real(t))));
      const Real ts = to_real(split_at);
      worst_split = std::fmax(worst_split, max_error_real(must(halves.left.evaluate(t)), rational_reference(b, wr, ts * to_real(t))));
    }
    CHECK(worst <= tol);
    CHECK(worst_split <= 2 * tol);
  }
}

TEMPLATE_TEST_CASE("circular arc: arcs far from the origin keep their accuracy", "[core][rational][arc][property]", double, float,
                   Q16_16) {
  using S = TestType;
  Random random(27);
  const int count = test_count(100);
  for (int c = 0; c < count; ++c) {
    const double radius = random.uniform(0.5, 100);
    const double cx = random.uniform(-30000, 30000);
    const double cy = random.uniform(-30000, 30000);
    const auto center = must(vec_from_doubles<S, 2>({cx, cy}));
    const double start_angle = random.uniform(-3.2, 3.2);
    double sweep = random.uniform(0.001, std::acos(-1.0));
    if (random.chance(0.5)) sweep = -sweep;
    const double x0 = to_double(center[0]);
    const double y0 = to_double(center[1]);
    const auto start = must(vec_from_doubles<S, 2>({x0 + radius * std::cos(start_angle), y0 + radius * std::sin(start_angle)}));
    const auto end = must(vec_from_doubles<S, 2>({x0 + radius * std::cos(start_angle + sweep), y0 + radius * std::sin(start_angle + sweep)}));
    INFO("case " << c << " centre " << cx << ", " << cy << " radius " << radius << " sweep " << sweep);
    const double scale = std::fabs(cx) + std::fabs(cy) + radius;
    // Fixed units are absolute: the bound depends on the radius only. Floats: on the coordinates.
    const double input = FixedPoint<S> ? 2 * unit<S>() : 4 * unit<S>() * scale;
    const double on_circle = FixedPoint<S> ? 8 * unit<S>() * (1 + radius) : 8 * unit<S>() * (radius + scale);
    const auto direction = sweep > 0 ? ArcDirection::CounterClockwise : ArcDirection::Clockwise;
    const auto arc = circular_arc<S, 7>(center, start, end, direction, from_double<S>(input).value());
    INFO("error " << error_name(arc.error()) << " at " << arc.where());
    REQUIRE(arc.has_value());
    check_arc(arc.value(), center, start, end, sweep, on_circle);
  }
}

TEMPLATE_TEST_CASE("rational bezier: 200 mm curves with moderate weights evaluate within a few units", "[core][rational][property]",
                   double, float, Q16_16) {
  using S = TestType;
  Random random(28);
  const int count = test_count(300);
  for (int c = 0; c < count; ++c) {
    const auto [points, weights, curve, b, wr] = random_rational<S>(random, random.integer(2, 8), 100, 0.5, 1);
    INFO("case " << c << " degree " << curve.degree());
    const double tol = rational_tolerance<S>(200 * std::sqrt(2.0), 0.5, 1, 100, curve.degree());
    double worst = 0;
    for (int k = 0; k < 8; ++k) {
      const S t = random.parameter<S>();
      worst = std::fmax(worst, max_error_real(must(curve.evaluate(t)), rational_reference(b, wr, to_real(t))));
    }
    CHECK(worst <= tol);
  }
}
