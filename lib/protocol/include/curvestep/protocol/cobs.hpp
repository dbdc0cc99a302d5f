// SPDX-License-Identifier: MIT
// COBS (Consistent Overhead Byte Stuffing): frames without 0x00 so 0x00 can delimit them.
//
// Why COBS: a receiver that joins mid-stream, or loses bytes, must find the next frame
// start without help. COBS (Cheshire and Baker, 1999) rewrites a block so that it contains
// no 0x00 byte; 0x00 then marks the end of every frame and a receiver resynchronises on the
// next 0x00 whatever garbage came before. Unlike HDLC escaping (worst case +100 %), the
// overhead is bounded: at most one byte per 254 bytes, plus one. For our frames (at most
// 164 bytes) that is exactly one byte, so buffer sizes are known at compile time.
//
// Encoding: the input is cut at each zero; each piece becomes a code byte (piece length + 1)
// followed by the piece's bytes, the zero itself being implied. A piece of 254 non-zero
// bytes gets code 0xFF and no implied zero. The implied zero after the last piece is dropped.
// This is the standard form: "11 22 00 33" encodes as "03 11 22 02 33".
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/core/result.hpp>

namespace curvestep::protocol {

/// Largest COBS encoding of `size` bytes: one code byte per 254 data bytes, plus one.
[[nodiscard]] constexpr std::size_t cobs_max_encoded_size(std::size_t size) noexcept { return size + size / 254 + 1; }

/// COBS-encodes `input` into `output` (no delimiter); returns the encoded length.
/// BufferTooSmall (index = bytes needed so far) if `output` cannot hold the encoding.
[[nodiscard]] constexpr Result<std::size_t> cobs_encode(std::span<const std::byte> input,
                                                        std::span<std::byte> output) noexcept {
  if (output.empty()) return fail(Error::BufferTooSmall, 1);
  std::size_t code_at = 0;  // where the current block's code byte goes
  std::size_t write = 1;
  std::uint8_t code = 1;
  for (std::size_t read = 0; read < input.size(); ++read) {
    const std::byte b = input[read];
    if (b == std::byte{0}) {
      output[code_at] = std::byte{code};
      code_at = write++;
      code = 1;
      if (code_at >= output.size()) return fail(Error::BufferTooSmall, write);
      continue;
    }
    if (write >= output.size()) return fail(Error::BufferTooSmall, write + 1);
    output[write++] = b;
    ++code;
    if (code == 0xFF && read + 1 < input.size()) {  // full block; more data follows
      output[code_at] = std::byte{code};
      code_at = write++;
      code = 1;
      if (code_at >= output.size()) return fail(Error::BufferTooSmall, write);
    }
  }
  output[code_at] = std::byte{code};
  return write;
}

/// Decodes one COBS block (without its delimiter) into `output`; returns the decoded length.
/// `output` may alias `input` (decoding in place is safe: the write position never passes the
/// read position). BadFraming (index = byte offset) on a zero byte or a code running past the
/// end; BufferTooSmall if `output` is too short.
[[nodiscard]] constexpr Result<std::size_t> cobs_decode(std::span<const std::byte> input,
                                                        std::span<std::byte> output) noexcept {
  std::size_t read = 0;
  std::size_t write = 0;
  while (read < input.size()) {
    const auto code = static_cast<std::uint8_t>(input[read]);
    if (code == 0) return fail(Error::BadFraming, read);
    ++read;
    for (std::uint8_t i = 1; i < code; ++i) {
      if (read >= input.size()) return fail(Error::BadFraming, read);
      const std::byte b = input[read];
      if (b == std::byte{0}) return fail(Error::BadFraming, read);
      if (write >= output.size()) return fail(Error::BufferTooSmall, write + 1);
      output[write++] = b;
      ++read;
    }
    if (code != 0xFF && read < input.size()) {
      if (write >= output.size()) return fail(Error::BufferTooSmall, write + 1);
      output[write++] = std::byte{0};
    }
  }
  return write;
}

}  // namespace curvestep::protocol
