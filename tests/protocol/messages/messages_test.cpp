// SPDX-License-Identifier: MIT
// Messages: every type round-trips, hand-computed payloads, malformed payloads are rejected.
#include <catch2/catch.hpp>

#include <bit>

#include <array>
#include <random>
#include <vector>

#include <curvestep/protocol/frame.hpp>
#include <curvestep/protocol/messages.hpp>
#include <support/numeric.hpp>

#include "../support/bytes.hpp"
#include "../support/payload.hpp"

using namespace curvestep;
using namespace curvestep::protocol;
using curvestep::protocol::testing::hex;
using curvestep::protocol::testing::to_hex;

namespace {

using curvestep::protocol::testing::payload_of;

Message round_trip(const Message& m) {
  const auto payload = payload_of(m);
  const auto r = decode_message(static_cast<std::uint8_t>(m.type()), payload);
  REQUIRE(r.has_value());
  REQUIRE(r.value().type() == m.type());
  // Encoding the decoded message again gives the same bytes.
  CHECK(payload_of(r.value()) == payload);
  return r.value();
}

std::int32_t random_raw(std::mt19937& rng) {
  return static_cast<std::int32_t>(rng());
}

/// Any 64-bit pattern as a double (NaNs and infinities included: the wire must carry them unchanged).
double random_double(std::mt19937& rng) {
  const std::uint64_t high = rng();
  return std::bit_cast<double>((high << 32) | rng());
}

WirePoint random_point(std::mt19937& rng, std::size_t axes) {
  WirePoint p{};
  for (std::size_t a = 0; a < axes; ++a) p[a] = random_raw(rng);
  return p;
}

QueueSegment random_segment(std::mt19937& rng) {
  QueueSegment s;
  s.kind = static_cast<SegmentKind>(rng() % 4);
  s.axis_count = static_cast<std::uint8_t>(2 + rng() % 2);
  s.rapid = rng() % 2 == 0;
  s.end_of_job = rng() % 2 == 0;
  s.has_feed = rng() % 2 == 0;
  s.feed_mm_per_s = s.has_feed ? random_raw(rng) : 0;
  s.degree = static_cast<std::uint8_t>(s.kind == SegmentKind::Line ? 1 : s.kind == SegmentKind::Arc ? 2 : 1 + rng() % 7);
  if (s.kind == SegmentKind::Arc) {
    s.direction = rng() % 2 == 0 ? ArcDirection::Clockwise : ArcDirection::CounterClockwise;
    s.points[0] = random_point(rng, s.axis_count);
    s.points[1] = random_point(rng, s.axis_count);
    s.points[2] = random_point(rng, 2);
    s.turns = rng() % 3 == 0 ? static_cast<std::uint32_t>(rng()) | 1u : 0;
  } else {
    for (std::size_t i = 0; i < s.point_count(); ++i) s.points[i] = random_point(rng, s.axis_count);
  }
  if (s.kind == SegmentKind::RationalBezier) {
    for (std::size_t i = 0; i < s.point_count(); ++i) s.weights[i] = 1 + static_cast<std::int32_t>(rng() % 0x7FFFFFFE);
  }
  s.stop_before = rng() % 2 == 0;
  s.rest_ticks = rng() % 3 == 0 ? static_cast<std::uint32_t>(rng()) | 1u : 0;
  s.end_rest_ticks = s.end_of_job && rng() % 2 == 0 ? static_cast<std::uint32_t>(rng()) | 1u : 0;
  return s;
}

bool same(const QueueSegment& a, const QueueSegment& b) {
  return a.kind == b.kind && a.axis_count == b.axis_count && a.degree == b.degree && a.rapid == b.rapid &&
         a.has_feed == b.has_feed && a.feed_mm_per_s == b.feed_mm_per_s && a.points == b.points &&
         a.weights == b.weights && a.end_of_job == b.end_of_job && a.turns == b.turns && a.stop_before == b.stop_before &&
         a.rest_ticks == b.rest_ticks && a.end_rest_ticks == b.end_rest_ticks &&
         (a.kind != SegmentKind::Arc || a.direction == b.direction);
}

SetpointBatch batch(std::uint32_t first, std::uint8_t axes, std::initializer_list<WirePoint> points) {
  SetpointBatch b;
  b.first_index = first;
  b.axis_count = axes;
  for (const WirePoint& p : points) b.setpoints[b.count++] = p;
  return b;
}

}  // namespace

