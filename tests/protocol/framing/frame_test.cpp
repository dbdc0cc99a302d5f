// SPDX-License-Identifier: MIT
// Frames: the documented example byte for byte, CRC coverage, length limits, the streaming decoder.
#include <catch2/catch.hpp>

#include <array>
#include <fstream>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include <curvestep/protocol/crc16.hpp>
#include <curvestep/protocol/frame.hpp>
#include <curvestep/protocol/frame_decoder.hpp>

#include "../support/bytes.hpp"

using namespace curvestep;
using namespace curvestep::protocol;
using curvestep::protocol::testing::bytes;
using curvestep::protocol::testing::hex;
using curvestep::protocol::testing::to_hex;

namespace {

// docs/protocol.md, "Worked example": QueueSegment, sequence 5, Line from (0, 0) to
// (10.5, -2.25) mm at 20 mm/s. Computed independently in Python (a table-driven CRC-32C,
// reflected polynomial 0x82F63B78, for the payload's check, binascii.crc_hqx for the frame's
// CRC-16, and a separate COBS routine: docs/protocol.md shows the script); the document shows
// the same bytes.
const char* const example_payload = "00 02 00 00 14 00 00 00 00 00 00 00 00 00 00 80 0a 00 00 c0 fd ff";
const char* const example_raw =
    "11 05 00 02 00 00 14 00 00 00 00 00 00 00 00 00 00 80 0a 00 00 c0 fd ff 7a bb 32 e6 79 04";
const char* const example_wire =
    "03 11 05 02 02 01 02 14 01 01 01 01 01 01 01 01 01 03 80 0a 01 0a c0 fd ff 7a bb 32 e6 79 04 00";
const char* const hello_wire = "02 01 02 05 09 34 12 1f 48 dc e1 36 69 00";  // Hello(version 5, session 0x1234), sequence 0
const char* const ack_wire = "05 03 07 06 28 07 a6 a8 6f 27 02 fd 00";       // Ack(6, 40), sequence 7

QueueSegment example_segment() {
  QueueSegment s;
  s.kind = SegmentKind::Line;
  s.axis_count = 2;
  s.has_feed = true;
  s.feed_mm_per_s = 20 * 65536;
  s.points[0] = {0, 0, 0};
  s.points[1] = {688128, -147456, 0};  // 10.5 * 65536, -2.25 * 65536
  return s;
}

std::vector<std::byte> wire_frame(const Message& m, std::uint8_t sequence) {
  std::vector<std::byte> out(max_encoded_frame_size);
  const auto r = encode_frame(m, sequence, out);
  REQUIRE(r.has_value());
  out.resize(r.value());
  return out;
}

/// Feeds bytes to a decoder; returns the frames and errors seen, in order.
struct FeedResult {
  std::vector<std::vector<std::byte>> frames;  // type, sequence, payload
  std::vector<Error> errors;
};

template <std::size_t Capacity>
FeedResult feed(FrameDecoder<Capacity>& decoder, std::span<const std::byte> data) {
  FeedResult result;
  for (const std::byte b : data) {
    const auto r = decoder.push(b);
    if (!r) {
      result.errors.push_back(r.error());
    } else if (r.value()) {
      std::vector<std::byte> f{std::byte{decoder.frame().type}, std::byte{decoder.frame().sequence}};
      f.insert(f.end(), decoder.frame().payload.begin(), decoder.frame().payload.end());
      result.frames.push_back(f);
    }
  }
  return result;
}

/// docs/protocol.md, found from this file's path, with '|' removed and whitespace collapsed.
std::string protocol_document() {
  const std::string here = __FILE__;
  const auto at = here.rfind("tests/protocol/");
  REQUIRE(at != std::string::npos);
  std::ifstream file(here.substr(0, at) + "docs/protocol.md");
  REQUIRE(file.good());
  std::stringstream text;
  text << file.rdbuf();
  std::string collapsed;
  for (const char c : text.str()) {
    const char d = (c == '|' || c == '\n' || c == '`') ? ' ' : c;
    if (d == ' ' && !collapsed.empty() && collapsed.back() == ' ') continue;
    collapsed.push_back(d);
  }
  return collapsed;
}

}  // namespace

TEST_CASE("frame: docs/protocol.md shows the same example bytes as this test", "[protocol][framing]") {
  const std::string doc = protocol_document();
  CHECK(doc.find(example_raw) != std::string::npos);
  CHECK(doc.find(example_wire) != std::string::npos);
  CHECK(doc.find(hello_wire) != std::string::npos);
  CHECK(doc.find(ack_wire) != std::string::npos);
}

