// SPDX-License-Identifier: MIT
// Link state machines: handshake, retransmission, duplicates, gaps, credit, restarts.
#include <catch2/catch.hpp>

#include "link_harness.hpp"

using namespace curvestep;
using namespace curvestep::protocol;
using namespace curvestep::protocol::testing;

namespace {

/// Connects a host and a controller over a perfect line at time `now`.
template <std::size_t Window>
void handshake(Host<Window>& host, Controller& controller, std::uint32_t now = 0) {
  host.sender.connect(0xBEEF, now);
  const auto hello = host.transmit(now);
  REQUIRE(hello.size() == 1);
  const auto replies = controller.receive(hello[0], now);
  REQUIRE(replies.size() == 1);
  host.receive(replies[0], now);
  REQUIRE(host.sender.state() == LinkState::Connected);
}

}  // namespace

TEST_CASE("link: the handshake reports the controller's capabilities and credit", "[protocol][link]") {
  Host<> host;
  Controller controller(5);
  handshake(host, controller);
  CHECK(host.sender.capabilities().queue_capacity == 5);
  CHECK(host.sender.capabilities().tick_rate_hz == 100000);
  CHECK(host.sender.capabilities().session == 0xBEEF);
  CHECK(host.sender.credit() == 5);
  CHECK(controller.receiver.connected());
  CHECK(controller.connects == 1);
}

TEST_CASE("link: a handshake with a wrong version is refused on both ends", "[protocol][link]") {
  SECTION("the controller refuses a host of another version") {
    Host<> host;
    Controller controller(5, {}, static_cast<std::uint16_t>(protocol_version + 1));
    host.sender.connect(1, 0);
    const auto replies = controller.receive(host.transmit(0)[0], 0);
    REQUIRE(replies.size() == 1);
    REQUIRE(controller.naks.size() == 1);
    CHECK(controller.naks[0].reason == Error::VersionMismatch);
    CHECK_FALSE(controller.receiver.connected());
    host.receive(replies[0], 0);
    CHECK(host.sender.state() == LinkState::Failed);
    CHECK(host.sender.last_error() == Error::VersionMismatch);
    REQUIRE(host.link_errors.size() == 1);
    CHECK(host.link_errors[0] == Error::VersionMismatch);
  }
  SECTION("a Hello of another version does not end an established session") {
    Host<> host;
    Controller controller(5);
    handshake(host, controller);
    REQUIRE(controller.receiver.connected());
    Bytes frame(max_encoded_frame_size);
    const auto size = encode_frame(Message(Hello{static_cast<std::uint16_t>(protocol_version + 1), 0x1234}), 0, frame);
    REQUIRE(size.has_value());
    frame.resize(size.value());
    (void)controller.receive(frame, 10);
    REQUIRE(controller.naks.size() == 1);
    CHECK(controller.naks[0].reason == Error::VersionMismatch);
    CHECK(controller.receiver.connected());
    CHECK(controller.connects == 1);
  }
  SECTION("the host refuses Capabilities of another version") {
    LinkSender<> sender;
    sender.connect(7, 0);
    Capabilities caps = controller_capabilities(4, static_cast<std::uint16_t>(protocol_version + 3));
    caps.session = 7;
    const auto r = sender.on_message(Message(caps), 0);
    REQUIRE_FALSE(r.has_value());
    CHECK(r.error() == Error::VersionMismatch);
    CHECK(sender.state() == LinkState::Failed);
    CHECK(sender.capabilities().version == protocol_version + 3);  // for the error message
    CHECK_FALSE(sender.submit(Message(Start{})).has_value());
  }
  SECTION("a host refused by the controller knows no controller version") {
    Host<> host;
    Controller controller(5, {}, static_cast<std::uint16_t>(protocol_version + 1));
    host.sender.connect(1, 0);
    host.receive(controller.receive(host.transmit(0)[0], 0)[0], 0);
    CHECK(host.sender.capabilities().version == 0);
  }
}

