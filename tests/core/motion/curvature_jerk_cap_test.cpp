// SPDX-License-Identifier: MIT
// The jerk a curve makes at speed v: with the curvature vector's rate D = d(κN)/ds, the jerk is
// j_t T + 3 v a_t κ N + v³ D, a part along the path of at most ½ j + v³κ² and one across it of at
// most 3 v a_t κ + v³|D| (the profile's own shares). The two are orthogonal, so the planner may run
// a curve up to the v at which (½ j + v³κ²)² + (3 v a_t κ + v³|D|)² = j², a_t kept at its value
// where the plain sum reaches j (v³(κ² + |D|) <= ¼ j, 3 v a_t κ <= ¼ j: the rule before). On a
// corner blend, where |D| >> κ², that is 1.29 times the speed. The curve's κ and |D| are computed here from its Bernstein form, by the
// test's own derivatives and differences, not by the planner's sampling.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <catch2/catch.hpp>

#include "motion_test_support.hpp"

using namespace curvestep;
using namespace curvestep::testing;

namespace {

using Point2 = std::array<double, 2>;

/// Point or derivative (order 0..2) of a planar quintic in Bernstein form, by differenced control points.
Point2 quintic_derivative(const std::array<Point2, 6>& c, double u, int order) {
  std::vector<Point2> q(c.begin(), c.end());
  double factor = 1;
  for (int d = 0; d < order; ++d) {
    factor *= static_cast<double>(q.size() - 1);
    for (std::size_t i = 0; i + 1 < q.size(); ++i) q[i] = {q[i + 1][0] - q[i][0], q[i + 1][1] - q[i][1]};
    q.pop_back();
  }
  while (q.size() > 1) {
    for (std::size_t i = 0; i + 1 < q.size(); ++i) q[i] = {(1 - u) * q[i][0] + u * q[i + 1][0], (1 - u) * q[i][1] + u * q[i + 1][1]};
    q.pop_back();
  }
  return {factor * q[0][0], factor * q[0][1]};
}

/// Curvature vector κN = (p'' |p'|² − p' (p'·p'')) / |p'|⁴.
Point2 curvature_vector(const std::array<Point2, 6>& c, double u) {
  const Point2 d1 = quintic_derivative(c, u, 1);
  const Point2 d2 = quintic_derivative(c, u, 2);
  const double s2 = d1[0] * d1[0] + d1[1] * d1[1];
  const double d12 = d1[0] * d2[0] + d1[1] * d2[1];
  return {(d2[0] * s2 - d1[0] * d12) / (s2 * s2), (d2[1] * s2 - d1[1] * d12) / (s2 * s2)};
}

/// The largest v with v³ = x and f(x) <= j², f increasing in x: bisection.
double largest_speed(double j, const auto& f) {
  double low = 0;
  double high = 1e9;
  for (int i = 0; i < 200; ++i) {
    const double mid = (low + high) / 2;
    (f(mid) <= j * j ? low : high) = mid;
  }
  return std::cbrt(low);
}

}  // namespace

