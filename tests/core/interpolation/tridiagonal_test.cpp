// SPDX-License-Identifier: MIT
// Tridiagonal and cyclic solvers against an independent dense Gaussian elimination (partial
// pivoting, double), plus the singular, ill-conditioned and buffer errors.
#include <array>
#include <cmath>
#include <random>
#include <span>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core.hpp>
#include <curvestep/core/interpolation/tridiagonal.hpp>
#include <support/numeric.hpp>

#include "interpolation_support.hpp"

using namespace curvestep;
using curvestep::testing::scalar;
using curvestep::testing::solve_tolerance;

namespace {
/// Dense solve with partial pivoting (the oracle: a different algorithm on the full matrix).
std::vector<double> dense_solve(std::vector<std::vector<double>> a, std::vector<double> b) {
  const std::size_t n = b.size();
  for (std::size_t k = 0; k < n; ++k) {
    std::size_t pivot = k;
    for (std::size_t i = k + 1; i < n; ++i) {
      if (std::fabs(a[i][k]) > std::fabs(a[pivot][k])) pivot = i;
    }
    std::swap(a[k], a[pivot]);
    std::swap(b[k], b[pivot]);
    for (std::size_t i = k + 1; i < n; ++i) {
      const double f = a[i][k] / a[k][k];
      for (std::size_t j = k; j < n; ++j) a[i][j] -= f * a[k][j];
      b[i] -= f * b[k];
    }
  }
  std::vector<double> x(n);
  for (std::size_t i = n; i-- > 0;) {
    double s = b[i];
    for (std::size_t j = i + 1; j < n; ++j) s -= a[i][j] * x[j];
    x[i] = s / a[i][i];
  }
  return x;
}

struct Band {
  std::vector<double> lower, diagonal, upper, rhs;
};

Band random_dominant_band(std::mt19937& random, std::size_t n) {
  std::uniform_real_distribution<double> off(-1, 1);
  std::uniform_real_distribution<double> value(-8, 8);
  Band band;
  for (std::size_t i = 0; i < n; ++i) {
    // Quantised to 1/256 so that the same matrix is exact in Q16.16 and float.
    const double a = std::round(off(random) * 256) / 256;
    const double c = std::round(off(random) * 256) / 256;
    const double margin = 0.5 + std::round(std::fabs(off(random)) * 256) / 256;
    band.lower.push_back(a);
    band.upper.push_back(c);
    band.diagonal.push_back((i % 2 == 0 ? 1 : -1) * (std::fabs(a) + std::fabs(c) + margin));
    band.rhs.push_back(std::round(value(random) * 256) / 256);
  }
  return band;
}

std::vector<std::vector<double>> dense(const Band& band, bool cyclic) {
  const std::size_t n = band.diagonal.size();
  std::vector<std::vector<double>> a(n, std::vector<double>(n, 0.0));
  for (std::size_t i = 0; i < n; ++i) {
    a[i][i] = band.diagonal[i];
    if (i > 0) a[i][i - 1] += band.lower[i];
    if (i + 1 < n) a[i][i + 1] += band.upper[i];
  }
  if (cyclic) {
    a[0][n - 1] += band.lower[0];
    a[n - 1][0] += band.upper[n - 1];
  }
  return a;
}
}  // namespace

TEMPLATE_TEST_CASE("interpolation: Thomas and Sherman-Morrison solvers agree with dense elimination", "[core][interpolation]",
                   double, float, Q16_16) {
  using S = TestType;
  std::mt19937 random(curvestep::testing::test_seed());
  const int cases = curvestep::testing::test_count(200);
  for (int c = 0; c < cases; ++c) {
    const std::size_t n = 1 + static_cast<std::size_t>(c % 12);
    const Band band = random_dominant_band(random, n);
    for (const bool cyclic : {false, true}) {
      const auto expected = dense_solve(dense(band, cyclic), band.rhs);
      std::array<S, 16> lower{}, diagonal{}, upper{}, values{};
      std::array<S, 32> scratch{};
      for (std::size_t i = 0; i < n; ++i) {
        lower[i] = scalar<S>(band.lower[i]);
        diagonal[i] = scalar<S>(band.diagonal[i]);
        upper[i] = scalar<S>(band.upper[i]);
        values[i] = scalar<S>(band.rhs[i]);
      }
      const auto solve = cyclic ? solve_cyclic_tridiagonal<S, S> : solve_tridiagonal<S, S>;
      const auto r = solve(std::span<const S>(lower.data(), n), std::span<const S>(diagonal.data(), n),
                           std::span<const S>(upper.data(), n), std::span<S>(values.data(), n), std::span<S>(scratch));
      REQUIRE(r.has_value());
      // Dominance margin >= 1/2 bounds |A^-1| by 2, so |x| <= 16 and errors stay a few units of |x|.
      for (std::size_t i = 0; i < n; ++i) CHECK(std::fabs(to_double(values[i]) - expected[i]) <= solve_tolerance<S>(16));
    }
  }
}

