// SPDX-License-Identifier: MIT
// QueuePiece (0x17, protocol version 4): payloads written by hand from the byte table of
// docs/protocol.md (binary64 patterns: 1.5 = 3ff8..., -2.0 = c000..., 0.1 = 3fb999999999999a, ...),
// a frame whose bytes come from the Python of docs/protocol.md (bitwise CRC-16 and CRC-32C), the
// decoder's errors with their byte offsets and the encoder's refusals.
#include <catch2/catch.hpp>

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <curvestep/core/motion/hermite_chunk.hpp>
#include <curvestep/core/motion/planned_piece.hpp>
#include <curvestep/protocol/frame.hpp>
#include <curvestep/protocol/messages.hpp>

#include "../support/bytes.hpp"

using namespace curvestep;
using namespace curvestep::protocol;
using curvestep::protocol::testing::hex;
using curvestep::protocol::testing::to_hex;

namespace {

constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();
constexpr double infinity = std::numeric_limits<double>::infinity();

// Little-endian binary64 patterns.
#define F_1_5 "00 00 00 00 00 00 f8 3f "
#define F_M2 "00 00 00 00 00 00 00 c0 "
#define F_0_1 "9a 99 99 99 99 99 b9 3f "
#define F_2 "00 00 00 00 00 00 00 40 "
#define F_M0_5 "00 00 00 00 00 00 e0 bf "
#define F_0_25 "00 00 00 00 00 00 d0 3f "
#define F_0 "00 00 00 00 00 00 00 00 "
#define F_0_5 "00 00 00 00 00 00 e0 3f "
#define F_M1 "00 00 00 00 00 00 f0 bf "
#define F_1 "00 00 00 00 00 00 f0 3f "
#define F_NAN "00 00 00 00 00 00 f8 7f "
#define F_INF "00 00 00 00 00 00 f0 7f "
#define F_MINF "00 00 00 00 00 00 f0 ff "

// End of job, 2 axes, 1 tick, segment 7, end (1.5, -2.0): 24 bytes.
const char* const exact_2_axes = "01 02 01 00 07 00 00 00 " F_1_5 F_M2;
// No flags, 3 axes, 1 tick, segment 0x12345678, end (1.5, -2.0, 0.1): 32 bytes.
const char* const exact_3_axes = "00 03 01 00 78 56 34 12 " F_1_5 F_M2 F_0_1;
// No flags, 3 axes, 256 ticks, segment 41, end (2, -0.5, 0.25), q1 (0.1, 0, 0), q2 (0.5, -1, 0),
// q3 (1, -2, 0.1), q4 (1.5, -0.5, 0.25), q5 (2, 1, -1): 152 bytes.
const char* const chunk_3_axes = "00 03 00 01 29 00 00 00 " F_2 F_M0_5 F_0_25  //
    F_0_1 F_0 F_0 F_0_5 F_M1 F_0 F_1 F_M2 F_0_1 F_1_5 F_M0_5 F_0_25 F_2 F_1 F_M1;

// Exact run (flag bit 1), 2 axes, 3 ticks, segment 5: end (2, -0.5), then the run's first two
// setpoints (1.5, -2) and (0.1, 0) in time order: 8 + 3 x 16 = 56 bytes.
const char* const exact_run_2_axes = "02 02 03 00 05 00 00 00 " F_2 F_M0_5 F_1_5 F_M2 F_0_1 F_0;

QueuePiece exact_2_axes_piece() {
  QueuePiece p;
  p.axis_count = 2;
  p.ticks = 1;
  p.end_of_job = true;
  p.segment = 7;
  p.end = {1.5, -2.0, 0.0};
  return p;
}

QueuePiece exact_3_axes_piece() {
  QueuePiece p;
  p.axis_count = 3;
  p.ticks = 1;
  p.segment = 0x12345678;
  p.end = {1.5, -2.0, 0.1};
  return p;
}

QueuePiece chunk_3_axes_piece() {
  QueuePiece p;
  p.axis_count = 3;
  p.ticks = 256;
  p.segment = 41;
  p.end = {2.0, -0.5, 0.25};
  p.controls = {{{0.1, 0.0, 0.0}, {0.5, -1.0, 0.0}, {1.0, -2.0, 0.1}, {1.5, -0.5, 0.25}, {2.0, 1.0, -1.0}}};
  return p;
}

std::vector<std::byte> encoded(const QueuePiece& p) {
  std::vector<std::byte> out(max_message_size);
  const auto size = encode(p, out);
  REQUIRE(size.has_value());
  out.resize(size.value());
  return out;
}

/// The payload `text` with byte `at` replaced by `value`.
std::vector<std::byte> with_byte(const char* text, std::size_t at, int value) {
  auto payload = hex(text);
  payload.at(at) = static_cast<std::byte>(value);
  return payload;
}

void check_fails(std::span<const std::byte> payload, Error code, std::size_t at) {
  const auto r = decode<QueuePiece>(payload);
  REQUIRE_FALSE(r.has_value());
  CHECK(r.error() == code);
  CHECK(r.where() == at);
}

void check_refused(const QueuePiece& p, Error code, std::size_t at) {
  std::array<std::byte, max_message_size> out{};
  const auto r = encode(p, out);
  REQUIRE_FALSE(r.has_value());
  CHECK(r.error() == code);
  CHECK(r.where() == at);
}

}  // namespace

