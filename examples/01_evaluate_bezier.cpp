// SPDX-License-Identifier: MIT
// Example 1: evaluate, split and differentiate a cubic Bézier in double and in Q16.16 fixed point.
#include <cstdio>

#include <curvestep/core.hpp>

int main() {
  using namespace curvestep;
  using namespace curvestep::literals;

  // The same cubic in double and in Q16.16 millimetres.
  const auto exact = Bezier<double, 2>::create({{{0, 0}}, {{1, 2}}, {{3, 3}}, {{4, 0}}});
  const auto fixed = Bezier<Q16_16, 2>::create({{{0_q16, 0_q16}}, {{1_q16, 2_q16}}, {{3_q16, 3_q16}}, {{4_q16, 0_q16}}});
  if (!exact || !fixed) return 1;

  const auto p = exact.value().evaluate(0.25).value();             // (29/32, 81/64)
  const auto q = fixed.value().evaluate(0.25_q16).value();         // the same, exactly
  const auto tangent = exact.value().derivative_at(0.5).value();   // (9/2, 3/4)
  const auto halves = fixed.value().split(0.5_q16).value();        // two cubics
  const auto bad = exact.value().evaluate(1.5);                    // an error, not a guess

  std::printf("p(1/4)   double (%g, %g)  Q16.16 (%g, %g)\n", p[0], p[1], q[0].to_double(), q[1].to_double());
  std::printf("p'(1/2)  (%g, %g)\n", tangent[0], tangent[1]);
  std::printf("left half ends at (%g, %g)\n", halves.left.back()[0].to_double(), halves.left.back()[1].to_double());
  std::printf("evaluate(1.5) -> error %d\n", static_cast<int>(bad.error()));
  return (p[0] == 29.0 / 32 && q[0].to_double() == 29.0 / 32 && !bad) ? 0 : 1;
}
