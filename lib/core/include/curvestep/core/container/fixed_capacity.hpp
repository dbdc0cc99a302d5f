// SPDX-License-Identifier: MIT
// FixedCapacity<Capacity>: the element count of a container stored inline, and the queries on it.
#pragma once

#include <cstddef>

namespace curvestep::detail {

/// The count of elements held by a container with room for Capacity (RingBuffer, InlineVector).
template <std::size_t Capacity>
class FixedCapacity {
  static_assert(Capacity > 0, "a fixed-capacity container needs room for at least one element");

 public:
  /// Room for this many elements.
  [[nodiscard]] static constexpr std::size_t capacity() noexcept { return Capacity; }
  /// Number of elements held.
  [[nodiscard]] constexpr std::size_t size() const noexcept { return size_; }
  /// True if no elements are held.
  [[nodiscard]] constexpr bool empty() const noexcept { return size_ == 0; }
  /// True if no more elements fit.
  [[nodiscard]] constexpr bool full() const noexcept { return size_ == Capacity; }
  /// Free room in elements.
  [[nodiscard]] constexpr std::size_t available() const noexcept { return Capacity - size_; }

 protected:
  std::size_t size_ = 0;  ///< elements held, at most Capacity
};

}  // namespace curvestep::detail
