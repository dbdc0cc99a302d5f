// SPDX-License-Identifier: MIT
// Little-endian fields, zig-zag mapping and LEB128 varints against published examples.
#include <catch2/catch.hpp>

#include <array>
#include <vector>

#include <curvestep/protocol/byte_io.hpp>
#include <curvestep/protocol/frame.hpp>

#include "../support/bytes.hpp"

using namespace curvestep;
using namespace curvestep::protocol;
using curvestep::protocol::testing::hex;
using curvestep::protocol::testing::to_hex;

TEST_CASE("byte io: zig-zag maps small magnitudes to small numbers", "[protocol][messages]") {
  // The mapping table of the Protocol Buffers encoding guide: 0, -1, 1, -2, 2^31-1, -2^31.
  CHECK(zigzag_encode(0) == 0u);
  CHECK(zigzag_encode(-1) == 1u);
  CHECK(zigzag_encode(1) == 2u);
  CHECK(zigzag_encode(-2) == 3u);
  CHECK(zigzag_encode(2147483647) == 4294967294u);
  CHECK(zigzag_encode(-2147483648LL) == 4294967295u);
  for (const std::int64_t v : {0LL, -1LL, 1LL, -4294967295LL, 4294967295LL, -9223372036854775807LL - 1}) {
    CHECK(zigzag_decode(zigzag_encode(v)) == v);
  }
}

TEST_CASE("byte io: varints match the Protocol Buffers examples", "[protocol][messages]") {
  // 1 -> 01, 150 -> 96 01, 300 -> ac 02 (Protocol Buffers encoding guide).
  std::array<std::byte, 16> out{};
  ByteWriter w(out);
  w.varint(1);
  w.varint(150);
  w.varint(300);
  const auto size = w.finish();
  REQUIRE(size.has_value());
  CHECK(to_hex(std::span<const std::byte>(out.data(), size.value())) == "01 96 01 ac 02");
  CHECK(varint_size(127) == 1);
  CHECK(varint_size(128) == 2);
  CHECK(varint_size(16383) == 2);
  CHECK(varint_size(16384) == 3);
  const auto in = hex("01 96 01 ac 02");
  ByteReader r(in);
  CHECK(r.varint() == 1u);
  CHECK(r.varint() == 150u);
  CHECK(r.varint() == 300u);
  CHECK(r.finish().has_value());
}

TEST_CASE("byte io: fields are little-endian", "[protocol][messages]") {
  std::array<std::byte, 16> out{};
  ByteWriter w(out);
  w.u16(0x1234);
  w.u32(0xA1B2C3D4u);
  w.i32(-2);
  REQUIRE(w.finish().has_value());
  CHECK(to_hex(std::span<const std::byte>(out.data(), w.size())) == "34 12 d4 c3 b2 a1 fe ff ff ff");
  ByteReader r(std::span<const std::byte>(out.data(), w.size()));
  CHECK(r.u16() == 0x1234);
  CHECK(r.u32() == 0xA1B2C3D4u);
  CHECK(r.i32() == -2);
  CHECK(r.finish().has_value());
}

TEST_CASE("byte io: the first overflow or short read sticks and names its offset", "[protocol][messages]") {
  std::array<std::byte, 3> out{};
  ByteWriter w(out);
  w.u16(1);
  w.u16(2);
  w.u8(3);
  const auto written = w.finish();
  REQUIRE_FALSE(written.has_value());
  CHECK(written.error() == Error::BufferTooSmall);
  CHECK(written.where() == 3);

  const auto in = hex("01 02 03");
  ByteReader r(in);
  (void)r.u16();
  (void)r.u16();
  const auto read = r.finish();
  REQUIRE_FALSE(read.has_value());
  CHECK(read.error() == Error::BadPayload);
  CHECK(read.where() == 3);
}

TEST_CASE("byte io: frames can be built at compile time", "[protocol][framing]") {
  constexpr auto ack_frame_size = [] {
    std::array<std::byte, max_encoded_frame_size> out{};
    return encode_frame(Message(Ack{6, 40}), 7, out).value();
  }();
  STATIC_REQUIRE(ack_frame_size == 13);  // docs/protocol.md: 05 03 07 06 28 07 a6 a8 6f 27 02 fd 00
}
