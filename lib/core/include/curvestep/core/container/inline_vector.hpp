// SPDX-License-Identifier: MIT
// InlineVector<T, Capacity>: a fixed-capacity sequence filled at the back (step edges, recordings); full means full, never grows.
#pragma once

#include <array>
#include <cstddef>

#include <curvestep/core/container/fixed_capacity.hpp>
#include <curvestep/core/contract.hpp>

namespace curvestep {

/// A sequence of at most Capacity elements, stored inline and appended at the back.
template <class T, std::size_t Capacity>
class InlineVector : public detail::FixedCapacity<Capacity> {
  using detail::FixedCapacity<Capacity>::size_;

 public:
  /// The element at `index` (contract: index < size()).
  [[nodiscard]] constexpr const T& operator[](std::size_t index) const {
    CURVESTEP_EXPECTS(index < size_);
    return items_[index];
  }
  /// Iteration over the held elements.
  [[nodiscard]] constexpr const T* begin() const noexcept { return items_.data(); }
  /// One past the last held element.
  [[nodiscard]] constexpr const T* end() const noexcept { return items_.data() + size_; }

  /// Appends a copy of `value`; false (and nothing stored) if full.
  [[nodiscard]] constexpr bool try_push(const T& value) noexcept(noexcept(T(value))) {
    if (size_ == Capacity) return false;
    items_[size_++] = value;
    return true;
  }
  /// Removes everything.
  constexpr void clear() noexcept { size_ = 0; }

 private:
  std::array<T, Capacity> items_{};
};

}  // namespace curvestep
