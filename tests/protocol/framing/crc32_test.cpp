// SPDX-License-Identifier: MIT
// CRC-32C (Castagnoli) against published check values.
#include <catch2/catch.hpp>

#include <array>
#include <string>
#include <vector>

#include <curvestep/protocol/crc32.hpp>

#include "../support/bytes.hpp"

using namespace curvestep::protocol;
using curvestep::protocol::testing::ascii;

TEST_CASE("crc32c: the standard check value of 123456789 is 0xE3069283", "[protocol][framing]") {
  // CRC RevEng catalogue, CRC-32/ISCSI: width 32, poly 0x1EDC6F41, init and xorout 0xFFFFFFFF, reflected, check 0xE3069283.
  CHECK(crc32c(ascii("123456789")) == 0xE3069283u);
}

TEST_CASE("crc32c: the iSCSI test vectors of RFC 3720 appendix B.4", "[protocol][framing]") {
  std::vector<std::byte> zeros(32, std::byte{0x00});
  std::vector<std::byte> ones(32, std::byte{0xFF});
  std::vector<std::byte> ascending(32);
  std::vector<std::byte> descending(32);
  for (std::size_t i = 0; i < 32; ++i) {
    ascending[i] = static_cast<std::byte>(i);
    descending[i] = static_cast<std::byte>(31 - i);
  }
  // RFC 3720 lists the CRC bytes as sent (little-endian): aa 36 91 8a, 43 ab a8 62, 4e 79 dd 46, 11 3f db 5c.
  CHECK(crc32c(zeros) == 0x8A9136AAu);
  CHECK(crc32c(ones) == 0x62A8AB43u);
  CHECK(crc32c(ascending) == 0x46DD794Eu);
  CHECK(crc32c(descending) == 0x113FDB5Cu);
}

TEST_CASE("crc32c: the empty message gives 0 and updating in pieces equals one pass", "[protocol][framing]") {
  CHECK(crc32c(ascii("")) == 0u);
  const auto data = ascii("123456789");
  const std::span<const std::byte> all(data);
  const std::uint32_t state = crc32c_update(crc32c_initial, all.first(4));
  CHECK(crc32c_final(crc32c_update(state, all.subspan(4))) == 0xE3069283u);
}

TEST_CASE("crc32c: the check value is computed at compile time", "[protocol][framing]") {
  constexpr std::array<std::byte, 9> digits{std::byte{'1'}, std::byte{'2'}, std::byte{'3'}, std::byte{'4'}, std::byte{'5'},
                                            std::byte{'6'}, std::byte{'7'}, std::byte{'8'}, std::byte{'9'}};
  STATIC_REQUIRE(crc32c(digits) == 0xE3069283u);
}
