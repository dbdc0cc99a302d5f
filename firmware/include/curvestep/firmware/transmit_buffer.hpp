// SPDX-License-Identifier: MIT
// TransmitBuffer: the App's outgoing bytes (whole frames), written to the board without blocking.
#pragma once

#include <array>
#include <cstddef>
#include <span>

#include <curvestep/core/container/ring_buffer.hpp>
#include <curvestep/firmware/app_settings.hpp>

namespace curvestep::firmware {

/// Whole encoded frames waiting for the serial line (transmit_buffer_bytes, no allocation).
class TransmitBuffer {
 public:
  /// Queues a whole frame; false (nothing queued) if it does not fit.
  [[nodiscard]] bool queue(std::span<const std::byte> bytes) noexcept {
    if (bytes_.available() < bytes.size()) return false;
    for (const std::byte b : bytes) [[maybe_unused]] const bool pushed = bytes_.try_push(b);
    return true;
  }

  /// Free bytes.
  [[nodiscard]] std::size_t available() const noexcept { return bytes_.available(); }

  /// Writes what the board takes now (board.write may take less than offered).
  template <class B>
  void flush(B& board) noexcept {
    std::array<std::byte, 64> chunk{};
    while (!bytes_.empty()) {
      std::size_t count = 0;
      while (count < chunk.size() && count < bytes_.size()) {
        chunk[count] = bytes_[count];
        ++count;
      }
      const std::size_t written = board.write(std::span<const std::byte>(chunk.data(), count));
      for (std::size_t i = 0; i < written && i < count; ++i) bytes_.pop_front();
      if (written < count) return;
    }
  }

 private:
  RingBuffer<std::byte, transmit_buffer_bytes> bytes_{};
};

}  // namespace curvestep::firmware
