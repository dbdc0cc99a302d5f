// SPDX-License-Identifier: MIT
// LinkSender: the sending half of a reliable stream (window, credit, retransmission), used in
// both directions: by the host for its commands (with the handshake), and by the controller for
// its SetpointBatch stream (opened by the handshake the controller received).
//
// Why it looks like this. The receiver is go-back-N with no reorder buffer (link_receiver.hpp),
// so the sender keeps every unacknowledged frame, already encoded, in a ring of `Window` slots
// and resends them in order when:
//   * the retransmission timer expires (one timer for the oldest unacknowledged frame, started
//     when it is first sent and restarted whenever an Ack makes progress, as in TCP), or
//   * a Nak names the oldest unacknowledged sequence number (an immediate go-back).
// Only timeouts count toward max_retransmits, and only timeouts in a row without progress:
// a Nak-triggered go-back is the normal repair of a damaged frame on a noisy line, and any
// acknowledgement that moves the window clears the count. After max_retransmits timeouts
// without progress the link fails, after about (max_retransmits + 1) x retransmit_timeout_ms
// of no progress: with LinkTimeout if nothing at all was heard from the peer in that time (it
// is gone), else with RetransmitLimit (index = the oldest sequence number: the peer talks but
// never takes the frame).
// With link_timeout_ms set, that timeout governs a silent peer and every lack of progress:
//   * a timeout counts toward max_retransmits only if the peer was heard since the previous
//     one, so a peer that is merely paused (a frozen process, a busy USB hub) is given the whole
//     link_timeout_ms of silence, not max_retransmits x retransmit_timeout_ms;
//   * frames outstanding and no acknowledgement that moves the window for link_timeout_ms fail
//     the link (RetransmitLimit if the peer was heard meanwhile and within the last half link
//     timeout, else LinkTimeout: it went silent), however many
//     Naks and go-backs kept the retransmission timer from expiring: on a line that damages
//     every long frame the Naks never stop, and without this bound nothing would ever fail.
// Sequence numbers are 8 bits; Window is at most 127, so "behind" and "ahead" can never be
// confused by the receiver.
// Flow control has two limits, both enforced by can_submit()/submit():
//   * the window: at most Window frames unacknowledged;
//   * the credit: a QueueSegment may be submitted only while segments_sent is before the
//     controller's credit_end (mod 2^16, taken from Capabilities and every Ack), so the host
//     never overruns the controller's queue whatever its size. Credit only moves forward.
// Handshake (host): connect() sends Hello(version, session) every retransmit_timeout_ms until a
// Capabilities with the same session arrives (LinkTimeout after max_retransmits tries). The
// controller's sender has no handshake of its own: open() starts its stream when the
// controller's LinkReceiver accepted a new session. A
// Capabilities with another version, or Nak(VersionMismatch), refuses the connection with
// VersionMismatch. Once connected, Nak(NotConnected) means the controller restarted:
// DeviceRestarted. With link_timeout_ms set, a connected host that hears nothing (the
// controller's heartbeat Acks included) for that long fails with LinkTimeout.
// Code size: the `Sends` parameter is the MessageSet this end submits (the host: commands and
// Hello; the controller: MessageSet<SetpointBatch>); only their encoders are linked, and a set
// without Hello has no handshake (no connect(), Capabilities ignored).
// Time is passed in (now_ms, wrapping uint32 arithmetic); nothing allocates. Memory is
// Window * (max_encoded_frame_size + 2) bytes plus counters: 8 slots take about 1.3 KiB.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/core/result.hpp>
#include <curvestep/protocol/frame.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::protocol {

/// Where the host's link end is.
enum class LinkState : std::uint8_t {
  Disconnected,  ///< connect() not called yet
  Connecting,    ///< Hello sent, waiting for Capabilities
  Connected,     ///< handshake done: submit() accepted
  Failed,        ///< gave up (see last_error()); connect() starts again
};

