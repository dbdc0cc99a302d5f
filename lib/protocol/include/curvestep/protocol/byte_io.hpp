// SPDX-License-Identifier: MIT
// Little-endian field writer and reader over caller-owned byte spans, with zig-zag varints.
//
// Both classes are sticky: after the first field that does not fit (or a field the caller
// marks invalid) every later call is a no-op, and finish() reports the first failure with its
// byte offset. Encoders and decoders then read like the byte tables in docs/protocol.md
// instead of checking every field.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/core/result.hpp>

namespace curvestep::protocol {

/// Maps a signed value to an unsigned one so small magnitudes stay small: 0,-1,1,-2 -> 0,1,2,3.
[[nodiscard]] constexpr std::uint64_t zigzag_encode(std::int64_t value) noexcept {
  const auto bits = static_cast<std::uint64_t>(value);
  return (bits << 1) ^ (value < 0 ? ~std::uint64_t{0} : std::uint64_t{0});
}

/// Inverse of zigzag_encode.
[[nodiscard]] constexpr std::int64_t zigzag_decode(std::uint64_t value) noexcept {
  const std::uint64_t magnitude = value >> 1;
  return static_cast<std::int64_t>((value & 1u) != 0 ? ~magnitude : magnitude);
}

/// Bytes an unsigned LEB128 varint of `value` takes (7 bits per byte).
[[nodiscard]] constexpr std::size_t varint_size(std::uint64_t value) noexcept {
  std::size_t size = 1;
  while (value >= 0x80u) {
    value >>= 7;
    ++size;
  }
  return size;
}

/// Writes little-endian fields into a span; the first overflow sticks and finish() reports it.
class ByteWriter {
 public:
  /// A writer over `output`, starting at its first byte.
  constexpr explicit ByteWriter(std::span<std::byte> output) noexcept : output_(output) {}

  /// Appends one byte.
  constexpr void u8(std::uint8_t value) noexcept {
    if (failed_) return;
    if (size_ >= output_.size()) {
      failed_ = true;
      return;
    }
    output_[size_++] = std::byte{value};
  }
  /// Appends a little-endian 16-bit value.
  constexpr void u16(std::uint16_t value) noexcept {
    u8(static_cast<std::uint8_t>(value & 0xFFu));
    u8(static_cast<std::uint8_t>(value >> 8));
  }
  /// Appends a little-endian 32-bit value.
  constexpr void u32(std::uint32_t value) noexcept {
    u16(static_cast<std::uint16_t>(value & 0xFFFFu));
    u16(static_cast<std::uint16_t>(value >> 16));
  }
  /// Appends a little-endian two's-complement 32-bit value (a Q16.16 raw value, for instance).
  constexpr void i32(std::int32_t value) noexcept { u32(static_cast<std::uint32_t>(value)); }
  /// Appends a little-endian 64-bit value.
  constexpr void u64(std::uint64_t value) noexcept {
    u32(static_cast<std::uint32_t>(value & 0xFFFFFFFFu));
    u32(static_cast<std::uint32_t>(value >> 32));
  }
  /// Appends an IEEE 754 binary64 value as its 64-bit pattern, little-endian (exact, NaN included).
  constexpr void f64(double value) noexcept { u64(std::bit_cast<std::uint64_t>(value)); }
  /// Appends an unsigned LEB128 varint: 7 bits per byte, low group first, 0x80 = more follows.
  constexpr void varint(std::uint64_t value) noexcept {
    while (value >= 0x80u) {
      u8(static_cast<std::uint8_t>((value & 0x7Fu) | 0x80u));
      value >>= 7;
    }
    u8(static_cast<std::uint8_t>(value));
  }

  /// Bytes written so far.
  [[nodiscard]] constexpr std::size_t size() const noexcept { return size_; }
  /// The byte count, or BufferTooSmall (index = bytes that fitted) if anything overflowed.
  [[nodiscard]] constexpr Result<std::size_t> finish() const noexcept {
    if (failed_) return fail(Error::BufferTooSmall, size_);
    return size_;
  }

 private:
  std::span<std::byte> output_;
  std::size_t size_ = 0;
  bool failed_ = false;
};

/// Reads little-endian fields from a span; the first short read or rejected field sticks.
class ByteReader {
 public:
  /// A reader over `input`, starting at its first byte.
  constexpr explicit ByteReader(std::span<const std::byte> input) noexcept : input_(input) {}

  /// Reads one byte (0 after a failure).
  constexpr std::uint8_t u8() noexcept {
    if (failed_) return 0;
    if (offset_ >= input_.size()) {
      reject(Error::BadPayload);
      return 0;
    }
    return static_cast<std::uint8_t>(input_[offset_++]);
  }
  /// Reads a little-endian 16-bit value.
  constexpr std::uint16_t u16() noexcept {
    const std::uint16_t low = u8();
    const std::uint16_t high = u8();
    return static_cast<std::uint16_t>(low | (high << 8));
  }
  /// Reads a little-endian 32-bit value.
  constexpr std::uint32_t u32() noexcept {
    const std::uint32_t low = u16();
    const std::uint32_t high = u16();
    return low | (high << 16);
  }
  /// Reads a little-endian two's-complement 32-bit value.
  constexpr std::int32_t i32() noexcept { return static_cast<std::int32_t>(u32()); }
  /// Reads a little-endian 64-bit value.
  constexpr std::uint64_t u64() noexcept {
    const std::uint64_t low = u32();
    const std::uint64_t high = u32();
    return low | (high << 32);
  }
  /// Reads an IEEE 754 binary64 value (the caller checks finiteness where it matters).
  constexpr double f64() noexcept { return std::bit_cast<double>(u64()); }
  /// Reads an unsigned LEB128 varint of at most `max_bytes` bytes (BadPayload if longer).
  constexpr std::uint64_t varint(std::size_t max_bytes = 10) noexcept {
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < max_bytes; ++i) {
      const std::size_t at = offset_;
      const std::uint8_t b = u8();
      if (failed_) return 0;
      value |= static_cast<std::uint64_t>(b & 0x7Fu) << (7 * i);
      if ((b & 0x80u) == 0) return value;
      if (i + 1 == max_bytes) {
        offset_ = at;
        reject(Error::BadPayload);
        return 0;
      }
    }
    return 0;
  }

  /// Marks the field that ends at the current offset as invalid (sticky; first failure wins).
  constexpr void reject(Error code) noexcept { reject_at(code, offset_); }
  /// Marks the input invalid at byte `offset` (sticky; first failure wins).
  constexpr void reject_at(Error code, std::size_t offset) noexcept {
    if (failed_) return;
    failed_ = true;
    failure_ = fail(code, offset);
  }

  /// Current byte offset.
  [[nodiscard]] constexpr std::size_t offset() const noexcept { return offset_; }
  /// True once a read ran short or a field was rejected.
  [[nodiscard]] constexpr bool failed() const noexcept { return failed_; }
  /// Success only if nothing failed and every byte was consumed (BadPayload at the first extra byte).
  [[nodiscard]] constexpr Result<void> finish() const noexcept {
    if (failed_) return failure_;
    if (offset_ != input_.size()) return fail(Error::BadPayload, offset_);
    return ok();
  }

 private:
  std::span<const std::byte> input_;
  std::size_t offset_ = 0;
  Failure failure_{Error::BadPayload, no_index};
  bool failed_ = false;
};

}  // namespace curvestep::protocol
