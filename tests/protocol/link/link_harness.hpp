// SPDX-License-Identifier: MIT
// Test harness: a host (LinkSender) and a controller (LinkReceiver + a bounded queue) joined by bytes.
#pragma once

#include <catch2/catch.hpp>

#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include <curvestep/protocol/frame.hpp>
#include <curvestep/protocol/frame_decoder.hpp>
#include <curvestep/protocol/link_receiver.hpp>
#include <curvestep/protocol/link_sender.hpp>

namespace curvestep::protocol::testing {

using Bytes = std::vector<std::byte>;

/// Every frame `sender` (a LinkSender) has due at `now_ms`; a poll error fails the test.
template <class Sender>
std::vector<Bytes> due_frames(Sender& sender, std::uint32_t now_ms) {
  std::vector<Bytes> frames;
  for (;;) {
    Bytes out(max_encoded_frame_size);
    const auto size = sender.poll(now_ms, out);
    REQUIRE(size.has_value());
    if (size.value() == 0) return frames;
    out.resize(size.value());
    frames.push_back(out);
  }
}

/// Capabilities of a test controller with `queue_capacity` segment slots.
inline Capabilities controller_capabilities(std::uint16_t queue_capacity, std::uint16_t version = protocol_version) {
  Capabilities c;
  c.version = version;
  c.queue_capacity = queue_capacity;
  c.axis_count = 3;
  c.tick_rate_hz = 100000;
  return c;
}

/// The controller side: receiver, decoder, a bounded segment queue and a log of what it saw.
struct Controller {
  explicit Controller(std::uint16_t queue_capacity, ReceiverSettings settings = {},
                      std::uint16_t version = protocol_version)
      : receiver(controller_capabilities(queue_capacity, version), settings), capacity(queue_capacity) {}

  LinkReceiver receiver;
  FrameDecoder<> decoder;
  std::size_t capacity;
  std::deque<QueueSegment> queue;
  std::vector<Message> delivered;  // every delivered command, in order
  std::vector<Nak> naks;           // every Nak sent
  int connects = 0;
  int queue_overruns = 0;

  [[nodiscard]] std::uint16_t free_slots() const { return static_cast<std::uint16_t>(capacity - queue.size()); }

  /// Bytes of the reply to `r` (empty if none).
  Bytes reply(const Reception& r) {
    if (r.reply == ReplyKind::Nak) naks.push_back(r.nak);
    Bytes out(max_encoded_frame_size);
    const auto size = receiver.encode_reply(r, out);
    REQUIRE(size.has_value());
    out.resize(size.value());
    return out;
  }

  /// Feeds received bytes; returns the reply frames.
  std::vector<Bytes> receive(const Bytes& data, std::uint32_t now_ms) {
    std::vector<Bytes> replies;
    for (const std::byte b : data) {
      const auto pushed = decoder.push(b);
      Reception r;
      if (!pushed) {
        r = receiver.on_bad_frame(pushed.error());
      } else if (pushed.value()) {
        r = receiver.on_frame(decoder.frame(), free_slots(), now_ms);
        if (r.disposition == Disposition::Connect) {
          ++connects;
          queue.clear();
        }
        if (r.disposition == Disposition::Deliver) {
          const auto m = decode_message(decoder.frame());
          REQUIRE(m.has_value());
          delivered.push_back(m.value());
          if (m.value().holds<QueueSegment>()) {
            if (queue.size() >= capacity) ++queue_overruns;
            queue.push_back(m.value().get<QueueSegment>());
          }
        }
      }
      Bytes out = reply(r);
      if (!out.empty()) replies.push_back(out);
    }
    return replies;
  }

  /// Periodic step: credit updates and heartbeats.
  std::vector<Bytes> poll(std::uint32_t now_ms) {
    std::vector<Bytes> replies;
    Bytes out = reply(receiver.poll(free_slots(), now_ms));
    if (!out.empty()) replies.push_back(out);
    return replies;
  }
};

/// The host side: sender, decoder and the messages it received.
template <std::size_t Window = 8>
struct Host {
  explicit Host(SenderSettings settings = {}) : sender(settings) {}

  LinkSender<Window> sender;
  FrameDecoder<> decoder;
  std::vector<Message> received;
  std::vector<Error> link_errors;

  /// Every frame due now.
  std::vector<Bytes> transmit(std::uint32_t now_ms) {
    std::vector<Bytes> frames;
    for (;;) {
      Bytes out(max_encoded_frame_size);
      const auto size = sender.poll(now_ms, out);
      if (!size) {
        link_errors.push_back(size.error());
        break;
      }
      if (size.value() == 0) break;
      out.resize(size.value());
      frames.push_back(out);
    }
    return frames;
  }

  /// Feeds bytes from the controller.
  void receive(const Bytes& data, std::uint32_t now_ms) {
    for (const std::byte b : data) {
      const auto pushed = decoder.push(b);
      if (!pushed || !pushed.value()) continue;
      const auto m = decode_message(decoder.frame());
      REQUIRE(m.has_value());
      received.push_back(m.value());
      const auto handled = sender.on_message(m.value(), now_ms);
      if (!handled) link_errors.push_back(handled.error());
    }
  }
};

/// A segment whose feed field carries `tag`, to identify it after delivery.
inline QueueSegment tagged_segment(std::int32_t tag) {
  QueueSegment s;
  s.kind = SegmentKind::Line;
  s.axis_count = 2;
  s.has_feed = true;
  s.feed_mm_per_s = tag;
  s.points[1] = {tag, -tag, 0};
  return s;
}

/// Appends the frames in `from` to one byte vector.
inline Bytes concatenate(const std::vector<Bytes>& from) {
  Bytes out;
  for (const Bytes& f : from) out.insert(out.end(), f.begin(), f.end());
  return out;
}

}  // namespace curvestep::protocol::testing