static_assert(is_known(0x17) && is_known(0x18) && is_known(0x19) && is_known(0x1a) && is_known(0x1b) && !is_known(0x1c));
static_assert(is_command(MessageType::QueuePiece) && is_sequenced(MessageType::QueuePiece));
static_assert(consumes_credit(MessageType::QueuePiece) && consumes_credit(MessageType::QueueSegment));
static_assert(!consumes_credit(MessageType::Start) && !consumes_credit(MessageType::SetpointBatch));
static_assert(is_sequenced_toward(Endpoint::Controller, 0x17) && !is_sequenced_toward(Endpoint::Host, 0x17));
static_assert(HostToController::contains<QueuePiece> && AllMessages::contains<QueuePiece> &&
              !ControllerToHost::contains<QueuePiece>);
static_assert(protocol_version >= 4);  // QueuePiece since version 4
static_assert(max_piece_ticks == curvestep::HermiteChunk::max_ticks);

TEST_CASE("queue piece: the protocol's tick rule is core's valid_piece_ticks", "[protocol][messages]") {
  for (std::uint32_t ticks = 0; ticks <= 0x10000; ++ticks) {
    INFO("ticks " << ticks);
    CHECK(valid_queue_piece_ticks(ticks) == curvestep::valid_piece_ticks(ticks));
    CHECK(valid_queue_piece_ticks(ticks, true) == curvestep::valid_piece_ticks(ticks, true));
  }
}

TEST_CASE("queue piece: an exact 2-axis piece is the 24 bytes of docs/protocol.md", "[protocol][messages]") {
  const auto expected = hex(exact_2_axes);
  REQUIRE(expected.size() == 24);
  CHECK(to_hex(encoded(exact_2_axes_piece())) == to_hex(expected));
  const auto back = decode<QueuePiece>(expected);
  REQUIRE(back.has_value());
  CHECK(back.value() == exact_2_axes_piece());
  CHECK(back.value().end[2] == 0.0);
  CHECK(queue_piece_size(2, 1) == 24);
}

TEST_CASE("queue piece: an exact 3-axis piece is 32 bytes with 0.1 exactly as sent", "[protocol][messages]") {
  const auto expected = hex(exact_3_axes);
  REQUIRE(expected.size() == 32);
  CHECK(to_hex(encoded(exact_3_axes_piece())) == to_hex(expected));
  const auto back = decode<QueuePiece>(expected);
  REQUIRE(back.has_value());
  CHECK(back.value() == exact_3_axes_piece());
  CHECK(std::bit_cast<std::uint64_t>(back.value().end[2]) == 0x3FB999999999999Au);
  CHECK(queue_piece_size(3, 1) == 32);
}

