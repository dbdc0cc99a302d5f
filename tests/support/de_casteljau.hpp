// SPDX-License-Identifier: MIT
// A reference de Casteljau subdivision written in the tests (long double, no library code): the
// expected control points of the two pieces of a Bézier split at t. For a rational curve, pass
// the homogeneous points (w·P, w). With dyadic control points and t a short binary fraction every
// step is exact, so a library split can be compared with it bit for bit.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace curvestep::testing {

template <std::size_t Dim>
struct ReferenceSplit {
  std::vector<std::array<long double, Dim>> left;
  std::vector<std::array<long double, Dim>> right;
};

/// The pieces on [0,t] and [t,1]: left[i] is the first point of the i-th de Casteljau row, right[i]
/// the last point of row n-i (rows computed as (1-t)·a + t·b).
template <std::size_t Dim>
ReferenceSplit<Dim> de_casteljau_split(std::vector<std::array<long double, Dim>> row, long double t) {
  const std::size_t n = row.size() - 1;
  ReferenceSplit<Dim> out;
  out.left.resize(n + 1);
  out.right.resize(n + 1);
  for (std::size_t level = 0; level <= n; ++level) {
    out.left[level] = row.front();
    out.right[n - level] = row[n - level];
    for (std::size_t i = 0; i + level < n; ++i) {
      for (std::size_t a = 0; a < Dim; ++a) row[i][a] = (1 - t) * row[i][a] + t * row[i + 1][a];
    }
  }
  return out;
}

}  // namespace curvestep::testing
