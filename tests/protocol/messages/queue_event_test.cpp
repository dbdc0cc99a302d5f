// SPDX-License-Identifier: MIT
// QueueEvent (0x18) and the messages described once by WireFields (Hello, Ack, Nak, ErrorReport):
// payloads written by hand from docs/protocol.md's byte tables, sizes, and refusals at the byte
// offset of the bad field.
#include <array>
#include <cstddef>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/protocol/messages.hpp>

#include "../support/bytes.hpp"
#include "../support/payload.hpp"

using namespace curvestep;
using namespace curvestep::protocol;
using curvestep::protocol::testing::hex;
using curvestep::protocol::testing::payload_of;
using curvestep::protocol::testing::to_hex;

// The sizes docs/protocol.md gives for the described messages.
static_assert(WireFields<Hello>::size == 4 && WireFields<Ack>::size == 3 && WireFields<Nak>::size == 2 &&
              WireFields<ErrorReport>::size == 4 && WireFields<QueueEvent>::size == 14);
static_assert(is_command(MessageType::QueueEvent) && consumes_credit(MessageType::QueueEvent));
static_assert(HostToController::contains<QueueEvent> && !ControllerToHost::contains<QueueEvent>);

TEST_CASE("queue event: an M4 S1000 after a dwell is 14 bytes in field order", "[protocol][messages]") {
  QueueEvent e;
  e.segment = 3;
  e.after_rest_ticks = 500;
  e.kind = MachineEventKind::SpindleOn;
  e.flag = true;
  e.value = 1000;
  // u32 segment 3, u32 after_rest_ticks 500 (0x1f4), u8 kind 1, u8 flag 1, u32 value 1000 (0x3e8)
  const auto expected = hex("03000000 f4010000 01 01 e8030000");
  CHECK(to_hex(payload_of(e)) == to_hex(expected));
  const auto back = decode<QueueEvent>(expected);
  REQUIRE(back.has_value());
  CHECK(back.value().segment == 3);
  CHECK(back.value().after_rest_ticks == 500);
  CHECK(back.value().kind == MachineEventKind::SpindleOn);
  CHECK(back.value().flag);
  CHECK(back.value().value == 1000);
}

TEST_CASE("queue event: a bad kind or flag is BadPayload at its byte, a short or long payload at its end",
          "[protocol][messages]") {
  const auto at = [](const char* text) { return decode<QueueEvent>(hex(text)); };
  CHECK(at("03000000 00000000 00 00 00000000").where() == 8);  // kind 0
  CHECK(at("03000000 00000000 0e 00 00000000").where() == 8);  // kind 14
  CHECK(at("03000000 00000000 07 02 00000000").where() == 9);  // flag 2
  const auto short_one = at("03000000 00000000 07 01 000000");
  REQUIRE_FALSE(short_one.has_value());
  CHECK(short_one.error() == Error::BadPayload);
  CHECK(short_one.where() == 13);
  CHECK(at("03000000 00000000 07 01 00000000 00").where() == 14);
  CHECK(at("03000000 00000000 0d 00 00000000").has_value());  // ProgramEnd, the last kind
}

TEST_CASE("described messages: the wire bytes of Hello, Ack, Nak and ErrorReport", "[protocol][messages]") {
  // The bytes of docs/protocol.md's tables (unchanged by describing the messages once).
  CHECK(to_hex(payload_of(Hello{4, 0x1234})) == to_hex(hex("0400 3412")));
  CHECK(to_hex(payload_of(Ack{6, 40})) == to_hex(hex("06 2800")));
  CHECK(to_hex(payload_of(Nak{5, Error::BadPayload})) == to_hex(hex("05 69")));
  CHECK(to_hex(payload_of(ErrorReport{Error::BadPayload, 4, 7})) == to_hex(hex("69 0400 07")));
  // An error code of 0 is "no error": refused at its byte.
  CHECK(decode<Nak>(hex("05 00")).where() == 1);
  CHECK(decode<ErrorReport>(hex("00 0400 07")).where() == 0);
  CHECK(decode<Ack>(hex("06 28")).where() == 2);
}

TEST_CASE("pause report: a tool change to tool 2 at setpoint 1029 is 9 bytes", "[protocol][messages]") {
  static_assert(WireFields<PauseReport>::size == 9 && ControllerToHost::contains<PauseReport>);
  const PauseReport r{1029, MachineEventKind::ToolChange, 2};
  // u32 setpoint 1029 (0x405), u8 kind 10, u32 value 2
  CHECK(to_hex(payload_of(r)) == to_hex(hex("05040000 0a 02000000")));
  const auto back = decode<PauseReport>(hex("05040000 0a 02000000"));
  REQUIRE(back.has_value());
  CHECK(back.value().setpoint_index == 1029);
  CHECK(back.value().kind == MachineEventKind::ToolChange);
  CHECK(back.value().value == 2);
  CHECK(decode<PauseReport>(hex("05040000 00 02000000")).where() == 4);
}