/// Timing of a sending link end.
struct SenderSettings {
  std::uint32_t retransmit_timeout_ms = 100;  ///< resend unacknowledged frames after this silence
  std::uint8_t max_retransmits = 10;          ///< timeouts in a row without progress (or Hellos) before failing
  /// Connected and nothing heard, or frames outstanding and none acknowledged, for this long:
  /// LinkTimeout or RetransmitLimit (0: never; then max_retransmits alone bounds both).
  std::uint32_t link_timeout_ms = 0;
};

/// A sending link end; `Window` frames may be unacknowledged at once; `Sends` (a MessageSet) is
/// what it may submit, plus Hello if it opens the link with a handshake.
template <std::size_t Window = 8, class Sends = AllMessages>
class LinkSender {
  static_assert(Window > 0 && Window <= 127, "Window must be 1..127 so 8-bit sequence numbers stay unambiguous");
  /// True if this end opens its link with Hello (the host); else open() starts the stream.
  static constexpr bool handshake = Sends::template contains<Hello>;

 public:
  /// A disconnected sender at `local` (the host by default) that sends toward the other end.
  constexpr explicit LinkSender(SenderSettings settings = {}, Endpoint local = Endpoint::Host) noexcept
      : settings_(settings), peer_(local == Endpoint::Host ? Endpoint::Controller : Endpoint::Host) {}

  /// Starts (or restarts) the handshake with a fresh, preferably random, `session` number.
  constexpr void connect(std::uint16_t session, std::uint32_t now_ms) noexcept
    requires handshake
  {
    reset(now_ms);
    state_ = LinkState::Connecting;
    session_ = session;
    hello_attempts_ = 0;
    hello_due_ = true;
  }

  /// Starts a new stream without a handshake of its own (the controller's setpoint stream, once
  /// its receiver accepted a new session): sequence 0, empty window, Connected.
  constexpr void open(std::uint32_t now_ms) noexcept {
    reset(now_ms);
    state_ = LinkState::Connected;
    heard_ms_ = now_ms;
  }

  /// True if `type` could be submitted now (connected, window not full, credit for a segment).
  [[nodiscard]] constexpr bool can_submit(MessageType type) const noexcept {
    if (state_ != LinkState::Connected || count_ >= Window) return false;
    return !consumes_credit(type) || credit() > 0;
  }

  /// Queues a sequenced message toward the peer for sending; returns its sequence number.
  /// NotConnected, QueueFull (window full or no credit), InvalidArgument (index = type) for a
  /// message outside `Sends` or one that does not travel in the sequenced stream toward the
  /// peer, or the encoder's error.
  [[nodiscard]] constexpr Result<std::uint8_t> submit(const Message& m) noexcept {
    return submit_as(m.type(), [&m](std::uint8_t sequence, std::span<std::byte> out) {
      return encode_frame<Sends>(m, sequence, out);
    });
  }

  /// submit() for a message struct of `Sends` (SetpointBatch, ...): encoded straight from `m`,
  /// without a Message copy of it on the stack.
  template <class M>
    requires(Sends::template contains<M>)
  [[nodiscard]] constexpr Result<std::uint8_t> submit(const M& m) noexcept {
    return submit_as(M::type, [&m](std::uint8_t sequence, std::span<std::byte> out) { return encode_frame(m, sequence, out); });
  }

