// SPDX-License-Identifier: MIT
// LinkSender<Window, Sends>: a sender restricted to its endpoint's messages puts the same bytes
// on the wire as the all-types sender, refuses other types, and has a handshake only with Hello.
#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

#include <curvestep/protocol/link_sender.hpp>

#include "link_harness.hpp"

using namespace curvestep;
using namespace curvestep::protocol;

namespace {

using testing::Bytes;
using testing::due_frames;
using SetpointOnly = LinkSender<4, MessageSet<SetpointBatch>>;

template <class Sender>
concept HasHandshake = requires(Sender& s) { s.connect(std::uint16_t{1}, std::uint32_t{0}); };

static_assert(HasHandshake<LinkSender<4>>);
static_assert(HasHandshake<LinkSender<4, HostToController>>);
static_assert(!HasHandshake<SetpointOnly>);
static_assert(!HasHandshake<LinkSender<4, ControllerToHost>>);

SetpointBatch batch(std::uint32_t first) {
  SetpointBatch b;
  b.first_index = first;
  b.axis_count = 2;
  b.count = 2;
  b.setpoints[0] = WirePoint{static_cast<std::int32_t>(first), -7, 0};
  b.setpoints[1] = WirePoint{static_cast<std::int32_t>(first) + 300, 9, 0};
  return b;
}

}  // namespace

TEST_CASE("link: a sender of setpoint batches only sends the all-types sender's bytes and refuses other types",
          "[protocol][link]") {
  LinkSender<4> all{SenderSettings{100, 3, 0}, Endpoint::Controller};
  SetpointOnly mine{SenderSettings{100, 3, 0}, Endpoint::Controller};
  all.open(0);
  mine.open(0);
  for (std::uint32_t i = 0; i < 3; ++i) {
    const auto a = all.submit(Message(batch(10 * i)));
    const auto b = mine.submit(Message(batch(10 * i)));
    REQUIRE(a.has_value());
    REQUIRE(b.has_value());
    CHECK(a.value() == b.value());
  }
  const auto all_frames = due_frames(all, 1);
  REQUIRE(all_frames.size() == 3);
  CHECK(due_frames(mine, 1) == all_frames);
  // A Nak of the second batch: both go back and resend the same two frames.
  const Message nak(Nak{1, Error::SequenceError});
  REQUIRE(all.on_message(Message(Ack{1, 0}), 2).has_value());
  REQUIRE(mine.on_message(Message(Ack{1, 0}), 2).has_value());
  REQUIRE(all.on_message(nak, 2).has_value());
  REQUIRE(mine.on_message(nak, 2).has_value());
  const auto resent = due_frames(all, 3);
  REQUIRE(resent.size() == 2);
  CHECK(resent[0] == all_frames[1]);
  CHECK(due_frames(mine, 3) == resent);
  // Types outside the set: InvalidArgument with the type as index, nothing queued.
  for (const Message& m : {Message(Start{}), Message(StatusReport{}), Message(Ack{}), Message(Capabilities{})}) {
    const auto r = mine.submit(m);
    REQUIRE_FALSE(r.has_value());
    CHECK(r.error() == Error::InvalidArgument);
    CHECK(r.where() == static_cast<std::uint8_t>(m.type()));
  }
  CHECK(mine.in_flight() == 2);
  // Without a handshake a Capabilities is no answer to anything: ignored, still connected.
  REQUIRE(mine.on_message(Message(Capabilities{}), 4).has_value());
  CHECK(mine.state() == LinkState::Connected);
}

TEST_CASE("link: a host sender of the host's messages sends the all-types sender's Hello and commands",
          "[protocol][link]") {
  LinkSender<4> all;
  LinkSender<4, HostToController> mine;
  all.connect(0xBEEF, 0);
  mine.connect(0xBEEF, 0);
  const auto hello = due_frames(all, 0);
  REQUIRE(hello.size() == 1);
  CHECK(due_frames(mine, 0) == hello);
  Capabilities caps;
  caps.session = 0xBEEF;
  caps.credit_end = 2;
  REQUIRE(all.on_message(Message(caps), 1).has_value());
  REQUIRE(mine.on_message(Message(caps), 1).has_value());
  REQUIRE(mine.state() == LinkState::Connected);
  QueueSegment segment;
  segment.points[1] = WirePoint{65536, 0, 0};
  for (const Message& m : {Message(segment), Message(Start{}), Message(StatusRequest{})}) {
    REQUIRE(all.submit(m).has_value());
    REQUIRE(mine.submit(m).has_value());
  }
  const auto frames = due_frames(all, 2);
  REQUIRE(frames.size() == 3);
  CHECK(due_frames(mine, 2) == frames);
  CHECK(mine.submit(Message(batch(0))).error() == Error::InvalidArgument);
}