TEST_CASE("queue piece: a 3-axis chunk of 256 ticks is 152 bytes and fits a message", "[protocol][messages]") {
  const auto expected = hex(chunk_3_axes);
  REQUIRE(expected.size() == 152);
  CHECK(expected.size() <= max_message_size);
  CHECK(to_hex(encoded(chunk_3_axes_piece())) == to_hex(expected));
  const auto back = decode<QueuePiece>(expected);
  REQUIRE(back.has_value());
  CHECK(back.value() == chunk_3_axes_piece());
  CHECK(queue_piece_size(3, 256) == 152);
  CHECK(queue_piece_size(2, 2) == 104);
}

TEST_CASE("queue piece: an exact run of 3 ticks is 56 bytes with its setpoints in time order", "[protocol][messages]") {
  QueuePiece p;
  p.axis_count = 2;
  p.ticks = 3;
  p.exact_run = true;
  p.segment = 5;
  p.end = {2.0, -0.5, 0.0};
  p.controls[0] = {1.5, -2.0, 0.0};
  p.controls[1] = {0.1, 0.0, 0.0};
  const auto expected = hex(exact_run_2_axes);
  REQUIRE(expected.size() == 56);
  CHECK(queue_piece_size(2, 3, true) == 56);
  CHECK(queue_piece_size(3, 6, true) == 152);  // the longest run fits a message like a chunk
  CHECK(to_hex(encoded(p)) == to_hex(expected));
  const auto back = decode<QueuePiece>(expected);
  REQUIRE(back.has_value());
  CHECK(back.value() == p);
  QueuePiece stray = p;
  stray.controls[2] = {1.0, 0.0, 0.0};  // a third earlier point: not sent with 3 ticks
  check_refused(stray, Error::InvalidArgument, 8 + 3 * 16);
  QueuePiece too_long = p;
  too_long.ticks = 7;
  check_refused(too_long, Error::InvalidArgument, 2);
}

TEST_CASE("queue piece: a rest of 500 ticks is 32 bytes, its end point alone", "[protocol][messages]") {
  // Flags 0x04 (rest), 3 axes, 500 ticks (0x01f4), segment 1, end (2, -0.5, 0.25).
  const auto expected = hex("04 03 f4 01 01 00 00 00 " F_2 F_M0_5 F_0_25);
  QueuePiece p;
  p.axis_count = 3;
  p.ticks = 500;
  p.rest = true;
  p.segment = 1;
  p.end = {2.0, -0.5, 0.25};
  REQUIRE(expected.size() == 32);
  CHECK(queue_piece_size(3, 500, false, true) == 32);
  CHECK(to_hex(encoded(p)) == to_hex(expected));
  const auto back = decode<QueuePiece>(expected);
  REQUIRE(back.has_value());
  CHECK(back.value() == p);
  QueuePiece none = p;
  none.ticks = 0;
  check_refused(none, Error::InvalidArgument, 2);
  QueuePiece stray = p;
  stray.controls[0] = {1.0, 0.0, 0.0};  // a rest sends no control point
  check_refused(stray, Error::InvalidArgument, 8 + 24);
  check_fails(hex("04 03 00 00 01 00 00 00 " F_2 F_M0_5 F_0_25), Error::BadPayload, 2);  // a rest of 0 ticks
}

