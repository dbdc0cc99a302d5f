// SPDX-License-Identifier: MIT
// Result<T>: a value or an Error plus the index of the input at fault (std::expected-like, no heap).
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include <curvestep/core/contract.hpp>
#include <curvestep/core/error.hpp>

namespace curvestep {

/// A failure: what went wrong and which input (control point, weight, knot, segment index).
struct Failure {
  Error code;                      ///< what went wrong
  std::uint16_t index = no_index;  ///< which input was at fault, or no_index
};

/// Builds a Failure; `index` names the offending input (clamped to no_index if too large).
[[nodiscard]] constexpr Failure fail(Error code, std::size_t index = no_index) noexcept {
  return Failure{code, index >= no_index ? no_index : static_cast<std::uint16_t>(index)};
}

/// A value of type T or a Failure. Member names follow std::expected so that switching to
/// C++23 later is a one-line alias. T must be default-constructible (curve types are).
template <class T>
class [[nodiscard]] Result {
  static_assert(std::is_default_constructible_v<T>, "Result<T> needs a default-constructible T");

 public:
  using value_type = T;

  constexpr Result(const T& value) noexcept(std::is_nothrow_copy_constructible_v<T>)  // NOLINT
      : value_(value) {}
  constexpr Result(T&& value) noexcept(std::is_nothrow_move_constructible_v<T>)  // NOLINT
      : value_(std::move(value)) {}
  constexpr Result(Failure failure) noexcept  // NOLINT: implicit, as with std::unexpected
      : failure_(failure), ok_(false) {}
  /// A value-initialised T, built in place: a function can fill `value()` and return the Result
  /// by name (no second copy of a large T on a microcontroller's stack).
  constexpr explicit Result(std::in_place_t) noexcept(std::is_nothrow_default_constructible_v<T>) : value_{} {}

  /// Turns this into a failure without building a Result (the value is left as it is, unused).
  constexpr Result& operator=(Failure failure) noexcept {
    failure_ = failure;
    ok_ = false;
    return *this;
  }

  [[nodiscard]] constexpr bool has_value() const noexcept { return ok_; }
  constexpr explicit operator bool() const noexcept { return ok_; }

  /// The value; calling this on a failure is a contract violation.
  [[nodiscard]] constexpr const T& value() const& {
    CURVESTEP_EXPECTS(ok_);
    return value_;
  }
  [[nodiscard]] constexpr T& value() & {
    CURVESTEP_EXPECTS(ok_);
    return value_;
  }
  [[nodiscard]] constexpr T&& value() && {
    CURVESTEP_EXPECTS(ok_);
    return std::move(value_);
  }
  constexpr const T& operator*() const& { return value(); }
  constexpr const T* operator->() const { return &value(); }

  /// The value, or `fallback` on failure.
  [[nodiscard]] constexpr T value_or(T fallback) const { return ok_ ? value_ : fallback; }

  /// The error code; only meaningful on failure.
  [[nodiscard]] constexpr Error error() const noexcept { return failure_.code; }
  /// Index of the input at fault (control point, weight, knot, segment), or no_index.
  [[nodiscard]] constexpr std::uint16_t where() const noexcept { return failure_.index; }
  [[nodiscard]] constexpr Failure failure() const noexcept { return failure_; }

 private:
  T value_{};
  Failure failure_{Error::InvalidArgument, no_index};
  bool ok_ = true;
};

/// Result of an operation with no value.
template <>
class [[nodiscard]] Result<void> {
 public:
  constexpr Result() noexcept = default;
  constexpr Result(Failure failure) noexcept : failure_(failure), ok_(false) {}  // NOLINT

  [[nodiscard]] constexpr bool has_value() const noexcept { return ok_; }
  constexpr explicit operator bool() const noexcept { return ok_; }
  [[nodiscard]] constexpr Error error() const noexcept { return failure_.code; }
  [[nodiscard]] constexpr std::uint16_t where() const noexcept { return failure_.index; }
  [[nodiscard]] constexpr Failure failure() const noexcept { return failure_; }

 private:
  Failure failure_{Error::InvalidArgument, no_index};
  bool ok_ = true;
};

/// Success value for Result<void>.
[[nodiscard]] constexpr Result<void> ok() noexcept { return {}; }

}  // namespace curvestep

/// Propagates a failure: `CURVESTEP_TRY(auto x, expr);` assigns expr's value to x or returns its failure.
#define CURVESTEP_DETAIL_CONCAT2(a, b) a##b
#define CURVESTEP_DETAIL_CONCAT(a, b) CURVESTEP_DETAIL_CONCAT2(a, b)
#define CURVESTEP_TRY(declaration, expression)                                            \
  auto&& CURVESTEP_DETAIL_CONCAT(curvestep_try_, __LINE__) = (expression);               \
  if (!CURVESTEP_DETAIL_CONCAT(curvestep_try_, __LINE__))                                 \
    return CURVESTEP_DETAIL_CONCAT(curvestep_try_, __LINE__).failure();                   \
  declaration = std::move(CURVESTEP_DETAIL_CONCAT(curvestep_try_, __LINE__)).value()

/// Propagates a failure of a Result<void>.
#define CURVESTEP_CHECK(expression)                                                       \
  do {                                                                                    \
    if (auto curvestep_check_result = (expression); !curvestep_check_result)              \
      return curvestep_check_result.failure();                                            \
  } while (false)