TEST_CASE("messages: every message type round-trips through encode and decode", "[protocol][messages]") {
  std::mt19937 rng(curvestep::testing::test_seed());
  const int count = curvestep::testing::test_count(200);
  for (int i = 0; i < count; ++i) {
    Hello hello{static_cast<std::uint16_t>(rng()), static_cast<std::uint16_t>(rng())};
    const auto h = round_trip(hello).get<Hello>();
    CHECK((h.version == hello.version && h.session == hello.session));

    Capabilities caps;
    caps.version = static_cast<std::uint16_t>(rng());
    caps.session = static_cast<std::uint16_t>(rng());
    caps.max_payload = static_cast<std::uint16_t>(rng());
    caps.queue_capacity = static_cast<std::uint16_t>(rng());
    caps.credit_end = static_cast<std::uint16_t>(rng());
    caps.fixed_total_bits = static_cast<std::uint8_t>(rng());
    caps.fixed_fraction_bits = static_cast<std::uint8_t>(rng());
    caps.axis_count = static_cast<std::uint8_t>(2 + rng() % 2);
    caps.max_degree = static_cast<std::uint8_t>(1 + rng() % 7);
    caps.tick_rate_hz = static_cast<std::uint32_t>(rng());
    caps.lookahead = static_cast<std::uint16_t>(rng());  // 0 (no planner on board) included
    const auto c = round_trip(caps).get<Capabilities>();
    CHECK((c.version == caps.version && c.session == caps.session && c.max_payload == caps.max_payload &&
           c.queue_capacity == caps.queue_capacity && c.credit_end == caps.credit_end &&
           c.fixed_total_bits == caps.fixed_total_bits && c.fixed_fraction_bits == caps.fixed_fraction_bits &&
           c.axis_count == caps.axis_count && c.max_degree == caps.max_degree && c.tick_rate_hz == caps.tick_rate_hz &&
           c.lookahead == caps.lookahead));

    Ack ack{static_cast<std::uint8_t>(rng()), static_cast<std::uint16_t>(rng())};
    const auto a = round_trip(ack).get<Ack>();
    CHECK((a.next_expected == ack.next_expected && a.credit_end == ack.credit_end));

    Nak nak{static_cast<std::uint8_t>(rng()), rng() % 2 == 0 ? Error::SequenceError : Error::QueueFull};
    const auto n = round_trip(nak).get<Nak>();
    CHECK((n.expected == nak.expected && n.reason == nak.reason));

    MachineConfiguration config;
    config.axis_count = static_cast<std::uint8_t>(2 + rng() % 2);
    config.profile = rng() % 2 == 0 ? ProfileKind::SCurve : ProfileKind::Trapezoid;
    config.max_velocity_mm_per_s = random_double(rng);
    config.max_acceleration_mm_per_s2 = random_double(rng);
    config.max_jerk_mm_per_s3 = random_double(rng);
    config.tolerance_mm = random_double(rng);
    config.junction_deviation_mm = random_double(rng);
    config.max_step_rate_hz = random_double(rng);
    config.default_feed_mm_per_s = random_raw(rng);
    config.rapid_mm_per_s = random_raw(rng);
    config.control_rate_hz = static_cast<std::uint32_t>(rng());
    for (std::size_t ax = 0; ax < config.axis_count; ++ax) {
      config.axes[ax] = AxisConfiguration{random_double(rng), random_double(rng), random_double(rng), random_raw(rng),
                                          random_raw(rng)};
    }
    const auto m = round_trip(config).get<MachineConfiguration>();
    // binary64 fields compare bit for bit (the wire carries the exact pattern)
    const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
    CHECK((m.axis_count == config.axis_count && m.profile == config.profile &&
           bits(m.max_velocity_mm_per_s) == bits(config.max_velocity_mm_per_s) &&
           bits(m.max_acceleration_mm_per_s2) == bits(config.max_acceleration_mm_per_s2) &&
           bits(m.max_jerk_mm_per_s3) == bits(config.max_jerk_mm_per_s3) &&
           bits(m.tolerance_mm) == bits(config.tolerance_mm) &&
           bits(m.junction_deviation_mm) == bits(config.junction_deviation_mm) &&
           bits(m.max_step_rate_hz) == bits(config.max_step_rate_hz) &&
           m.default_feed_mm_per_s == config.default_feed_mm_per_s && m.rapid_mm_per_s == config.rapid_mm_per_s &&
           m.control_rate_hz == config.control_rate_hz));
    for (std::size_t ax = 0; ax < config.axis_count; ++ax) {
      CHECK((bits(m.axes[ax].steps_per_mm) == bits(config.axes[ax].steps_per_mm) &&
             m.axes[ax].min_position_mm == config.axes[ax].min_position_mm &&
             m.axes[ax].max_position_mm == config.axes[ax].max_position_mm &&
             bits(m.axes[ax].max_velocity_mm_per_s) == bits(config.axes[ax].max_velocity_mm_per_s) &&
             bits(m.axes[ax].max_acceleration_mm_per_s2) == bits(config.axes[ax].max_acceleration_mm_per_s2)));
    }

    const QueueSegment segment = random_segment(rng);
    CHECK(same(round_trip(segment).get<QueueSegment>(), segment));

    CHECK(round_trip(Start{}).holds<Start>());
    CHECK(round_trip(FeedHold{}).holds<FeedHold>());
    CHECK(round_trip(Resume{}).holds<Resume>());
    CHECK(round_trip(Abort{}).holds<Abort>());
    CHECK(round_trip(StatusRequest{}).holds<StatusRequest>());

    StatusReport status;
    status.state = static_cast<MachineState>(rng() % 4);
    status.error = static_cast<std::uint8_t>(rng());
    status.axis_count = static_cast<std::uint8_t>(2 + rng() % 2);
    status.queue_depth = static_cast<std::uint16_t>(rng());
    status.max_queue_depth = static_cast<std::uint16_t>(rng());
    status.setpoint_index = static_cast<std::uint32_t>(rng());
    status.limit_switches = static_cast<std::uint8_t>(rng());
    status.tick_overruns = static_cast<std::uint32_t>(rng());
    status.worst_tick_us = static_cast<std::uint32_t>(rng());
    status.feed_override_percent = static_cast<std::uint16_t>(rng());
    status.rapid_override_percent = static_cast<std::uint16_t>(rng());
    status.override_index = static_cast<std::uint32_t>(rng());
    status.position = random_point(rng, status.axis_count);
    const auto s = round_trip(status).get<StatusReport>();
    CHECK((s.state == status.state && s.error == status.error && s.axis_count == status.axis_count &&
           s.queue_depth == status.queue_depth && s.max_queue_depth == status.max_queue_depth &&
           s.setpoint_index == status.setpoint_index && s.limit_switches == status.limit_switches &&
           s.tick_overruns == status.tick_overruns && s.worst_tick_us == status.worst_tick_us &&
           s.rapid_override_percent == status.rapid_override_percent && s.override_index == status.override_index &&
           s.position == status.position));

    SetpointBatch setpoints;
    setpoints.first_index = static_cast<std::uint32_t>(rng());
    setpoints.axis_count = static_cast<std::uint8_t>(2 + rng() % 2);
    setpoints.count = static_cast<std::uint8_t>(1 + rng() % 4);  // any deltas, even full-range ones, fit 4 setpoints
    for (std::size_t k = 0; k < setpoints.count; ++k) setpoints.setpoints[k] = random_point(rng, setpoints.axis_count);
    const auto b = round_trip(setpoints).get<SetpointBatch>();
    CHECK((b.first_index == setpoints.first_index && b.axis_count == setpoints.axis_count &&
           b.count == setpoints.count && b.setpoints == setpoints.setpoints));

    ErrorReport report{Error::BadPayload, static_cast<std::uint16_t>(rng()), static_cast<std::uint8_t>(rng())};
    const auto e = round_trip(report).get<ErrorReport>();
    CHECK((e.code == report.code && e.index == report.index && e.sequence == report.sequence));
  }
}

