// SPDX-License-Identifier: MIT
// Message sets: each endpoint's decoder takes exactly the types docs/protocol.md sends toward it,
// decodes them as the all-types decoder does, and refuses the others as UnknownMessage; the
// set-restricted encoders give the same bytes and refuse the others as InvalidArgument.
#include <catch2/catch.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <curvestep/protocol/frame.hpp>
#include <curvestep/protocol/messages.hpp>

#include "../support/bytes.hpp"
#include "../support/payload.hpp"

using namespace curvestep;
using namespace curvestep::protocol;
using curvestep::protocol::testing::hex;
using curvestep::protocol::testing::to_hex;

namespace {

/// The direction column of docs/protocol.md's table of message types.
enum class Direction { ToController, ToHost, Both };

/// One well-formed message per type, its payload written out by hand from the byte tables of
/// docs/protocol.md (not produced by the encoders).
struct Vector {
  std::uint8_t type;
  Direction direction;
  std::string payload;
};

std::string zeros(std::size_t count) {
  std::string out;
  for (std::size_t i = 0; i < count; ++i) out += "00 ";
  return out;
}

std::vector<Vector> vectors() {
  return {
      {0x01, Direction::ToController, "05 00 34 12"},  // Hello: version 5, session 0x1234
      // Capabilities: version 4, session 0x1234, payload 162, queue 16, credit 16, 32/16 bits,
      // 3 axes, degree 7, 1 MHz ticks, look-ahead 8
      {0x02, Direction::ToHost, "04 00 34 12 a2 00 10 00 10 00 20 10 03 07 40 42 0f 00 08 00"},
      {0x03, Direction::Both, "06 28 00"},  // Ack: next 6, credit edge 40
      {0x04, Direction::Both, "05 69"},     // Nak: expected 5, BadPayload (105)
      // MachineConfiguration: 2 axes, S-curve, max velocity 1.0 (binary64), every other field 0
      {0x10, Direction::ToController, "02 00 00 00 00 00 00 00 f0 3f " + zeros(62 - 10 + 2 * 32)},
      // QueueSegment: a 2-axis line, no flags, (1, 2) -> (3, 4) mm in Q16.16
      {0x11, Direction::ToController, "00 00 00 00 01 00 00 00 02 00 00 00 03 00 00 00 04 00"},
      {0x12, Direction::ToController, ""},  // Start
      {0x13, Direction::ToController, ""},  // FeedHold
      {0x14, Direction::ToController, ""},  // Resume
      {0x15, Direction::ToController, ""},  // Abort
      {0x16, Direction::ToController, ""},  // StatusRequest
      // QueuePiece: end of job, 2 axes, 1 tick (exact), segment 7, end (1.5, -2.0) mm in binary64
      {0x17, Direction::ToController, "01 02 01 00 07 00 00 00 00 00 00 00 00 00 f8 3f 00 00 00 00 00 00 00 c0"},
      // QueueEvent: before segment 3, 500 ticks into the rest there, SpindleOn, counter-clockwise, 1000 rev/min
      {0x18, Direction::ToController, "03 00 00 00 f4 01 00 00 01 01 e8 03 00 00"},
      {0x19, Direction::ToController, "96 00 32 00"},  // FeedOverride: feed 150 %, rapid 50 %
      // StatusReport: running, no error, 2 axes, depth 3, deepest 5, setpoint 100, no switch closed,
      // 2 tick overruns, worst tick 1234 us, feed override 150 %, rapid 50 %, set before setpoint 90,
      // at (1, -1) mm
      {0x20, Direction::ToHost, "01 00 02 03 00 05 00 64 00 00 00 00 02 00 00 00 d2 04 00 00 96 00 32 00 5a 00 00 00 00 00 01 00 00 00 ff ff"},
      // SetpointBatch: the hand-computed zig-zag batch of messages_test.cpp
      {0x21, Direction::ToHost, "e8 03 00 00 03 03 00 00 01 00 00 00 02 00 00 80 ff ff c8 01 01 00 80 80 01 81 80 01 7e"},
      {0x22, Direction::ToHost, "69 04 00 07"},  // ErrorReport: BadPayload, index 4, sequence 7
      {0x23, Direction::ToHost, "05 04 00 00 0a 02 00 00 00"},  // PauseReport: setpoint 1029, tool change, tool 2
      {0x1a, Direction::ToController, "03"},  // SeekSwitch: switch 3 (y max)
      // SetPosition: axes x and z (0b101), x 1 mm, y 0, z -0.5 mm
      {0x1b, Direction::ToController, "05 00 00 01 00 00 00 00 00 00 80 ff ff"},
      // SwitchReport: switch 0 (x min), setpoint 300, at (-3.3 mm as 0xfffcb333, 2 mm, 0)
      {0x24, Direction::ToHost, "00 2c 01 00 00 33 b3 fc ff 00 00 02 00 00 00 00 00"},
  };
}

bool toward_controller(Direction d) { return d != Direction::ToHost; }
bool toward_host(Direction d) { return d != Direction::ToController; }

using curvestep::protocol::testing::payload_of;

/// `Set`'s decoder on every vector: the types `in_set` names decode exactly as the all-types
/// decoder does (same type, and the payload encodes back to the same bytes); the others are
/// UnknownMessage with the type as index. Every type is also checked truncated by one byte.
template <class Set, class InSet>
void check_decoder(InSet in_set) {
  for (const Vector& v : vectors()) {
    INFO("type " << static_cast<int>(v.type));
    const auto payload = hex(v.payload);
    const auto all = decode_message(v.type, payload);
    REQUIRE(all.has_value());
    CHECK(to_hex(payload_of(all.value())) == to_hex(payload));
    const auto mine = decode_message<Set>(v.type, payload);
    if (in_set(v)) {
      REQUIRE(mine.has_value());
      CHECK(mine.value().type() == static_cast<MessageType>(v.type));
      CHECK(to_hex(payload_of(mine.value())) == to_hex(payload));
    } else {
      REQUIRE_FALSE(mine.has_value());
      CHECK(mine.error() == Error::UnknownMessage);
      CHECK(mine.where() == v.type);
    }
    if (payload.empty()) continue;
    const auto cut = std::span<const std::byte>(payload).first(payload.size() - 1);
    const auto all_cut = decode_message(v.type, cut);
    const auto mine_cut = decode_message<Set>(v.type, cut);
    REQUIRE_FALSE(all_cut.has_value());
    REQUIRE_FALSE(mine_cut.has_value());
    CHECK(mine_cut.error() == (in_set(v) ? all_cut.error() : Error::UnknownMessage));
    CHECK(mine_cut.where() == (in_set(v) ? all_cut.where() : v.type));
  }
}

// Compile-time: the named sets against the direction column of docs/protocol.md.
static_assert(HostToController::contains<Hello> && HostToController::contains<Ack> && HostToController::contains<Nak> &&
              HostToController::contains<MachineConfiguration> && HostToController::contains<QueueSegment> &&
              HostToController::contains<Start> && HostToController::contains<FeedHold> &&
              HostToController::contains<Resume> && HostToController::contains<Abort> &&
              HostToController::contains<StatusRequest> && HostToController::contains<QueuePiece>);
static_assert(!HostToController::contains<Capabilities> && !HostToController::contains<StatusReport> &&
              !HostToController::contains<SetpointBatch> && !HostToController::contains<ErrorReport>);
static_assert(ControllerToHost::contains<Capabilities> && ControllerToHost::contains<Ack> &&
              ControllerToHost::contains<Nak> && ControllerToHost::contains<StatusReport> &&
              ControllerToHost::contains<SetpointBatch> && ControllerToHost::contains<ErrorReport>);
static_assert(!ControllerToHost::contains<Hello> && !ControllerToHost::contains<MachineConfiguration> &&
              !ControllerToHost::contains<QueueSegment> && !ControllerToHost::contains<Start> &&
              !ControllerToHost::contains<StatusRequest> && !ControllerToHost::contains<QueuePiece>);
static_assert(!MessageSet<>::contains<Hello> && !MessageSet<>::contains_type(0x01));

/// AllMessages holds exactly the types is_known() names.
constexpr bool all_messages_are_the_known_types() {
  for (int t = 0; t < 256; ++t) {
    const auto type = static_cast<std::uint8_t>(t);
    if (AllMessages::contains_type(type) != is_known(type)) return false;
  }
  return true;
}
static_assert(all_messages_are_the_known_types());

/// Every type of `set` is sequenced toward `receiver` or travels outside both streams: a set
/// never contains a type of the other direction's stream.
template <class... Ts>
constexpr bool no_foreign_stream(MessageSet<Ts...>, Endpoint receiver) {
  const Endpoint sender = receiver == Endpoint::Host ? Endpoint::Controller : Endpoint::Host;
  return (!is_sequenced_toward(sender, static_cast<std::uint8_t>(Ts::type)) && ...);
}
static_assert(no_foreign_stream(HostToController{}, Endpoint::Controller));
static_assert(no_foreign_stream(ControllerToHost{}, Endpoint::Host));

// Compile-time decoding: a set's decoder works in constant expressions too.
constexpr std::array<std::byte, 3> ack_payload{std::byte{0x06}, std::byte{0x28}, std::byte{0x00}};
static_assert(decode_message<ControllerToHost>(0x03, ack_payload).value().get<Ack>().credit_end == 40);
static_assert(decode_message<HostToController>(0x22, {}).error() == Error::UnknownMessage);
static_assert(decode_message<HostToController>(0x22, {}).where() == 0x22);

}  // namespace

