// SPDX-License-Identifier: MIT
// printf-free formatting of integers into a byte sink (a callable taking one char).
#pragma once

#include <cstdint>
#include <string_view>

namespace curvestep::stm32 {

/// Writes `text` through `put`.
template <typename Put>
void put_text(Put&& put, std::string_view text) noexcept {
  for (const char c : text) put(c);
}

/// Writes `value` as 0x followed by 8 hexadecimal digits.
template <typename Put>
void put_hex(Put&& put, std::uint32_t value) noexcept {
  put('0');
  put('x');
  for (int shift = 28; shift >= 0; shift -= 4) {
    const auto digit = static_cast<unsigned>((value >> shift) & 0xFu);
    put(static_cast<char>(digit < 10 ? '0' + digit : 'a' + digit - 10));
  }
}

/// Writes `value` in decimal.
template <typename Put>
void put_decimal(Put&& put, std::uint64_t value) noexcept {
  char digits[20];
  int count = 0;
  do {
    digits[count++] = static_cast<char>('0' + value % 10);
    value /= 10;
  } while (value != 0);
  while (count > 0) put(digits[--count]);
}

/// Writes `value` in decimal with a sign.
template <typename Put>
void put_signed(Put&& put, std::int64_t value) noexcept {
  if (value < 0) {
    put('-');
    put_decimal(put, static_cast<std::uint64_t>(-(value + 1)) + 1);
  } else {
    put_decimal(put, static_cast<std::uint64_t>(value));
  }
}

}  // namespace curvestep::stm32