  /// Next bytes to transmit into `out` (one whole frame), or 0 if nothing is due. Fails with
  /// LinkTimeout or RetransmitLimit when the link gives up (state becomes Failed).
  [[nodiscard]] constexpr Result<std::size_t> poll(std::uint32_t now_ms, std::span<std::byte> out) noexcept {
    if constexpr (handshake) {
      if (state_ == LinkState::Connecting) {
        if (!hello_due_ && now_ms - timer_ms_ < settings_.retransmit_timeout_ms) return std::size_t{0};
        if (hello_attempts_ > settings_.max_retransmits) return give_up(Error::LinkTimeout, session_);
        CURVESTEP_TRY(const std::size_t size, encode_frame(Hello{protocol_version, session_}, 0, out));
        ++hello_attempts_;
        hello_due_ = false;
        timer_ms_ = now_ms;
        return size;
      }
    }
    if (state_ != LinkState::Connected) return std::size_t{0};
    if (settings_.link_timeout_ms != 0 && now_ms - heard_ms_ >= settings_.link_timeout_ms) {
      return give_up(Error::LinkTimeout, now_ms - heard_ms_);
    }
    if (transmitted_ > 0 && settings_.link_timeout_ms != 0 && now_ms - progress_ms_ >= settings_.link_timeout_ms) {
      // The peer talks but never takes the frame only if it still talks: heard since the last
      // progress and within the last half link timeout. A frame it sent just before it went silent
      // (a cut line) does not make a gone peer a talking one.
      const bool talking = static_cast<std::int32_t>(heard_ms_ - progress_ms_) > 0 && now_ms - heard_ms_ < settings_.link_timeout_ms / 2;
      if (talking) return give_up(Error::RetransmitLimit, first_sequence_);
      return give_up(Error::LinkTimeout, now_ms - heard_ms_);
    }
    if (transmitted_ > 0 && now_ms - timer_ms_ >= settings_.retransmit_timeout_ms) {
      // With a link timeout a silent peer is judged by it alone: only timeouts the peer was heard in count.
      const bool counts = settings_.link_timeout_ms == 0 || heard_since_timeout_;
      heard_since_timeout_ = false;
      if (counts && timeouts_ >= settings_.max_retransmits) {
        const std::uint32_t silence = now_ms - heard_ms_;
        if (silence >= settings_.retransmit_timeout_ms * timeouts_) return give_up(Error::LinkTimeout, silence);
        return give_up(Error::RetransmitLimit, first_sequence_);
      }
      if (counts) ++timeouts_;
      go_back(now_ms);
    }
    if (sent_ >= count_) return std::size_t{0};
    const Slot& slot = slots_[(oldest_ + sent_) % Window];
    if (out.size() < slot.size) return fail(Error::BufferTooSmall, slot.size);
    for (std::size_t i = 0; i < slot.size; ++i) out[i] = slot.bytes[i];
    if (transmitted_ == 0) {  // the oldest frame's first transmission starts the timer and the progress watch
      timer_ms_ = now_ms;
      progress_ms_ = now_ms;
      heard_since_timeout_ = false;
    }
    ++sent_;
    if (sent_ > transmitted_) transmitted_ = sent_;
    return std::size_t{slot.size};
  }

  /// Handles a message from the peer: Capabilities (with a handshake), Ack and Nak drive the
  /// link; other messages are the application's and ignored here. Fails with VersionMismatch,
  /// DeviceRestarted or RetransmitLimit (state becomes Failed).
  [[nodiscard]] constexpr Result<void> on_message(const Message& m, std::uint32_t now_ms) noexcept {
    heard(now_ms);
    switch (m.type()) {
      case MessageType::Capabilities:
        if constexpr (handshake) return on_capabilities(m.get<Capabilities>(), now_ms);
        return ok();
      case MessageType::Ack: on_ack(m.get<Ack>().next_expected, m.get<Ack>().credit_end, true, now_ms); return ok();
      case MessageType::Nak: return on_nak(m.get<Nak>(), now_ms);
      default: return ok();
    }
  }

  /// The peer was heard at `now_ms` (any frame of its, also those handled elsewhere).
  constexpr void heard(std::uint32_t now_ms) noexcept {
    heard_ms_ = now_ms;
    heard_since_timeout_ = true;
  }

