// SPDX-License-Identifier: MIT
// Example 2: an exact semicircle as a rational Bézier in Q16.16, checked against the true circle.
#include <cmath>
#include <cstdio>

#include <curvestep/core.hpp>

int main() {
  using namespace curvestep;
  using namespace curvestep::literals;

  const Vec2<Q16_16> centre{{10_q16, 10_q16}};
  const auto arc = circular_arc<Q16_16>(centre, {{60_q16, 10_q16}}, {{-40_q16, 10_q16}}, ArcDirection::CounterClockwise,
                                        0.001_q16);
  if (!arc) return 1;
  double worst = 0;
  for (int k = 0; k <= 1000; ++k) {
    const auto p = arc.value().point_at(Q16_16::from_double(k / 1000.0).value());
    const double r = std::hypot(p[0].to_double() - 10, p[1].to_double() - 10);
    worst = std::fmax(worst, std::fabs(r - 50));
  }
  std::printf("semicircle r=50 mm as a rational cubic: max radial error %.3f um\n", worst * 1000);
  return worst < 0.01 ? 0 : 1;
}