TEST_CASE("queue piece: a 2-axis chunk sends no z and decodes z as 0", "[protocol][messages]") {
  QueuePiece p;
  p.axis_count = 2;
  p.ticks = 2;
  p.end = {1.5, -2.0, 0.0};
  p.controls = {{{0.1, 0.0, 0.0}, {0.5, -1.0, 0.0}, {1.0, -2.0, 0.0}, {1.5, -0.5, 0.0}, {2.0, 1.0, 0.0}}};
  const auto expected = hex("00 02 02 00 00 00 00 00 " F_1_5 F_M2 F_0_1 F_0 F_0_5 F_M1 F_1 F_M2 F_1_5 F_M0_5 F_2 F_1);
  REQUIRE(expected.size() == 104);
  CHECK(to_hex(encoded(p)) == to_hex(expected));
  const auto back = decode<QueuePiece>(expected);
  REQUIRE(back.has_value());
  CHECK(back.value() == p);
}

TEST_CASE("queue piece: every valid tick count decodes and no other does", "[protocol][messages]") {
  for (std::uint32_t ticks = 0; ticks <= 0xFFFF; ++ticks) {
    const bool valid = ticks == 1 || ticks == 2 || ticks == 4 || ticks == 8 || ticks == 16 || ticks == 32 ||
                       ticks == 64 || ticks == 128 || ticks == 256;
    QueuePiece p;
    p.axis_count = 2;
    p.ticks = static_cast<std::uint16_t>(ticks);
    std::vector<std::byte> payload = hex("00 02 00 00 00 00 00 00");
    payload[2] = static_cast<std::byte>(ticks & 0xFFu);
    payload[3] = static_cast<std::byte>(ticks >> 8);
    payload.resize(ticks > 1 ? 104 : 24, std::byte{0});
    const auto r = decode<QueuePiece>(payload);
    std::array<std::byte, max_message_size> out{};
    const auto e = encode(p, out);
    if (valid) {
      REQUIRE(r.has_value());
      CHECK(r.value().ticks == ticks);
      REQUIRE(e.has_value());
      CHECK(e.value() == payload.size());
    } else {
      INFO("ticks " << ticks);
      REQUIRE_FALSE(r.has_value());
      CHECK(r.error() == Error::BadPayload);
      CHECK(r.where() == 2);
      REQUIRE_FALSE(e.has_value());
      CHECK(e.error() == Error::InvalidArgument);
      CHECK(e.where() == 2);
    }
  }
}

TEST_CASE("queue piece: a frame round trip through encode_frame and parse_frame", "[protocol][messages]") {
  // The frame bytes (type 17, sequence 03) from the Python of docs/protocol.md.
  const char* const wire = "06 17 03 01 02 01 02 07 01 01 01 01 01 01 01 01 03 f8 3f 01 01 01 01 01 01 08 c0 32 29 "
                           "fe 8b 8c 6e 00";
  std::vector<std::byte> out(max_encoded_frame_size);
  const auto size = encode_frame(exact_2_axes_piece(), 3, out);
  REQUIRE(size.has_value());
  out.resize(size.value());
  CHECK(to_hex(out) == wire);
  std::vector<std::byte> held(max_encoded_frame_size);
  const auto held_size = encode_frame<HostToController>(Message(exact_2_axes_piece()), 3, held);
  REQUIRE(held_size.has_value());
  held.resize(held_size.value());
  CHECK(to_hex(held) == wire);

  for (const QueuePiece& piece : {exact_2_axes_piece(), exact_3_axes_piece(), chunk_3_axes_piece()}) {
    std::vector<std::byte> frame(max_encoded_frame_size);
    const auto n = encode_frame(piece, 200, frame);
    REQUIRE(n.has_value());
    CHECK(n.value() <= max_encoded_frame_size);
    std::vector<std::byte> raw(max_frame_size);
    const auto raw_size = cobs_decode(std::span<const std::byte>(frame).first(n.value() - 1), raw);
    REQUIRE(raw_size.has_value());
    const auto parsed = parse_frame(std::span<const std::byte>(raw).first(raw_size.value()));
    REQUIRE(parsed.has_value());
    CHECK(parsed.value().type == 0x17);
    CHECK(parsed.value().sequence == 200);
    const auto m = decode_message<HostToController>(parsed.value());
    REQUIRE(m.has_value());
    REQUIRE(m.value().holds<QueuePiece>());
    CHECK(m.value().get<QueuePiece>() == piece);
  }
}