  /// Where the link is.
  [[nodiscard]] constexpr LinkState state() const noexcept { return state_; }
  /// Why the link failed (NotConnected before any failure).
  [[nodiscard]] constexpr Error last_error() const noexcept { return error_; }
  /// The controller's capabilities (meaningful once Connected; after a VersionMismatch refusal
  /// of its Capabilities, `version` is the controller's version, else 0).
  [[nodiscard]] constexpr const Capabilities& capabilities() const noexcept { return capabilities_; }
  /// Frames submitted and not yet acknowledged.
  [[nodiscard]] constexpr std::size_t in_flight() const noexcept { return count_; }
  /// True if every submitted frame was acknowledged.
  [[nodiscard]] constexpr bool idle() const noexcept { return count_ == 0; }
  /// Segments the host may still submit under the controller's credit.
  [[nodiscard]] constexpr std::uint16_t credit() const noexcept {
    const auto remaining = static_cast<std::int16_t>(static_cast<std::uint16_t>(credit_end_ - segments_sent_));
    return remaining > 0 ? static_cast<std::uint16_t>(remaining) : std::uint16_t{0};
  }
  /// Segments submitted in this session (mod 2^16).
  [[nodiscard]] constexpr std::uint16_t segments_sent() const noexcept { return segments_sent_; }
  /// The credit edge last granted by the controller.
  [[nodiscard]] constexpr std::uint16_t credit_end() const noexcept { return credit_end_; }
  /// Window capacity in frames.
  [[nodiscard]] static constexpr std::size_t window() noexcept { return Window; }
  /// Go-backs so far (timeouts and Naks), a measure of line quality; wraps.
  [[nodiscard]] constexpr std::uint32_t go_backs() const noexcept { return go_backs_; }
  /// Milliseconds since the window last moved (or its oldest frame was first sent), at `now_ms`.
  [[nodiscard]] constexpr std::uint32_t ms_without_progress(std::uint32_t now_ms) const noexcept { return now_ms - progress_ms_; }
  /// Timeouts in a row without progress (compared with max_retransmits).
  [[nodiscard]] constexpr std::uint8_t timeouts_without_progress() const noexcept { return timeouts_; }

 private:
  /// Checks and takes the next window slot for a message of `type`; `encode(sequence, out)` writes its frame.
  template <class Encode>
  [[nodiscard]] constexpr Result<std::uint8_t> submit_as(MessageType type, Encode&& encode) noexcept {
    if (state_ != LinkState::Connected) return fail(Error::NotConnected);
    if (!Sends::contains_type(static_cast<std::uint8_t>(type)) || !is_sequenced_toward(peer_, static_cast<std::uint8_t>(type))) {
      return fail(Error::InvalidArgument, static_cast<std::uint8_t>(type));
    }
    if (!can_submit(type)) return fail(Error::QueueFull, count_);
    const auto sequence = static_cast<std::uint8_t>(first_sequence_ + count_);
    Slot& slot = slots_[(oldest_ + count_) % Window];
    CURVESTEP_TRY(const std::size_t size, encode(sequence, std::span<std::byte>(slot.bytes)));
    slot.size = static_cast<std::uint16_t>(size);
    ++count_;
    if (consumes_credit(type)) ++segments_sent_;
    return sequence;
  }

  struct Slot {
    std::array<std::byte, max_encoded_frame_size> bytes{};
    std::uint16_t size = 0;
  };

  constexpr void reset(std::uint32_t now_ms) noexcept {
    capabilities_ = Capabilities{};
    capabilities_.version = 0;  // none heard yet
    timer_ms_ = now_ms;
    progress_ms_ = now_ms;
    heard_since_timeout_ = false;
    count_ = 0;
    sent_ = 0;
    transmitted_ = 0;
    oldest_ = 0;
    first_sequence_ = 0;
    segments_sent_ = 0;
    credit_end_ = 0;
    timeouts_ = 0;
    error_ = Error::NotConnected;
  }

  [[nodiscard]] constexpr Failure give_up(Error code, std::size_t index) noexcept {
    state_ = LinkState::Failed;
    error_ = code;
    return fail(code, index);
  }

