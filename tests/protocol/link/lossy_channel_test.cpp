// SPDX-License-Identifier: MIT
// Randomized: a message stream crosses a lossy, corrupting, duplicating, reordering line and
// arrives exactly once, in order, without ever overrunning the controller's queue.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <vector>

#include <support/numeric.hpp>

#include "link_harness.hpp"

using namespace curvestep;
using namespace curvestep::protocol;
using namespace curvestep::protocol::testing;

namespace {

/// One direction of a bad serial line: whole frames are lost, bit-flipped, duplicated,
/// delayed by a random jitter (so they overtake each other) and interleaved with garbage.
class BadLine {
 public:
  struct Rates {
    double loss = 0.08;
    double corruption = 0.05;
    double duplication = 0.05;
    double garbage = 0.03;
    std::uint32_t latency_ms = 2;
    std::uint32_t jitter_ms = 6;
  };

  BadLine(std::mt19937& rng, Rates rates) : rng_(rng), rates_(rates) {}

  void send(Bytes frame, std::uint32_t now_ms) {
    if (chance(rates_.loss)) {
      ++lost;
      return;
    }
    if (chance(rates_.corruption)) {
      const std::size_t at = rng_() % frame.size();
      frame[at] ^= static_cast<std::byte>(1u << (rng_() % 8));
      ++corrupted;
    }
    if (chance(rates_.garbage)) {
      Bytes noise(1 + rng_() % 6);
      for (std::byte& b : noise) b = static_cast<std::byte>(rng_());
      noise.insert(noise.end(), frame.begin(), frame.end());
      frame = noise;
    }
    const int copies = chance(rates_.duplication) ? 2 : 1;
    if (copies == 2) ++duplicated;
    for (int i = 0; i < copies; ++i) {
      in_transit_.push_back({now_ms + rates_.latency_ms + static_cast<std::uint32_t>(rng_() % (rates_.jitter_ms + 1)),
                             order_++, frame});
    }
  }

  /// Bytes arriving at `now_ms`, frames in arrival order.
  Bytes deliver(std::uint32_t now_ms) {
    std::stable_sort(in_transit_.begin(), in_transit_.end(),
                     [](const Flight& a, const Flight& b) { return a.arrival_ms < b.arrival_ms; });
    Bytes out;
    std::size_t n = 0;
    while (n < in_transit_.size() && in_transit_[n].arrival_ms <= now_ms) {
      if (in_transit_[n].order < newest_delivered_) ++reordered;
      newest_delivered_ = std::max(newest_delivered_, in_transit_[n].order);
      out.insert(out.end(), in_transit_[n].bytes.begin(), in_transit_[n].bytes.end());
      ++n;
    }
    in_transit_.erase(in_transit_.begin(), in_transit_.begin() + static_cast<std::ptrdiff_t>(n));
    return out;
  }

  int lost = 0;
  int corrupted = 0;
  int duplicated = 0;
  int reordered = 0;

 private:
  struct Flight {
    std::uint32_t arrival_ms;
    std::uint64_t order;
    Bytes bytes;
  };
  bool chance(double p) { return std::uniform_real_distribution<double>(0.0, 1.0)(rng_) < p; }

