// SPDX-License-Identifier: MIT
// Frames: [type][sequence][payload][CRC-16 LE], COBS-encoded and ended by one 0x00 byte.
//
// Why this layout. A serial line loses, corrupts and (through USB adapters and restarts)
// truncates bytes; the frame must survive all three without help from the payload:
//   * the 0x00 delimiter plus COBS lets a receiver find the next frame after any garbage,
//     because 0x00 never occurs inside an encoded frame;
//   * the CRC-16/CCITT-FALSE covers type, sequence and payload, so a corrupted header is
//     caught exactly like corrupted data (every 1-3 bit error is detected, see crc16.hpp);
//   * the messages that carry machine data (MachineConfiguration, QueueSegment, SetpointBatch)
//     end their payload with a CRC-32C of type and payload (messages.hpp; why: crc32.hpp);
//     parse_frame checks it too, so a frame that passes the CRC-16 by chance is still refused
//     (BadCrc) before the link acknowledges it;
//   * the sequence number in every frame lets the link layer detect loss, duplicates and
//     reordering (link_sender.hpp, link_receiver.hpp);
//   * there is no length field: COBS delimits the frame, and a length byte would be one
//     more thing to corrupt. The payload length is the frame length minus four.
// Sizes: a frame holds at most max_payload_size (162) payload bytes, 166 bytes before COBS
// and 168 on the wire, so the whole receive buffer of a small controller is 167 bytes.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/core/result.hpp>
#include <curvestep/protocol/cobs.hpp>
#include <curvestep/protocol/crc16.hpp>
#include <curvestep/protocol/crc32.hpp>
#include <curvestep/protocol/limits.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::protocol {

/// A checked frame: header fields and a view of the payload (valid while the buffer lives).
struct Frame {
  std::uint8_t type = 0;                  ///< raw message type (may be unknown to this version)
  std::uint8_t sequence = 0;              ///< sender's sequence number
  std::span<const std::byte> payload{};   ///< payload bytes, 0..max_payload_size
};

/// Builds the frame for `type`, `sequence` and `payload` into `out`: COBS bytes then 0x00.
/// FrameTooLong if the payload exceeds max_payload_size; BufferTooSmall if `out` is too short.
[[nodiscard]] constexpr Result<std::size_t> encode_frame(std::uint8_t type, std::uint8_t sequence,
                                                         std::span<const std::byte> payload,
                                                         std::span<std::byte> out) noexcept {
  if (payload.size() > max_payload_size) return fail(Error::FrameTooLong, payload.size());
  std::array<std::byte, max_frame_size> raw{};
  raw[0] = std::byte{type};
  raw[1] = std::byte{sequence};
  for (std::size_t i = 0; i < payload.size(); ++i) raw[frame_header_size + i] = payload[i];
  const std::size_t body = frame_header_size + payload.size();
  const std::uint16_t crc = crc16(std::span<const std::byte>(raw.data(), body));
  raw[body] = std::byte{static_cast<std::uint8_t>(crc & 0xFFu)};
  raw[body + 1] = std::byte{static_cast<std::uint8_t>(crc >> 8)};
  CURVESTEP_TRY(const std::size_t encoded, cobs_encode(std::span<const std::byte>(raw.data(), body + frame_crc_size), out));
  if (encoded >= out.size()) return fail(Error::BufferTooSmall, encoded + 1);
  out[encoded] = std::byte{0};
  return encoded + 1;
}

/// Builds the frame carrying message `m` with `sequence` into `out` (see the overload above).
[[nodiscard]] constexpr Result<std::size_t> encode_frame(const Message& m, std::uint8_t sequence,
                                                         std::span<std::byte> out) noexcept {
  std::array<std::byte, max_payload_size> payload{};
  CURVESTEP_TRY(const std::size_t size, encode(m, payload));
  return encode_frame(static_cast<std::uint8_t>(m.type()), sequence, std::span<const std::byte>(payload.data(), size),
                      out);
}

/// Checks a COBS-decoded frame (without delimiter): FrameTooShort below 4 bytes, FrameTooLong
/// above max_frame_size (index = length), BadCrc (index = sequence byte as received) if the
/// frame's CRC-16 or, for the types that carry one, the message's CRC-32C does not match.
[[nodiscard]] constexpr Result<Frame> parse_frame(std::span<const std::byte> raw) noexcept {
  if (raw.size() < min_frame_size) return fail(Error::FrameTooShort, raw.size());
  if (raw.size() > max_frame_size) return fail(Error::FrameTooLong, raw.size());
  const std::size_t body = raw.size() - frame_crc_size;
  const std::uint16_t expected = crc16(raw.first(body));
  const auto received = static_cast<std::uint16_t>(static_cast<std::uint16_t>(raw[body]) |
                                                   (static_cast<std::uint16_t>(raw[body + 1]) << 8));
  if (expected != received) return fail(Error::BadCrc, static_cast<std::uint8_t>(raw[1]));
  Frame frame;
  frame.type = static_cast<std::uint8_t>(raw[0]);
  frame.sequence = static_cast<std::uint8_t>(raw[1]);
  frame.payload = raw.subspan(frame_header_size, body - frame_header_size);
  if (carries_message_crc(frame.type) && !message_crc_matches(frame.type, frame.payload)) {
    return fail(Error::BadCrc, frame.sequence);
  }
  return frame;
}

/// Decodes the message a checked frame carries (UnknownMessage, BadPayload).
[[nodiscard]] constexpr Result<Message> decode_message(const Frame& frame) noexcept {
  return decode_message(frame.type, frame.payload);
}

}  // namespace curvestep::protocol
