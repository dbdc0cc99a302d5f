// SPDX-License-Identifier: MIT
#include <curvestep/host/link/host_link.hpp>

#include <array>
#include <random>

#include <curvestep/core/error_text.hpp>
#include <curvestep/protocol/frame.hpp>

namespace curvestep::host::link {

std::string describe_error(Error code) {
  return std::string(describe(code)) + " (" + std::string(error_name(code)) + ")";
}

std::string limit_switch_name(std::uint16_t bit) {
  if (bit >= 6) return "switch " + std::to_string(bit);
  return std::string(1, "XYZ"[bit / 2]) + (bit % 2 == 0 ? " min" : " max");
}

HostLink::HostLink(Transport& transport, protocol::SenderSettings settings)
    : transport_(transport),
      sender_(settings),
      receiver_(protocol::Capabilities{}, protocol::ReceiverSettings{250, 0}, protocol::Endpoint::Host),
      epoch_(std::chrono::steady_clock::now()) {}

std::uint32_t HostLink::now_ms() const noexcept {
  const auto elapsed = std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - epoch_);
  return static_cast<std::uint32_t>(elapsed.count());
}

void HostLink::raise(const Failure& failure) const {
  std::string text = transport_.name() + ": link failed: " + describe_error(failure.code);
  if (failure.code == Error::RetransmitLimit) {
    text += " (frame " + std::to_string(failure.index) + " never acknowledged): no progress for " +
            std::to_string(sender_.ms_without_progress(now_ms())) + " ms although the controller answered (" +
            std::to_string(statistics_.frames_received) + " good and " + std::to_string(statistics_.frames_rejected) +
            " damaged frame(s) received so far: a line too noisy to carry a whole frame?)";
  }
  if (failure.code == Error::LinkTimeout) text += ": the controller stopped answering";
  if (failure.code == Error::DeviceRestarted) text += ": the controller restarted and lost the session";
  if (failure.code == Error::VersionMismatch) {
    const std::uint16_t theirs = sender_.capabilities().version;
    text += theirs != 0 ? ": the controller speaks protocol version " + std::to_string(theirs) + ", this host speaks version " +
                              std::to_string(protocol::protocol_version)
                        : ": the controller refused this host's protocol version " + std::to_string(protocol::protocol_version);
    text += "; update the firmware or the host tools so both versions match";
  }
  throw LinkError(failure.code, text);
}

void HostLink::connect(const Handler& handler) {
  std::random_device random;
  const std::uint32_t begin = now_ms();
  const LinkStatistics before = statistics_;
  std::uint32_t pause_ms = 100;
  for (;;) {
    receiver_.close();
    sender_.connect(static_cast<std::uint16_t>(random()), now_ms());
    try {
      while (sender_.state() == protocol::LinkState::Connecting) pump(10, handler);
    } catch (const LinkError& e) {
      // A round of Hellos without an answer ends here; anything else is final.
      if (e.code() != Error::LinkTimeout || sender_.state() != protocol::LinkState::Failed) throw;
    }
    if (sender_.state() == protocol::LinkState::Connected) break;
    const Failure failure{sender_.last_error(), no_index};
    const std::uint32_t elapsed = now_ms() - begin;
    if (failure.code != Error::LinkTimeout || elapsed + pause_ms >= handshake_timeout_ms_) {
      if (failure.code != Error::LinkTimeout) raise(failure);
      const std::size_t damaged = statistics_.frames_rejected - before.frames_rejected;
      const std::size_t good = statistics_.frames_received - before.frames_received;
      std::string text = transport_.name() + ": link failed: " + describe_error(failure.code) + ": no answer to Hello in " +
                         std::to_string(elapsed) + " ms: ";
      text += damaged == 0 && good == 0 ? std::string("nothing arrived (is the controller on this port and powered?)")
                                        : std::to_string(damaged) + " damaged frame(s) and " + std::to_string(good) +
                                              " other frame(s) arrived (a noisy line, a wrong baud rate or another program on the port?)";
      throw LinkError(failure.code, text);
    }
    // A quiet pause (bytes still read and decoded), then a new session.
    const std::uint32_t pause_end = now_ms() + pause_ms;
    while (static_cast<std::int32_t>(pause_end - now_ms()) > 0) {
      std::array<std::byte, 512> bytes{};
      const std::size_t count = transport_.read(bytes, 10);
      for (std::size_t i = 0; i < count; ++i) {
        const auto pushed = decoder_.push(bytes[i]);
        if (!pushed) ++statistics_.frames_rejected;
        if (pushed && pushed.value()) ++statistics_.frames_received;
      }
    }
    pause_ms = pause_ms * 2 > 1000 ? 1000 : pause_ms * 2;
  }
  receiver_.open(now_ms());  // the controller opened its setpoint stream (sequence 0) with this session
}

