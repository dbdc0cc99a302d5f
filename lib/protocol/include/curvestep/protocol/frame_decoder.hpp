// SPDX-License-Identifier: MIT
// FrameDecoder: a streaming, fixed-capacity decoder that takes received bytes one at a time.
//
// Why byte at a time: a UART interrupt or a DMA half-transfer delivers bytes in whatever
// chunks it likes; the decoder must not care. It accumulates bytes until a 0x00 delimiter,
// then COBS-decodes in place and checks length and CRC. Any failure drops only the bytes
// up to that delimiter, so the decoder resynchronises on the next 0x00 after garbage, a
// restart of the peer or a lost delimiter. A run longer than the buffer is dropped up to
// the next 0x00 and reported once as FrameTooLong. Empty frames (0x00 0x00) are ignored,
// so a sender may prefix frames with 0x00 to flush a receiver's partial garbage.
// Memory: Capacity bytes (default 167, the largest frame on the wire without its delimiter) plus three counters.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/core/result.hpp>
#include <curvestep/protocol/cobs.hpp>
#include <curvestep/protocol/frame.hpp>
#include <curvestep/protocol/limits.hpp>

namespace curvestep::protocol {

/// Accumulates bytes into frames; `Capacity` bytes of buffer (delimiter excluded).
template <std::size_t Capacity = max_encoded_frame_size - 1>
class FrameDecoder {
  static_assert(Capacity >= min_frame_size + 1, "FrameDecoder needs room for the smallest frame");

 public:
  /// Feeds one byte. Returns true when a checked frame is ready (read it with frame() before
  /// the next push), false when more bytes are needed, or the error that dropped a frame:
  /// FrameTooLong, BadFraming, FrameTooShort or BadCrc.
  [[nodiscard]] constexpr Result<bool> push(std::byte b) noexcept {
    if (b != std::byte{0}) {
      if (discarding_) return false;
      if (size_ >= Capacity) {
        discarding_ = true;
        size_ = 0;
        return fail(Error::FrameTooLong, Capacity);
      }
      buffer_[size_++] = b;
      return false;
    }
    const std::size_t size = size_;
    const bool discarded = discarding_;
    size_ = 0;
    discarding_ = false;
    if (discarded || size == 0) return false;
    const std::span<std::byte> stored(buffer_.data(), size);
    CURVESTEP_TRY(const std::size_t decoded, cobs_decode(stored, stored));
    CURVESTEP_TRY(frame_, parse_frame(std::span<const std::byte>(buffer_.data(), decoded)));
    return true;
  }

  /// The frame completed by the last push that returned true.
  [[nodiscard]] constexpr const Frame& frame() const noexcept { return frame_; }
  /// Bytes waiting for a delimiter.
  [[nodiscard]] constexpr std::size_t buffered() const noexcept { return size_; }
  /// Buffer capacity in bytes.
  [[nodiscard]] static constexpr std::size_t capacity() noexcept { return Capacity; }
  /// Drops any partial frame.
  constexpr void reset() noexcept {
    size_ = 0;
    discarding_ = false;
  }

 private:
  std::array<std::byte, Capacity> buffer_{};
  Frame frame_{};
  std::size_t size_ = 0;
  bool discarding_ = false;
};

}  // namespace curvestep::protocol
