// SPDX-License-Identifier: MIT
// Vec<S, Dim>: a point or vector of Dim scalars (2 or 3 for machines, any Dim for homogeneous maths).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>

#include <curvestep/core/result.hpp>
#include <curvestep/core/scalar.hpp>

namespace curvestep {

/// A point or vector with Dim coordinates of scalar type S.
template <Scalar S, std::size_t Dim>
struct Vec {
  static_assert(Dim > 0, "Vec needs at least one coordinate");
  using scalar_type = S;
  static constexpr std::size_t dimension = Dim;

  std::array<S, Dim> coordinates{};

  [[nodiscard]] constexpr S& operator[](std::size_t i) { return coordinates[i]; }
  [[nodiscard]] constexpr const S& operator[](std::size_t i) const { return coordinates[i]; }

  [[nodiscard]] constexpr S x() const requires(Dim >= 1) { return coordinates[0]; }
  [[nodiscard]] constexpr S y() const requires(Dim >= 2) { return coordinates[1]; }
  [[nodiscard]] constexpr S z() const requires(Dim >= 3) { return coordinates[2]; }

  friend constexpr bool operator==(const Vec&, const Vec&) = default;

  [[nodiscard]] friend constexpr Vec operator+(Vec a, const Vec& b) {
    for (std::size_t i = 0; i < Dim; ++i) a[i] = a[i] + b[i];
    return a;
  }
  [[nodiscard]] friend constexpr Vec operator-(Vec a, const Vec& b) {
    for (std::size_t i = 0; i < Dim; ++i) a[i] = a[i] - b[i];
    return a;
  }
  [[nodiscard]] friend constexpr Vec operator-(Vec a) {
    for (std::size_t i = 0; i < Dim; ++i) a[i] = -a[i];
    return a;
  }
  [[nodiscard]] friend constexpr Vec operator*(Vec a, S k) {
    for (std::size_t i = 0; i < Dim; ++i) a[i] = a[i] * k;
    return a;
  }
  [[nodiscard]] friend constexpr Vec operator*(S k, Vec a) { return a * k; }
  [[nodiscard]] friend constexpr Vec operator/(Vec a, S k) {
    for (std::size_t i = 0; i < Dim; ++i) a[i] = a[i] / k;
    return a;
  }
  constexpr Vec& operator+=(const Vec& b) { return *this = *this + b; }
  constexpr Vec& operator-=(const Vec& b) { return *this = *this - b; }
};

template <Scalar S>
using Vec2 = Vec<S, 2>;
template <Scalar S>
using Vec3 = Vec<S, 3>;

/// Builds a Vec from its coordinates: make_vec(x, y) or make_vec(x, y, z).
template <Scalar S, class... Rest>
[[nodiscard]] constexpr Vec<S, 1 + sizeof...(Rest)> make_vec(S first, Rest... rest) {
  return Vec<S, 1 + sizeof...(Rest)>{{first, static_cast<S>(rest)...}};
}

/// Component-wise (1-t)*a + t*b.
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr Vec<S, Dim> lerp(const Vec<S, Dim>& a, const Vec<S, Dim>& b, S t) {
  Vec<S, Dim> r;
  for (std::size_t i = 0; i < Dim; ++i) r[i] = lerp(a[i], b[i], t);
  return r;
}

/// Component-wise lerp, checked (any t).
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr Result<Vec<S, Dim>> checked_lerp(const Vec<S, Dim>& a, const Vec<S, Dim>& b, S t) noexcept {
  Vec<S, Dim> r;
  for (std::size_t i = 0; i < Dim; ++i) {
    const auto c = checked_lerp(a[i], b[i], t);
    if (!c) return c.failure();
    r[i] = c.value();
  }
  return r;
}

/// a - b, checked per coordinate.
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr Result<Vec<S, Dim>> checked_sub(const Vec<S, Dim>& a, const Vec<S, Dim>& b) noexcept {
  Vec<S, Dim> r;
  for (std::size_t i = 0; i < Dim; ++i) {
    const auto c = checked_sub(a[i], b[i]);
    if (!c) return c.failure();
    r[i] = c.value();
  }
  return r;
}

/// a * k, checked per coordinate.
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr Result<Vec<S, Dim>> checked_scale(const Vec<S, Dim>& a, S k) noexcept {
  Vec<S, Dim> r;
  for (std::size_t i = 0; i < Dim; ++i) {
    const auto c = checked_mul(a[i], k);
    if (!c) return c.failure();
    r[i] = c.value();
  }
  return r;
}

/// Dot product.
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr S dot(const Vec<S, Dim>& a, const Vec<S, Dim>& b) {
  S sum{};
  for (std::size_t i = 0; i < Dim; ++i) sum = sum + a[i] * b[i];
  return sum;
}

/// |a|^2.
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr S squared_norm(const Vec<S, Dim>& a) {
  return dot(a, a);
}

namespace detail {
/// sqrt(n) rounded to nearest.
[[nodiscard]] constexpr std::uint64_t rounded_sqrt(std::uint64_t n) noexcept {
  std::uint64_t root = integer_sqrt(n);
  if (n - root * root > root) ++root;  // n >= (root + 1/2)^2
  return root;
}
}  // namespace detail

/// Euclidean length |a|. Fixed: the rounded square root of the exact sum of the squared raw
/// values, so |a|² never has to fit the format (Q16.16: it would not above 181) and the result is
/// within half a unit; a length beyond the range is a contract violation.
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr S norm(const Vec<S, Dim>& a) {
  if constexpr (FixedPoint<S>) {
    static_assert(sizeof(typename S::rep) <= 4, "squared raw values must fit 64 bits");
    std::uint64_t largest = 0;
    for (std::size_t i = 0; i < Dim; ++i) {
      const auto raw = static_cast<std::int64_t>(a[i].raw());
      const auto m = static_cast<std::uint64_t>(raw < 0 ? -raw : raw);
      if (m > largest) largest = m;
    }
    // Drop low bits only if Dim squares of the largest value could overflow 64 bits.
    int shift = 0;
    std::uint64_t bound = 0;
    while (__builtin_mul_overflow((largest >> shift) * (largest >> shift), std::uint64_t{Dim}, &bound) ||
           ((largest >> shift) >> 32) != 0) {
      ++shift;
    }
    std::uint64_t sum = 0;
    for (std::size_t i = 0; i < Dim; ++i) {
      const auto raw = static_cast<std::int64_t>(a[i].raw());
      const std::uint64_t m = static_cast<std::uint64_t>(raw < 0 ? -raw : raw) >> shift;
      sum += m * m;
    }
    const std::uint64_t root = detail::rounded_sqrt(sum) << shift;
    const auto r = S::from_wide(static_cast<typename S::wide>(root));
    CURVESTEP_EXPECTS(root <= static_cast<std::uint64_t>(std::numeric_limits<typename S::rep>::max()) && r.has_value());
    return r.value();
  } else {
    return sqrt(squared_norm(a));
  }
}

/// Largest |coordinate| (the infinity norm).
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr S max_norm(const Vec<S, Dim>& a) {
  S m{};
  for (std::size_t i = 0; i < Dim; ++i) {
    const S c = abs(a[i]);
    if (c > m) m = c;
  }
  return m;
}

/// Euclidean distance |a - b|.
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr S distance(const Vec<S, Dim>& a, const Vec<S, Dim>& b) {
  return norm(a - b);
}

/// 2D cross product (z of the 3D cross product): positive when b turns left of a.
template <Scalar S>
[[nodiscard]] constexpr S cross(const Vec<S, 2>& a, const Vec<S, 2>& b) {
  return a[0] * b[1] - a[1] * b[0];
}

/// 3D cross product.
template <Scalar S>
[[nodiscard]] constexpr Vec<S, 3> cross(const Vec<S, 3>& a, const Vec<S, 3>& b) {
  return Vec<S, 3>{{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}

/// Converts every coordinate of input data to S (checked).
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr Result<Vec<S, Dim>> vec_from_doubles(const std::array<double, Dim>& values) noexcept {
  Vec<S, Dim> r;
  for (std::size_t i = 0; i < Dim; ++i) {
    const auto c = from_double<S>(values[i]);
    if (!c) return fail(c.error(), i);
    r[i] = c.value();
  }
  return r;
}

/// The coordinates as doubles.
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr std::array<double, Dim> to_doubles(const Vec<S, Dim>& v) noexcept {
  std::array<double, Dim> r{};
  for (std::size_t i = 0; i < Dim; ++i) r[i] = to_double(v[i]);
  return r;
}

/// Converts a Vec between scalar types (checked: the target may not hold the value).
template <Scalar To, Scalar From, std::size_t Dim>
[[nodiscard]] constexpr Result<Vec<To, Dim>> vec_cast(const Vec<From, Dim>& v) noexcept {
  return vec_from_doubles<To, Dim>(to_doubles(v));
}

}  // namespace curvestep
