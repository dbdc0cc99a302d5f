// SPDX-License-Identifier: MIT
// flatten: the polyline stays within the tolerance (dense long-double sampling) and is near-minimal.
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/bspline/bspline.hpp>
#include <curvestep/core/bspline/nurbs.hpp>
#include <curvestep/core/curve/circular_arc.hpp>
#include <curvestep/core/curve/composite_bezier.hpp>
#include <curvestep/core/sampling/flatten.hpp>
#include <support/numeric.hpp>

#include "sampling_reference.hpp"

using namespace curvestep;
using namespace curvestep::testing;  // support/numeric.hpp, sampling_reference.hpp

namespace {

template <class S, std::size_t Dim>
using Vertices = std::vector<FlattenVertex<S, Dim>>;

template <class Curve>
Vertices<typename Curve::scalar_type, Curve::dimension> run_flatten(const Curve& curve, double tolerance) {
  using S = typename Curve::scalar_type;
  Vertices<S, Curve::dimension> vertices;
  const auto count = flatten(curve, scalar<S>(tolerance), [&](const FlattenVertex<S, Curve::dimension>& v) { vertices.push_back(v); });
  INFO("flatten error " << static_cast<int>(count.error()) << " after " << vertices.size() << " vertices");
  REQUIRE(count.has_value());
  REQUIRE(count.value() == vertices.size());
  return vertices;
}

template <std::size_t Dim, class S>
std::array<long double, Dim> as_long_double(const Vec<S, Dim>& v) {
  std::array<long double, Dim> r{};
  for (std::size_t k = 0; k < Dim; ++k) r[k] = static_cast<long double>(to_double(v[k]));
  return r;
}

/// Largest distance from the curve (sampled densely between each pair of vertices, by an
/// independent evaluation `exact(t)`) to the chord between them.
template <std::size_t Dim, class S, class Exact>
long double measured_deviation(const Vertices<S, Dim>& vertices, Exact exact, int samples_per_chord = 48) {
  long double worst = 0;
  for (std::size_t k = 0; k + 1 < vertices.size(); ++k) {
    const auto a = as_long_double<Dim>(vertices[k].point);
    const auto b = as_long_double<Dim>(vertices[k + 1].point);
    const long double t0 = vertices[k].parameter;
    const long double t1 = vertices[k + 1].parameter;
    REQUIRE(t0 < t1);
    for (int j = 0; j <= samples_per_chord; ++j) {
      const long double t = t0 + (t1 - t0) * j / samples_per_chord;
      worst = std::fmax(worst, distance_to_segment<Dim>(exact(t), a, b));
    }
  }
  return worst;
}

/// Segments an arc of the same curvature needs: ∫ κ / (2 acos(1 - κ ε)) ds (2D Bézier, long double).
long double minimum_segments(const curvestep::testing::ReferencePolygon<2>& polygon, long double tolerance) {
  const std::size_t n = polygon.size() - 1;
  curvestep::testing::ReferencePolygon<2> first, second;
  for (std::size_t i = 0; i < n; ++i) {
    first.push_back({n * (polygon[i + 1][0] - polygon[i][0]), n * (polygon[i + 1][1] - polygon[i][1])});
  }
  for (std::size_t i = 0; i + 1 < n; ++i) {
    second.push_back({(n - 1) * (first[i + 1][0] - first[i][0]), (n - 1) * (first[i + 1][1] - first[i][1])});
  }
  constexpr int samples = 4000;
  long double total = 0;
  for (int j = 0; j < samples; ++j) {
    const long double t = (j + 0.5L) / samples;
    const auto d1 = reference_point<2>(first, t);
    const auto d2 = second.empty() ? std::array<long double, 2>{0, 0} : reference_point<2>(second, t);
    const long double speed = std::hypot(d1[0], d1[1]);
    if (speed == 0) continue;
    const long double kappa = std::fabs(d1[0] * d2[1] - d1[1] * d2[0]) / (speed * speed * speed);
    const long double c = 1 - kappa * tolerance;
    const long double half_angle = c <= -1 ? std::acos(-1.0L) : std::acos(c);
    if (half_angle > 0) total += kappa / (2 * half_angle) * speed / samples;
  }
  return total;
}

template <class S>
Bezier<S, 2, 7> random_bezier(std::mt19937& rng, std::size_t degree) {
  std::uniform_real_distribution<double> coordinate(0.0, 100.0);
  std::array<Vec<S, 2>, 8> points{};
  for (std::size_t i = 0; i <= degree; ++i) {
    points[i] = point<S>(std::round(coordinate(rng) * 256) / 256, std::round(coordinate(rng) * 256) / 256);
  }
  return Bezier<S, 2, 7>::create(std::span<const Vec<S, 2>>(points.data(), degree + 1)).value();
}

}  // namespace

