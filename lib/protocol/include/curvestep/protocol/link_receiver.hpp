// SPDX-License-Identifier: MIT
// LinkReceiver: the receiving half of a reliable stream (acks, naks, credit; the handshake at
// the controller), used in both directions: by the controller for the host's commands, and by
// the host for the controller's SetpointBatch stream.
//
// Why it looks like this. The controller is the side with the least memory and the hard
// real-time job, so the receiving half is the simple one: go-back-N. It keeps no reorder
// buffer, only the next sequence number it expects:
//   * sequence == expected: the frame is delivered to the application, expected advances,
//     and an Ack(next_expected, credit_end) goes back;
//   * sequence behind expected (a duplicate, (seq - expected) mod 256 >= 128): ignored and
//     acknowledged again, because the host evidently missed the first Ack;
//   * sequence ahead of expected (a gap): discarded, and one Nak(expected) asks the host
//     to go back; further frames of the same gap are discarded silently so one loss does
//     not trigger a storm of retransmissions. The Nak is armed again when the sender has
//     evidently gone back and the gap is still there (an ahead frame no further ahead than
//     the last one seen: a new round of resends), or after nak_interval_ms;
//   * a damaged frame (bad CRC, framing, length) is always Nak-ed: it is direct evidence of
//     a loss, and on a noisy line a Nak repairs it at once where the sender's timer would
//     wait (and count toward its retransmission limit). The sender goes back on a Nak only
//     once everything outstanding has been (re)sent, so several Naks for one round of frames
//     cause one go-back, not a storm.
// Credit: the host may send a QueueSegment only while it has credit. The controller
// advertises credit_end = (segments accepted so far) + (free queue slots), modulo 2^16. That
// edge only ever moves forward (like TCP's right window edge), so a stale or reordered Ack can
// never shrink what the host was promised, and the host, which counts the segments it sent,
// can never overrun the queue. Control messages (Start, FeedHold, Abort, StatusRequest, ...)
// take no credit, so Abort gets through even when the queue is full.
// Handshake: Hello carries a version and a host-chosen session number. A version mismatch (or a
// Hello of the wrong length) is refused with Nak(VersionMismatch); a new session resets sequence
// and credit; a repeated Hello of the current session (a retransmission) only repeats the Capabilities answer.
// Sequenced frames before any handshake get Nak(NotConnected), which tells a host that was
// connected that the controller restarted.
// At the host (Endpoint::Host) there is no Hello to receive: open() starts the stream when the
// host's own handshake succeeded, only SetpointBatch frames are sequenced, and the Acks carry
// credit_end 0 (the host takes whatever the controller sends; the controller ignores it).
// The controller also sends an Ack when credit grows and, if configured, every ack_interval_ms
// as a heartbeat, so a lost credit update cannot deadlock the link.
// It decodes only Hello and encodes only Capabilities, Ack and Nak (each through its own typed
// codec, so no all-types codec is linked).
// Cost: no buffers; a handful of bytes of state; every call is O(1).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/core/result.hpp>
#include <curvestep/protocol/frame.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::protocol {

/// What the application should do with a received frame.
enum class Disposition : std::uint8_t {
  Ignore,   ///< nothing to deliver (duplicate, gap, link-control frame, refused)
  Deliver,  ///< new in-order frame: decode it (decode_message<HostToController>(frame), or decode<T> by its type) and act on it
  Connect,  ///< a new session started: the application should reset its job state
};

/// Which reply the controller should send.
enum class ReplyKind : std::uint8_t {
  None,          ///< nothing to send
  Ack,           ///< send reply_ack
  Nak,           ///< send reply_nak
  Capabilities,  ///< send the receiver's capabilities
};

/// Result of one receiver step: what to deliver and what to answer.
struct Reception {
  Disposition disposition = Disposition::Ignore;  ///< what to do with the frame
  ReplyKind reply = ReplyKind::None;              ///< what to answer
  Ack ack{};                                      ///< the Ack to send, if reply == Ack
  Nak nak{};                                      ///< the Nak to send, if reply == Nak
};

/// Settings of the controller's link end.
struct ReceiverSettings {
  std::uint32_t ack_interval_ms = 0;    ///< heartbeat Ack period while connected (0: none)
  std::uint32_t link_timeout_ms = 0;    ///< silence after which check_link fails (0: never)
  std::uint32_t nak_interval_ms = 20;   ///< a further Nak for the same gap after this long (0: one per gap)
};

/// The controller's end of the link; allocation-free, time passed in as now_ms.
class LinkReceiver {
 public:
  /// A receiver that answers Hello with `capabilities` (its version, queue capacity, ...);
  /// `local` is the end it serves (the controller unless told otherwise).
  constexpr explicit LinkReceiver(const Capabilities& capabilities, ReceiverSettings settings = {},
                                  Endpoint local = Endpoint::Controller) noexcept
      : capabilities_(capabilities), settings_(settings), local_(local) {}