TEST_CASE("messages: a setpoint batch encodes as hand-computed zig-zag varints", "[protocol][messages]") {
  // first index 1000; (1, 2, -0.5) mm; then deltas (+100, -1, 0) and (+8192, -8193, +63) raw.
  // zig-zag: 100 -> 200 = c8 01; -1 -> 1 = 01; 0 -> 00; 8192 -> 16384 = 80 80 01;
  // -8193 -> 16385 = 81 80 01; 63 -> 126 = 7e.
  const auto b = batch(1000, 3, {{65536, 131072, -32768}, {65636, 131071, -32768}, {73828, 122878, -32705}});
  CHECK(to_hex(payload_of(b)) ==
        "e8 03 00 00 03 03 00 00 01 00 00 00 02 00 00 80 ff ff c8 01 01 00 80 80 01 81 80 01 7e");
  CHECK(encoded_size(b, 3) == 29);
}

TEST_CASE("messages: Capabilities encodes its 20 bytes little-endian with the look-ahead last", "[protocol][messages]") {
  const Capabilities c{.version = 4, .session = 0x1234, .max_payload = 162, .queue_capacity = 16, .credit_end = 16,
                       .axis_count = 3, .max_degree = 7, .tick_rate_hz = 1000000, .lookahead = 8};
  // docs/protocol.md, Capabilities: u16 version, session, max_payload, queue, credit; u8 32, 16,
  // axes, degree; u32 tick rate (1000000 = 0x000f4240); u16 look-ahead.
  CHECK(to_hex(payload_of(Message(c))) == "04 00 34 12 a2 00 10 00 10 00 20 10 03 07 40 42 0f 00 08 00");
}

