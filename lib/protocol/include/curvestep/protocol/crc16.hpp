// SPDX-License-Identifier: MIT
// CRC-16/CCITT-FALSE over frame header and payload.
//
// Why this variant: CRC-16/CCITT-FALSE (also listed as CRC-16/IBM-3740) is the polynomial
// x^16 + x^12 + x^5 + 1 (0x1021), initial value 0xFFFF, no input or output reflection, no
// final XOR. Its check value over the ASCII bytes "123456789" is 0x29B1. Because the
// polynomial has the factor (x + 1) it detects every error of odd weight, and its Hamming
// distance is 4 for messages up to 32751 bits: every 1-, 2- and 3-bit error in one of our
// frames (at most 164 bytes) is detected, and every burst of up to 16 bits. A non-zero
// initial value also catches leading zero bytes that a zero-initialised CRC would miss.
// The bitwise form costs no table flash; a frame of 164 bytes is about 1300 shift/XOR steps.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace curvestep::protocol {

/// Initial value of CRC-16/CCITT-FALSE.
inline constexpr std::uint16_t crc16_initial = 0xFFFF;

/// Folds `data` into a running CRC-16/CCITT-FALSE `state` (start with crc16_initial).
[[nodiscard]] constexpr std::uint16_t crc16_update(std::uint16_t state, std::span<const std::byte> data) noexcept {
  for (const std::byte b : data) {
    state = static_cast<std::uint16_t>(state ^ (static_cast<std::uint16_t>(b) << 8));
    for (int bit = 0; bit < 8; ++bit) {
      const bool top = (state & 0x8000u) != 0;
      state = static_cast<std::uint16_t>(state << 1);
      if (top) state = static_cast<std::uint16_t>(state ^ 0x1021u);
    }
  }
  return state;
}

/// CRC-16/CCITT-FALSE of `data` (poly 0x1021, init 0xFFFF, unreflected, no final XOR).
[[nodiscard]] constexpr std::uint16_t crc16(std::span<const std::byte> data) noexcept {
  return crc16_update(crc16_initial, data);
}

}  // namespace curvestep::protocol