  std::mt19937& rng_;
  Rates rates_;
  std::vector<Flight> in_transit_;
  std::uint64_t order_ = 0;
  std::uint64_t newest_delivered_ = 0;
};

/// Message number `i` of the stream: mostly segments, with commands mixed in.
Message stream_message(int i) {
  switch (i % 7) {
    case 3: return Message(StatusRequest{});
    case 5: return Message(i % 2 == 0 ? Message(FeedHold{}) : Message(Resume{}));
    default: return Message(tagged_segment(i));
  }
}

/// True if `m` is message number `i` of the stream.
bool is_stream_message(const Message& m, int i) {
  const Message expected = stream_message(i);
  if (m.type() != expected.type()) return false;
  if (!m.holds<QueueSegment>()) return true;
  return m.get<QueueSegment>().feed_mm_per_s == i && m.get<QueueSegment>().points[1][0] == i;
}

/// Runs `total` messages from a host with `Window` frames through two bad lines to a
/// controller with `queue_capacity` slots, and checks delivery and flow control.
template <std::size_t Window>
void run_stream(std::uint32_t seed, int total, BadLine::Rates rates, std::uint16_t queue_capacity) {
  INFO("seed " << seed << " messages " << total << " window " << Window << " queue " << queue_capacity);
  std::mt19937 rng(seed);
  BadLine to_controller(rng, rates);
  BadLine to_host(rng, rates);

  Host<Window> host(SenderSettings{40, 60, 2000});
  Controller controller(queue_capacity, ReceiverSettings{30, 0});
  host.sender.connect(static_cast<std::uint16_t>(rng()), 0);

  int next = 0;
  std::uint32_t now = 0;
  const std::uint32_t deadline = 2000000;
  std::size_t max_queue = 0;
  int max_in_flight_segments = 0;
  for (; now < deadline; ++now) {
    // Host: submit what the window and credit allow, transmit, receive.
    while (next < total && host.sender.can_submit(stream_message(next).type())) {
      REQUIRE(host.sender.submit(stream_message(next)).has_value());
      ++next;
    }
    for (Bytes& f : host.transmit(now)) to_controller.send(std::move(f), now);
    host.receive(to_host.deliver(now), now);
    REQUIRE(host.link_errors.empty());
    const int outstanding = static_cast<int>(static_cast<std::uint16_t>(host.sender.segments_sent() -
                                                                        controller.receiver.segments_accepted())) +
                            static_cast<int>(controller.queue.size());
    max_in_flight_segments = std::max(max_in_flight_segments, outstanding);

    // Controller: receive, execute a segment now and then, advertise credit.
    for (Bytes& f : controller.receive(to_controller.deliver(now), now)) to_host.send(std::move(f), now);
    if (!controller.queue.empty() && rng() % 4 == 0) controller.queue.pop_front();
    max_queue = std::max(max_queue, controller.queue.size());
    for (Bytes& f : controller.poll(now)) to_host.send(std::move(f), now);

    if (next == total && host.sender.idle()) break;
  }

  INFO("lost " << to_controller.lost << "+" << to_host.lost << " corrupted " << to_controller.corrupted << "+"
               << to_host.corrupted << " duplicated " << to_controller.duplicated << "+" << to_host.duplicated
               << " reordered " << to_controller.reordered << "+" << to_host.reordered << " at " << now << " ms");
  REQUIRE(now < deadline);
  CHECK(controller.connects == 1);
  REQUIRE(controller.delivered.size() == static_cast<std::size_t>(total));
  for (int i = 0; i < total; ++i) {
    INFO("message " << i);
    CHECK(is_stream_message(controller.delivered[static_cast<std::size_t>(i)], i));
  }
  CHECK(controller.queue_overruns == 0);
  CHECK(max_queue <= queue_capacity);
  CHECK(max_in_flight_segments <= queue_capacity);
  for (const Nak& n : controller.naks) CHECK(n.reason != Error::QueueFull);
  // The line really was bad in every way.
  CHECK(to_controller.lost > 0);
  CHECK(to_controller.corrupted > 0);
  CHECK(to_controller.duplicated > 0);
  CHECK(to_controller.reordered > 0);
  CHECK(to_host.lost > 0);
  CHECK(to_host.reordered > 0);
}

/// A batch of one setpoint whose coordinates carry its index.
SetpointBatch indexed_batch(std::uint32_t first, std::uint8_t count) {
  SetpointBatch b;
  b.first_index = first;
  b.axis_count = 3;
  b.count = count;
  for (std::size_t k = 0; k < count; ++k) {
    const auto i = static_cast<std::int32_t>(first + k);
    b.setpoints[k] = WirePoint{i, -i, 3 * i};
  }
  return b;
}

/// The controller's setpoint stream (LinkSender at the controller) to the host (LinkReceiver at
/// the host) through two bad lines: every setpoint arrives exactly once and in order.
template <std::size_t Window>
void run_setpoint_stream(std::uint32_t seed, std::uint32_t setpoints, BadLine::Rates rates) {
  INFO("seed " << seed << " setpoints " << setpoints << " window " << Window);
  std::mt19937 rng(seed);
  BadLine to_host(rng, rates);
  BadLine to_controller(rng, rates);
  LinkSender<Window> sender(SenderSettings{40, 10, 0}, Endpoint::Controller);
  LinkReceiver receiver(Capabilities{}, ReceiverSettings{30, 0}, Endpoint::Host);
  FrameDecoder<> host_decoder;
  FrameDecoder<> controller_decoder;
  sender.open(0);
  receiver.open(0);
  std::vector<std::uint32_t> received;
  std::uint32_t next = 0;
  std::uint32_t now = 0;
  const std::uint32_t deadline = 2000000;
  const auto host_reply = [&](const Reception& r) {
    Bytes out(max_encoded_frame_size);
    const auto size = receiver.encode_reply(r, out);
    REQUIRE(size.has_value());
    out.resize(size.value());
    if (!out.empty()) to_controller.send(std::move(out), now);
  };
  for (; now < deadline; ++now) {
    while (next < setpoints && sender.can_submit(MessageType::SetpointBatch)) {
      const auto count = static_cast<std::uint8_t>(std::min<std::uint32_t>(static_cast<std::uint32_t>(1 + rng() % 24), setpoints - next));
      REQUIRE(sender.submit(Message(indexed_batch(next, count))).has_value());
      next += count;
    }
    for (;;) {
      Bytes out(max_encoded_frame_size);
      const auto size = sender.poll(now, out);
      REQUIRE(size.has_value());  // never gives up: every timeout is followed by progress in time
      if (size.value() == 0) break;
      out.resize(size.value());
      to_host.send(std::move(out), now);
    }
    for (const std::byte b : to_host.deliver(now)) {
      const auto pushed = host_decoder.push(b);
      if (!pushed) {
        host_reply(receiver.on_bad_frame(pushed.error()));
        continue;
      }
      if (!pushed.value()) continue;
      const Reception r = receiver.on_frame(host_decoder.frame(), 0, now);
      host_reply(r);
      if (r.disposition != Disposition::Deliver) continue;
      const auto m = decode_message(host_decoder.frame());
      REQUIRE(m.has_value());
      const auto& batch = m.value().get<SetpointBatch>();
      for (std::size_t k = 0; k < batch.count; ++k) {
        received.push_back(batch.first_index + static_cast<std::uint32_t>(k));
        CHECK(batch.setpoints[k][2] == 3 * static_cast<std::int32_t>(batch.first_index + k));
      }
    }
    host_reply(receiver.poll(0, now));
    for (const std::byte b : to_controller.deliver(now)) {
      const auto pushed = controller_decoder.push(b);
      if (!pushed || !pushed.value()) continue;
      const auto m = decode_message(controller_decoder.frame());
      REQUIRE(m.has_value());
      REQUIRE((m.value().holds<Ack>() || m.value().holds<Nak>()));
      REQUIRE(sender.on_message(m.value(), now).has_value());
    }
    if (next == setpoints && sender.idle()) break;
  }
  INFO("lost " << to_host.lost << "+" << to_controller.lost << " corrupted " << to_host.corrupted << "+"
               << to_controller.corrupted << " duplicated " << to_host.duplicated << " reordered " << to_host.reordered
               << " go-backs " << sender.go_backs() << " at " << now << " ms");
  REQUIRE(now < deadline);
  REQUIRE(received.size() == setpoints);
  for (std::uint32_t i = 0; i < setpoints; ++i) REQUIRE(received[i] == i);  // none lost, none twice, in order
  CHECK(sender.go_backs() > 0);
  CHECK(to_host.lost > 0);
  CHECK(to_host.corrupted > 0);
  CHECK(to_host.duplicated > 0);
  CHECK(to_controller.lost > 0);
}

}  // namespace