TEST_CASE("link: Hello is repeated after the timeout and gives up with LinkTimeout", "[protocol][link]") {
  Host<> host(SenderSettings{100, 3});
  host.sender.connect(9, 1000);
  CHECK(host.transmit(1000).size() == 1);
  CHECK(host.transmit(1099).empty());
  CHECK(host.transmit(1100).size() == 1);
  CHECK(host.transmit(1200).size() == 1);
  CHECK(host.transmit(1300).size() == 1);  // fourth Hello: three retransmissions
  CHECK(host.transmit(1400).empty());
  REQUIRE(host.link_errors.size() == 1);
  CHECK(host.link_errors[0] == Error::LinkTimeout);
  CHECK(host.sender.state() == LinkState::Failed);
}

TEST_CASE("link: a repeated Hello of the same session does not reset the controller", "[protocol][link]") {
  Host<> host;
  Controller controller(4);
  host.sender.connect(77, 0);
  const auto hello = host.transmit(0)[0];
  controller.receive(hello, 0);
  host.receive(concatenate(controller.receive(hello, 1)), 1);  // the first answer was lost
  REQUIRE(host.sender.state() == LinkState::Connected);
  REQUIRE(host.sender.submit(Message(tagged_segment(1))).has_value());
  controller.receive(concatenate(host.transmit(2)), 2);
  CHECK(controller.receiver.expected_sequence() == 1);
  controller.receive(hello, 3);  // a late copy of the Hello
  CHECK(controller.receiver.expected_sequence() == 1);
  CHECK(controller.connects == 1);
  CHECK(controller.queue.size() == 1);
}

TEST_CASE("link: a lost frame is retransmitted after the timeout", "[protocol][link]") {
  Host<> host(SenderSettings{100, 5});
  Controller controller(8);
  handshake(host, controller);
  REQUIRE(host.sender.submit(Message(tagged_segment(10))).has_value());
  const auto first = host.transmit(10);
  REQUIRE(first.size() == 1);  // lost on the line
  CHECK(host.transmit(50).empty());
  CHECK(host.transmit(109).empty());
  const auto again = host.transmit(110);
  REQUIRE(again.size() == 1);
  CHECK(again[0] == first[0]);  // the same bytes, the same sequence number
  host.receive(concatenate(controller.receive(again[0], 111)), 111);
  CHECK(host.sender.idle());
  REQUIRE(controller.delivered.size() == 1);
  CHECK(controller.delivered[0].get<QueueSegment>().feed_mm_per_s == 10);
  CHECK(host.transmit(500).empty());  // acknowledged: nothing more to resend
}

TEST_CASE("link: a gap is answered by one Nak and the host goes back at once", "[protocol][link]") {
  Host<> host;
  Controller controller(8);
  handshake(host, controller);
  for (int i = 0; i < 4; ++i) REQUIRE(host.sender.submit(Message(tagged_segment(i))).has_value());
  const auto frames = host.transmit(10);
  REQUIRE(frames.size() == 4);
  // frame 0 is lost; 1, 2, 3 arrive out of order with respect to the expected 0
  std::vector<Bytes> replies;
  for (int i = 1; i < 4; ++i) {
    const auto r = controller.receive(frames[static_cast<std::size_t>(i)], 11);
    replies.insert(replies.end(), r.begin(), r.end());
  }
  CHECK(controller.delivered.empty());
  REQUIRE(controller.naks.size() == 1);  // one Nak per gap, not one per frame
  CHECK(controller.naks[0].expected == 0);
  CHECK(controller.naks[0].reason == Error::SequenceError);
  host.receive(concatenate(replies), 12);
  const auto resent = host.transmit(13);  // no timeout needed
  REQUIRE(resent.size() == 4);
  CHECK(resent[0] == frames[0]);
  host.receive(concatenate(controller.receive(concatenate(resent), 14)), 14);
  REQUIRE(controller.delivered.size() == 4);
  for (int i = 0; i < 4; ++i) CHECK(controller.delivered[static_cast<std::size_t>(i)].get<QueueSegment>().feed_mm_per_s == i);
  CHECK(host.sender.idle());
}

