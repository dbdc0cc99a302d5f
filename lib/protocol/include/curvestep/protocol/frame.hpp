// SPDX-License-Identifier: MIT
// Frames: [type][sequence][message][CRC-32C LE][CRC-16 LE], COBS-encoded, ended by one 0x00 byte.
// The payload is the message followed by its CRC-32C.
//
// Why this layout. A serial line loses, corrupts and (through USB adapters and restarts)
// truncates bytes; the frame must survive all three without help from the payload:
//   * the 0x00 delimiter plus COBS lets a receiver find the next frame after any garbage,
//     because 0x00 never occurs inside an encoded frame;
//   * the CRC-16/CCITT-FALSE covers type, sequence and payload, so a corrupted header is
//     caught exactly like corrupted data (every 1-3 bit error is detected, see crc16.hpp);
//   * every payload ends with a CRC-32C of type, sequence and message (why: crc32.hpp);
//     parse_frame checks it after the CRC-16, so a damaged frame that passes the CRC-16 by
//     chance (once in 65536) is still refused (BadCrc) before the link acknowledges it, and
//     Frame::payload is the message alone;
//   * the sequence number in every frame lets the link layer detect loss, duplicates and
//     reordering (link_sender.hpp, link_receiver.hpp);
//   * there is no length field: COBS delimits the frame, and a length byte would be one
//     more thing to corrupt. The message length is the frame length minus eight.
// Sizes: a message has at most max_message_size (158) bytes, a payload 162, a frame 166 bytes
// before COBS and 168 on the wire, so the whole receive buffer of a small controller is 167.
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

/// A checked frame: header fields and a view of the message (valid while the buffer lives).
struct Frame {
  std::uint8_t type = 0;                  ///< raw message type (may be unknown to this version)
  std::uint8_t sequence = 0;              ///< sender's sequence number
  std::span<const std::byte> payload{};   ///< the message bytes (its CRC-32C checked and removed), 0..max_message_size
};

namespace detail {

/// Completes a frame whose header and message fill raw[0, body): appends the message's CRC-32C
/// and the frame's CRC-16, COBS-encodes it into `out` and ends it with 0x00.
[[nodiscard]] constexpr Result<std::size_t> finish_frame(std::array<std::byte, max_frame_size>& raw, std::size_t body,
                                                         std::span<std::byte> out) noexcept {
  const std::uint32_t check = crc32c(std::span<const std::byte>(raw.data(), body));
  for (std::size_t i = 0; i < message_crc_size; ++i) raw[body + i] = std::byte{static_cast<std::uint8_t>(check >> (8 * i))};
  body += message_crc_size;
  const std::uint16_t crc = crc16(std::span<const std::byte>(raw.data(), body));
  raw[body] = std::byte{static_cast<std::uint8_t>(crc & 0xFFu)};
  raw[body + 1] = std::byte{static_cast<std::uint8_t>(crc >> 8)};
  CURVESTEP_TRY(const std::size_t encoded, cobs_encode(std::span<const std::byte>(raw.data(), body + frame_crc_size), out));
  if (encoded >= out.size()) return fail(Error::BufferTooSmall, encoded + 1);
  out[encoded] = std::byte{0};
  return encoded + 1;
}

}  // namespace detail

/// Builds the frame for `type`, `sequence` and `message` into `out`: the message's CRC-32C and
/// the frame's CRC-16 are appended, then COBS bytes and 0x00. FrameTooLong if the message
/// exceeds max_message_size; BufferTooSmall if `out` is too short.
[[nodiscard]] constexpr Result<std::size_t> encode_frame(std::uint8_t type, std::uint8_t sequence,
                                                         std::span<const std::byte> message,
                                                         std::span<std::byte> out) noexcept {
  if (message.size() > max_message_size) return fail(Error::FrameTooLong, message.size());
  std::array<std::byte, max_frame_size> raw{};
  raw[0] = std::byte{type};
  raw[1] = std::byte{sequence};
  for (std::size_t i = 0; i < message.size(); ++i) raw[frame_header_size + i] = message[i];
  return detail::finish_frame(raw, frame_header_size + message.size(), out);
}

/// Builds the frame carrying message struct `m` (Ack, SetpointBatch, ...) with `sequence` into
/// `out` (see the overload above); links the encoder of M only.
template <class M>
  requires(AllMessages::contains<M>)
[[nodiscard]] constexpr Result<std::size_t> encode_frame(const M& m, std::uint8_t sequence,
                                                         std::span<std::byte> out) noexcept {
  std::array<std::byte, max_frame_size> raw{};  // the message is encoded in place, after the header
  raw[0] = std::byte{static_cast<std::uint8_t>(M::type)};
  raw[1] = std::byte{sequence};
  CURVESTEP_TRY(const std::size_t size, encode(m, std::span<std::byte>(raw).subspan(frame_header_size, max_message_size)));
  return detail::finish_frame(raw, frame_header_size + size, out);
}

/// Builds the frame carrying the message `m` holds, if its type is in `Set` (only the set's
/// encoders are instantiated); InvalidArgument (index = type) for a type outside the set.
template <class Set = AllMessages>
[[nodiscard]] constexpr Result<std::size_t> encode_frame(const Message& m, std::uint8_t sequence,
                                                         std::span<std::byte> out) noexcept {
  std::array<std::byte, max_message_size> payload{};
  CURVESTEP_TRY(const std::size_t size, encode<Set>(m, payload));
  return encode_frame(static_cast<std::uint8_t>(m.type()), sequence, std::span<const std::byte>(payload.data(), size),
                      out);
}

/// Checks a COBS-decoded frame (without delimiter): FrameTooShort below 8 bytes, FrameTooLong
/// above max_frame_size (index = length), BadCrc (index = sequence byte as received) if the
/// frame's CRC-16 or the payload's CRC-32C does not match.
[[nodiscard]] constexpr Result<Frame> parse_frame(std::span<const std::byte> raw) noexcept {
  if (raw.size() < min_frame_size) return fail(Error::FrameTooShort, raw.size());
  if (raw.size() > max_frame_size) return fail(Error::FrameTooLong, raw.size());
  const std::size_t body = raw.size() - frame_crc_size;
  const std::uint16_t expected = crc16(raw.first(body));
  const auto received = static_cast<std::uint16_t>(static_cast<std::uint16_t>(raw[body]) |
                                                   (static_cast<std::uint16_t>(raw[body + 1]) << 8));
  if (expected != received) return fail(Error::BadCrc, static_cast<std::uint8_t>(raw[1]));
  const std::size_t message_end = body - message_crc_size;
  std::uint32_t check = 0;
  for (std::size_t i = 0; i < message_crc_size; ++i) check |= static_cast<std::uint32_t>(raw[message_end + i]) << (8 * i);
  if (check != crc32c(raw.first(message_end))) return fail(Error::BadCrc, static_cast<std::uint8_t>(raw[1]));
  Frame frame;
  frame.type = static_cast<std::uint8_t>(raw[0]);
  frame.sequence = static_cast<std::uint8_t>(raw[1]);
  frame.payload = raw.subspan(frame_header_size, message_end - frame_header_size);
  return frame;
}

/// Decodes the message a checked frame carries if its type is in `Set` (UnknownMessage,
/// BadPayload; see decode_message(type, payload)).
template <class Set = AllMessages>
[[nodiscard]] constexpr Result<Message> decode_message(const Frame& frame) noexcept {
  return decode_message<Set>(frame.type, frame.payload);
}

}  // namespace curvestep::protocol