TEST_CASE("messages: Capabilities with look-ahead 0 decodes (version 4: no planner on board)", "[protocol][messages]") {
  // version 4, session 0, payload 162, queue 16, credit 16, 32/16 bits, 3 axes, degree 7, 1 MHz, look-ahead 0
  const auto c = decode<Capabilities>(hex("0400 0000 a200 1000 1000 20 10 03 07 40420f00 0000"));
  REQUIRE(c.has_value());
  CHECK(c.value().lookahead == 0);
  CHECK(c.value().version == 4);
  CHECK(c.value().tick_rate_hz == 1000000);
}

TEST_CASE("messages: Capabilities with degree 0 decodes only with look-ahead 0 (a controller without a planner takes no segments)",
          "[protocol][messages]") {
  // As above with degree 0 (byte 13): what App<_, _, _, 0> sends.
  const auto executor = decode<Capabilities>(hex("0400 0000 a200 1000 1000 20 10 03 00 40420f00 0000"));
  REQUIRE(executor.has_value());
  CHECK(executor.value().max_degree == 0);
  // Degree 0 with look-ahead 8, and degree 8 with look-ahead 0, are refused at the degree byte.
  const auto planner = decode<Capabilities>(hex("0400 0000 a200 1000 1000 20 10 03 00 40420f00 0800"));
  REQUIRE_FALSE(planner.has_value());
  CHECK(planner.error() == curvestep::Error::BadPayload);
  CHECK(planner.failure().index == 13);
  const auto too_high = decode<Capabilities>(hex("0400 0000 a200 1000 1000 20 10 03 08 40420f00 0000"));
  REQUIRE_FALSE(too_high.has_value());
  CHECK(too_high.failure().index == 13);
}

TEST_CASE("messages: a 3-axis 1 kHz setpoint stream fits 115200 baud with 39 percent spare", "[protocol][messages]") {
  // Worst case of docs/protocol.md: every axis moves 8191 raw (0.125 mm) per 1 ms setpoint,
  // i.e. 125 mm/s per axis, so every delta takes two varint bytes.
  SetpointBatch b;
  b.axis_count = 3;
  b.count = max_setpoints_per_batch;
  for (std::size_t k = 1; k < b.count; ++k) {
    const auto step = static_cast<std::int32_t>(k) * 8191;
    b.setpoints[k] = {step, -step, k % 2 == 1 ? 8191 : 0};
  }
  CHECK(encoded_size(b, b.count) == 6 + 12 + 23 * 6);
  std::vector<std::byte> wire(max_encoded_frame_size);
  const auto size = encode_frame(Message(b), 0, wire);
  REQUIRE(size.has_value());
  CHECK(size.value() == 166);  // 2 header + 156 message + 4 CRC-32C + 2 CRC-16 + 1 COBS code + 1 delimiter
  const double bytes_per_second = 166.0 * 1000.0 / static_cast<double>(max_setpoints_per_batch);
  const double link_bytes_per_second = 115200.0 / 10.0;  // 8N1: 10 bit times per byte
  CHECK(bytes_per_second == Approx(6916.667).epsilon(1e-6));
  CHECK(bytes_per_second <= 0.61 * link_bytes_per_second);  // 60.04 %
}