TEST_CASE("link: duplicates are ignored and acknowledged again", "[protocol][link]") {
  Host<> host;
  Controller controller(8);
  handshake(host, controller);
  REQUIRE(host.sender.submit(Message(tagged_segment(5))).has_value());
  const auto frame = host.transmit(1);
  REQUIRE(frame.size() == 1);
  const auto first = controller.receive(frame[0], 2);
  const auto second = controller.receive(frame[0], 3);  // a duplicate (e.g. the Ack was lost)
  CHECK(controller.delivered.size() == 1);
  CHECK(controller.queue.size() == 1);
  REQUIRE(second.size() == 1);
  FrameDecoder<> decoder;
  bool seen = false;
  for (const std::byte b : second[0]) {
    const auto pushed = decoder.push(b);
    REQUIRE(pushed.has_value());
    if (!pushed.value()) continue;
    const auto m = decode_message(decoder.frame());
    REQUIRE(m.has_value());
    REQUIRE(m.value().holds<Ack>());
    CHECK(m.value().get<Ack>().next_expected == 1);
    seen = true;
  }
  CHECK(seen);
  host.receive(concatenate(first), 4);
  host.receive(concatenate(second), 5);
  CHECK(host.sender.idle());
}

TEST_CASE("link: the window never lets the host exceed the advertised credit", "[protocol][link]") {
  Host<16> host;
  Controller controller(3);
  handshake(host, controller);
  int submitted = 0;
  while (host.sender.can_submit(MessageType::QueueSegment)) {
    REQUIRE(host.sender.submit(Message(tagged_segment(submitted))).has_value());
    ++submitted;
  }
  CHECK(submitted == 3);
  const auto refused = host.sender.submit(Message(tagged_segment(99)));
  REQUIRE_FALSE(refused.has_value());
  CHECK(refused.error() == Error::QueueFull);
  // Commands that take no queue slot still go through: Abort is never blocked by a full queue.
  CHECK(host.sender.can_submit(MessageType::Abort));
  host.receive(concatenate(controller.receive(concatenate(host.transmit(1)), 2)), 2);
  CHECK(controller.queue.size() == 3);
  CHECK(host.sender.credit() == 0);
  CHECK_FALSE(host.sender.can_submit(MessageType::QueueSegment));
  // The controller executes one segment; its next poll advertises one more credit.
  controller.queue.pop_front();
  host.receive(concatenate(controller.poll(3)), 3);
  CHECK(host.sender.credit() == 1);
  REQUIRE(host.sender.submit(Message(tagged_segment(3))).has_value());
  CHECK_FALSE(host.sender.can_submit(MessageType::QueueSegment));
  host.receive(concatenate(controller.receive(concatenate(host.transmit(4)), 4)), 4);
  CHECK(controller.queue.size() == 3);
  CHECK(controller.queue_overruns == 0);
}

TEST_CASE("link: a window of frames is the other limit", "[protocol][link]") {
  Host<2> host;
  Controller controller(10);
  handshake(host, controller);
  REQUIRE(host.sender.submit(Message(StatusRequest{})).has_value());
  REQUIRE(host.sender.submit(Message(Start{})).has_value());
  CHECK_FALSE(host.sender.can_submit(MessageType::StatusRequest));
  CHECK(host.sender.submit(Message(Resume{})).error() == Error::QueueFull);
  CHECK(host.sender.submit(Message(Ack{})).error() == Error::InvalidArgument);
}

TEST_CASE("link: stale acknowledgements never shrink the credit", "[protocol][link]") {
  LinkSender<> sender;
  sender.connect(3, 0);
  Capabilities caps = controller_capabilities(4);
  caps.session = 3;
  caps.credit_end = 4;
  REQUIRE(sender.on_message(Message(caps), 0).has_value());
  REQUIRE(sender.on_message(Message(Ack{0, 9}), 1).has_value());
  CHECK(sender.credit() == 9);
  REQUIRE(sender.on_message(Message(Ack{0, 6}), 2).has_value());  // an older Ack arriving late
  CHECK(sender.credit() == 9);
}

TEST_CASE("link: the controller refuses a segment beyond the credit it granted", "[protocol][link]") {
  Controller controller(1);
  Host<> host;
  handshake(host, controller);
  Bytes wire(max_encoded_frame_size);
  for (std::uint8_t seq = 0; seq < 2; ++seq) {
    const auto size = encode_frame(Message(tagged_segment(seq)), seq, wire);
    REQUIRE(size.has_value());
    controller.receive(Bytes(wire.begin(), wire.begin() + static_cast<std::ptrdiff_t>(size.value())), 1);
  }
  CHECK(controller.queue.size() == 1);
  REQUIRE(controller.naks.size() == 1);
  CHECK(controller.naks[0].reason == Error::QueueFull);
  CHECK(controller.naks[0].expected == 1);
}

