// SPDX-License-Identifier: MIT
// Single-producer single-consumer byte ring buffer shared between an interrupt handler and the main loop.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>

namespace curvestep::stm32 {

/// Lock-free SPSC byte queue of `Capacity` (a power of two) bytes: one side pushes, the other pops.
/// The indices run freely modulo 2^32; head - tail is the fill level.
template <std::size_t Capacity>
class RingBuffer {
  static_assert(Capacity >= 2 && (Capacity & (Capacity - 1)) == 0, "capacity must be a power of two");
  static_assert(std::atomic<std::uint32_t>::is_always_lock_free, "needs lock-free 32-bit atomics");

 public:
  static constexpr std::size_t capacity = Capacity;  ///< bytes it can hold

  /// Appends `byte`; false (and nothing stored) when full.
  bool push(std::uint8_t byte) noexcept {
    const std::uint32_t head = head_.load(std::memory_order_relaxed);
    const std::uint32_t tail = tail_.load(std::memory_order_acquire);
    if (head - tail == Capacity) return false;
    data_[head & mask] = byte;
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  /// Removes the oldest byte into `byte`; false when empty.
  bool pop(std::uint8_t& byte) noexcept {
    const std::uint32_t tail = tail_.load(std::memory_order_relaxed);
    const std::uint32_t head = head_.load(std::memory_order_acquire);
    if (head == tail) return false;
    byte = data_[tail & mask];
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  /// Bytes currently stored.
  [[nodiscard]] std::size_t size() const noexcept {
    return head_.load(std::memory_order_acquire) - tail_.load(std::memory_order_acquire);
  }
  /// True when nothing is stored.
  [[nodiscard]] bool empty() const noexcept { return size() == 0; }
  /// Bytes that can still be pushed.
  [[nodiscard]] std::size_t free_space() const noexcept { return Capacity - size(); }

 private:
  static constexpr std::uint32_t mask = static_cast<std::uint32_t>(Capacity - 1);
  std::array<std::uint8_t, Capacity> data_{};
  std::atomic<std::uint32_t> head_{0};
  std::atomic<std::uint32_t> tail_{0};
};

}  // namespace curvestep::stm32