TEST_CASE("queue piece: a host's decoder refuses it as UnknownMessage", "[protocol][messages]") {
  const auto r = decode_message<ControllerToHost>(0x17, hex(exact_2_axes));
  REQUIRE_FALSE(r.has_value());
  CHECK(r.error() == Error::UnknownMessage);
  CHECK(r.where() == 0x17);
}

TEST_CASE("queue piece: reserved flag bits axis counts and tick counts are BadPayload at their byte",
          "[protocol][messages]") {
  for (const int flags : {0x08, 0x10, 0x20, 0x40, 0x80, 0x0C, 0x0F}) {
    INFO("flags " << flags);
    check_fails(with_byte(exact_2_axes, 0, flags), Error::BadPayload, 0);
  }
  check_fails(with_byte(exact_2_axes, 0, 0x06), Error::BadPayload, 2);  // a rest cannot be an exact run
  check_fails(with_byte(exact_2_axes, 0, 0x02), Error::BadPayload, 2);  // an exact run of one tick
  check_fails(with_byte(exact_run_2_axes, 2, 7), Error::BadPayload, 2);  // a run of 7 ticks
  for (const int axes : {0, 1, 4, 255}) {
    INFO("axes " << axes);
    check_fails(with_byte(exact_2_axes, 1, axes), Error::BadPayload, 1);
  }
  check_fails(with_byte(exact_2_axes, 2, 0), Error::BadPayload, 2);     // 0 ticks
  check_fails(with_byte(exact_2_axes, 2, 3), Error::BadPayload, 2);     // 3 ticks
  check_fails(hex("00 03 00 02 29 00 00 00"), Error::BadPayload, 2);    // 512 ticks (header alone)
  check_fails(with_byte(chunk_3_axes, 3, 0x81), Error::BadPayload, 2);  // 0x8100 ticks
  check_fails(hex("00 03 00 01 29 00 00"), Error::BadPayload, 7);       // a header one byte short
}

TEST_CASE("queue piece: a length other than the one axis_count and ticks give is BadPayload", "[protocol][messages]") {
  const auto exact = hex(exact_2_axes);
  const auto chunk = hex(chunk_3_axes);
  // one byte short: index = the first missing byte; one byte long: index = the first extra byte
  check_fails(std::span<const std::byte>(exact).first(23), Error::BadPayload, 23);
  auto longer = exact;
  longer.push_back(std::byte{0});
  check_fails(longer, Error::BadPayload, 24);
  check_fails(std::span<const std::byte>(chunk).first(151), Error::BadPayload, 151);
  // a 3-axis exact piece's bytes declared as 2 axes: 8 bytes too many
  check_fails(with_byte(exact_3_axes, 1, 2), Error::BadPayload, 24);
  // a 3-axis exact piece's bytes declared as a chunk of 4 ticks: 120 bytes missing
  check_fails(with_byte(exact_3_axes, 2, 4), Error::BadPayload, 32);
  // a chunk's bytes declared as an exact piece: the controls are extra bytes
  check_fails(with_byte(chunk_3_axes, 3, 0), Error::BadPayload, 2);  // 0 ticks: the tick count first
  auto as_exact = chunk;
  as_exact[2] = std::byte{1};
  as_exact[3] = std::byte{0};
  check_fails(as_exact, Error::BadPayload, 32);
  // every truncation is BadPayload
  for (std::size_t n = 0; n < chunk.size(); ++n) {
    const auto r = decode<QueuePiece>(std::span<const std::byte>(chunk).first(n));
    REQUIRE_FALSE(r.has_value());
    CHECK(r.error() == Error::BadPayload);
  }
  // a wrong length is reported before a non-finite value
  check_fails(hex("00 02 01 00 00 00 00 00 " F_NAN), Error::BadPayload, 16);
}