TEST_CASE("link: retransmission gives up with RetransmitLimit when the controller talks but never acknowledges",
          "[protocol][link]") {
  Host<> host(SenderSettings{100, 2});
  Controller controller(4);
  handshake(host, controller);
  REQUIRE(host.sender.submit(Message(Start{})).has_value());
  CHECK(host.transmit(0).size() == 1);
  host.receive(controller.reply(Reception{Disposition::Ignore, ReplyKind::Ack, Ack{0, 4}, Nak{}}), 50);  // no progress
  CHECK(host.transmit(100).size() == 1);
  host.receive(controller.reply(Reception{Disposition::Ignore, ReplyKind::Ack, Ack{0, 4}, Nak{}}), 150);
  CHECK(host.transmit(200).size() == 1);
  host.receive(controller.reply(Reception{Disposition::Ignore, ReplyKind::Ack, Ack{0, 4}, Nak{}}), 250);
  CHECK(host.transmit(300).empty());
  REQUIRE(host.link_errors.size() == 1);
  CHECK(host.link_errors[0] == Error::RetransmitLimit);
  CHECK(host.sender.state() == LinkState::Failed);
}

TEST_CASE("link: retransmission to a silent controller gives up with LinkTimeout", "[protocol][link]") {
  Host<> host(SenderSettings{100, 2});
  Controller controller(4);
  handshake(host, controller);
  REQUIRE(host.sender.submit(Message(Start{})).has_value());
  CHECK(host.transmit(0).size() == 1);
  CHECK(host.transmit(100).size() == 1);
  CHECK(host.transmit(200).size() == 1);
  CHECK(host.transmit(300).empty());
  REQUIRE(host.link_errors.size() == 1);
  CHECK(host.link_errors[0] == Error::LinkTimeout);  // nothing heard since the handshake: the controller is gone
  CHECK(host.sender.state() == LinkState::Failed);
}

TEST_CASE("link: a receiver Naks every damaged frame and a gap once per round of resends", "[protocol][link]") {
  Controller controller(4, ReceiverSettings{0, 0, 20});
  Host<> host;
  handshake(host, controller);
  // Damaged frames are direct evidence of a loss: each one is Nak-ed.
  CHECK(controller.receiver.on_bad_frame(Error::BadCrc, 1).reply == ReplyKind::Nak);
  CHECK(controller.receiver.on_bad_frame(Error::BadCrc, 2).reply == ReplyKind::Nak);
  for (int i = 0; i < 3; ++i) REQUIRE(host.sender.submit(Message(Start{})).has_value());
  const auto frames = host.transmit(3);
  REQUIRE(frames.size() == 3);
  const auto naks_before = controller.naks.size();
  // frame 0 lost; 1 and 2 are ahead: one Nak for the gap (the damage above already Nak-ed it)
  controller.receive(frames[1], 4);
  controller.receive(frames[2], 4);
  CHECK(controller.naks.size() == naks_before);
  // a new round (frame 1 again: no further ahead than before) with frame 0 lost again: Nak again
  controller.receive(frames[1], 5);
  CHECK(controller.naks.size() == naks_before + 1);
  controller.receive(frames[2], 5);
  CHECK(controller.naks.size() == naks_before + 1);
  // and after nak_interval_ms a further ahead frame is Nak-ed too
  controller.receive(frames[2], 30);
  CHECK(controller.naks.size() == naks_before + 2);
  for (const Nak& n : controller.naks) CHECK(n.expected == 0);
}

TEST_CASE("link: a controller that restarted answers NotConnected and the host reports DeviceRestarted", "[protocol][link]") {
  Host<> host;
  Controller controller(4);
  handshake(host, controller);
  Controller rebooted(4);
  REQUIRE(host.sender.submit(Message(StatusRequest{})).has_value());
  const auto replies = rebooted.receive(concatenate(host.transmit(1)), 1);
  REQUIRE(rebooted.naks.size() == 1);
  CHECK(rebooted.naks[0].reason == Error::NotConnected);
  CHECK(rebooted.delivered.empty());
  host.receive(concatenate(replies), 2);
  REQUIRE(host.link_errors.size() == 1);
  CHECK(host.link_errors[0] == Error::DeviceRestarted);
  CHECK(host.sender.state() == LinkState::Failed);
}