TEST_CASE("messages: the encoder refuses batches that leave the payload limit", "[protocol][messages]") {
  SetpointBatch b;
  b.axis_count = 3;
  b.count = max_setpoints_per_batch;
  for (std::size_t k = 0; k < b.count; ++k) {
    const std::int32_t big = k % 2 == 0 ? 0x40000000 : -0x40000000;
    b.setpoints[k] = {big, big, big};
  }
  std::array<std::byte, max_message_size> out{};
  const auto r = encode(b, out);
  REQUIRE_FALSE(r.has_value());
  CHECK(r.error() == Error::BufferTooSmall);
  CHECK(encoded_size(b, b.count) > max_message_size);
}

TEST_CASE("messages: every truncation of every payload is BadPayload", "[protocol][messages]") {
  std::mt19937 rng(curvestep::testing::test_seed());
  QueueSegment rational = random_segment(rng);
  rational.kind = SegmentKind::RationalBezier;
  rational.degree = 7;
  rational.axis_count = 3;
  for (std::size_t i = 0; i < 8; ++i) rational.weights[i] = 65536;
  MachineConfiguration config;
  QueuePiece chunk;
  chunk.ticks = 8;
  chunk.end = {1.5, -2.0, 0.25};
  chunk.controls[4] = {1.0, 2.0, 3.0};
  QueuePiece exact;
  exact.axis_count = 2;
  exact.end = {-2.0, 1.5, 0.0};
  const std::vector<Message> messages{Message(Hello{}),          Message(Capabilities{}), Message(Ack{}),
                                      Message(Nak{}),            Message(config),         Message(rational),
                                      Message(chunk),            Message(exact),          Message(StatusReport{}),
                                      Message(batch(5, 2, {{1, 2, 0}, {300, -300, 0}})),
                                      Message(ErrorReport{})};
  for (const Message& m : messages) {
    const auto payload = payload_of(m);
    INFO("type " << static_cast<int>(m.type()) << " payload " << to_hex(payload));
    for (std::size_t n = 0; n < payload.size(); ++n) {
      const auto r = decode_message(static_cast<std::uint8_t>(m.type()), std::span<const std::byte>(payload).first(n));
      REQUIRE_FALSE(r.has_value());
      CHECK(r.error() == Error::BadPayload);
    }
    auto longer = payload;
    longer.push_back(std::byte{0});
    const auto r = decode_message(static_cast<std::uint8_t>(m.type()), longer);
    REQUIRE_FALSE(r.has_value());
    CHECK(r.error() == Error::BadPayload);
    CHECK(r.where() == payload.size());
  }
}

TEST_CASE("messages: empty commands reject any payload byte", "[protocol][messages]") {
  const auto one = hex("00");
  for (const MessageType t : {MessageType::Start, MessageType::FeedHold, MessageType::Resume, MessageType::Abort,
                              MessageType::StatusRequest}) {
    CHECK(decode_message(static_cast<std::uint8_t>(t), {}).has_value());
    CHECK(decode_message(static_cast<std::uint8_t>(t), one).error() == Error::BadPayload);
  }
}

TEST_CASE("messages: unknown message types are UnknownMessage with the type as index", "[protocol][messages]") {
  for (int t = 0; t < 256; ++t) {
    const auto type = static_cast<std::uint8_t>(t);
    const auto r = decode_message(type, {});
    if (is_known(type)) continue;
    REQUIRE_FALSE(r.has_value());
    CHECK(r.error() == Error::UnknownMessage);
    CHECK(r.where() == t);
  }
}

TEST_CASE("messages: malformed segment fields are BadPayload at their byte offset", "[protocol][messages]") {
  // kind 4 does not exist
  CHECK(decode<QueueSegment>(hex("04 00")).where() == 0);
  // the rest flag (0x80; end of job in version 1) with a rest of 0 ticks (offset 2)
  CHECK(decode<QueueSegment>(hex("00 80 00000000 00000000 00000000 00000000 00000000")).where() == 2);
  // the rest flag with its count cut short: the payload ends at offset 2
  CHECK(decode<QueueSegment>(hex("00 80 0000")).error() == Error::BadPayload);
  // the turns flag on a line
  CHECK(decode<QueueSegment>(hex("00 20 00000000 00000000 00000000 00000000 00000000")).where() == 1);
  // an arc with the turns flag but zero turns (offset 2)
  CHECK(decode<QueueSegment>(hex("01 20 00000000 00000000 00000000 00000000 00000000 00000000 00000000")).where() == 2);
  // clockwise flag on a line
  CHECK(decode<QueueSegment>(hex("00 08 00000000 00000000 00000000 00000000")).where() == 1);
  // Bezier of degree 0 and 8
  CHECK(decode<QueueSegment>(hex("02 00 00")).where() == 2);
  CHECK(decode<QueueSegment>(hex("02 00 08")).where() == 2);
  // rational linear segment with weight 0 for the second point (offset 3 + 16 + 4)
  const auto r = decode<QueueSegment>(hex("03 00 01 00000000 00000000 00000100 00000000 00000100 00000000"));
  REQUIRE_FALSE(r.has_value());
  CHECK(r.error() == Error::BadPayload);
  CHECK(r.where() == 23);
  // the same with weight 1.0 decodes
  CHECK(decode<QueueSegment>(hex("03 00 01 00000000 00000000 00000100 00000000 00000100 00000100")).has_value());
}

