// SPDX-License-Identifier: MIT
// Elliptical arcs: sampled points lie on the ellipse the arc was built from, on the right branch.
//
// Each case starts from a centre-form ellipse arc (centre, radii, rotation, start angle, sweep)
// chosen at random, computes its end points and flags, imports the endpoint-form "A" command and
// checks the pieces against the centre form: the importer's own centre never enters the oracle.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/host/svg_import.hpp>
#include <support/numeric.hpp>

#include "svg_test_support.hpp"

using namespace curvestep;
using namespace curvestep::host;
using namespace curvestep::testing;

namespace {

constexpr double pi = std::numbers::pi;

std::string number(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

struct Ellipse {
  double cx, cy, rx, ry, phi_deg;
  [[nodiscard]] std::pair<double, double> at(double theta) const {
    const double phi = phi_deg * pi / 180;
    const double x = rx * std::cos(theta);
    const double y = ry * std::sin(theta);
    return {cx + std::cos(phi) * x - std::sin(phi) * y, cy + std::sin(phi) * x + std::cos(phi) * y};
  }
  /// (value of the ellipse equation, angle of the point) for a user-space point.
  [[nodiscard]] std::pair<double, double> locate(double x, double y) const {
    const double phi = phi_deg * pi / 180;
    const double dx = x - cx;
    const double dy = y - cy;
    const double u = (std::cos(phi) * dx + std::sin(phi) * dy) / rx;
    const double v = (-std::sin(phi) * dx + std::cos(phi) * dy) / ry;
    return {u * u + v * v, std::atan2(v, u)};
  }
};

/// Checks every imported arc piece against `e` from angle theta1 over sweep delta.
void check_arc(const Job& job, const Ellipse& e, double theta1, double delta) {
  const auto expected_pieces = static_cast<std::size_t>(std::ceil(std::fabs(delta) / (pi / 2)));
  const auto pieces = drawn(job);
  REQUIRE(pieces.size() == expected_pieces);
  // The middle weight cos(δ/2) of each piece, δ = delta / pieces, travels as Q16.16: on the grid
  // and within half a step (2^-17) of the exact value (1e-12 for the two computations of δ).
  const double exact_weight = std::cos(delta / static_cast<double>(2 * expected_pieces));
  for (const auto& p : pieces) {
    REQUIRE(p.type == SegmentType::RationalBezier);
    CHECK(on_q16_grid(p.weights[1]));
    CHECK(std::fabs(p.weights[1] - exact_weight) <= 0x1p-17 + 1e-12);
  }
  const double direction = delta > 0 ? 1 : -1;
  double progress_before = -1e-6;
  for (std::size_t i = 0; i < job.segments.size(); ++i) {
    if (job.segments[i].rapid()) continue;
    for (int k = 0; k <= 24; ++k) {
      const auto p = job.segments[i].point(k / 24.0);
      const auto [equation, angle] = e.locate(p[0], 100 - p[1]);
      // Two roundings move the curve off the ellipse. The control points move by at most 2^-17 mm
      // per axis (2^-17·√2 = 1.08e-5 mm), and so does the curve (a convex combination of them):
      // at most 1.08e-5 / 3 = 3.6e-6 in the unit frame (radii >= 3 mm), so u² + v² by at most
      // 2·3.6e-6 + 3.6e-6² = 7.2e-6. The rounded weight adds at most
      // (1 - c²)|w² - c²| / (c² (1 + w)²) <= (1/2)(2^-17 · 2) / ((1/2)(1 + √2/2)²) = 5.3e-6
      // (c² >= 1/2, |w - c| <= 2^-17, w + c <= 2; svg_test_support.hpp). Sum 1.25e-5 < 2e-5.
      CHECK(equation == Approx(1).margin(2e-5));
      // Progress along the sweep direction from theta1, in [-slack, 2π - slack): the slack covers
      // the Q16.16 rounding of the points (at most 2^-17 mm on radii of at least 3 mm).
      constexpr double slack = 1e-4;
      double progress = std::fmod(direction * (angle - theta1), 2 * pi);
      if (progress < -slack) progress += 2 * pi;
      if (progress >= 2 * pi - slack) progress -= 2 * pi;
      CHECK(progress >= progress_before - slack);
      CHECK(progress <= std::fabs(delta) + slack);
      progress_before = progress;
    }
  }
  CHECK(progress_before == Approx(std::fabs(delta)).margin(1e-5));
}

}  // namespace

TEST_CASE("svg: random elliptical arcs lie on their ellipse between the right angles", "[host_tools][svg]") {
  std::mt19937_64 random(test_seed());
  std::uniform_real_distribution<double> centre(30, 70), radius(3, 25), rotation(-360, 360), angle(0, 2 * pi), sweep(0.05, 2 * pi - 0.05);
  const int count = test_count(200);
  for (int n = 0; n < count; ++n) {
    const Ellipse e{centre(random), centre(random), radius(random), radius(random), rotation(random)};
    const double theta1 = angle(random);
    double delta = sweep(random);
    if (std::fabs(delta - pi) < 0.02) continue;  // the large-arc flag is ambiguous at half a turn
    if (random() % 2 == 0) delta = -delta;
    const auto [x1, y1] = e.at(theta1);
    const auto [x2, y2] = e.at(theta1 + delta);
    const std::string flags = std::string(std::fabs(delta) > pi ? "1" : "0") + " " + (delta > 0 ? "1" : "0");
    const std::string absolute = "M " + number(x1) + " " + number(y1) + " A " + number(e.rx) + " " + number(e.ry) + " " +
                                 number(e.phi_deg) + " " + flags + " " + number(x2) + " " + number(y2);
    const std::string relative = "m " + number(x1) + " " + number(y1) + " a " + number(e.rx) + " " + number(e.ry) + " " +
                                 number(e.phi_deg) + " " + flags + " " + number(x2 - x1) + " " + number(y2 - y1);
    for (const auto& d : {absolute, relative}) {
      INFO(d);
      const Job job = import_page("<path d=\"" + d + "\"/>").job;
      check_connected(job);
      check_arc(job, e, theta1, delta);
    }
  }
}

TEST_CASE("svg: radii too small for the chord are scaled up until they just reach", "[host_tools][svg]") {
  // Circle: radius 10 for a chord of 100 becomes 50 about (50,50); sweep 1 passes (50,0).
  const Job circle = import_page("<path d=\"M 0 50 A 10 10 0 0 1 100 50\"/>").job;
  check_arc(circle, Ellipse{50, 50, 50, 50, 0}, pi, pi);
  const auto halves = drawn(circle);
  check_points(halves[0], {on_page(0, 50), on_page(0, 0), on_page(50, 0)});
  // Ellipse 10 x 5 for a chord of 100: Λ = 25, radii x5 -> 50 x 25; sweep 0 goes through (50,75).
  const Job ellipse = import_page("<path d=\"M 0 50 A 10 5 0 1 0 100 50\"/>").job;
  check_arc(ellipse, Ellipse{50, 50, 50, 25, 0}, pi, -pi);
  check_points(drawn(ellipse)[0], {on_page(0, 50), on_page(0, 75), on_page(50, 75)});
  // Rotated by 90°: the x radius lies along user y. Radius 20 x 5 for the horizontal chord 40 stays
  // (Λ = (20/5)² > 1 -> scaled by 4 to 80 x 20): the horizontal half-axis is 20.
  const Job rotated = import_page("<path d=\"M 30 50 A 20 5 90 0 1 70 50\"/>").job;
  check_arc(rotated, Ellipse{50, 50, 80, 20, 90}, pi / 2, pi);
}

TEST_CASE("svg: an arc's weight travels as the nearest Q16.16 value", "[host_tools][svg]") {
  // A 60° arc of radius 10 about (50,50) from angle 0 to 60° (sweep 1): one piece, middle weight
  // cos(30°) = √3/2 = 0.8660254; √3/2 · 65536 = 56755.84 rounds to 56756.
  const Job job = import_page("<path d=\"M 60 50 A 10 10 0 0 1 55 58.660254037844386\"/>").job;
  const auto pieces = drawn(job);
  REQUIRE(pieces.size() == 1);
  REQUIRE(pieces[0].weights.size() == 3);
  CHECK(pieces[0].weights[0] == 1.0);
  CHECK(pieces[0].weights[1] == 56756.0 / 65536.0);
  CHECK(pieces[0].weights[2] == 1.0);
  REQUIRE(job.segments.back().kind() == SegmentKind::RationalBezier);
  CHECK(job.segments.back().rational().weight(1) == 56756.0 / 65536.0);
  // Off the circle: with the exact points, |P|²/r² - 1 is at most eta = (1 - 3/4)|w² - 3/4| /
  // ((3/4)(1 + w)²) for w = 56756/65536 (svg_test_support.hpp); rounding the points moves the
  // curve by at most e = 2^-17·√2 mm, 1.08e-6 of r = 10. So |P|/r <= sqrt(1 + eta) + e/r.
  const double w = 56756.0 / 65536.0;
  const double eta = conic_off_circle_bound(std::sqrt(3.0) / 2, w);
  const double e = 0x1p-17 * std::sqrt(2.0) / 10;
  const double bound = (std::sqrt(1 + eta) + e) * (std::sqrt(1 + eta) + e) - 1 + 1e-12;
  for (int k = 0; k <= 16; ++k) {
    const auto p = job.segments.back().point(k / 16.0);
    const double x = p[0] - 50;
    const double y = (100 - p[1]) - 50;
    CHECK((x * x + y * y) / 100 == Approx(1).margin(bound));
  }
}

TEST_CASE("svg: arcs with a zero radius are lines and negative radii are their absolute values", "[host_tools][svg]") {
  const auto line = drawn(import_page("<path d=\"M 10 10 A 0 5 0 0 1 20 20\"/>").job);
  REQUIRE(line.size() == 1);
  CHECK(line[0].type == SegmentType::Line);
  check_points(line[0], {on_page(10, 10), on_page(20, 20)});
  const auto positive = drawn(import_page("<path d=\"M 10 10 A 10 20 30 0 1 30 20\"/>").job);
  const auto negative = drawn(import_page("<path d=\"M 10 10 A -10 -20 30 0 1 30 20\"/>").job);
  REQUIRE(positive.size() == negative.size());
  for (std::size_t i = 0; i < positive.size(); ++i) check_points(negative[i], positive[i].points);
}

TEST_CASE("svg: the small arc of an enormous ellipse is its chord", "[host_tools][svg]") {
  // Radius 1e300 over a 10 mm chord: the sagitta 100 / (8e300) is far below the Q16.16 grid.
  const auto pieces = drawn(import_page("<path d=\"M 0 0 A 1e300 1e300 0 0 1 10 0\"/>").job);
  REQUIRE(pieces.size() == 1);
  check_points(pieces[0], {on_page(0, 0), on_page(10, 0)});
  // Radius 1e6: still a rational arc, whose middle bulges by 12.5e-6 mm (below one grid step).
  const Job job = import_page("<path d=\"M 0 0 A 1e6 1e6 0 0 1 10 0\"/>").job;
  const auto arc = drawn(job);
  REQUIRE(arc.size() == 1);
  CHECK(arc[0].type == SegmentType::RationalBezier);
  // Its weight cos(5e-6) = 1 - 1.25e-11 rounds to 1 on the Q16.16 grid.
  CHECK(arc[0].weights[1] == 1.0);
  CHECK(near(job.segments.back().point(0.5), on_page(5, 0), 2 * grid_mm));
}