TEST_CASE("link: a corrupted frame is answered by a Nak so the host resends at once", "[protocol][link]") {
  Host<> host;
  Controller controller(4);
  handshake(host, controller);
  REQUIRE(host.sender.submit(Message(tagged_segment(1))).has_value());
  auto frame = host.transmit(1)[0];
  frame[5] ^= std::byte{0x10};
  host.receive(concatenate(controller.receive(frame, 2)), 2);
  REQUIRE(controller.naks.size() == 1);
  CHECK(controller.naks[0].reason == Error::BadCrc);
  const auto resent = host.transmit(3);
  REQUIRE(resent.size() == 1);
  controller.receive(resent[0], 4);
  CHECK(controller.delivered.size() == 1);
}

TEST_CASE("link: the controller sends heartbeats and detects a silent host", "[protocol][link]") {
  Host<> host;
  Controller controller(4, ReceiverSettings{50, 500});
  handshake(host, controller, 0);
  CHECK(controller.poll(49).empty());
  CHECK(controller.poll(50).size() == 1);
  CHECK(controller.poll(60).empty());
  CHECK(controller.receiver.check_link(499).has_value());
  const auto timeout = controller.receiver.check_link(500);
  REQUIRE_FALSE(timeout.has_value());
  CHECK(timeout.error() == Error::LinkTimeout);
}

TEST_CASE("link: unknown message types take a sequence number and reach the application", "[protocol][link]") {
  Host<> host;
  Controller controller(4);
  handshake(host, controller);
  Bytes wire(max_encoded_frame_size);
  const auto size = encode_frame(0x7E, 0, {}, wire);
  REQUIRE(size.has_value());
  wire.resize(size.value());
  for (const std::byte b : wire) {
    const auto pushed = controller.decoder.push(b);
    REQUIRE(pushed.has_value());
    if (!pushed.value()) continue;
    const Reception r = controller.receiver.on_frame(controller.decoder.frame(), 4, 1);
    CHECK(r.disposition == Disposition::Deliver);
    CHECK(r.reply == ReplyKind::Ack);
    CHECK(decode_message(controller.decoder.frame()).error() == Error::UnknownMessage);
  }
  CHECK(controller.receiver.expected_sequence() == 1);
}

TEST_CASE("link: an Ack that arrives after a Nak-triggered go-back still releases the frames", "[protocol][link]") {
  Host<> host(SenderSettings{100, 5});
  Controller controller(8);
  handshake(host, controller);
  for (int i = 0; i < 3; ++i) REQUIRE(host.sender.submit(Message(tagged_segment(i))).has_value());
  const auto replies = controller.receive(concatenate(host.transmit(0)), 1);
  REQUIRE(host.sender.on_message(Message(Nak{0, Error::BadCrc}), 2).has_value());  // an old Nak: go back
  host.receive(concatenate(replies), 3);  // before anything was resent, the Acks arrive
  CHECK(host.sender.idle());
  CHECK(host.transmit(4).empty());
  CHECK(controller.delivered.size() == 3);
}

TEST_CASE("link: a late Ack that arrives after a timeout still releases the frames", "[protocol][link]") {
  Host<> host(SenderSettings{100, 5});
  Controller controller(8);
  handshake(host, controller);
  for (int i = 0; i < 3; ++i) REQUIRE(host.sender.submit(Message(tagged_segment(i))).has_value());
  const auto replies = controller.receive(concatenate(host.transmit(0)), 1);
  const auto resent = host.transmit(100);  // the Acks are slow: the host goes back
  CHECK(resent.size() == 3);
  host.receive(concatenate(replies), 101);  // now they arrive
  CHECK(host.sender.idle());
  CHECK(host.transmit(300).empty());
  controller.receive(concatenate(resent), 102);  // the retransmissions are duplicates
  CHECK(controller.delivered.size() == 3);
}