TEST_CASE("messages: other malformed fields are BadPayload", "[protocol][messages]") {
  CHECK(decode<Nak>(hex("05 00")).error() == Error::BadPayload);            // reason 0 is not an error
  CHECK(decode<StatusReport>(hex("04 00 02 0000 0000 00000000 00 00000000 00000000 6400 6400 00000000 00000000 00000000")).where() == 0);  // state 4
  CHECK(decode<StatusReport>(hex("00 00 04 0000 0000 00000000 00 00000000 00000000 6400 6400 00000000 00000000 00000000")).where() == 2);  // 4 axes
  CHECK(decode<SetpointBatch>(hex("00000000 03 00")).where() == 5);         // zero setpoints
  CHECK(decode<SetpointBatch>(hex("00000000 03 19")).where() == 5);         // 25 setpoints
  CHECK(decode<MachineConfiguration>(hex("01")).where() == 0);              // one axis
  CHECK(decode<MachineConfiguration>(hex("02 02")).where() == 1);           // reserved profile flag bit 1
  CHECK(decode<Capabilities>(hex("0100 0000 a000 1000 1000 20 10 05 07 00000000 0100")).where() == 12);  // 5 axes
  // a varint longer than 5 bytes, and a delta that leaves the int32 range
  CHECK(decode<SetpointBatch>(hex("00000000 02 02 00000000 00000000 ffffffffff01 00")).error() == Error::BadPayload);
  const auto overflow = decode<SetpointBatch>(hex("00000000 02 02 ffffff7f 00000000 02 00"));
  REQUIRE_FALSE(overflow.has_value());
  CHECK(overflow.where() == 14);  // the first delta: 4 + 1 + 1 + 2 * 4
}

TEST_CASE("messages: encoders refuse messages that cannot be represented", "[protocol][messages]") {
  std::array<std::byte, max_payload_size> out{};
  QueueSegment s;
  s.kind = SegmentKind::Bezier;
  s.degree = 8;
  CHECK(encode(s, out).error() == Error::InvalidArgument);
  s.degree = 2;
  s.axis_count = 4;
  CHECK(encode(s, out).error() == Error::InvalidArgument);
  s.axis_count = 2;
  s.kind = SegmentKind::RationalBezier;
  s.weights = {65536, 0, 65536};
  const auto w = encode(s, out);
  CHECK(w.error() == Error::NonPositiveWeight);
  CHECK(w.where() == 1);
  SetpointBatch empty;
  CHECK(encode(empty, out).error() == Error::InvalidArgument);
  std::array<std::byte, 3> tiny{};
  CHECK(encode(Capabilities{}, tiny).error() == Error::BufferTooSmall);
  QueueSegment line_with_turns;
  line_with_turns.turns = 1;
  CHECK(encode(line_with_turns, out).error() == Error::InvalidArgument);
}

