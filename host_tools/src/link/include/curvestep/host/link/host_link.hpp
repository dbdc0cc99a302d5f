// SPDX-License-Identifier: MIT
// HostLink: the host's end of the link over a Transport: lib/protocol's LinkSender (handshake,
// window, credit, retransmission) for the host's commands, a LinkReceiver (Endpoint::Host) for
// the controller's sequenced SetpointBatch stream (each batch delivered once and in order,
// acknowledged, damaged or missing ones Nak-ed so the controller resends them), and a
// FrameDecoder for the controller's frames.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

#include <curvestep/core/error.hpp>
#include <curvestep/host/link/transport.hpp>
#include <curvestep/protocol/frame_decoder.hpp>
#include <curvestep/protocol/link_receiver.hpp>
#include <curvestep/protocol/link_sender.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::host::link {

/// The link failed: `code` is the protocol's reason (LinkTimeout, RetransmitLimit, ...).
class LinkError : public std::runtime_error {
 public:
  /// An error with a one-line message.
  LinkError(Error code, const std::string& message) : std::runtime_error(message), code_(code) {}
  /// The protocol's error code.
  [[nodiscard]] Error code() const noexcept { return code_; }

 private:
  Error code_;
};

/// Counters for reports and tests.
struct LinkStatistics {
  std::size_t frames_received = 0;   ///< good frames from the controller
  std::size_t frames_rejected = 0;   ///< damaged frames (CRC, framing, length, payload)
  std::size_t bytes_sent = 0;        ///< bytes written, retransmissions included
  std::size_t batches_delivered = 0; ///< setpoint batches delivered (each exactly once)
  std::size_t batches_repeated = 0;  ///< setpoint batches received again (resent by the controller) and dropped
};

/// Host end of the link on one transport.
class HostLink {
 public:
  /// Window of unacknowledged frames.
  static constexpr std::size_t window = 8;
  /// Called for every message that is not Capabilities, Ack or Nak (SetpointBatch: once each, in order).
  using Handler = std::function<void(const protocol::Message&)>;

  /// A link over `transport` (not owned) with the sender's timing.
  HostLink(Transport& transport, protocol::SenderSettings settings);

  /// How long connect() keeps trying, ms (default_handshake_timeout_ms).
  static constexpr std::uint32_t default_handshake_timeout_ms = 10000;
  /// Handshake: sends Hello until Capabilities arrives. A round of Hellos that draws no answer (the
  /// sender gives up after max_retransmits) is retried with a new session after a pause that doubles
  /// from 100 ms up to 1 s, until handshake_timeout_ms have passed. Throws LinkError (LinkTimeout
  /// naming what arrived meanwhile: damaged frames, other frames or nothing; VersionMismatch) or
  /// TransportError.
  void connect(const Handler& handler);
  /// Sets how long connect() keeps trying, ms.
  void set_handshake_timeout_ms(std::uint32_t timeout_ms) noexcept { handshake_timeout_ms_ = timeout_ms; }
  /// True if `type` may be submitted now (window and credit).
  [[nodiscard]] bool can_submit(protocol::MessageType type) const noexcept { return sender_.can_submit(type); }
  /// Queues a host command. Throws LinkError if the sender refuses it.
  void submit(const protocol::Message& message);
  /// Takes in the bytes already waiting, sends what is due, waits up to wait_ms for more, and
  /// decodes them, calling `handler` for application messages. Silence is judged after the
  /// waiting bytes were read: a host that did not pump for longer than the link timeout fails
  /// only if the controller sent nothing meanwhile. Throws LinkError if the link gives up,
  /// TransportError if the line closes.
  void pump(int wait_ms, const Handler& handler);
  /// The controller's limits (after connect).
  [[nodiscard]] const protocol::Capabilities& capabilities() const noexcept { return sender_.capabilities(); }
  /// True if every submitted frame was acknowledged.
  [[nodiscard]] bool idle() const noexcept { return sender_.idle(); }
  /// Frames submitted and not yet acknowledged (the oldest ones of those submitted).
  [[nodiscard]] std::size_t in_flight() const noexcept { return sender_.in_flight(); }
  /// Counters.
  [[nodiscard]] const LinkStatistics& statistics() const noexcept { return statistics_; }
  /// Milliseconds since this link was made (wrapping, the sender's clock).
  [[nodiscard]] std::uint32_t now_ms() const noexcept;

 private:
  void transmit_due();
  /// Reads and decodes bytes until none arrive within wait_ms (the first read) or at once (the next).
  void receive(int wait_ms, const Handler& handler);
  [[noreturn]] void raise(const Failure& failure) const;

  void on_frame(const protocol::Frame& frame, const Handler& handler);
  void reply(const protocol::Reception& reception);

  Transport& transport_;
  protocol::LinkSender<window> sender_;
  protocol::LinkReceiver receiver_;
  protocol::FrameDecoder<> decoder_;
  std::chrono::steady_clock::time_point epoch_;
  LinkStatistics statistics_;
  std::uint32_t handshake_timeout_ms_ = default_handshake_timeout_ms;
};

/// One line naming the error code and its meaning ("link timeout (LinkTimeout)").
[[nodiscard]] std::string describe_error(Error code);
/// A limit switch by its bit number (HardLimit's index, StatusReport::limit_switches): "X min", "Z max".
[[nodiscard]] std::string limit_switch_name(std::uint16_t bit);

}  // namespace curvestep::host::link