TEST_CASE("link: a host that hears nothing for the link timeout fails with LinkTimeout", "[protocol][link]") {
  Host<> host(SenderSettings{100, 10, 300});
  Controller controller(4, ReceiverSettings{100, 0});
  handshake(host, controller, 0);
  for (std::uint32_t now = 1; now < 1000; ++now) {
    host.receive(concatenate(controller.poll(now)), now);  // heartbeats keep the link alive
    CHECK(host.transmit(now).empty());
  }
  REQUIRE(host.link_errors.empty());
  CHECK(host.transmit(1199).empty());  // the controller went silent after its heartbeat at 900
  CHECK(host.link_errors.empty());
  CHECK(host.transmit(1200).empty());
  REQUIRE(host.link_errors.size() == 1);
  CHECK(host.link_errors[0] == Error::LinkTimeout);
  CHECK(host.sender.state() == LinkState::Failed);
}

namespace {

/// The controller's setpoint stream: a sender at the controller and a receiver at the host.
struct SetpointStream {
  LinkSender<4> sender{SenderSettings{100, 3, 0}, Endpoint::Controller};
  LinkReceiver receiver{Capabilities{}, ReceiverSettings{}, Endpoint::Host};
  FrameDecoder<> host_decoder;
  std::vector<std::uint32_t> delivered;  // first_index of each delivered batch

  SetpointStream() {
    sender.open(0);
    receiver.open(0);
  }

  static SetpointBatch batch(std::uint32_t first) {
    SetpointBatch b;
    b.first_index = first;
    b.axis_count = 2;
    b.count = 1;
    b.setpoints[0] = WirePoint{static_cast<std::int32_t>(first), 0, 0};
    return b;
  }

  std::vector<Bytes> transmit(std::uint32_t now) { return due_frames(sender, now); }

  /// The host takes `frame`; returns its reply (Ack or Nak) as a message, if any.
  std::vector<Message> host_receives(const Bytes& frame, std::uint32_t now) {
    std::vector<Message> replies;
    for (const std::byte b : frame) {
      const auto pushed = host_decoder.push(b);
      Reception r;
      if (!pushed) {
        r = receiver.on_bad_frame(pushed.error());
      } else if (pushed.value()) {
        r = receiver.on_frame(host_decoder.frame(), 0, now);
        if (r.disposition == Disposition::Deliver) {
          delivered.push_back(decode_message(host_decoder.frame()).value().get<SetpointBatch>().first_index);
        }
      }
      if (r.reply == ReplyKind::Ack) replies.emplace_back(r.ack);
      if (r.reply == ReplyKind::Nak) replies.emplace_back(r.nak);
    }
    return replies;
  }

  void controller_receives(const std::vector<Message>& replies, std::uint32_t now) {
    for (const Message& m : replies) REQUIRE(sender.on_message(m, now).has_value());
  }
};

}  // namespace

TEST_CASE("link: setpoint batches are numbered, acknowledged by the host and released by the controller",
          "[protocol][link]") {
  SetpointStream s;
  for (std::uint32_t i = 0; i < 3; ++i) {
    const auto sequence = s.sender.submit(Message(SetpointStream::batch(10 * i)));
    REQUIRE(sequence.has_value());
    CHECK(sequence.value() == i);
  }
  const auto frames = s.transmit(0);
  REQUIRE(frames.size() == 3);
  for (const Bytes& f : frames) {
    const auto replies = s.host_receives(f, 1);
    REQUIRE(replies.size() == 1);
    REQUIRE(replies[0].holds<Ack>());
    CHECK(replies[0].get<Ack>().credit_end == 0);  // the host grants no credit: batches take none
    s.controller_receives(replies, 1);
  }
  CHECK(s.delivered == std::vector<std::uint32_t>{0, 10, 20});
  CHECK(s.sender.idle());
}

TEST_CASE("link: a lost setpoint batch is Nak-ed at the next one and resent, and repeats are not delivered twice",
          "[protocol][link]") {
  SetpointStream s;
  for (std::uint32_t i = 0; i < 3; ++i) REQUIRE(s.sender.submit(Message(SetpointStream::batch(i))).has_value());
  const auto frames = s.transmit(0);
  REQUIRE(frames.size() == 3);
  s.controller_receives(s.host_receives(frames[0], 1), 1);
  // frames[1] is lost; frames[2] shows the gap
  const auto gap = s.host_receives(frames[2], 2);
  REQUIRE(gap.size() == 1);
  REQUIRE(gap[0].holds<Nak>());
  CHECK(gap[0].get<Nak>().expected == 1);
  CHECK(gap[0].get<Nak>().reason == Error::SequenceError);
  s.controller_receives(gap, 2);
  const auto resent = s.transmit(3);
  REQUIRE(resent.size() == 2);  // go-back-N: batches 1 and 2
  s.controller_receives(s.host_receives(resent[0], 4), 4);
  s.controller_receives(s.host_receives(resent[1], 4), 4);
  // a stray copy of batch 0 is acknowledged again but not delivered
  const auto again = s.host_receives(frames[0], 5);
  REQUIRE(again.size() == 1);
  CHECK(again[0].holds<Ack>());
  CHECK(s.delivered == std::vector<std::uint32_t>{0, 1, 2});
  CHECK(s.sender.idle());
  CHECK(s.sender.go_backs() == 1);
}

