// SPDX-License-Identifier: MIT
// Checked<S>: a scalar that remembers whether any operation on the way overflowed or lost
// finiteness, so analysis formulas can be written plainly and checked once at the end.
#pragma once

#include <curvestep/core/result.hpp>
#include <curvestep/core/scalar.hpp>

namespace curvestep::detail {

template <Scalar S>
struct Checked {
  S value{};
  Error error = Error::FixedOverflow;
  bool ok = true;

  constexpr Checked() = default;
  constexpr Checked(S v) : value(v) {}  // NOLINT: implicit on purpose

  [[nodiscard]] constexpr Result<S> result() const noexcept {
    if (!ok) return fail(error);
    return value;
  }

  template <class Op>
  [[nodiscard]] static constexpr Checked combine(const Checked& a, const Checked& b, Op op) noexcept {
    Checked r;
    if (!a.ok) return a;
    if (!b.ok) return b;
    auto v = op(a.value, b.value);
    if (!v) {
      r.ok = false;
      r.error = v.error();
      return r;
    }
    r.value = v.value();
    return r;
  }
  friend constexpr Checked operator+(const Checked& a, const Checked& b) noexcept {
    return combine(a, b, [](S x, S y) { return checked_add(x, y); });
  }
  friend constexpr Checked operator-(const Checked& a, const Checked& b) noexcept {
    return combine(a, b, [](S x, S y) { return checked_sub(x, y); });
  }
  friend constexpr Checked operator*(const Checked& a, const Checked& b) noexcept {
    return combine(a, b, [](S x, S y) { return checked_mul(x, y); });
  }
  friend constexpr Checked operator/(const Checked& a, const Checked& b) noexcept {
    return combine(a, b, [](S x, S y) { return checked_div(x, y); });
  }
};

/// sqrt of a checked non-negative value.
template <Scalar S>
[[nodiscard]] constexpr Checked<S> checked_sqrt(const Checked<S>& a) noexcept {
  if (!a.ok) return a;
  if (a.value < S{}) {
    Checked<S> r;
    r.ok = false;
    r.error = Error::InvalidArgument;
    return r;
  }
  return Checked<S>(sqrt(a.value));
}

}  // namespace curvestep::detail
