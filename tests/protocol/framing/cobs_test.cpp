// SPDX-License-Identifier: MIT
// COBS against the standard examples (Cheshire and Baker; the Wikipedia COBS example table).
#include <catch2/catch.hpp>

#include <array>
#include <vector>

#include <curvestep/protocol/cobs.hpp>

#include "../support/bytes.hpp"

using namespace curvestep;
using namespace curvestep::protocol;
using curvestep::protocol::testing::bytes;
using curvestep::protocol::testing::to_hex;

namespace {

std::vector<std::byte> encoded(const std::vector<std::byte>& input) {
  std::vector<std::byte> out(cobs_max_encoded_size(input.size()));
  const auto r = cobs_encode(input, out);
  REQUIRE(r.has_value());
  out.resize(r.value());
  return out;
}

std::vector<std::byte> decoded(const std::vector<std::byte>& input) {
  std::vector<std::byte> out(input.size());
  const auto r = cobs_decode(input, out);
  REQUIRE(r.has_value());
  out.resize(r.value());
  return out;
}

std::vector<std::byte> run(int first, int last) {
  std::vector<std::byte> out;
  for (int v = first; v <= last; ++v) out.push_back(static_cast<std::byte>(v));
  return out;
}

std::vector<std::byte> join(std::vector<std::byte> a, const std::vector<std::byte>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

struct Example {
  std::vector<std::byte> plain;
  std::vector<std::byte> stuffed;
};

std::vector<Example> standard_examples() {
  return {
      {bytes({0x00}), bytes({0x01, 0x01})},
      {bytes({0x00, 0x00}), bytes({0x01, 0x01, 0x01})},
      {bytes({0x00, 0x11, 0x00}), bytes({0x01, 0x02, 0x11, 0x01})},
      {bytes({0x11, 0x22, 0x00, 0x33}), bytes({0x03, 0x11, 0x22, 0x02, 0x33})},
      {bytes({0x11, 0x22, 0x33, 0x44}), bytes({0x05, 0x11, 0x22, 0x33, 0x44})},
      {bytes({0x11, 0x00, 0x00, 0x00}), bytes({0x02, 0x11, 0x01, 0x01, 0x01})},
      // 254 non-zero bytes fill one block exactly: no trailing code byte.
      {run(0x01, 0xFE), join(bytes({0xFF}), run(0x01, 0xFE))},
      {join(bytes({0x00}), run(0x01, 0xFE)), join(bytes({0x01, 0xFF}), run(0x01, 0xFE))},
      {run(0x01, 0xFF), join(join(bytes({0xFF}), run(0x01, 0xFE)), bytes({0x02, 0xFF}))},
      {join(run(0x02, 0xFF), bytes({0x00})), join(join(bytes({0xFF}), run(0x02, 0xFF)), bytes({0x01, 0x01}))},
      {join(run(0x03, 0xFF), bytes({0x00, 0x01})), join(join(bytes({0xFE}), run(0x03, 0xFF)), bytes({0x02, 0x01}))},
  };
}

}  // namespace

TEST_CASE("cobs: the standard examples encode byte for byte", "[protocol][framing]") {
  for (const Example& e : standard_examples()) {
    INFO("input " << to_hex(e.plain));
    CHECK(to_hex(encoded(e.plain)) == to_hex(e.stuffed));
  }
}

TEST_CASE("cobs: the standard examples decode back to the input", "[protocol][framing]") {
  for (const Example& e : standard_examples()) {
    INFO("input " << to_hex(e.stuffed));
    CHECK(to_hex(decoded(e.stuffed)) == to_hex(e.plain));
  }
}

TEST_CASE("cobs: encoded data never contains a zero and stays within the overhead bound", "[protocol][framing]") {
  std::vector<std::byte> data;
  for (int i = 0; i < 600; ++i) data.push_back(static_cast<std::byte>((i * 37) % 7 == 0 ? 0 : i % 256));
  for (std::size_t n = 0; n <= data.size(); n += 13) {
    const std::vector<std::byte> input(data.begin(), data.begin() + static_cast<std::ptrdiff_t>(n));
    const auto out = encoded(input);
    CHECK(out.size() <= cobs_max_encoded_size(n));
    for (const std::byte b : out) REQUIRE(b != std::byte{0});
    CHECK(decoded(out) == input);
  }
}

TEST_CASE("cobs: decoding in place gives the same result", "[protocol][framing]") {
  auto buffer = bytes({0x03, 0x11, 0x22, 0x02, 0x33});
  const auto r = cobs_decode(buffer, buffer);
  REQUIRE(r.has_value());
  buffer.resize(r.value());
  CHECK(to_hex(buffer) == "11 22 00 33");
}

TEST_CASE("cobs: a zero inside the encoded data or a code past the end is BadFraming", "[protocol][framing]") {
  std::array<std::byte, 16> out{};
  const auto zero = bytes({0x03, 0x11, 0x00, 0x02, 0x33});
  const auto r1 = cobs_decode(zero, out);
  REQUIRE_FALSE(r1.has_value());
  CHECK(r1.error() == Error::BadFraming);
  CHECK(r1.where() == 2);
  const auto short_block = bytes({0x05, 0x11, 0x22});
  const auto r2 = cobs_decode(short_block, out);
  REQUIRE_FALSE(r2.has_value());
  CHECK(r2.error() == Error::BadFraming);
  CHECK(r2.where() == 3);
  const auto zero_code = bytes({0x00});
  CHECK(cobs_decode(zero_code, out).error() == Error::BadFraming);
}

TEST_CASE("cobs: an output buffer that is too small is BufferTooSmall, never an overrun", "[protocol][framing]") {
  const auto input = bytes({0x11, 0x22, 0x00, 0x33});
  for (std::size_t size = 0; size < 5; ++size) {
    std::vector<std::byte> out(size);
    const auto r = cobs_encode(input, out);
    REQUIRE_FALSE(r.has_value());
    CHECK(r.error() == Error::BufferTooSmall);
  }
  const auto stuffed = bytes({0x03, 0x11, 0x22, 0x02, 0x33});
  std::array<std::byte, 3> small{};
  CHECK(cobs_decode(stuffed, small).error() == Error::BufferTooSmall);
}
