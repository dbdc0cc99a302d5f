// SPDX-License-Identifier: MIT
// Uses the installed headers: evaluates the seed cubic and encodes a protocol frame.
#include <cstdio>

#include <curvestep/core.hpp>
#include <curvestep/protocol.hpp>

int main() {
  using namespace curvestep;
  const auto curve = Bezier<double, 2>::create({{{0, 0}}, {{1, 2}}, {{3, 3}}, {{4, 0}}});
  if (!curve) return 1;
  const auto p = curve.value().evaluate(0.25).value();
  std::printf("p(1/4) = (%g, %g)\n", p[0], p[1]);
  return (p[0] == 29.0 / 32 && p[1] == 81.0 / 64) ? 0 : 1;
}