TEMPLATE_TEST_CASE("flatten: random Bezier curves stay within 0.1, 0.01 and 0.001 mm with near-minimal vertex counts",
                   "[core][sampling][flatten][acceptance]", double, float, Q16_16) {
  using S = TestType;
  std::mt19937 rng(curvestep::testing::test_seed() + 7);
  const int count = curvestep::testing::test_count(8);
  for (const double tolerance : {0.1, 0.01, 0.001}) {
    long double worst_ratio = 0;
    long double total_segments = 0;
    long double total_minimum = 0;
    long double worst_deviation = 0;
    for (int c = 0; c < count; ++c) {
      const std::size_t degree = 2 + static_cast<std::size_t>(c % 3);  // quadratic, cubic, quartic
      const auto curve = random_bezier<S>(rng, degree);
      const auto polygon = reference_polygon(curve);
      const auto vertices = run_flatten(curve, tolerance);
      REQUIRE(vertices.front().parameter == 0.0);
      REQUIRE(vertices.back().parameter == 1.0);
      const long double deviation =
          measured_deviation<2>(vertices, [&](long double t) { return reference_point<2>(polygon, t); });
      worst_deviation = std::fmax(worst_deviation, deviation);
      CHECK(deviation <= tolerance);
      const long double minimum = minimum_segments(polygon, tolerance);
      const auto segments = static_cast<long double>(vertices.size() - 1);
      total_segments += segments;
      total_minimum += minimum;
      const long double ratio = segments / std::fmax(1.0L, std::ceil(minimum));
      worst_ratio = std::fmax(worst_ratio, ratio);
      INFO("degree " << degree << " segments " << segments << " minimum " << static_cast<double>(minimum));
      CHECK(ratio <= 2.0L);
    }
    WARN("flatten tolerance " << tolerance << ": worst deviation " << static_cast<double>(worst_deviation)
                              << ", segments / minimum overall " << static_cast<double>(total_segments / total_minimum)
                              << ", worst per curve " << static_cast<double>(worst_ratio));
  }
}

TEMPLATE_TEST_CASE("flatten: a circular arc needs at most twice the segments of the optimal inscribed polygon",
                   "[core][sampling][flatten]", double, float, Q16_16) {
  using S = TestType;
  constexpr long double pi = 3.14159265358979323846264338327950288L;
  const double radius = 50;
  const auto arc = circular_arc<S>(point<S>(0, 0), point<S>(radius, 0), point<S>(0, radius), ArcDirection::CounterClockwise,
                                   scalar<S>(0.01))
                       .value();
  for (const double tolerance : {0.1, 0.01, 0.001}) {
    const auto vertices = run_flatten(arc, tolerance);
    long double worst = 0;
    for (std::size_t k = 0; k + 1 < vertices.size(); ++k) {
      const auto a = as_long_double<2>(vertices[k].point);
      const auto b = as_long_double<2>(vertices[k + 1].point);
      for (int j = 0; j <= 64; ++j) {  // the arc between the vertices' angles
        const long double angle0 = std::atan2(a[1], a[0]);
        const long double angle1 = std::atan2(b[1], b[0]);
        const long double angle = angle0 + (angle1 - angle0) * j / 64;
        const std::array<long double, 2> q{radius * std::cos(angle), radius * std::sin(angle)};
        worst = std::fmax(worst, distance_to_segment<2>(q, a, b));
      }
    }
    CHECK(worst <= tolerance);
    const long double optimal = std::ceil((pi / 2) / (2 * std::acos(1 - tolerance / radius)));
    const auto segments = static_cast<long double>(vertices.size() - 1);
    INFO("tolerance " << tolerance << " segments " << segments << " optimal " << static_cast<double>(optimal));
    CHECK(segments <= 2 * optimal);
    CHECK(segments >= optimal);
  }
}