void HostLink::reply(const protocol::Reception& reception) {
  if (reception.reply == protocol::ReplyKind::None) return;
  std::array<std::byte, protocol::max_encoded_frame_size> frame{};
  const auto size = receiver_.encode_reply(reception, frame);
  if (!size || size.value() == 0) return;
  transport_.write(std::span<const std::byte>(frame.data(), size.value()));
  statistics_.bytes_sent += size.value();
}

void HostLink::on_frame(const protocol::Frame& frame, const Handler& handler) {
  const auto message = protocol::decode_message(frame);
  const bool sequenced = protocol::is_sequenced_toward(protocol::Endpoint::Host, frame.type);
  if (!message) {
    // With a 32-bit CRC a malformed payload is a sender bug, not noise; a sequenced one is
    // refused like a damaged frame, so it is resent rather than acknowledged and lost.
    ++statistics_.frames_rejected;
    if (sequenced) reply(receiver_.on_bad_frame(message.error()));
    return;
  }
  ++statistics_.frames_received;
  sender_.heard(now_ms());
  if (sequenced) {
    const std::uint8_t expected = receiver_.expected_sequence();
    const protocol::Reception r = receiver_.on_frame(frame, 0, now_ms());
    reply(r);
    if (r.disposition != protocol::Disposition::Deliver) {
      const bool behind = static_cast<std::uint8_t>(frame.sequence - expected) >= 128;
      if (receiver_.connected() && behind) ++statistics_.batches_repeated;
      return;
    }
    ++statistics_.batches_delivered;
  } else {
    (void)receiver_.on_frame(frame, 0, now_ms());  // any frame shows the controller is alive
    const auto handled = sender_.on_message(message.value(), now_ms());
    if (!handled) raise(handled.failure());
  }
  // Reports before this session's Capabilities were sent to an earlier session (a serial port
  // keeps what a controller sent after its last host left, e.g. ErrorReport(LinkTimeout)).
  if (sender_.state() != protocol::LinkState::Connected) return;
  const auto type = message.value().type();
  if (type != protocol::MessageType::Capabilities && type != protocol::MessageType::Ack &&
      type != protocol::MessageType::Nak && handler) {
    handler(message.value());
  }
}

void HostLink::submit(const protocol::Message& message) {
  const auto submitted = sender_.submit(message);
  if (!submitted) raise(submitted.failure());
}

void HostLink::transmit_due() {
  std::array<std::byte, protocol::max_encoded_frame_size> frame{};
  for (;;) {
    const auto size = sender_.poll(now_ms(), frame);
    if (!size) raise(size.failure());
    if (size.value() == 0) return;
    transport_.write(std::span<const std::byte>(frame.data(), size.value()));
    statistics_.bytes_sent += size.value();
  }
}

void HostLink::pump(int wait_ms, const Handler& handler) {
  // What arrived while this host was busy elsewhere (planning, reading a file) is taken in before
  // the sender judges silence and resends: the controller's heartbeats and Acks in the port's
  // buffer show it alive, however long the host was away.
  receive(0, handler);
  transmit_due();
  receive(wait_ms, handler);
  reply(receiver_.poll(0, now_ms()));  // heartbeat Ack of the setpoint stream
  transmit_due();
}

void HostLink::receive(int wait_ms, const Handler& handler) {
  std::array<std::byte, 512> bytes{};
  std::size_t count = transport_.read(bytes, wait_ms);
  while (count > 0) {
    for (std::size_t i = 0; i < count; ++i) {
      const auto pushed = decoder_.push(bytes[i]);
      if (!pushed) {
        ++statistics_.frames_rejected;
        reply(receiver_.on_bad_frame(pushed.error(), now_ms()));  // a Nak: the controller resends at once
        continue;
      }
      if (pushed.value()) on_frame(decoder_.frame(), handler);
    }
    count = transport_.read(bytes, 0);
  }
}

}  // namespace curvestep::host::link