TEMPLATE_TEST_CASE("interpolation: singular tridiagonal systems are reported with the row", "[core][interpolation]", double, float,
                   Q16_16) {
  using S = TestType;
  const S one = from_int<S>(1);
  const std::array<S, 3> lower{S{}, one, one};
  const std::array<S, 3> diagonal{one, one, one};
  const std::array<S, 3> upper{one, one, S{}};
  std::array<S, 3> values{one, one, one};
  std::array<S, 6> scratch{};
  // Rows 0 and 1 are equal: the second pivot is 1 − 1·1 = 0.
  const auto r = solve_tridiagonal(std::span<const S>(lower), std::span<const S>(diagonal), std::span<const S>(upper),
                                   std::span<S>(values), std::span<S>(scratch));
  CHECK(r.error() == Error::SingularSystem);
  CHECK(r.where() == 1);
  // The closed-quadratic circulant x_i + x_{i+1} = d_i (indices mod 4) is singular for even length.
  const std::array<S, 4> cyclic_lower{S{}, S{}, S{}, S{}};
  const std::array<S, 4> cyclic_diagonal{one, one, one, one};
  const std::array<S, 4> cyclic_upper{one, one, one, one};
  std::array<S, 4> cyclic_values{one, one, one, one};
  std::array<S, 8> cyclic_scratch{};
  const auto c = solve_cyclic_tridiagonal(std::span<const S>(cyclic_lower), std::span<const S>(cyclic_diagonal),
                                          std::span<const S>(cyclic_upper), std::span<S>(cyclic_values), std::span<S>(cyclic_scratch));
  CHECK(c.error() == Error::SingularSystem);
  // The same loop of odd length 3 is regular: x = d/2 for d = (1,1,1).
  std::array<S, 3> odd_values{one, one, one};
  REQUIRE(solve_cyclic_tridiagonal(std::span<const S>(cyclic_lower.data(), 3), std::span<const S>(cyclic_diagonal.data(), 3),
                                   std::span<const S>(cyclic_upper.data(), 3), std::span<S>(odd_values), std::span<S>(cyclic_scratch))
              .has_value());
  for (const S x : odd_values) CHECK(to_double(x) == 0.5);
}

TEMPLATE_TEST_CASE("interpolation: nearly singular systems are reported as ill-conditioned", "[core][interpolation]", double,
                   float, Q16_16) {
  using S = TestType;
  const S one = from_int<S>(1);
  const S almost = one - resolution<S>();
  const std::array<S, 2> lower{S{}, almost};
  const std::array<S, 2> diagonal{one, one};
  const std::array<S, 2> upper{one, S{}};
  std::array<S, 2> values{one, one};
  std::array<S, 2> scratch{};
  // Pivot 1 − (1 − ε) = ε: one unit of resolution against a row of magnitude 2.
  const auto r = solve_tridiagonal(std::span<const S>(lower), std::span<const S>(diagonal), std::span<const S>(upper),
                                   std::span<S>(values), std::span<S>(scratch));
  CHECK(r.error() == Error::SingularSystem);
}

TEMPLATE_TEST_CASE("interpolation: solver scratch buffers that are too small are reported", "[core][interpolation]", double, float,
                   Q16_16) {
  using S = TestType;
  const S two = from_int<S>(2);
  const std::array<S, 3> band{two, two, two};
  std::array<S, 3> values{};
  std::array<S, 2> scratch{};
  CHECK(solve_tridiagonal(std::span<const S>(band), std::span<const S>(band), std::span<const S>(band), std::span<S>(values),
                          std::span<S>(scratch))
            .error() == Error::BufferTooSmall);
  std::array<S, 5> cyclic_scratch{};
  CHECK(solve_cyclic_tridiagonal(std::span<const S>(band), std::span<const S>(band), std::span<const S>(band),
                                 std::span<S>(values), std::span<S>(cyclic_scratch))
            .error() == Error::BufferTooSmall);
}