TEST_CASE("queue piece: a NaN or infinite coordinate is NotFinite at its byte offset", "[protocol][messages]") {
  check_fails(hex("00 02 01 00 00 00 00 00 " F_1_5 F_NAN), Error::NotFinite, 16);
  check_fails(hex("00 02 01 00 00 00 00 00 " F_MINF F_NAN), Error::NotFinite, 8);  // the first one
  check_fails(hex("00 03 01 00 00 00 00 00 " F_1_5 F_M2 F_INF), Error::NotFinite, 24);
  // chunk: q3.z at 8 + 3 * 24 + 16 = 96, q5.x at 8 + 5 * 24 = 128
  const auto chunk = hex(chunk_3_axes);
  auto q3z = chunk;
  for (std::size_t i = 0; i < 8; ++i) q3z[96 + i] = hex(F_INF)[i];
  check_fails(q3z, Error::NotFinite, 96);
  auto q5x = chunk;
  for (std::size_t i = 0; i < 8; ++i) q5x[128 + i] = hex(F_NAN)[i];
  check_fails(q5x, Error::NotFinite, 128);
  // the largest finite binary64 and a subnormal are fine
  CHECK(decode<QueuePiece>(hex("00 02 01 00 00 00 00 00 ff ff ff ff ff ff ef 7f 01 00 00 00 00 00 00 80")).has_value());
}

TEST_CASE("queue piece: the encoder refuses what the decoder would refuse", "[protocol][messages]") {
  QueuePiece p = exact_2_axes_piece();
  p.axis_count = 1;
  check_refused(p, Error::InvalidArgument, 1);
  p.axis_count = 4;
  check_refused(p, Error::InvalidArgument, 1);
  p = exact_2_axes_piece();
  for (const std::uint16_t ticks : {std::uint16_t{0}, std::uint16_t{3}, std::uint16_t{384}, std::uint16_t{512}}) {
    p.ticks = ticks;
    check_refused(p, Error::InvalidArgument, 2);
  }
  // non-finite values: NotFinite at their byte offset
  p = exact_2_axes_piece();
  p.end[1] = not_a_number;
  check_refused(p, Error::NotFinite, 16);
  p = chunk_3_axes_piece();
  p.controls[4][1] = -infinity;  // q5.y: 8 + 5 * 24 + 8
  check_refused(p, Error::NotFinite, 136);
  p = chunk_3_axes_piece();
  p.end[0] = infinity;
  check_refused(p, Error::NotFinite, 8);
}

TEST_CASE("queue piece: the encoder refuses a non-zero value it would not send", "[protocol][messages]") {
  // z with two axes: InvalidArgument at the byte offset of the point that would carry it
  QueuePiece p = exact_2_axes_piece();
  p.end[2] = 0.5;
  check_refused(p, Error::InvalidArgument, 8);
  p.end[2] = not_a_number;
  check_refused(p, Error::InvalidArgument, 8);
  QueuePiece chunk;
  chunk.axis_count = 2;
  chunk.ticks = 4;
  chunk.controls[1][2] = 1.0;  // q2 starts at 8 + 2 * 16
  check_refused(chunk, Error::InvalidArgument, 40);
  // controls of an exact piece (they are not sent)
  QueuePiece exact = exact_3_axes_piece();
  exact.controls[0][0] = 0.1;  // q1 would start at 8 + 24
  check_refused(exact, Error::InvalidArgument, 32);
  exact = exact_3_axes_piece();
  exact.controls[4][2] = -1.0;  // q5 would start at 8 + 5 * 24
  check_refused(exact, Error::InvalidArgument, 128);
  // a buffer too small
  std::array<std::byte, 151> small{};
  CHECK(encode(chunk_3_axes_piece(), small).error() == Error::BufferTooSmall);
}
