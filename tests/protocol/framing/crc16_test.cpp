// SPDX-License-Identifier: MIT
// CRC-16/CCITT-FALSE against published check values.
#include <catch2/catch.hpp>

#include <curvestep/protocol/crc16.hpp>

#include "../support/bytes.hpp"

using namespace curvestep::protocol;
using curvestep::protocol::testing::ascii;

TEST_CASE("crc16: the standard check value of 123456789 is 0x29B1", "[protocol][framing]") {
  // CRC RevEng catalogue, CRC-16/IBM-3740 (alias CCITT-FALSE): width 16, poly 0x1021, init 0xFFFF, check 0x29B1.
  CHECK(crc16(ascii("123456789")) == 0x29B1);
}

TEST_CASE("crc16: published values for the empty string, A and 256 times A", "[protocol][framing]") {
  // The empty message leaves the initial value; "A" and 256 x "A" are the classic CRC-CCITT (0xFFFF) examples.
  CHECK(crc16(ascii("")) == 0xFFFF);
  CHECK(crc16(ascii("A")) == 0xB915);
  CHECK(crc16(ascii(std::string(256, 'A'))) == 0xEA0B);
}

TEST_CASE("crc16: updating in pieces equals one pass", "[protocol][framing]") {
  const auto data = ascii("123456789");
  const std::span<const std::byte> all(data);
  const std::uint16_t state = crc16_update(crc16_initial, all.first(4));
  CHECK(crc16_update(state, all.subspan(4)) == 0x29B1);
}

TEST_CASE("crc16: the check value is computed at compile time", "[protocol][framing]") {
  constexpr std::array<std::byte, 3> abc{std::byte{'1'}, std::byte{'2'}, std::byte{'3'}};
  constexpr std::uint16_t value = crc16(abc);
  STATIC_REQUIRE(value == crc16(std::span<const std::byte>(abc)));
  CHECK(value == crc16(ascii("123")));
}