TEST_CASE("frame: the worked example of docs/protocol.md encodes byte for byte", "[protocol][framing]") {
  std::array<std::byte, max_payload_size> payload{};
  const auto size = encode(example_segment(), payload);
  REQUIRE(size.has_value());
  CHECK(to_hex(std::span<const std::byte>(payload.data(), size.value())) == example_payload);
  CHECK(to_hex(wire_frame(example_segment(), 5)) == example_wire);
}

TEST_CASE("frame: the worked example decodes to the same segment", "[protocol][framing]") {
  FrameDecoder<> decoder;
  const auto wire = hex(example_wire);
  const FeedResult r = feed(decoder, wire);
  REQUIRE(r.errors.empty());
  REQUIRE(r.frames.size() == 1);
  const auto raw = hex(example_raw);
  CHECK(to_hex(r.frames[0]) == to_hex(std::span<const std::byte>(raw).first(raw.size() - frame_crc_size - message_crc_size)));
  const auto m = decode_message(static_cast<std::uint8_t>(r.frames[0][0]), std::span<const std::byte>(r.frames[0]).subspan(2));
  REQUIRE(m.has_value());
  const QueueSegment& s = m.value().get<QueueSegment>();
  CHECK(s.points[1][0] == 688128);
  CHECK(s.points[1][1] == -147456);
  CHECK(s.feed_mm_per_s == 1310720);
}

TEST_CASE("frame: every single-bit flip of the sample frame is detected by the CRC", "[protocol][framing]") {
  const auto raw = hex(example_raw);
  REQUIRE(parse_frame(raw).has_value());
  int flips = 0;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      auto corrupted = raw;
      corrupted[i] ^= static_cast<std::byte>(1u << bit);
      const auto r = parse_frame(corrupted);
      INFO("byte " << i << " bit " << bit);
      REQUIRE_FALSE(r.has_value());
      CHECK(r.error() == Error::BadCrc);
      ++flips;
    }
  }
  CHECK(flips == 30 * 8);
}

TEST_CASE("frame: a damaged frame whose CRC-16 still matches is refused by its payload's CRC-32C",
          "[protocol][framing]") {
  auto raw = hex(example_raw);
  raw[10] ^= std::byte{0x01};  // feed byte changed...
  const std::size_t body = raw.size() - frame_crc_size;
  const std::uint16_t crc = crc16(std::span<const std::byte>(raw).first(body));
  raw[body] = std::byte{static_cast<std::uint8_t>(crc & 0xFFu)};  // ...and the CRC-16 made to match, as a
  raw[body + 1] = std::byte{static_cast<std::uint8_t>(crc >> 8)};  // random damage does once in 65536
  const auto r = parse_frame(raw);
  REQUIRE_FALSE(r.has_value());
  CHECK(r.error() == Error::BadCrc);
  CHECK(r.where() == 5);  // the sequence number
}

TEST_CASE("frame: every two-bit error of the sample frame is detected", "[protocol][framing]") {
  // CRC-16/CCITT-FALSE alone has Hamming distance 4 at this length, so every 2-bit error is caught.
  const auto raw = hex(example_raw);
  const std::size_t bits = raw.size() * 8;
  std::size_t pairs = 0;
  for (std::size_t a = 0; a < bits; ++a) {
    for (std::size_t b = a + 1; b < bits; ++b) {
      auto corrupted = raw;
      corrupted[a / 8] ^= static_cast<std::byte>(1u << (a % 8));
      corrupted[b / 8] ^= static_cast<std::byte>(1u << (b % 8));
      if (parse_frame(corrupted).has_value()) FAIL("undetected flip of bits " << a << " and " << b);
      ++pairs;
    }
  }
  CHECK(pairs == bits * (bits - 1) / 2);
}

TEST_CASE("frame: every single-bit flip of the sample frame on the wire is rejected by the decoder", "[protocol][framing]") {
  const auto wire = hex(example_wire);
  for (std::size_t i = 0; i + 1 < wire.size(); ++i) {  // the delimiter itself is not flipped
    for (int bit = 0; bit < 8; ++bit) {
      auto corrupted = wire;
      corrupted[i] ^= static_cast<std::byte>(1u << bit);
      FrameDecoder<> decoder;
      const FeedResult r = feed(decoder, corrupted);
      INFO("byte " << i << " bit " << bit);
      CHECK(r.frames.empty());
      CHECK_FALSE(r.errors.empty());
    }
  }
}