TEST_CASE("link: Nak-triggered go-backs do not count toward max_retransmits", "[protocol][link]") {
  SetpointStream s;  // max_retransmits 3
  REQUIRE(s.sender.submit(Message(SetpointStream::batch(0))).has_value());
  REQUIRE(s.sender.submit(Message(SetpointStream::batch(1))).has_value());
  (void)s.transmit(0);
  // Ten damaged deliveries in a row, each Nak-ed at once: the sender keeps going back.
  for (std::uint32_t k = 0; k < 10; ++k) {
    s.controller_receives({Message(Nak{0, Error::BadCrc})}, 10 * k + 1);
    CHECK(s.transmit(10 * k + 2).size() == 2);
  }
  CHECK(s.sender.state() == LinkState::Connected);
  CHECK(s.sender.timeouts_without_progress() == 0);
  CHECK(s.sender.go_backs() == 10);
}

TEST_CASE("link: only timeouts in a row without progress count toward max_retransmits", "[protocol][link]") {
  SetpointStream s;  // 100 ms timeout, max_retransmits 3
  REQUIRE(s.sender.submit(Message(SetpointStream::batch(0))).has_value());
  REQUIRE(s.sender.submit(Message(SetpointStream::batch(1))).has_value());
  (void)s.transmit(0);
  CHECK(s.transmit(100).size() == 2);
  CHECK(s.transmit(200).size() == 2);
  CHECK(s.sender.timeouts_without_progress() == 2);
  // progress (batch 0 acknowledged) clears the count
  s.controller_receives({Message(Ack{1, 0})}, 250);
  CHECK(s.sender.timeouts_without_progress() == 0);
  CHECK(s.transmit(350).size() == 1);
  CHECK(s.transmit(450).size() == 1);
  CHECK(s.transmit(550).size() == 1);
  CHECK(s.sender.timeouts_without_progress() == 3);
  s.controller_receives({Message(Ack{1, 0})}, 600);  // the host still talks (a heartbeat), without progress
  Bytes out(max_encoded_frame_size);
  const auto failed = s.sender.poll(650, out);
  REQUIRE_FALSE(failed.has_value());
  CHECK(failed.error() == Error::RetransmitLimit);
  CHECK(failed.where() == 1);  // the oldest unacknowledged sequence number
}

TEST_CASE("link: each end submits only its own sequenced messages", "[protocol][link]") {
  SetpointStream s;
  CHECK(s.sender.submit(Message(Start{})).error() == Error::InvalidArgument);
  CHECK(s.sender.submit(Message(StatusReport{})).error() == Error::InvalidArgument);
  Host<> host;
  Controller controller(4);
  handshake(host, controller);
  CHECK(host.sender.submit(Message(SetpointStream::batch(0))).error() == Error::InvalidArgument);
  CHECK(host.sender.submit(Message(Ack{})).error() == Error::InvalidArgument);
}

TEST_CASE("link: the host's receiver ignores setpoint frames until its handshake opened it", "[protocol][link]") {
  LinkReceiver receiver(Capabilities{}, ReceiverSettings{}, Endpoint::Host);
  Bytes wire(max_encoded_frame_size);
  const auto size = encode_frame(Message(SetpointStream::batch(0)), 0, wire);
  REQUIRE(size.has_value());
  FrameDecoder<> decoder;
  Reception r;
  for (std::size_t i = 0; i < size.value(); ++i) {
    const auto pushed = decoder.push(wire[i]);
    if (pushed && pushed.value()) r = receiver.on_frame(decoder.frame(), 0, 0);
  }
  CHECK(r.disposition == Disposition::Ignore);
  CHECK(r.reply == ReplyKind::None);  // no Nak(NotConnected): that is the controller's answer only
  CHECK(receiver.on_bad_frame(Error::BadCrc).reply == ReplyKind::None);
  receiver.open(0);
  for (std::size_t i = 0; i < size.value(); ++i) {
    const auto pushed = decoder.push(wire[i]);
    if (pushed && pushed.value()) r = receiver.on_frame(decoder.frame(), 0, 0);
  }
  CHECK(r.disposition == Disposition::Deliver);
  CHECK(r.reply == ReplyKind::Ack);
}