TEST_CASE("flatten: a full circle of four quarter arcs and a cubic B-spline through its Bezier pieces",
          "[core][sampling][flatten]") {
  const auto circle = full_circle<double>(point<double>(10, 10), 25.0).value();
  std::size_t total = 0;
  for (const auto& quarter : circle) {
    const auto vertices = run_flatten(quarter, 0.01);
    total += vertices.size() - 1;
    for (std::size_t k = 0; k + 1 < vertices.size(); ++k) {
      const auto a = as_long_double<2>(vertices[k].point);
      const auto b = as_long_double<2>(vertices[k + 1].point);
      // Chord sagitta: R - distance from the centre to the chord's midpoint.
      const long double mx = (a[0] + b[0]) / 2 - 10, my = (a[1] + b[1]) / 2 - 10;
      CHECK(25.0L - std::hypot(mx, my) <= 0.01L);
    }
  }
  CHECK(total <= 2 * static_cast<std::size_t>(std::ceil(2 * 3.14159265358979 / (2 * std::acos(1 - 0.01 / 25)))));

  using Spline = BSpline<double, 2, 3, 16>;
  const std::array<Vec<double, 2>, 6> control{point<double>(0, 0), point<double>(10, 30), point<double>(30, 30),
                                              point<double>(40, 0), point<double>(60, 10), point<double>(70, 40)};
  const std::array<double, 10> knots{0, 0, 0, 0, 1, 2, 3, 3, 3, 3};
  const auto spline = Spline::create(control, knots, 3).value();
  std::vector<FlattenVertex<double, 2>> vertices;
  const auto count = flatten(spline, 0.005, [&](const FlattenVertex<double, 2>& v) { vertices.push_back(v); });
  REQUIRE(count.has_value());
  CHECK(vertices.front().parameter == 0.0);
  CHECK(vertices.back().parameter == 3.0);
  // Reference: de Boor evaluation (an algorithm independent of Bezier extraction).
  const long double deviation = measured_deviation<2>(vertices, [&](long double u) {
    const auto p = spline.evaluate(static_cast<double>(u)).value();
    return std::array<long double, 2>{p[0], p[1]};
  });
  CHECK(deviation <= 0.005L);
}

TEMPLATE_TEST_CASE("flatten: buffers, straight lines, points and invalid tolerances", "[core][sampling][flatten][errors]",
                   double, float, Q16_16) {
  using S = TestType;
  const auto line = Bezier<S, 2, 7>::create({point<S>(0, 0), point<S>(1, 1), point<S>(2, 2), point<S>(3, 3)}).value();
  std::array<Vec<S, 2>, 4> buffer{};
  const auto written = flatten_into(line, scalar<S>(0.01), std::span<Vec<S, 2>>(buffer));
  REQUIRE(written.has_value());
  CHECK(written.value() == 2);  // a straight line is one chord
  CHECK(buffer[0] == point<S>(0, 0));
  CHECK(buffer[1] == point<S>(3, 3));
  const auto curved = Bezier<S, 2, 7>::create({point<S>(0, 0), point<S>(0, 40), point<S>(40, 40), point<S>(40, 0)}).value();
  const auto small = flatten_into(curved, scalar<S>(0.01), std::span<Vec<S, 2>>(buffer));
  CHECK(small.error() == Error::BufferTooSmall);
  CHECK(small.where() == 4);
  CHECK(flatten_into(curved, S{}, std::span<Vec<S, 2>>(buffer)).error() == Error::InvalidTolerance);
  CHECK(flatten_into(curved, scalar<S>(-1), std::span<Vec<S, 2>>(buffer)).error() == Error::InvalidTolerance);
  if constexpr (FixedPoint<S>) {  // one raw unit cannot hold a 1-raw-unit tolerance after rounding
    CHECK(flatten_into(curved, resolution<S>(), std::span<Vec<S, 2>>(buffer)).error() == Error::InvalidTolerance);
  }
  const auto dot = Bezier<S, 2, 7>::create({point<S>(5, 5)}).value();
  CHECK(flatten_into(dot, scalar<S>(0.01), std::span<Vec<S, 2>>(buffer)).value() == 1);
  std::size_t calls = 0;
  const auto stopped = flatten(curved, scalar<S>(0.001), [&](const FlattenVertex<S, 2>&) { return ++calls < 3; });
  CHECK(stopped.value() == 3);
}

