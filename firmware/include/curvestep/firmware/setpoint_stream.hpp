// SPDX-License-Identifier: MIT
// SetpointStream: the controller's reliable SetpointBatch stream (protocol version 2).
//
// The tick puts each setpoint into a ring (board_setpoint_buffer<B>(), 48 by default); submit()
// moves full batches (up to 24 setpoints) into the window of a LinkSender<W> (the same
// go-back-N code the host uses for its commands, W = board_setpoint_window<B>()), which numbers
// them, keeps them encoded until the host acknowledges them and resends them on a timeout or a
// Nak; transmit() hands due frames to the TransmitBuffer. Nothing is ever dropped: when the ring
// is full the App stops advancing its interpolator (App::ready_to_tick). On a noisy line the
// batches shrink (halved on every go-back, down to min_setpoints_per_batch, grown by one per
// clean batch): at 2 % damaged bytes a 160-byte frame arrives 4 % of the time, a 40-byte one 45 %.
// The sender gives up after 255 timeouts without progress (RetransmitLimit, or LinkTimeout if
// nothing at all was heard from the host meanwhile: heard() tells it of every frame).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/core/container/ring_buffer.hpp>
#include <curvestep/core/result.hpp>
#include <curvestep/firmware/app_settings.hpp>
#include <curvestep/firmware/transmit_buffer.hpp>
#include <curvestep/protocol/frame.hpp>
#include <curvestep/protocol/link_sender.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::firmware {

/// The setpoint stream of an App on board B.
template <class B>
class SetpointStream {
 public:
  /// Frames of setpoint batches that may be unacknowledged at once.
  static constexpr std::size_t window = board_setpoint_window<B>();
  /// The sender: SetpointBatch only (so it links only that encoder), no handshake of its own.
  using Sender = protocol::LinkSender<window, protocol::MessageSet<protocol::SetpointBatch>>;

  /// A closed stream (open() when a session starts).
  explicit SetpointStream(std::uint32_t retransmit_timeout_ms) noexcept
      : sender_(protocol::SenderSettings{retransmit_timeout_ms, 255, 0}, protocol::Endpoint::Controller) {}

  /// Starts the stream afresh at sequence 0 (a new session): nothing buffered, full batches.
  void open(std::uint32_t now) noexcept {
    setpoints_.clear();
    sender_.open(now);
    batch_limit_ = protocol::max_setpoints_per_batch;
    seen_go_backs_ = 0;
  }

  /// True if no further setpoint fits (the tick must not advance).
  [[nodiscard]] bool full() const noexcept { return setpoints_.full(); }

  /// Buffers setpoint `index` at `position` (the caller checked full()).
  void push(std::uint32_t index, const protocol::WirePoint& position) noexcept {
    [[maybe_unused]] const bool pushed = setpoints_.try_push(Indexed{index, position});
  }

  /// Moves buffered setpoints into the window as batches of `axis_count` axes; `stopped`: send
  /// a short batch too (a stopped or stalled interpolator must not hold back what it produced).
  /// Go-backs seen are added to `go_backs`.
  void submit(bool stopped, std::uint8_t axis_count, std::uint32_t& go_backs) noexcept {
    adapt_batch_size(go_backs);
    while (!setpoints_.empty() && sender_.can_submit(protocol::MessageType::SetpointBatch)) {
      if (setpoints_.size() < batch_limit_ && !stopped) return;
      protocol::SetpointBatch batch;
      batch.axis_count = axis_count;
      batch.first_index = setpoints_.front().index;
      std::size_t count = 0;
      while (count < setpoints_.size() && count < batch_limit_ &&
             setpoints_[count].index == batch.first_index + count) {
        batch.setpoints[count] = setpoints_[count].position;
        ++count;
      }
      // Fast axes take up to 5 varint bytes per delta: keep the batch within one payload.
      while (count > 1 && protocol::encoded_size(batch, count) > protocol::max_message_size) --count;
      batch.count = static_cast<std::uint8_t>(count);
      if (!sender_.submit(batch)) return;  // cannot happen: checked can_submit and size
      for (std::size_t i = 0; i < count; ++i) setpoints_.pop_front();
      if (batch_limit_ < protocol::max_setpoints_per_batch && sender_.go_backs() == seen_go_backs_) ++batch_limit_;
    }
  }

  /// Hands due frames (new or resent) to `out`, keeping transmit_reserve_bytes for replies; the
  /// sender's failure (RetransmitLimit, LinkTimeout) if it gave up. Not inlined: its frame
  /// buffer must not sit in poll()'s frame, under the command handlers.
  [[nodiscard, gnu::noinline]] Result<void> transmit(std::uint32_t now, TransmitBuffer& out) noexcept {
    if (sender_.state() != protocol::LinkState::Connected) return ok();
    std::array<std::byte, protocol::max_encoded_frame_size> frame{};
    while (out.available() >= protocol::max_encoded_frame_size + transmit_reserve_bytes) {
      const auto size = sender_.poll(now, frame);
      if (!size) return size.failure();
      if (size.value() == 0) return ok();
      [[maybe_unused]] const bool queued = out.queue(std::span<const std::byte>(frame.data(), size.value()));
    }
    return ok();
  }

  /// The host's Ack or Nak of the stream (decoded with those two decoders only); the sender's
  /// failure if it gives up. Not inlined: its decoded Message (about 300 bytes) must not sit in
  /// receive()'s frame, under the deepest call chain (dispatch -> queue_segment -> planning).
  [[nodiscard, gnu::noinline]] Result<void> on_reply(const protocol::Frame& frame, std::uint32_t now) noexcept {
    const auto m = protocol::decode_message<protocol::MessageSet<protocol::Ack, protocol::Nak>>(frame);
    if (!m) return ok();
    return sender_.on_message(m.value(), now);
  }

  /// The host was heard at `now` (any valid frame): the sender tells a silent host
  /// (LinkTimeout) from one that talks but never acknowledges (RetransmitLimit).
  void heard(std::uint32_t now) noexcept { sender_.heard(now); }

  /// True once the sender gave up (only a new session reopens it).
  [[nodiscard]] bool failed() const noexcept { return sender_.state() == protocol::LinkState::Failed; }

  /// The sender (window, go-backs), for diagnostics and tests.
  [[nodiscard]] const Sender& sender() const noexcept { return sender_; }

 private:
  struct Indexed {
    std::uint32_t index = 0;
    protocol::WirePoint position{};
  };

  /// Halves the batch size after each retransmission round (short frames survive a noisy line).
  void adapt_batch_size(std::uint32_t& go_backs) noexcept {
    if (sender_.go_backs() == seen_go_backs_) return;
    go_backs += sender_.go_backs() - seen_go_backs_;
    seen_go_backs_ = sender_.go_backs();
    batch_limit_ = batch_limit_ / 2 < min_setpoints_per_batch ? min_setpoints_per_batch : batch_limit_ / 2;
  }

  Sender sender_;
  RingBuffer<Indexed, board_setpoint_buffer<B>()> setpoints_{};
  std::size_t batch_limit_ = protocol::max_setpoints_per_batch;
  std::uint32_t seen_go_backs_ = 0;
};

}  // namespace curvestep::firmware
