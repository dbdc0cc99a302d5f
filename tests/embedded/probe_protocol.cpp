// SPDX-License-Identifier: MIT
// Probe: frame encoder, streaming decoder, message codecs and both link state machines.
#include <array>
#include <cstddef>
#include <cstdint>

#include <curvestep/protocol.hpp>

#include "probe.hpp"

namespace curvestep::probe {
namespace {

using namespace curvestep::protocol;

/// Feeds `size` bytes into the controller end; returns reply bytes written to `reply`.
std::size_t controller_step(FrameDecoder<>& decoder, LinkReceiver& receiver, std::span<const std::byte> bytes,
                            std::uint32_t now_ms, std::span<std::byte> reply) {
  std::size_t written = 0;
  for (const std::byte b : bytes) {
    const auto pushed = decoder.push(b);
    Reception r;
    if (!pushed) {
      r = receiver.on_bad_frame(pushed.error());
    } else if (pushed.value()) {
      r = receiver.on_frame(decoder.frame(), 4, now_ms);
      if (r.disposition == Disposition::Deliver) {
        const auto m = decode_message(decoder.frame());
        if (m && m.value().holds<QueueSegment>()) {
          const QueueSegment& segment = m.value().get<QueueSegment>();
          sink = sink + segment.points[1][0];
          if (auto curve = to_rational_bezier<2>(segment)) sink = sink + curve.value().point_at(Q16_16::from_raw(32768))[0].raw();
        }
        if (!m) sink = sink + static_cast<std::int32_t>(m.error());
      }
    }
    if (auto n = receiver.encode_reply(r, reply.subspan(written))) written += n.value();
  }
  return written;
}

void feed_host(FrameDecoder<>& decoder, LinkSender<4>& sender, std::span<const std::byte> bytes, std::uint32_t now_ms) {
  for (const std::byte b : bytes) {
    const auto pushed = decoder.push(b);
    if (!pushed || !pushed.value()) continue;
    if (auto m = decode_message(decoder.frame())) {
      if (!sender.on_message(m.value(), now_ms)) sink = sink + 1;
    }
  }
}

}  // namespace

void probe_protocol() {
  Capabilities caps;
  caps.queue_capacity = 4;
  caps.tick_rate_hz = 100000;
  LinkReceiver receiver(caps, ReceiverSettings{50, 1000});
  LinkSender<4> sender;
  FrameDecoder<> controller_decoder;
  FrameDecoder<> host_decoder;
  std::array<std::byte, max_encoded_frame_size> wire{};
  std::array<std::byte, 4 * max_encoded_frame_size> reply{};

  sender.connect(static_cast<std::uint16_t>(sink), 0);
  for (std::uint32_t now = 0; now < 40; ++now) {
    if (sender.state() == LinkState::Connected && sender.can_submit(MessageType::QueueSegment)) {
      QueueSegment s;
      s.kind = SegmentKind::RationalBezier;
      s.degree = 2;
      s.points[1] = {static_cast<std::int32_t>(now) << 16, sink, 0};
      s.weights = {65536, 46341, 65536};
      (void)sender.submit(Message(s));
    }
    for (;;) {
      const auto n = sender.poll(now, wire);
      if (!n || n.value() == 0) break;
      const std::size_t answered = controller_step(controller_decoder, receiver, std::span<const std::byte>(wire.data(), n.value()), now, reply);
      feed_host(host_decoder, sender, std::span<const std::byte>(reply.data(), answered), now);
    }
    const std::size_t heartbeat = receiver.encode_reply(receiver.poll(4, now), reply).value_or(0);
    feed_host(host_decoder, sender, std::span<const std::byte>(reply.data(), heartbeat), now);
  }

  SetpointBatch batch;
  batch.axis_count = 3;
  batch.count = 3;
  batch.setpoints[1] = {sink, 2, 3};
  batch.setpoints[2] = {sink + 100, -2, 3};
  if (auto n = encode_frame(Message(batch), receiver.next_outgoing_sequence(), wire)) {
    FrameDecoder<> decoder;
    for (std::size_t i = 0; i < n.value(); ++i) {
      const auto pushed = decoder.push(wire[i]);
      if (pushed && pushed.value()) {
        if (auto m = decode_message(decoder.frame())) sink = sink + m.value().get<SetpointBatch>().setpoints[2][0];
      }
    }
  }
  sink = sink + static_cast<std::int32_t>(sender.in_flight()) + static_cast<std::int32_t>(receiver.credit_end());
}

}  // namespace curvestep::probe