TEST_CASE("link: Naks that never end still fail the link after the link timeout without progress (issue 19.4)",
          "[protocol][link]") {
  // A line that damages every long frame: the controller Naks each damaged copy, each Nak sends the
  // host back at once and restarts its timer, so no timeout ever expires and the count stays 0.
  Host<> host(SenderSettings{100, 10, 3000});
  Controller controller(4);
  handshake(host, controller);
  REQUIRE(host.sender.submit(Message(Start{})).has_value());
  CHECK(host.transmit(0).size() == 1);
  std::uint32_t now = 0;
  for (now = 50; now < 10000 && host.link_errors.empty(); now += 50) {
    host.receive(controller.reply(Reception{Disposition::Ignore, ReplyKind::Nak, Ack{}, Nak{0, Error::BadCrc}}), now);
    (void)host.transmit(now);
  }
  REQUIRE(host.link_errors.size() == 1);
  CHECK(host.link_errors[0] == Error::RetransmitLimit);  // the controller talks: it never takes the frame
  CHECK(host.sender.timeouts_without_progress() == 0);
  CHECK(now - 50 == 3000);
}

TEST_CASE("link: a controller that answers once after the last progress and then goes silent is gone (LinkTimeout)",
          "[protocol][link]") {
  // A cut line: the controller's last heartbeat arrives just after the last acknowledgement that
  // moved the window, then nothing. It was reported as RetransmitLimit ("the controller answered"),
  // or LinkTimeout, depending on which of the two came last before the cut (a flaky HIL test).
  Host<> host(SenderSettings{100, 10, 1500});
  Controller controller(4);
  handshake(host, controller);
  REQUIRE(host.sender.submit(Message(Start{})).has_value());
  CHECK(host.transmit(0).size() == 1);
  host.receive(controller.reply(Reception{Disposition::Ignore, ReplyKind::Ack, Ack{0, 0}, Nak{}}), 10);  // heard, no progress
  std::uint32_t now = 10;
  for (now = 20; now < 5000 && host.link_errors.empty(); now += 10) (void)host.transmit(now);
  REQUIRE(host.link_errors.size() == 1);
  CHECK(host.link_errors[0] == Error::LinkTimeout);
}

TEST_CASE("link: with a link timeout a silent pause is judged by it, not by max_retransmits (issue 19.6)", "[protocol][link]") {
  Host<> host(SenderSettings{100, 10, 30000});
  Controller controller(4);
  handshake(host, controller, 0);
  REQUIRE(host.sender.submit(Message(Start{})).has_value());
  CHECK(host.transmit(0).size() == 1);
  for (std::uint32_t now = 100; now <= 5000; now += 100) (void)host.transmit(now);  // frozen for 5 s: resent, never counted
  CHECK(host.link_errors.empty());
  CHECK(host.sender.timeouts_without_progress() == 0);
  host.receive(controller.reply(Reception{Disposition::Ignore, ReplyKind::Ack, Ack{1, 4}, Nak{}}), 5003);  // thawed
  CHECK(host.sender.idle());
  CHECK(host.transmit(5004).empty());
  CHECK(host.link_errors.empty());
  // Still silent for the whole link timeout: LinkTimeout.
  REQUIRE(host.sender.submit(Message(Start{})).has_value());
  CHECK(host.transmit(6000).size() == 1);
  for (std::uint32_t now = 6100; now < 5003 + 30000; now += 100) (void)host.transmit(now);
  CHECK(host.link_errors.empty());
  (void)host.transmit(5003 + 30000);
  REQUIRE(host.link_errors.size() == 1);
  CHECK(host.link_errors[0] == Error::LinkTimeout);
}