  /// Starts a new stream without a Hello (the host's receiver, once its own handshake is done):
  /// next expected sequence 0, no credit.
  constexpr void open(std::uint32_t now_ms) noexcept {
    connected_ = true;
    expected_ = 0;
    last_ahead_ = 0;
    segments_accepted_ = 0;
    nak_sent_ = false;
    credit_end_ = 0;
    advertised_credit_end_ = 0;
    last_ack_ms_ = now_ms;
    last_frame_ms_ = now_ms;
  }

  /// Ends the stream: sequenced frames are ignored (host) or Nak-ed NotConnected (controller).
  constexpr void close() noexcept { connected_ = false; }

  /// Handles one checked frame from the host. `free_queue_slots` is the number of empty queue
  /// slots before this frame is processed. `enforce_credit` false: a credit command is delivered
  /// (and counted) even beyond the credit, because the application refuses it by its state
  /// anyway (the controller without a configuration answers ConfigurationMissing, not QueueFull).
  [[nodiscard]] constexpr Reception on_frame(const Frame& frame, std::uint16_t free_queue_slots,
                                             std::uint32_t now_ms, bool enforce_credit = true) noexcept {
    last_frame_ms_ = now_ms;
    const bool controller = local_ == Endpoint::Controller;
    if (controller && frame.type == static_cast<std::uint8_t>(MessageType::Hello)) {
      return on_hello(frame, free_queue_slots, now_ms);
    }
    const auto type = static_cast<MessageType>(frame.type);
    // Frames outside the sequenced stream toward this end (Ack, Nak, reports, ...) are the
    // application's. At the controller, unknown types take a sequence number like any command
    // and are delivered, so the application reports UnknownMessage.
    if (!is_sequenced_toward(local_, frame.type)) return {};
    if (!connected_) return controller ? nak(Error::NotConnected, true, now_ms) : Reception{};
    const auto distance = static_cast<std::uint8_t>(frame.sequence - expected_);
    if (distance >= 128) {  // behind: a duplicate of something already delivered
      return acknowledge(free_queue_slots, now_ms);
    }
    if (distance != 0) {  // ahead: a gap
      if (nak_sent_ && distance <= last_ahead_) nak_sent_ = false;  // the sender went back: still a gap
      last_ahead_ = distance;
      return nak(Error::SequenceError, false, now_ms);
    }
    last_ahead_ = 0;
    grow_credit(free_queue_slots);
    if (enforce_credit && consumes_credit(type) && segments_accepted_ == credit_end_) {
      return nak(Error::QueueFull, true, now_ms);
    }
    ++expected_;
    nak_sent_ = false;
    if (consumes_credit(type)) ++segments_accepted_;
    Reception r = acknowledge_current(now_ms);
    r.disposition = Disposition::Deliver;
    return r;
  }

  /// Handles a frame the decoder dropped (BadCrc, BadFraming, ...): one Nak per gap, so the host
  /// retransmits at once instead of waiting for its timeout.
  [[nodiscard]] constexpr Reception on_bad_frame(Error reason) noexcept { return on_bad_frame(reason, last_frame_ms_); }

  /// As above, at time `now_ms`.
  [[nodiscard]] constexpr Reception on_bad_frame(Error reason, std::uint32_t now_ms) noexcept {
    if (!connected_) return {};
    Reception r = nak(reason, true, now_ms);
    nak_sent_ = true;  // the gap this damage opened is Nak-ed
    last_nak_ms_ = now_ms;
    return r;
  }

  /// Periodic step: an Ack if credit grew since the last one or the heartbeat is due.
  [[nodiscard]] constexpr Reception poll(std::uint16_t free_queue_slots, std::uint32_t now_ms) noexcept {
    if (!connected_) return {};
    grow_credit(free_queue_slots);
    const bool grew = credit_end_ != advertised_credit_end_;
    const bool due = settings_.ack_interval_ms != 0 && now_ms - last_ack_ms_ >= settings_.ack_interval_ms;
    if (!grew && !due) return {};
    return acknowledge_current(now_ms);
  }

  /// LinkTimeout (index = ms of silence, capped at 0xFFFF) if connected and nothing arrived for link_timeout_ms.
  [[nodiscard]] constexpr Result<void> check_link(std::uint32_t now_ms) const noexcept {
    if (!connected_ || settings_.link_timeout_ms == 0) return ok();
    const std::uint32_t silence = now_ms - last_frame_ms_;
    if (silence >= settings_.link_timeout_ms) return fail(Error::LinkTimeout, silence);
    return ok();
  }