TEST_CASE("frame: a frame shorter than header and CRC is FrameTooShort", "[protocol][framing]") {
  // The first n bytes of one buffer (a vector of n bytes per round makes GCC 12 at -O3 warn,
  // wrongly, that parse_frame reads past it: -Warray-bounds).
  std::array<std::byte, min_frame_size> buffer{};
  buffer.fill(std::byte{0x11});
  for (std::size_t n = 0; n < min_frame_size; ++n) {
    const auto raw = std::span<const std::byte>(buffer).first(n);
    const auto r = parse_frame(raw);
    REQUIRE_FALSE(r.has_value());
    CHECK(r.error() == Error::FrameTooShort);
  }
  FrameDecoder<> decoder;
  const auto wire = bytes({0x04, 0x11, 0x05, 0x28, 0x00});  // COBS of 3 bytes: too short
  const FeedResult r = feed(decoder, wire);
  REQUIRE(r.errors.size() == 1);
  CHECK(r.errors[0] == Error::FrameTooShort);
}

TEST_CASE("frame: a truncated frame fails its CRC", "[protocol][framing]") {
  const auto raw = hex(example_raw);
  for (std::size_t n = min_frame_size; n < raw.size(); ++n) {
    const auto r = parse_frame(std::span<const std::byte>(raw).first(n));
    REQUIRE_FALSE(r.has_value());
    CHECK(r.error() == Error::BadCrc);
  }
}

TEST_CASE("frame: payloads above the maximum are FrameTooLong on both ends", "[protocol][framing]") {
  std::vector<std::byte> payload(max_message_size + 1, std::byte{0x5A});
  std::vector<std::byte> out(400);
  const auto r = encode_frame(0x11, 0, payload, out);
  REQUIRE_FALSE(r.has_value());
  CHECK(r.error() == Error::FrameTooLong);

  payload.resize(max_message_size);
  const auto fits = encode_frame(0x11, 0, payload, out);
  REQUIRE(fits.has_value());
  CHECK(fits.value() == max_encoded_frame_size);

  const std::vector<std::byte> raw(max_frame_size + 1, std::byte{0x5A});
  CHECK(parse_frame(raw).error() == Error::FrameTooLong);

  // An endless run of non-zero bytes overflows the decoder once, then it resynchronises.
  FrameDecoder<> decoder;
  std::vector<std::byte> stream(500, std::byte{0x5A});
  stream.push_back(std::byte{0});
  const auto good = wire_frame(Message(Start{}), 9);
  stream.insert(stream.end(), good.begin(), good.end());
  const FeedResult fed = feed(decoder, stream);
  REQUIRE(fed.errors.size() == 1);
  CHECK(fed.errors[0] == Error::FrameTooLong);
  REQUIRE(fed.frames.size() == 1);
  CHECK(to_hex(fed.frames[0]) == "12 09");
}

TEST_CASE("frame: the decoder resynchronises on 0x00 after garbage", "[protocol][framing]") {
  const auto first = wire_frame(Message(Hello{1, 0x1234}), 0);
  const auto second = wire_frame(example_segment(), 5);
  std::vector<std::byte> stream = bytes({0x37, 0x99, 0x01, 0xFF, 0x42});  // garbage, then a frame
  stream.insert(stream.end(), first.begin(), first.end());
  const auto tail = bytes({0x00, 0x00, 0x13, 0x77, 0x00});  // empty frames and garbage
  stream.insert(stream.end(), tail.begin(), tail.end());
  stream.insert(stream.end(), second.begin(), second.end());
  FrameDecoder<> decoder;
  const FeedResult r = feed(decoder, stream);
  // The garbage runs into the first frame up to its delimiter, so that frame is lost;
  // the frame after the stray delimiters arrives intact.
  CHECK(r.errors.size() == 2);
  REQUIRE(r.frames.size() == 1);
  CHECK(r.frames[0][0] == std::byte{0x11});
  CHECK(r.frames[0][1] == std::byte{0x05});

  // With a leading 0x00 (which senders may add) the garbage cannot swallow the frame.
  std::vector<std::byte> flushed = bytes({0x37, 0x99, 0x00});
  flushed.insert(flushed.end(), first.begin(), first.end());
  FrameDecoder<> decoder2;
  const FeedResult r2 = feed(decoder2, flushed);
  CHECK(r2.errors.size() == 1);
  REQUIRE(r2.frames.size() == 1);
  CHECK(to_hex(r2.frames[0]) == "01 00 01 00 34 12");
}

TEST_CASE("frame: the Hello and Ack examples of docs/protocol.md encode byte for byte", "[protocol][framing]") {
  CHECK(to_hex(wire_frame(Message(Hello{5, 0x1234}), 0)) == hello_wire);
  CHECK(to_hex(wire_frame(Message(Ack{6, 40}), 7)) == ack_wire);
}

TEST_CASE("frame: a too small output buffer is BufferTooSmall", "[protocol][framing]") {
  for (std::size_t n = 0; n < 32; ++n) {
    std::vector<std::byte> out(n);
    const auto r = encode_frame(Message(example_segment()), 5, out);
    REQUIRE_FALSE(r.has_value());
    CHECK(r.error() == Error::BufferTooSmall);
  }
}