TEST_CASE("link: the controller's setpoint stream crosses a bad line to the host exactly once and in order",
          "[protocol][link]") {
  run_setpoint_stream<4>(curvestep::testing::test_seed() + 2, 20000, BadLine::Rates{});
}

TEST_CASE("link: the setpoint stream survives a very bad line with a window of one frame", "[protocol][link]") {
  BadLine::Rates harsh;
  harsh.loss = 0.2;
  harsh.corruption = 0.15;
  harsh.duplication = 0.2;
  harsh.garbage = 0.1;
  harsh.jitter_ms = 20;
  run_setpoint_stream<1>(curvestep::testing::test_seed() + 3, 3000, harsh);
}

TEST_CASE("link: a randomized stream crosses a bad line exactly once and in order", "[protocol][link]") {
  run_stream<8>(curvestep::testing::test_seed(), curvestep::testing::test_count(400), BadLine::Rates{}, 5);
}

TEST_CASE("link: a randomized stream crosses a very bad line with a small window and queue", "[protocol][link]") {
  BadLine::Rates harsh;
  harsh.loss = 0.25;
  harsh.corruption = 0.15;
  harsh.duplication = 0.2;
  harsh.garbage = 0.1;
  harsh.jitter_ms = 20;
  run_stream<3>(curvestep::testing::test_seed() + 1, curvestep::testing::test_count(400) / 2, harsh, 2);
}