  /// Encodes the reply of `r` as a frame into `out` (0 bytes if there is none).
  [[nodiscard]] constexpr Result<std::size_t> encode_reply(const Reception& r, std::span<std::byte> out) noexcept {
    switch (r.reply) {
      case ReplyKind::None: return std::size_t{0};
      case ReplyKind::Ack: return encode_frame(r.ack, next_outgoing_sequence(), out);
      case ReplyKind::Nak: return encode_frame(r.nak, next_outgoing_sequence(), out);
      case ReplyKind::Capabilities: break;
    }
    return encode_frame(capabilities_, next_outgoing_sequence(), out);
  }

  /// Sequence number for the next controller-to-host frame (a free-running diagnostic counter).
  [[nodiscard]] constexpr std::uint8_t next_outgoing_sequence() noexcept { return outgoing_sequence_++; }

  /// True after a successful handshake.
  [[nodiscard]] constexpr bool connected() const noexcept { return connected_; }
  /// The next sequence number expected from the host.
  [[nodiscard]] constexpr std::uint8_t expected_sequence() const noexcept { return expected_; }
  /// The credit edge granted so far (segments accepted + free slots, mod 2^16).
  [[nodiscard]] constexpr std::uint16_t credit_end() const noexcept { return credit_end_; }
  /// Segments accepted in this session (mod 2^16).
  [[nodiscard]] constexpr std::uint16_t segments_accepted() const noexcept { return segments_accepted_; }
  /// The capabilities sent in answer to Hello (credit_end and session filled in).
  [[nodiscard]] constexpr const Capabilities& capabilities() const noexcept { return capabilities_; }

 private:
  [[nodiscard]] constexpr Reception on_hello(const Frame& frame, std::uint16_t free_queue_slots,
                                             std::uint32_t now_ms) noexcept {
    Reception r;
    const auto hello = decode<Hello>(frame.payload);
    // A Hello of another layout (the wrong length) is another protocol version's: refused like
    // one that names another version. Its sequence byte is not looked at.
    if (!hello || hello.value().version != capabilities_.version) {
      // Refused, but an established session (and its link watchdog) stays as it is: a stray
      // Hello from another host version must not silently disconnect the running job.
      r.reply = ReplyKind::Nak;
      r.nak = Nak{expected_, Error::VersionMismatch};
      return r;
    }
    r.reply = ReplyKind::Capabilities;
    if (connected_ && hello.value().session == capabilities_.session) return r;  // a retransmitted Hello
    connected_ = true;
    expected_ = 0;
    last_ahead_ = 0;
    segments_accepted_ = 0;
    nak_sent_ = false;
    credit_end_ = free_queue_slots;
    advertised_credit_end_ = credit_end_;
    last_ack_ms_ = now_ms;
    capabilities_.session = hello.value().session;
    capabilities_.credit_end = credit_end_;
    r.disposition = Disposition::Connect;
    return r;
  }

  constexpr void grow_credit(std::uint16_t free_queue_slots) noexcept {
    const auto edge = static_cast<std::uint16_t>(segments_accepted_ + free_queue_slots);
    if (static_cast<std::int16_t>(static_cast<std::uint16_t>(edge - credit_end_)) > 0) credit_end_ = edge;
  }

  [[nodiscard]] constexpr Reception acknowledge(std::uint16_t free_queue_slots, std::uint32_t now_ms) noexcept {
    grow_credit(free_queue_slots);
    return acknowledge_current(now_ms);
  }

  [[nodiscard]] constexpr Reception acknowledge_current(std::uint32_t now_ms) noexcept {
    Reception r;
    r.reply = ReplyKind::Ack;
    r.ack = Ack{expected_, credit_end_};
    advertised_credit_end_ = credit_end_;
    last_ack_ms_ = now_ms;
    return r;
  }

  [[nodiscard]] constexpr Reception nak(Error reason, bool always, std::uint32_t now_ms) noexcept {
    Reception r;
    const bool rearmed = settings_.nak_interval_ms != 0 && now_ms - last_nak_ms_ >= settings_.nak_interval_ms;
    if (!always && nak_sent_ && !rearmed) return r;
    if (!always) {
      nak_sent_ = true;
      last_nak_ms_ = now_ms;
    }
    r.reply = ReplyKind::Nak;
    r.nak = Nak{expected_, reason};
    return r;
  }

  Capabilities capabilities_;
  ReceiverSettings settings_;
  std::uint32_t last_frame_ms_ = 0;
  std::uint32_t last_ack_ms_ = 0;
  std::uint32_t last_nak_ms_ = 0;
  std::uint16_t credit_end_ = 0;
  std::uint16_t advertised_credit_end_ = 0;
  std::uint16_t segments_accepted_ = 0;
  std::uint8_t expected_ = 0;
  std::uint8_t last_ahead_ = 0;  // distance ahead of the last out-of-order frame (0: none since the last delivery)
  std::uint8_t outgoing_sequence_ = 0;
  Endpoint local_ = Endpoint::Controller;
  bool connected_ = false;
  bool nak_sent_ = false;
};

}  // namespace curvestep::protocol
