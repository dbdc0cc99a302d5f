// SPDX-License-Identifier: MIT
// Golden-section search for the minimum of a unimodal function on an interval (deterministic).
#pragma once

namespace curvestep::detail {

/// Where a search ended: the abscissa and the function value there.
struct GoldenSectionResult {
  double x = 0;
  double value = 0;
};

/// The minimum of `f` on [low, high], assumed unimodal there, after `iterations` reductions of the
/// bracket by the golden ratio (each keeps 61.8% of it). For a maximum, minimise -f.
template <class Function>
[[nodiscard]] GoldenSectionResult golden_section_minimum(Function f, double low, double high, int iterations) {
  constexpr double ratio = 0.6180339887498949;
  double x1 = high - ratio * (high - low);
  double x2 = low + ratio * (high - low);
  double f1 = f(x1);
  double f2 = f(x2);
  for (int i = 0; i < iterations; ++i) {
    if (f1 < f2) {
      high = x2;
      x2 = x1;
      f2 = f1;
      x1 = high - ratio * (high - low);
      f1 = f(x1);
    } else {
      low = x1;
      x1 = x2;
      f1 = f2;
      x2 = low + ratio * (high - low);
      f2 = f(x2);
    }
  }
  return f1 < f2 ? GoldenSectionResult{x1, f1} : GoldenSectionResult{x2, f2};
}

}  // namespace curvestep::detail
