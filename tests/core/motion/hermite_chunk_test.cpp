// SPDX-License-Identifier: MIT
// HermiteChunk: the quintic Hermite between two states reproduces any quintic path (positions,
// velocities, accelerations given exactly), its stepped values follow the polynomial, and
// chunk_error_bound has the documented values.
#include <array>
#include <cmath>
#include <limits>

#include <catch2/catch.hpp>

#include "motion_test_support.hpp"

using namespace curvestep;
using namespace curvestep::testing;

namespace {
/// x(t) = Σ c_i t^i per axis, and its first two derivatives.
struct Quintic {
  std::array<std::array<double, 6>, 3> c{};
  [[nodiscard]] double value(std::size_t axis, double t, int order) const {
    double sum = 0;
    for (int i = 5; i >= order; --i) {
      double factor = 1;
      for (int k = 0; k < order; ++k) factor *= i - k;
      sum = sum * t + factor * c[axis][static_cast<std::size_t>(i)];  // Horner: Σ i!/(i-order)! c_i t^(i-order)
    }
    return sum;
  }
  [[nodiscard]] PathTickState state(double t) const {
    PathTickState s;
    for (std::size_t axis = 0; axis < 3; ++axis) {
      s.position[axis] = value(axis, t, 0);
      s.velocity[axis] = value(axis, t, 1);
      s.acceleration[axis] = value(axis, t, 2);
    }
    s.smooth = true;
    return s;
  }
};
}  // namespace

TEST_CASE("motion: the Hermite chunk reproduces a quintic path and steps it by additions", "[core][motion][chunks]") {
  Quintic x;
  x.c = {{{120, 40, -300, 2000, -9000, 15000}, {-35, 10, 800, -1500, 4000, -3000}, {2, 1, 0, 0, 0, 0}}};
  const double h = 0.064;  // 64 ticks at 1 kHz
  const auto a = x.state(0.25);
  const auto b = x.state(0.25 + h);
  const auto q = HermiteChunk::controls(a, b, h);
  // Control points of the documented form.
  for (std::size_t axis = 0; axis < 3; ++axis) {
    CHECK(q[0][axis] == 0.0);
    CHECK(q[1][axis] == Approx(h * a.velocity[axis] / 5).margin(1e-15));
    CHECK(q[5][axis] == b.position[axis] - a.position[axis]);
  }
  // Middle and quarters: the path itself (a quintic is its own Hermite).
  const auto half = HermiteChunk::at_half(q);
  const auto quarter = HermiteChunk::at_quarter(q);
  const auto three = HermiteChunk::at_three_quarters(q);
  for (std::size_t axis = 0; axis < 3; ++axis) {
    CHECK(half[axis] + a.position[axis] == Approx(x.value(axis, 0.25 + h / 2, 0)).margin(1e-11));
    CHECK(quarter[axis] + a.position[axis] == Approx(x.value(axis, 0.25 + h / 4, 0)).margin(1e-11));
    CHECK(three[axis] + a.position[axis] == Approx(x.value(axis, 0.25 + 3 * h / 4, 0)).margin(1e-11));
  }
  // Stepped: every tick on the polynomial.
  HermiteChunk chunk;
  REQUIRE(chunk.start(a.position, q, 64).has_value());
  double worst = 0;
  for (int k = 1; k <= 64; ++k) {
    const auto p = chunk.next();
    for (std::size_t axis = 0; axis < 3; ++axis) worst = std::fmax(worst, std::fabs(p[axis] - x.value(axis, 0.25 + h * k / 64, 0)));
  }
  CHECK(worst <= 1e-11);
  // Non-finite control points are refused.
  auto bad = q;
  bad[2][1] = std::numeric_limits<double>::infinity();
  CHECK(chunk.start(a.position, bad, 8).error() == Error::NotFinite);
}

TEST_CASE("motion: chunk_error_bound takes the smallest of the tolerance, speed, acceleration and jerk terms", "[core][motion][chunks]") {
  const MachineLimits m = test_machine();  // 1 kHz, tolerance 0.01, v 200, a 2000, j 50000
  // 16 ticks: h = 0.016 s; jerk term 1e-3 · 50000 · 0.016³ / 384 = 5.3333e-7 mm is the smallest.
  CHECK(chunk_error_bound(16, m) == Approx(5.333333e-7).epsilon(1e-6));
  // 2 ticks: h = 0.002 s; jerk term 1e-3 · 50000 · 8e-9 / 384 = 1.0417e-9 mm.
  CHECK(chunk_error_bound(2, m) == Approx(1.0416667e-9).epsilon(1e-6));
  // 256 ticks: the tolerance term 1e-3 · 0.01 = 1e-5 mm.
  CHECK(chunk_error_bound(256, m) == Approx(1e-5).epsilon(1e-12));
  // A low acceleration limit makes its term the smallest: 1e-3 · 10 · 0.064² / 24 = 1.7067e-6 mm.
  MachineLimits slow = m;
  slow.a_max_mm_per_s2 = 10;
  slow.j_max_mm_per_s3 = 1e7;
  CHECK(chunk_error_bound(64, slow) == Approx(1.7066667e-6).epsilon(1e-6));
}