TEST_CASE("motion: a corner blend runs at the speed where the orthogonal jerk parts reach j_max, not their sum",
          "[core][motion]") {
  // A 10° corner at the origin between +x and the direction at 10°, blended by a quintic whose first
  // and last three control points lie on the lines (curvature 0 at both ends: G2 with the lines).
  const double pi = std::acos(-1.0);
  const Point2 out{std::cos(10 * pi / 180), std::sin(10 * pi / 180)};
  const double d = 0.3;
  const std::array<Point2, 6> c{Point2{-d, 0}, Point2{-0.6 * d, 0}, Point2{-0.2 * d, 0},
                                Point2{0.2 * d * out[0], 0.2 * d * out[1]}, Point2{0.6 * d * out[0], 0.6 * d * out[1]},
                                Point2{d * out[0], d * out[1]}};
  std::array<MachinePoint, 6> control{};
  for (std::size_t i = 0; i < 6; ++i) control[i] = mp(c[i][0], c[i][1]);
  const std::vector<PathSegment> job{line(mp(-20, 0), control[0]), PathSegment::make_bezier(control).value(),
                                     line(control[5], mp(20 * out[0], 20 * out[1]))};

  // κ and |D| on the blend, densely.
  constexpr int samples = 20000;
  double max_kappa = 0;
  double max_rate = 0;
  Point2 previous = curvature_vector(c, 0);
  for (int k = 1; k <= samples; ++k) {
    const double u = static_cast<double>(k) / samples;
    const Point2 kn = curvature_vector(c, u);
    const Point2 d1 = quintic_derivative(c, u - 0.5 / samples, 1);
    const double ds = std::hypot(d1[0], d1[1]) / samples;
    max_kappa = std::max(max_kappa, std::hypot(kn[0], kn[1]));
    max_rate = std::max(max_rate, std::hypot(kn[0] - previous[0], kn[1] - previous[1]) / ds);
    previous = kn;
  }
  const MachineLimits m = test_machine();
  const double j = m.j_max_mm_per_s3;
  const double k2 = max_kappa * max_kappa;
  // The planner measures |D| with a 25 % margin; both rules are taken with it.
  const double rate = 1.25 * max_rate;
  const double by_sum = largest_speed(j, [&](double x) { return std::pow(4 * x * (k2 + rate), 2); });
  // The tangential acceleration keeps its value at by_sum, a_t = j / (12 by_sum κ): its part across
  // the path, 3 v a_t κ, is ¼ j v / by_sum.
  const double by_orthogonal_parts = largest_speed(j, [&](double x) {
    return std::pow(0.5 * j + x * k2, 2) + std::pow(0.25 * j * std::cbrt(x) / by_sum + x * rate, 2);
  });
  INFO("blend: κ_max " << max_kappa << " /mm, |dκN/ds| " << max_rate << " /mm²; caps " << by_sum << " and "
                       << by_orthogonal_parts << " mm/s");
  REQUIRE(by_orthogonal_parts > 1.25 * by_sum);
  REQUIRE(by_orthogonal_parts < m.feed_mm_per_s);                  // the curvature binds, not the feed
  REQUIRE(std::sqrt(0.5 * m.a_max_mm_per_s2 / max_kappa) > by_orthogonal_parts);  // nor the centripetal cap

  const auto sp = run_job<double>(job, m);
  const auto peaks = measure(sp, m.rate_hz);
  CHECK(peaks.jerk <= j * 1.01);
  CHECK(peaks.acceleration <= m.a_max_mm_per_s2 * 1.01);
  // The slowest speed near the corner (setpoints within 0.4 mm of it), by differences of positions.
  double slowest = m.feed_mm_per_s;
  for (std::size_t i = 1; i < sp.size(); ++i) {
    const double x = to_double(sp[i].position[0]);
    const double y = to_double(sp[i].position[1]);
    if (std::hypot(x, y) > 0.4) continue;
    const double v = std::hypot(x - to_double(sp[i - 1].position[0]), y - to_double(sp[i - 1].position[1])) * m.rate_hz;
    slowest = std::min(slowest, v);
  }
  INFO("slowest speed at the corner " << slowest << " mm/s");
  CHECK(slowest > 1.2 * by_sum);
  CHECK(slowest <= 1.01 * by_orthogonal_parts);
}