  /// Resend everything unacknowledged, from the oldest frame, and restart the timer.
  constexpr void go_back(std::uint32_t now_ms) noexcept {
    sent_ = 0;
    timer_ms_ = now_ms;
    ++go_backs_;
  }

  [[nodiscard]] constexpr Result<void> on_capabilities(const Capabilities& c, std::uint32_t now_ms) noexcept {
    if (state_ != LinkState::Connecting || c.session != session_) return ok();  // stale or repeated answer
    capabilities_ = c;  // kept even when refused, so the caller can name the controller's version
    if (c.version != protocol_version) return give_up(Error::VersionMismatch, c.version);
    credit_end_ = c.credit_end;
    state_ = LinkState::Connected;
    heard_ms_ = now_ms;
    return ok();
  }

  constexpr void on_ack(std::uint8_t next_expected, std::uint16_t credit_end, bool has_credit,
                        std::uint32_t now_ms) noexcept {
    if (state_ != LinkState::Connected) return;
    if (has_credit && static_cast<std::int16_t>(static_cast<std::uint16_t>(credit_end - credit_end_)) > 0) {
      credit_end_ = credit_end;
    }
    const auto acknowledged = static_cast<std::uint8_t>(next_expected - first_sequence_);
    if (acknowledged == 0 || acknowledged > transmitted_) return;  // no progress, or stale
    oldest_ = (oldest_ + acknowledged) % Window;
    count_ -= acknowledged;
    transmitted_ -= acknowledged;
    sent_ = sent_ > acknowledged ? sent_ - acknowledged : 0;
    first_sequence_ = next_expected;
    timer_ms_ = now_ms;
    progress_ms_ = now_ms;
    heard_since_timeout_ = false;  // a new timer: the next timeout counts if the peer is heard before it
    timeouts_ = 0;
  }

  [[nodiscard]] constexpr Result<void> on_nak(const Nak& nak, std::uint32_t now_ms) noexcept {
    if (state_ == LinkState::Connecting) {
      if (nak.reason == Error::VersionMismatch) return give_up(Error::VersionMismatch, nak.expected);
      return ok();
    }
    if (state_ != LinkState::Connected) return ok();
    if (nak.reason == Error::NotConnected) return give_up(Error::DeviceRestarted, nak.expected);
    on_ack(nak.expected, 0, false, now_ms);
    // One go-back per round: Naks that arrive while a resend is still going out are covered by it.
    if (nak.expected == first_sequence_ && sent_ > 0 && sent_ >= count_) go_back(now_ms);
    return ok();
  }

  std::array<Slot, Window> slots_{};
  Capabilities capabilities_{};
  SenderSettings settings_;
  std::uint32_t timer_ms_ = 0;
  std::uint32_t heard_ms_ = 0;  // when the controller last sent anything
  std::uint32_t progress_ms_ = 0;  // the last acknowledgement that moved the window (or the first transmission)
  std::size_t oldest_ = 0;  // slot index of the oldest unacknowledged frame
  std::size_t count_ = 0;   // unacknowledged frames
  std::size_t sent_ = 0;    // of those, how many have been (re)transmitted since the last go-back
  std::size_t transmitted_ = 0;  // of those, how many have been transmitted at least once
  std::uint16_t segments_sent_ = 0;
  std::uint16_t credit_end_ = 0;
  std::uint32_t go_backs_ = 0;
  std::uint16_t session_ = 0;
  std::uint8_t first_sequence_ = 0;  // sequence number of the oldest unacknowledged frame
  std::uint8_t hello_attempts_ = 0;
  std::uint8_t timeouts_ = 0;  // timeouts in a row without progress
  Endpoint peer_ = Endpoint::Controller;
  bool hello_due_ = false;
  bool heard_since_timeout_ = false;  // the peer was heard since the timer last started or expired
  LinkState state_ = LinkState::Disconnected;
  Error error_ = Error::NotConnected;
};

}  // namespace curvestep::protocol