TEST_CASE("message sets: the named sets hold exactly the types docs/protocol.md sends toward each end",
          "[protocol][messages]") {
  std::vector<bool> listed(256, false);
  for (const Vector& v : vectors()) {
    INFO("type " << static_cast<int>(v.type));
    listed[v.type] = true;
    CHECK(HostToController::contains_type(v.type) == toward_controller(v.direction));
    CHECK(ControllerToHost::contains_type(v.type) == toward_host(v.direction));
    CHECK(AllMessages::contains_type(v.type));
  }
  for (int t = 0; t < 256; ++t) {
    if (listed[static_cast<std::size_t>(t)]) continue;
    const auto type = static_cast<std::uint8_t>(t);
    CHECK_FALSE(AllMessages::contains_type(type));
    CHECK_FALSE(HostToController::contains_type(type));
    CHECK_FALSE(ControllerToHost::contains_type(type));
  }
}

TEST_CASE("message sets: a controller's decoder takes the host's messages and refuses the others as UnknownMessage",
          "[protocol][messages]") {
  check_decoder<HostToController>([](const Vector& v) { return toward_controller(v.direction); });
}

TEST_CASE("message sets: a host's decoder takes the controller's messages and refuses the others as UnknownMessage",
          "[protocol][messages]") {
  check_decoder<ControllerToHost>([](const Vector& v) { return toward_host(v.direction); });
}

