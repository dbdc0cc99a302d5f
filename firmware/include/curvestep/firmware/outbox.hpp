// SPDX-License-Identifier: MIT
// Outbox: the App's outgoing frames (link replies, reports) on their way to the serial line.
//
// Every frame is encoded whole into the TransmitBuffer (transmit_buffer.hpp), numbered by the
// link's outgoing sequence (LinkReceiver::next_outgoing_sequence), or not queued at all when it does
// not fit: it is then counted in `dropped` (AppStatistics::dropped_frames). The setpoint stream queues its
// batches into the same buffer (SetpointStream::transmit, buffer()); flush() writes what the board
// takes without waiting. An ErrorReport names the sequence number of the frame being answered
// (answering()), or, for a fault met while running, of the last frame received.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/core/result.hpp>
#include <curvestep/firmware/transmit_buffer.hpp>
#include <curvestep/protocol/frame.hpp>
#include <curvestep/protocol/link_receiver.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::firmware {

/// The transmit buffer and the sequence number ErrorReports answer.
class Outbox {
 public:
  /// The frame now being answered (its sequence number goes into ErrorReports).
  void answering(std::uint8_t sequence) noexcept { sequence_ = sequence; }
  /// The ErrorReport of `failure` for the frame being answered.
  [[nodiscard]] protocol::ErrorReport error_report(Failure failure) const noexcept {
    return protocol::ErrorReport{failure.code, failure.index, sequence_};
  }

  /// Queues the link's reply to a reception (Ack, Nak, Capabilities), if it has one.
  void reply(protocol::LinkReceiver& link, const protocol::Reception& r, std::uint32_t& dropped) noexcept {
    if (r.reply != protocol::ReplyKind::None) encode_reply(link, r, dropped);
  }
  /// Queues message `m` as the link's next outgoing frame.
  template <class M>
  void send(protocol::LinkReceiver& link, const M& m, std::uint32_t& dropped) noexcept {
    std::array<std::byte, protocol::max_encoded_frame_size> frame{};
    const auto size = protocol::encode_frame(m, link.next_outgoing_sequence(), frame);
    if (size) queue(std::span<const std::byte>(frame.data(), size.value()), dropped);
  }

  /// The buffer the setpoint stream queues its batches into.
  [[nodiscard]] TransmitBuffer& buffer() noexcept { return transmit_; }
  /// Writes what `board` takes now.
  template <class B>
  void flush(B& board) noexcept {
    transmit_.flush(board);
  }

 private:
  /// Not inlined: its frame buffer must not sit in poll()'s frame, under the command handlers.
  [[gnu::noinline]] void encode_reply(protocol::LinkReceiver& link, const protocol::Reception& r, std::uint32_t& dropped) noexcept {
    std::array<std::byte, protocol::max_encoded_frame_size> frame{};
    const auto size = link.encode_reply(r, frame);
    if (size) queue(std::span<const std::byte>(frame.data(), size.value()), dropped);
  }

  void queue(std::span<const std::byte> frame, std::uint32_t& dropped) noexcept {
    if (!transmit_.queue(frame)) ++dropped;
  }

  TransmitBuffer transmit_{};
  std::uint8_t sequence_ = 0;  ///< the sequence number of the frame being answered
};

}  // namespace curvestep::firmware