TEST_CASE("flatten: the 9-point NURBS circle is flattened within tolerance with near-optimal chords",
          "[core][sampling][flatten]") {
  // seed_004 Appendix A: knots {0,0,0,1/4,1/4,1/2,1/2,3/4,3/4,1,1,1}, weights 1, sqrt(2)/2 alternating.
  const double r = 20;
  const double s = std::sqrt(0.5);
  using Circle = Nurbs<double, 2, 2, 16>;
  const auto circle = Circle::create({point<double>(r, 0), point<double>(r, r), point<double>(0, r), point<double>(-r, r),
                                      point<double>(-r, 0), point<double>(-r, -r), point<double>(0, -r), point<double>(r, -r),
                                      point<double>(r, 0)},
                                     {1, s, 1, s, 1, s, 1, s, 1}, {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1}, 2)
                          .value();
  std::vector<FlattenVertex<double, 2>> vertices;
  REQUIRE(flatten(circle, 0.01, [&](const FlattenVertex<double, 2>& v) { vertices.push_back(v); }).has_value());
  CHECK(vertices.front().parameter == 0.0);
  CHECK(vertices.back().parameter == 1.0);
  for (std::size_t k = 0; k + 1 < vertices.size(); ++k) {
    const auto a = as_long_double<2>(vertices[k].point);
    const auto b = as_long_double<2>(vertices[k + 1].point);
    CHECK(std::hypot(a[0], a[1]) == Approx(r).margin(1e-9));
    CHECK(r - std::hypot((a[0] + b[0]) / 2, (a[1] + b[1]) / 2) <= 0.01L);  // the chord's sagitta
  }
  const double optimal = std::ceil(2 * 3.14159265358979323846 / (2 * std::acos(1 - 0.01 / r)));
  INFO("segments " << vertices.size() - 1 << " optimal " << optimal);
  CHECK(static_cast<double>(vertices.size() - 1) <= 2 * optimal);
}

TEMPLATE_TEST_CASE("flatten: composite Bezier curves are flattened segment by segment on their global parameter",
                   "[core][sampling][flatten]", double, float, Q16_16) {
  using S = TestType;
  using Segment = Bezier<S, 2, 3>;
  CompositeBezier<S, 2, 3, 4> path(scalar<S>(1));
  REQUIRE(path.try_append(Segment::create({point<S>(0, 0), point<S>(0, 40), point<S>(40, 40), point<S>(40, 0)}).value(),
                          scalar<S>(2)));
  REQUIRE(path.try_append(Segment::create({point<S>(40, 0), point<S>(40, -30), point<S>(70, -30), point<S>(80, 10)}).value(),
                          scalar<S>(4)));
  std::vector<FlattenVertex<S, 2>> vertices;
  REQUIRE(flatten(path, scalar<S>(0.01), [&](const FlattenVertex<S, 2>& v) { vertices.push_back(v); }).has_value());
  CHECK(vertices.front().parameter == 1.0);
  CHECK(vertices.back().parameter == 4.0);
  // Reference: each segment's control points in long double, located by the global parameter.
  const auto first = reference_polygon(path.segment(0));
  const auto second = reference_polygon(path.segment(1));
  const long double deviation = measured_deviation<2>(vertices, [&](long double u) {
    return u <= 2 ? reference_point<2>(first, u - 1) : reference_point<2>(second, (u - 2) / 2);
  });
  CHECK(deviation <= 0.01L);
  CompositeBezier<S, 2, 3, 4> broken;
  REQUIRE(broken.try_append(Segment::create({point<S>(0, 0), point<S>(1, 1)}).value(), scalar<S>(1)));
  REQUIRE(broken.try_append(Segment::create({point<S>(2, 2), point<S>(3, 3)}).value(), scalar<S>(2)));
  const auto refused = flatten(broken, scalar<S>(0.01), [](const FlattenVertex<S, 2>&) {});
  CHECK(refused.error() == Error::NotContinuous);
  CHECK(refused.where() == 1);
}