TEST_CASE("motion: a curvature jump between tangent arcs run near their jerk cap keeps the jerk within j_max",
          "[core][motion]") {
  // Tangent arcs of R 5 and 5.14 mm: at the joint the curvature jumps by 1/5 − 1/5.14 per mm within
  // one tick, beside the arcs' own jerk from curvature (near the whole budget at their cap) and the
  // profile's jerk where it starts braking for the stop 2.7 mm later. The junction speed must leave
  // the jump only what the arcs' parts leave of j_max at that speed.
  MachineLimits m = test_machine();
  m.feed_mm_per_s = 100;
  const double pi = std::acos(-1.0);
  const double r2 = 5.14;
  const double sweep = 90 * pi / 180;
  // Arc 1: centre (0, 5), from (0, 0) three quarters of a turn counter-clockwise to (-5, 5), where
  // it runs along -y (long enough to reach its cap); arc 2 goes on from there, counter-clockwise
  // around (-5 + r2, 5), for 30 degrees.
  const MachinePoint centre2 = mp(-5 + r2, 5);
  const MachinePoint end2 = mp(centre2[0] - r2 * std::cos(sweep), centre2[1] - r2 * std::sin(sweep));
  const std::vector<PathSegment> job{line(mp(-30, 0), mp(0, 0)), arc(mp(0, 0), mp(-5, 5), mp(0, 5), ArcDirection::CounterClockwise),
                                     arc(mp(-5, 5), end2, centre2, ArcDirection::CounterClockwise)};
  const auto sp = run_job<double>(job, m);
  const auto peaks = measure(sp, m.rate_hz);
  CHECK(peaks.jerk <= m.j_max_mm_per_s3 * 1.01);
  CHECK(peaks.acceleration <= m.a_max_mm_per_s2 * 1.01);

  // The joint's worst case, from the arcs' geometry: the profile's ½ j and v³κ² along the path (its
  // acceleration is 0 at a joint), across it a circle's |d(κN)/ds| = κ² times v³ and the jump
  // v²(1/5 − 1/r2)/Δt, for either arc. At the sum rule's jump cap, v² |Δκ| = ½ j Δt (67.7 mm/s, which
  // the arcs allowed once their cap rose), this is 1.06 j.
  const auto plan_of = [&](const PathSegment& s) { return plan_segment(s, PathLengthTable<64>::build(s).value(), m).value(); };
  const double v = junction_speed(plan_of(job[1]), plan_of(job[2]), m);
  const double j = m.j_max_mm_per_s3;
  for (const double kappa : {1 / 5.0, 1 / r2}) {
    const double along = 0.5 * j + v * v * v * kappa * kappa;
    const double across = v * v * v * kappa * kappa + v * v * (1 / 5.0 - 1 / r2) * m.rate_hz;
    INFO("junction speed " << v << " mm/s, κ " << kappa);
    CHECK(std::hypot(along, across) <= j);
  }
  CHECK(v > 0.9 * std::sqrt(0.5 * j / (m.rate_hz * (1 / 5.0 - 1 / r2))));
  // Around the joint (the ticks within 1 mm of it): the jerk there, and the speed it is passed at.
  std::size_t joint = 0;
  for (std::size_t i = 0; i < sp.size(); ++i) {
    const auto d = [&](std::size_t k) { return std::hypot(to_double(sp[k].position[0]) + 5, to_double(sp[k].position[1]) - 5); };
    if (d(i) < d(joint)) joint = i;
  }
  const std::vector<Setpoint<double>> near(sp.begin() + static_cast<std::ptrdiff_t>(joint - 20), sp.begin() + static_cast<std::ptrdiff_t>(joint + 20));
  const auto at_joint = measure(near, m.rate_hz);
  INFO("joint passed at " << at_joint.speed << " mm/s");
  CHECK(at_joint.speed > 40);
  CHECK(at_joint.jerk <= m.j_max_mm_per_s3 * 1.01);
}

TEST_CASE("motion: arcs and a helix run above the speed of the sum rule keep every limit from rest to rest",
          "[core][motion]") {
  // At feed 100 mm/s an arc of R 5 mm is capped by the jerk from curvature (the sum rule's speed
  // v0 = (¼ j / (κ² + 1.25 κ²))^(1/3) = 51.8 mm/s, the orthogonal parts' 1.32 v0, below the
  // centripetal √(½ a / κ) = 70.7 mm/s): each job starts and stops on curves, so the profile speeds
  // up and slows down where the curvature's jerk is near its whole share.
  MachineLimits m = test_machine();
  m.feed_mm_per_s = 100;
  const double kappa = 1 / 5.0;
  const double v0 = std::cbrt(0.25 * m.j_max_mm_per_s3 / (2.25 * kappa * kappa));
  const std::vector<std::vector<PathSegment>> jobs{
      {arc(mp(0, 0), mp(0, 10), mp(0, 5), ArcDirection::CounterClockwise), arc(mp(0, 10), mp(0, 20), mp(0, 15), ArcDirection::Clockwise)},
      {PathSegment::make_arc(mp(5, 0, 0), mp(5, 0, 6), mp(0, 0), ArcDirection::CounterClockwise, 2, 1e-9).value()},
  };
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    INFO("job " << k);
    const auto sp = run_job<double>(jobs[k], m);
    const auto peaks = measure(sp, m.rate_hz);
    CHECK(peaks.speed > 1.1 * v0);  // the new cap is reached: the test runs where it binds
    CHECK(peaks.jerk <= m.j_max_mm_per_s3 * 1.01);
    CHECK(peaks.acceleration <= m.a_max_mm_per_s2 * 1.01);
  }
}

