// SPDX-License-Identifier: MIT
// Test helpers for the protocol suites: byte vectors from hex, printable byte sequences.
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>
#include <vector>

namespace curvestep::protocol::testing {

/// Bytes from integer literals.
inline std::vector<std::byte> bytes(std::initializer_list<int> values) {
  std::vector<std::byte> out;
  for (const int v : values) out.push_back(static_cast<std::byte>(v));
  return out;
}

/// Bytes from a hex string such as "03 11 05"; spaces are ignored.
inline std::vector<std::byte> hex(const std::string& text) {
  std::vector<std::byte> out;
  std::string digits;
  for (const char c : text) {
    if (c == ' ' || c == '\n') continue;
    digits.push_back(c);
    if (digits.size() == 2) {
      out.push_back(static_cast<std::byte>(std::stoul(digits, nullptr, 16)));
      digits.clear();
    }
  }
  return out;
}

/// Bytes of an ASCII string.
inline std::vector<std::byte> ascii(const std::string& text) {
  std::vector<std::byte> out;
  for (const char c : text) out.push_back(static_cast<std::byte>(c));
  return out;
}

/// Hex text of bytes, for readable failure messages.
inline std::string to_hex(std::span<const std::byte> data) {
  static constexpr char digits[] = "0123456789abcdef";
  std::string out;
  for (const std::byte b : data) {
    const auto v = static_cast<unsigned>(b);
    if (!out.empty()) out.push_back(' ');
    out.push_back(digits[v >> 4]);
    out.push_back(digits[v & 15u]);
  }
  return out;
}

}  // namespace curvestep::protocol::testing
