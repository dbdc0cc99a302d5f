// SPDX-License-Identifier: MIT
// Protocol constants: version, frame and payload sizes, message capacities.
#pragma once

#include <cstddef>
#include <cstdint>

namespace curvestep::protocol {

/// Protocol version exchanged in the handshake; both ends must agree exactly.
inline constexpr std::uint16_t protocol_version = 5;

/// Bytes of frame header: message type, sequence number.
inline constexpr std::size_t frame_header_size = 2;
/// Bytes of the frame's CRC-16 trailer.
inline constexpr std::size_t frame_crc_size = 2;
/// Bytes of the CRC-32C that ends every payload (over type, sequence and message).
inline constexpr std::size_t message_crc_size = 4;
/// Largest message (the payload without its CRC-32C): the 3-axis MachineConfiguration, 158 bytes.
inline constexpr std::size_t max_message_size = 158;
/// Largest payload of one frame: the message and its CRC-32C.
inline constexpr std::size_t max_payload_size = max_message_size + message_crc_size;
/// Largest frame before COBS: header + payload + CRC.
inline constexpr std::size_t max_frame_size = frame_header_size + max_payload_size + frame_crc_size;
/// Largest frame on the wire: COBS adds one byte per 254 (so one here), plus the 0x00 delimiter.
inline constexpr std::size_t max_encoded_frame_size = max_frame_size + max_frame_size / 254 + 1 + 1;
/// Smallest frame before COBS: header, the CRC-32C of an empty message and the CRC-16.
inline constexpr std::size_t min_frame_size = frame_header_size + message_crc_size + frame_crc_size;

/// Highest Bézier degree a queue segment can carry (8 control points).
inline constexpr std::size_t max_segment_degree = 7;
/// Most axes a message carries (X, Y, Z).
inline constexpr std::size_t max_axes = 3;
/// Most setpoints in one setpoint batch.
inline constexpr std::size_t max_setpoints_per_batch = 24;

static_assert(max_encoded_frame_size == 168, "docs/protocol.md states 168 bytes on the wire");

}  // namespace curvestep::protocol