TEST_CASE("messages: a MachineConfiguration of two axes encodes as hand-computed binary64 and Q16.16 fields",
          "[protocol][messages]") {
  MachineConfiguration c;
  c.axis_count = 2;
  c.profile = ProfileKind::Trapezoid;
  c.max_velocity_mm_per_s = 200;
  c.max_acceleration_mm_per_s2 = 2000;
  c.max_jerk_mm_per_s3 = 50000;
  c.tolerance_mm = 0.01;
  c.junction_deviation_mm = 0.05;
  c.max_step_rate_hz = 100000;
  c.default_feed_mm_per_s = 50 * 65536;
  c.rapid_mm_per_s = 0;
  c.control_rate_hz = 1000;
  for (std::size_t a = 0; a < 2; ++a) c.axes[a] = AxisConfiguration{80, 200, 2000, -100 * 65536, 100 * 65536};
  // Python: struct.pack('<BBdddddd', 2, 1, 200, 2000, 50000, 0.01, 0.05, 100000) + '<iiI' (50 << 16, 0, 1000)
  // + 2 x ('<ddd', 80, 200, 2000) + '<ii' (-100 << 16, 100 << 16): 62 + 2 x 32 = 126 bytes (docs/protocol.md)
  const auto expected = hex(
      "02 01 0000000000006940 0000000000409f40 00000000006ae840 7b14ae47e17a843f 9a9999999999a93f 00000000006af840"
      " 00003200 00000000 e8030000"
      " 0000000000005440 0000000000006940 0000000000409f40 00009cff 00006400"
      " 0000000000005440 0000000000006940 0000000000409f40 00009cff 00006400");
  CHECK(to_hex(payload_of(c)) == to_hex(expected));
  CHECK(expected.size() == configuration_header_size + 2 * configuration_axis_size);
  MachineConfiguration three = c;
  three.axis_count = 3;
  CHECK(payload_of(three).size() == 158);
  CHECK(payload_of(three).size() <= max_message_size);
}

TEST_CASE("messages: a helical arc carries its extra turns and the end-of-job flag", "[protocol][messages]") {
  QueueSegment s;
  s.kind = SegmentKind::Arc;
  s.axis_count = 3;
  s.degree = 2;
  s.end_of_job = true;
  s.turns = 2;
  s.points[0] = WirePoint{10 * 65536, 0, 0};
  s.points[1] = WirePoint{10 * 65536, 0, -65536};
  s.points[2] = WirePoint{0, 0, 0};
  // kind 1, flags 0x34 (three axes 0x04, end of job 0x10, turns 0x20), turns 2, start, end, centre XY
  const auto expected = hex("01 34 02000000 00000a00 00000000 00000000 00000a00 00000000 0000ffff 00000000 00000000");
  CHECK(to_hex(payload_of(s)) == to_hex(expected));
  const auto back = decode<QueueSegment>(expected);
  REQUIRE(back.has_value());
  CHECK(back.value().turns == 2);
  CHECK(back.value().end_of_job);
  CHECK(back.value().points[1][2] == -65536);
}

TEST_CASE("messages: a segment after a dwell carries its stop and rest ticks", "[protocol][messages]") {
  QueueSegment s;  // a 2-axis line
  s.stop_before = true;
  s.rest_ticks = 500;
  s.points[0] = WirePoint{10 * 65536, 0, 0};
  s.points[1] = WirePoint{20 * 65536, 0, 0};
  // kind 0, flags 0xc0 (stop before 0x40, rest 0x80), rest 500 (0x1f4), start XY, end XY
  const auto expected = hex("00 c0 f4010000 00000a00 00000000 00001400 00000000");
  CHECK(to_hex(payload_of(s)) == to_hex(expected));
  const auto back = decode<QueueSegment>(expected);
  REQUIRE(back.has_value());
  CHECK(back.value().stop_before);
  CHECK(back.value().rest_ticks == 500);
  // The rest flag with a count of 0 is malformed at the count's offset (2).
  const auto zero = decode<QueueSegment>(hex("00 c0 00000000 00000a00 00000000 00001400 00000000"));
  REQUIRE_FALSE(zero.has_value());
  CHECK(zero.error() == Error::BadPayload);
  CHECK(zero.where() == 2);
  // A stop alone adds no byte.
  QueueSegment stop = s;
  stop.rest_ticks = 0;
  CHECK(to_hex(payload_of(stop)) == to_hex(hex("00 40 00000a00 00000000 00001400 00000000")));
}

