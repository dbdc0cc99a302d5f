// SPDX-License-Identifier: MIT
// Bernstein basis polynomials B^n_i(t) = C(n,i) t^i (1-t)^(n-i).
//
// All n+1 values are computed by the triangular scheme B^{k+1}_i = t B^k_{i-1} + (1-t) B^k_i
// (partition of unity is kept to rounding; every entry is a convex combination for t in [0,1]).
#pragma once

#include <array>
#include <cstddef>

#include <curvestep/core/contract.hpp>
#include <curvestep/core/scalar.hpp>

namespace curvestep {

/// B^n_0(t) .. B^n_n(t) in the first n+1 entries; contract: n <= MaxDegree.
template <std::size_t MaxDegree, Scalar S>
[[nodiscard]] constexpr std::array<S, MaxDegree + 1> bernstein_all(std::size_t n, S t) {
  CURVESTEP_EXPECTS(n <= MaxDegree);
  std::array<S, MaxDegree + 1> b{};
  b[0] = from_int<S>(1);
  const S one_minus_t = from_int<S>(1) - t;
  for (std::size_t k = 1; k <= n; ++k) {
    b[k] = t * b[k - 1];
    for (std::size_t i = k - 1; i >= 1; --i) b[i] = t * b[i - 1] + one_minus_t * b[i];
    b[0] = one_minus_t * b[0];
  }
  return b;
}

/// One Bernstein polynomial B^n_i(t); 0 for i > n.
template <Scalar S>
[[nodiscard]] constexpr S bernstein(std::size_t n, std::size_t i, S t) {
  if (i > n) return S{};
  constexpr std::size_t limit = 32;
  CURVESTEP_EXPECTS(n <= limit);
  return bernstein_all<limit>(n, t)[i];
}

}  // namespace curvestep
