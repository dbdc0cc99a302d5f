// SPDX-License-Identifier: MIT
// FeedOverride (0x19): the payload written by hand from docs/protocol.md's byte table, its size,
// the round trip through a frame, and where it travels (a command toward the controller that
// takes no queue credit).
#include <catch2/catch.hpp>

#include <curvestep/protocol/messages.hpp>

#include "../support/bytes.hpp"
#include "../support/payload.hpp"

using namespace curvestep;
using namespace curvestep::protocol;
using curvestep::protocol::testing::hex;
using curvestep::protocol::testing::payload_of;
using curvestep::protocol::testing::to_hex;

static_assert(WireFields<FeedOverride>::size == 4);
static_assert(static_cast<std::uint8_t>(MessageType::FeedOverride) == 0x19 && is_known(0x19));
static_assert(is_command(MessageType::FeedOverride) && !consumes_credit(MessageType::FeedOverride));
static_assert(HostToController::contains<FeedOverride> && !ControllerToHost::contains<FeedOverride>);

TEST_CASE("feed override message: 150 percent feed and 25 percent rapid are 4 bytes in field order", "[protocol][messages]") {
  FeedOverride m;
  m.feed_percent = 150;
  m.rapid_percent = 25;
  // u16 feed 150 (0x0096), u16 rapid 25 (0x0019), little-endian
  const auto expected = hex("9600 1900");
  CHECK(to_hex(payload_of(m)) == to_hex(expected));
  const auto back = decode<FeedOverride>(expected);
  REQUIRE(back.has_value());
  CHECK(back.value().feed_percent == 150);
  CHECK(back.value().rapid_percent == 25);
}

TEST_CASE("feed override message: decodes as a Message by its type byte, and a short payload is refused at its end",
          "[protocol][messages]") {
  const auto message = decode_message(0x19, hex("0a00 6400"));
  REQUIRE(message.has_value());
  REQUIRE(message.value().holds<FeedOverride>());
  CHECK(message.value().get<FeedOverride>().feed_percent == 10);
  CHECK(message.value().get<FeedOverride>().rapid_percent == 100);
  CHECK(to_hex(payload_of(message.value())) == to_hex(hex("0a00 6400")));
  const auto cut = decode<FeedOverride>(hex("9600 19"));
  REQUIRE_FALSE(cut.has_value());
  CHECK(cut.error() == Error::BadPayload);
  CHECK(cut.where() == 3);  // the first missing byte
}