TEST_CASE("message sets: a small set of its own and the empty set decode only their types",
          "[protocol][messages]") {
  check_decoder<MessageSet<Ack, Nak>>([](const Vector& v) { return v.type == 0x03 || v.type == 0x04; });
  check_decoder<MessageSet<>>([](const Vector&) { return false; });
  check_decoder<AllMessages>([](const Vector&) { return true; });
}

TEST_CASE("message sets: every type outside a decoder's set is UnknownMessage, defined or not",
          "[protocol][messages]") {
  for (int t = 0; t < 256; ++t) {
    const auto type = static_cast<std::uint8_t>(t);
    if (HostToController::contains_type(type)) continue;
    const auto r = decode_message<HostToController>(type, {});
    REQUIRE_FALSE(r.has_value());
    CHECK(r.error() == Error::UnknownMessage);
    CHECK(r.where() == t);
  }
}

TEST_CASE("message sets: a set's encoders give the all-types bytes and refuse other types as InvalidArgument",
          "[protocol][messages]") {
  for (const Vector& v : vectors()) {
    INFO("type " << static_cast<int>(v.type));
    const auto payload = hex(v.payload);
    const Message m = decode_message(v.type, payload).value();
    std::vector<std::byte> out(max_payload_size);
    const auto to_controller = encode<HostToController>(m, out);
    if (toward_controller(v.direction)) {
      REQUIRE(to_controller.has_value());
      CHECK(to_hex(std::span<const std::byte>(out).first(to_controller.value())) == to_hex(payload));
    } else {
      REQUIRE_FALSE(to_controller.has_value());
      CHECK(to_controller.error() == Error::InvalidArgument);
      CHECK(to_controller.where() == v.type);
    }
    // Frames: the set's encode_frame gives the all-types frame, or refuses the type.
    std::vector<std::byte> all_frame(max_encoded_frame_size);
    std::vector<std::byte> host_frame(max_encoded_frame_size);
    const auto all_size = encode_frame(m, 9, all_frame);
    REQUIRE(all_size.has_value());
    all_frame.resize(all_size.value());
    const auto host_size = encode_frame<ControllerToHost>(m, 9, host_frame);
    if (toward_host(v.direction)) {
      REQUIRE(host_size.has_value());
      host_frame.resize(host_size.value());
      CHECK(to_hex(host_frame) == to_hex(all_frame));
    } else {
      REQUIRE_FALSE(host_size.has_value());
      CHECK(host_size.error() == Error::InvalidArgument);
      CHECK(host_size.where() == v.type);
    }
  }
}

TEST_CASE("message sets: encoding a message struct as a frame gives the bytes of the Message frame",
          "[protocol][messages]") {
  const Ack ack{6, 40};
  std::vector<std::byte> typed(max_encoded_frame_size);
  std::vector<std::byte> held(max_encoded_frame_size);
  const auto typed_size = encode_frame(ack, 7, typed);
  const auto held_size = encode_frame(Message(ack), 7, held);
  REQUIRE(typed_size.has_value());
  REQUIRE(held_size.has_value());
  typed.resize(typed_size.value());
  held.resize(held_size.value());
  CHECK(to_hex(typed) == to_hex(held));
  // The frame carries type 0x03, sequence 7 and the message 06 28 00.
  std::vector<std::byte> raw(max_frame_size);
  const auto raw_size = cobs_decode(std::span<const std::byte>(typed).first(typed.size() - 1), raw);
  REQUIRE(raw_size.has_value());
  const auto parsed = parse_frame(std::span<const std::byte>(raw).first(raw_size.value()));
  REQUIRE(parsed.has_value());
  CHECK(parsed.value().type == 0x03);
  CHECK(parsed.value().sequence == 7);
  CHECK(to_hex(parsed.value().payload) == "06 28 00");
}
