// SPDX-License-Identifier: MIT
// Binomial coefficients and least common multiples for small degrees (compile-time friendly).
#pragma once

#include <cstdint>

namespace curvestep::detail {

/// C(n, k) for n <= 60 (exact in 64 bits); 0 for k > n.
[[nodiscard]] constexpr std::int64_t binomial(std::size_t n, std::size_t k) noexcept {
  if (k > n) return 0;
  if (k > n - k) k = n - k;
  std::int64_t c = 1;
  for (std::size_t i = 1; i <= k; ++i) {
    c = c * static_cast<std::int64_t>(n - k + i) / static_cast<std::int64_t>(i);
  }
  return c;
}

[[nodiscard]] constexpr std::int64_t gcd(std::int64_t a, std::int64_t b) noexcept {
  while (b != 0) {
    const std::int64_t r = a % b;
    a = b;
    b = r;
  }
  return a < 0 ? -a : a;
}

[[nodiscard]] constexpr std::int64_t lcm(std::int64_t a, std::int64_t b) noexcept {
  return a / gcd(a, b) * b;
}

}  // namespace curvestep::detail