namespace {

/// Seconds from the first setpoint until the speed, by differences of positions, first reaches `speed`.
double time_to_reach(const std::vector<Setpoint<double>>& sp, double speed, double rate_hz) {
  for (std::size_t i = 1; i < sp.size(); ++i) {
    double d2 = 0;
    for (std::size_t axis = 0; axis < 3; ++axis) d2 += std::pow(to_double(sp[i].position[axis]) - to_double(sp[i - 1].position[axis]), 2);
    if (std::sqrt(d2) * rate_hz >= speed) return static_cast<double>(i) / rate_hz;
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace

TEST_CASE("motion: a gently curved arc changes speed with the jerk its curvature leaves, not half of it", "[core][motion]") {
  // From rest an S-curve of jerk j_t and acceleration cap a reaches Δv in 2 √(Δv / j_t), or in
  // Δv / a + a / j_t once Δv >= a² / j_t. A profile that kept half the jerk on every curve took j_t =
  // ½ j whatever the curvature. What a curve leaves, worked by hand from its geometry at the fastest
  // speed it may run (its feed under a 200 % override, v_h) and, for an arc, |d(κN)/ds| = κ² (the
  // planner's margin 1.25 included), capped at ¾ j:
  //   R 50 mm, feed 50: v_h 100, along v_h³κ² = 400, across 3 v_h a κ + v_h³ 1.25 κ² <= 12 500 with
  //     a <= a_max: √(j² − 12 500²) − 400 = 48 012 of j 50 000, so ¾ j: 50 mm/s after 72.9 ms, not
  //     89.4 ms.
  //   R 5 mm, feed 30: the sum rule's speed v0 = (¼ j / (2.25 κ²))^⅓ = 51.8 mm/s; below it a_t <=
  //     j / (12 v κ) (694 mm/s² at 30 mm/s), above it a_t keeps j / (12 v0 κ) (402 mm/s² at v_h 60):
  //     across 3 κ v_h 402 + v_h³ 1.25 κ² = 14 478 + 10 800, along v_h³κ² = 8 640, so j_t =
  //     √(j² − 25 278²) − 8 640 = 0.69 j: 30 mm/s after 63.4 ms, not 71.0 ms.
  MachineLimits m = test_machine();
  const double j = m.j_max_mm_per_s3;
  struct Case {
    double radius, feed, acceleration, expected_jerk;
  };
  const double kappa = 1 / 5.0;
  const double v0 = std::cbrt(0.25 * j / (2.25 * kappa * kappa));
  const double v_high = 60;
  const double across = 3 * kappa * v_high * j / (12 * v0 * kappa) + std::pow(v_high, 3) * 1.25 * kappa * kappa;
  const double tight_jerk = std::sqrt(j * j - across * across) - std::pow(v_high, 3) * kappa * kappa;
  REQUIRE(tight_jerk > 0.6 * j);
  REQUIRE(tight_jerk < 0.7 * j);
  for (const Case c : {Case{50, 50, m.a_max_mm_per_s2, 0.75 * j}, Case{5, 30, j / (12 * 30 * kappa), tight_jerk}}) {
    INFO("arc R " << c.radius << " mm at feed " << c.feed << " mm/s");
    m.feed_mm_per_s = c.feed;
    const double r = c.radius;
    const std::vector<PathSegment> job{arc(mp(0, 0), mp(0, 2 * r), mp(0, r), ArcDirection::CounterClockwise)};
    const auto sp = run_job<double>(job, m);
    const auto peaks = measure(sp, m.rate_hz);
    CHECK(peaks.jerk <= j * 1.01);
    CHECK(peaks.acceleration <= m.a_max_mm_per_s2 * 1.01);
    const auto change_time = [&](double dv, double jerk) {
      return dv >= c.acceleration * c.acceleration / jerk ? dv / c.acceleration + c.acceleration / jerk : 2 * std::sqrt(dv / jerk);
    };
    const double reached = time_to_reach(sp, 0.999 * c.feed, m.rate_hz);
    const double with_half = change_time(0.999 * c.feed, 0.5 * j);
    const double expected = change_time(0.999 * c.feed, c.expected_jerk);
    INFO("reached the feed after " << reached << " s; " << expected << " s expected, " << with_half << " s with half the jerk");
    CHECK(reached < expected + 0.002);
    CHECK(reached > expected - 0.002);
  }
}

TEST_CASE("motion: a line into an arc tangent to 4 decimals, its kink and curvature jump together, keeps the jerk within the corner's excess",
          "[core][motion]") {
  // From a random G-code job (benchmarks/path_speed/random_jobs.py, seed 15, job 23): a line into an
  // arc of R 50 mm whose rounded coordinates leave a kink of ≈ 4·10⁻⁵ rad, on a machine of j 5000,
  // a 1000 at feed 25 mm/s. The joint is passed at the curvature jump's cap, v²/R = ½ j Δt
  // (11.18 mm/s), where the arc's profile takes ¾ j (curve_profile_jerk) and the line brakes into
  // the joint with its whole j. The line's start moves through one tick's distance in 24 steps, so
  // the joint falls at every place between two setpoints; the measured jerk must stay within the
  // 0.75 % a corner's velocity jump may add (corner_jump_share). Without the joint's combined rule
  // for the kink beside the jump it measured 1.016 j.
  MachineLimits m = test_machine();
  m.j_max_mm_per_s3 = 5000;
  m.a_max_mm_per_s2 = 1000;
  m.feed_mm_per_s = 25;
  const MachinePoint joint = mp(151.1266, -241.5299);
  const MachinePoint before = mp(150.0427, -241.4694);
  const MachinePoint centre = mp(151.1266 + 2.7845, -241.5299 + 49.9224);
  const MachinePoint end = mp(203.3027, -199.3839);
  const double length = norm(joint - before);
  const MachinePoint direction = (joint - before) * (1 / length);
  const double kink = std::acos(std::fmin(1.0, dot(direction, mp(49.9224, -2.7845) * (1 / norm(mp(49.9224, -2.7845))))));
  INFO("kink " << kink << " rad");
  REQUIRE(kink > 1e-5);
  REQUIRE(kink < 1e-4);
  double worst = 0;
  for (int k = 0; k < 24; ++k) {
    const MachinePoint start = joint - direction * (3.0 + 0.011 * k / 24);
    const std::vector<PathSegment> job{line(start, joint),
                                       PathSegment::make_arc(joint, end, centre, ArcDirection::CounterClockwise, 0, 1e-3).value()};
    worst = std::max(worst, measure(run_job<double>(job, m), m.rate_hz).jerk);
  }
  INFO("largest measured jerk " << worst << " mm/s³");
  CHECK(worst <= m.j_max_mm_per_s3 * (1 + detail::corner_limit_excess));
}

TEST_CASE("motion: with the trapezoid profile the jerk from curvature caps nothing, j_max changes no plan",
          "[core][motion]") {
  // The trapezoid changes speed by steps of acceleration (as grbl): it limits no jerk, so neither
  // may the jerk a curve makes cap its speed or its acceleration. An arc of R 5 mm at feed 100 runs
  // at its centripetal cap √(½ a_max R) = 70.7 mm/s (the S-curve's jerk cap there: 68.4 mm/s), and
  // machines that differ only in j_max plan every acceptance job alike.
  MachineLimits m = test_machine();
  m.jerk_limited = false;
  m.feed_mm_per_s = 100;
  const std::vector<PathSegment> arc_job{arc(mp(0, 0), mp(0, 10), mp(0, 5), ArcDirection::CounterClockwise),
                                         arc(mp(0, 10), mp(0, 0), mp(0, 5), ArcDirection::CounterClockwise)};
  const auto peaks = measure(run_job<double>(arc_job, m), m.rate_hz);
  const double centripetal = std::sqrt(0.5 * m.a_max_mm_per_s2 * 5);
  INFO("peak speed " << peaks.speed << " mm/s, centripetal cap " << centripetal);
  CHECK(peaks.speed > 0.995 * centripetal);
  CHECK(peaks.speed <= 1.001 * centripetal);
  CHECK(peaks.acceleration <= m.a_max_mm_per_s2 * 1.01);
  MachineLimits low_jerk = m;
  low_jerk.j_max_mm_per_s3 = 2000;
  auto jobs = acceptance_jobs();
  jobs.push_back(arc_job);
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    INFO("job " << k);
    const auto a = run_job<double>(jobs[k], m);
    const auto b = run_job<double>(jobs[k], low_jerk);
    REQUIRE(a.size() == b.size());
    // The same plan; the stepped setpoints may differ within the chunks' error bound, which j_max
    // scales (chunk_error_bound: each stream within 10⁻³ of the tolerance of the exact path).
    double largest_difference = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      for (std::size_t axis = 0; axis < 3; ++axis) {
        largest_difference = std::max(largest_difference, std::fabs(a[i].position[axis] - b[i].position[axis]));
      }
    }
    CHECK(largest_difference <= 2e-3 * m.tolerance_mm);
  }
}
