// SPDX-License-Identifier: MIT
// RingBuffer<T, Capacity>: a fixed-capacity FIFO queue (segments, bytes); full means full, never grows.
#pragma once

#include <array>
#include <cstddef>

#include <curvestep/core/container/fixed_capacity.hpp>
#include <curvestep/core/contract.hpp>

namespace curvestep {

/// A first-in first-out queue of at most Capacity elements, stored inline.
template <class T, std::size_t Capacity>
class RingBuffer : public detail::FixedCapacity<Capacity> {
  using detail::FixedCapacity<Capacity>::size_;

 public:
  /// Appends a copy of `value`; false (and no change) when full.
  [[nodiscard]] constexpr bool try_push(const T& value) noexcept(noexcept(T(value))) {
    if (this->full()) return false;
    items_[(head_ + size_) % Capacity] = value;
    ++size_;
    return true;
  }
  /// The i-th element from the front; contract i < size().
  [[nodiscard]] constexpr T& operator[](std::size_t i) {
    CURVESTEP_EXPECTS(i < size_);
    return items_[(head_ + i) % Capacity];
  }
  [[nodiscard]] constexpr const T& operator[](std::size_t i) const {
    CURVESTEP_EXPECTS(i < size_);
    return items_[(head_ + i) % Capacity];
  }
  [[nodiscard]] constexpr T& front() { return (*this)[0]; }
  [[nodiscard]] constexpr const T& front() const { return (*this)[0]; }
  /// Removes the front element; contract: not empty.
  constexpr void pop_front() {
    CURVESTEP_EXPECTS(size_ > 0);
    head_ = (head_ + 1) % Capacity;
    --size_;
  }
  /// Removes everything.
  constexpr void clear() noexcept {
    head_ = 0;
    size_ = 0;
  }

 private:
  std::array<T, Capacity> items_{};
  std::size_t head_ = 0;
};

}  // namespace curvestep