TEST_CASE("messages: the job's last segment carries the rest after it in end_rest_ticks", "[protocol][messages]") {
  QueueSegment s;  // a 2-axis line, the job's last, then a 2 s dwell at 1 kHz
  s.end_of_job = true;
  s.end_rest_ticks = 2000;
  s.points[0] = WirePoint{0, 0, 0};
  s.points[1] = WirePoint{10 * 65536, 0, 0};
  // kind 0 | 0x80 (end rest), flags 0x10 (end of job), end rest 2000 (0x7d0), start XY, end XY
  const auto expected = hex("80 10 d0070000 00000000 00000000 00000a00 00000000");
  CHECK(to_hex(payload_of(s)) == to_hex(expected));
  const auto back = decode<QueueSegment>(expected);
  REQUIRE(back.has_value());
  CHECK(back.value().kind == SegmentKind::Line);
  CHECK(back.value().end_of_job);
  CHECK(back.value().end_rest_ticks == 2000);
  // Only on the job's last segment: without the end-of-job flag the kind byte is malformed (0).
  const auto not_last = decode<QueueSegment>(hex("80 00 d0070000 00000000 00000000 00000a00 00000000"));
  REQUIRE_FALSE(not_last.has_value());
  CHECK(not_last.error() == Error::BadPayload);
  CHECK(not_last.where() == 0);
  // A count of 0 is malformed at its offset (2); encoding refuses a rest without the flag.
  const auto zero = decode<QueueSegment>(hex("80 10 00000000 00000000 00000000 00000a00 00000000"));
  REQUIRE_FALSE(zero.has_value());
  CHECK(zero.where() == 2);
  QueueSegment middle = s;
  middle.end_of_job = false;
  std::array<std::byte, 160> out{};
  CHECK_FALSE(encode(middle, out).has_value());
}

TEST_CASE("messages: a StatusReport carries the deepest queue and the tick overruns of the session", "[protocol][messages]") {
  StatusReport r;
  r.state = MachineState::Running;
  r.axis_count = 3;
  r.queue_depth = 17;
  r.max_queue_depth = 32;
  r.setpoint_index = 123456;
  r.limit_switches = 0x06;  // x max (bit 1) and y min (bit 2) closed
  r.tick_overruns = 3;
  r.worst_tick_us = 612;
  r.position = WirePoint{65536, 2 * 65536, -32768};
  // Python: struct.pack('<BBBHHIBIIHHI', 1, 0, 3, 17, 32, 123456, 6, 3, 612, 100, 100, 0) + '<iii' (65536, 131072,
  // -32768): 40 bytes (the overrides at their defaults: 100 %, 100 %, set before setpoint 0)
  const auto bytes = hex("01 00 03 1100 2000 40e20100 06 03000000 64020000 6400 6400 00000000 00000100 00000200 0080ffff");
  CHECK(to_hex(payload_of(r)) == to_hex(bytes));
  const auto back = decode<StatusReport>(bytes);
  REQUIRE(back.has_value());
  CHECK(back.value().limit_switches == 0x06);
  CHECK(back.value().tick_overruns == 3);
  CHECK(back.value().worst_tick_us == 612);
  CHECK(back.value().feed_override_percent == 100);
  CHECK(back.value().position == r.position);
  // One byte short of the third axis: BadPayload.
  CHECK(decode<StatusReport>(std::span<const std::byte>(bytes).first(bytes.size() - 1)).error() == Error::BadPayload);
}

TEST_CASE("messages: setpoint batches travel in the sequenced stream toward the host only", "[protocol][messages]") {
  CHECK(is_sequenced_toward(Endpoint::Host, static_cast<std::uint8_t>(MessageType::SetpointBatch)));
  CHECK_FALSE(is_sequenced_toward(Endpoint::Controller, static_cast<std::uint8_t>(MessageType::SetpointBatch)));
  for (int t = 0x10; t <= 0x17; ++t) {
    CHECK(is_sequenced_toward(Endpoint::Controller, static_cast<std::uint8_t>(t)));
    CHECK_FALSE(is_sequenced_toward(Endpoint::Host, static_cast<std::uint8_t>(t)));
  }
  for (const MessageType t : {MessageType::Hello, MessageType::Capabilities, MessageType::Ack, MessageType::Nak,
                              MessageType::StatusReport, MessageType::ErrorReport}) {
    CHECK_FALSE(is_sequenced_toward(Endpoint::Controller, static_cast<std::uint8_t>(t)));
    CHECK_FALSE(is_sequenced_toward(Endpoint::Host, static_cast<std::uint8_t>(t)));
  }
  CHECK(is_sequenced_toward(Endpoint::Controller, 0x30));  // unknown: a command from a newer host
}

TEST_CASE("messages: the largest segment fits the payload limit", "[protocol][messages]") {
  QueueSegment s;
  s.kind = SegmentKind::RationalBezier;
  s.degree = 7;
  s.axis_count = 3;
  s.has_feed = true;
  s.weights.fill(65536);
  CHECK(payload_of(s).size() == 3 + 4 + 8 * 12 + 8 * 4);
  CHECK(payload_of(s).size() <= max_message_size);
}
