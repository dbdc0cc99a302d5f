// SPDX-License-Identifier: MIT
// Fuzz harness: the receive path of the controller, byte stream -> FrameDecoder -> LinkReceiver.
//
// The input is a program of operations, so that the fuzzer reaches the link state machine with
// frames whose CRC is right (it could never forge them byte by byte):
//   0: a well-formed frame (type, sequence, payload from the input), pushed byte by byte;
//   1: up to 32 raw bytes (garbage, partial frames, stray delimiters);
//   2: a well-formed frame with one byte flipped;
//   3: time passes, the queue frees or fills (poll, check_link);
//   4: a delimiter then a well-formed frame: the decoder must resynchronise and return it.
// Properties: no crash, sanitizer report or contract violation; every reply encodes into a
// 166-byte buffer and parses back; within one session the credit edge never moves back and the
// segments accepted never pass it; a delivered frame is the next expected sequence number.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/protocol.hpp>

#include "fuzz_support.hpp"

namespace {

using namespace curvestep;
using namespace curvestep::protocol;

struct Harness {
  FrameDecoder<> decoder;
  LinkReceiver receiver{Capabilities{.queue_capacity = 8}, ReceiverSettings{.ack_interval_ms = 50, .link_timeout_ms = 500}};
  std::uint16_t free_slots = 8;
  std::uint32_t now_ms = 0;
  std::uint16_t session = 0;
  bool was_connected = false;
  std::uint16_t credit_end = 0;

  void check_reply(const Reception& r) {
    std::array<std::byte, max_encoded_frame_size> out{};
    const auto size = receiver.encode_reply(r, out);
    CURVESTEP_FUZZ_ASSERT(size.has_value());
    if (size.value() == 0) {
      CURVESTEP_FUZZ_ASSERT(r.reply == ReplyKind::None);
      return;
    }
    std::array<std::byte, max_encoded_frame_size> raw{};
    const auto decoded = cobs_decode(std::span<const std::byte>(out.data(), size.value() - 1), raw);
    CURVESTEP_FUZZ_ASSERT(decoded.has_value());
    const auto frame = parse_frame(std::span<const std::byte>(raw.data(), decoded.value()));
    CURVESTEP_FUZZ_ASSERT(frame.has_value());
    CURVESTEP_FUZZ_ASSERT(decode_message(frame.value()).has_value());
  }

  void check_credit() {
    if (!receiver.connected()) {
      was_connected = false;
      return;
    }
    const std::uint16_t now = receiver.credit_end();
    if (was_connected && receiver.capabilities().session == session) {
      CURVESTEP_FUZZ_ASSERT(static_cast<std::int16_t>(static_cast<std::uint16_t>(now - credit_end)) >= 0);
    }
    CURVESTEP_FUZZ_ASSERT(static_cast<std::int16_t>(static_cast<std::uint16_t>(now - receiver.segments_accepted())) >= 0);
    was_connected = true;
    session = receiver.capabilities().session;
    credit_end = now;
  }

  void on_frame(const Frame& frame) {
    const std::uint8_t expected = receiver.expected_sequence();
    const Reception r = receiver.on_frame(frame, free_slots, now_ms);
    if (r.disposition == Disposition::Deliver) {
      CURVESTEP_FUZZ_ASSERT(frame.sequence == expected);
      const auto message = decode_message(frame);
      if (message && consumes_credit(message.value().type()) && free_slots > 0) --free_slots;
    }
    check_reply(r);
    check_credit();
  }

  /// Pushes bytes; returns how many frames completed.
  std::size_t push(std::span<const std::byte> bytes) {
    std::size_t frames = 0;
    for (const std::byte b : bytes) {
      const auto pushed = decoder.push(b);
      if (!pushed) {
        const Reception r = receiver.on_bad_frame(pushed.error());
        check_reply(r);
        continue;
      }
      if (pushed.value()) {
        ++frames;
        on_frame(decoder.frame());
      }
    }
    return frames;
  }
};

std::size_t build_frame(curvestep::fuzz::InputReader& in, std::array<std::byte, max_encoded_frame_size>& wire, Frame& sent,
                        std::array<std::byte, max_payload_size>& payload) {
  const std::uint8_t selector = in.u8();
  // Mostly the host's own types, so the state machine is reached; sometimes anything.
  static constexpr std::array<std::uint8_t, 9> types{0x01, 0x10, 0x11, 0x11, 0x12, 0x13, 0x15, 0x16, 0x17};
  const std::uint8_t type = selector < 224 ? types[selector % types.size()] : selector;
  const std::uint8_t sequence = in.u8();
  const std::size_t length = in.u8() % (max_message_size + 1);
  const auto body = in.bytes(length);
  for (std::size_t i = 0; i < body.size(); ++i) payload[i] = std::byte{body[i]};
  if (type == 0x01 && body.size() < 4) {  // a Hello of the right version, so sessions happen
    const std::array<std::uint8_t, 4> hello{static_cast<std::uint8_t>(protocol_version & 0xFFu),
                                            static_cast<std::uint8_t>(protocol_version >> 8),
                                            body.empty() ? std::uint8_t{0} : body[0], 0};
    for (std::size_t i = 0; i < 4; ++i) payload[i] = std::byte{hello[i]};
    sent.payload = std::span<const std::byte>(payload.data(), 4);
  } else {
    sent.payload = std::span<const std::byte>(payload.data(), body.size());
  }
  sent.type = type;
  sent.sequence = sequence;
  const auto size = encode_frame(type, sequence, sent.payload, wire);
  CURVESTEP_FUZZ_ASSERT(size.has_value());
  return size.value();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  curvestep::contract_handler = curvestep::fuzz::report_contract;
  curvestep::fuzz::InputReader in(data, size);
  Harness h;
  std::array<std::byte, max_encoded_frame_size> wire{};
  std::array<std::byte, max_payload_size> payload{};
  for (int step = 0; step < 256 && !in.empty(); ++step) {
    Frame sent;
    switch (in.u8() % 5) {
      case 0: {
        const std::size_t n = build_frame(in, wire, sent, payload);
        (void)h.push(std::span<const std::byte>(wire.data(), n));
        break;
      }
      case 1: {
        const auto raw = in.bytes(in.u8() % 33);
        (void)h.push(std::as_bytes(raw));
        break;
      }
      case 2: {
        const std::size_t n = build_frame(in, wire, sent, payload);
        const std::size_t at = in.u8() % n;
        wire[at] ^= std::byte{static_cast<std::uint8_t>(in.u8() | 1u)};
        (void)h.push(std::span<const std::byte>(wire.data(), n));
        break;
      }
      case 3: {
        h.now_ms += in.u16();
        const std::uint8_t change = in.u8();
        h.free_slots = static_cast<std::uint16_t>(change < 128 ? (h.free_slots < 8 ? h.free_slots + 1 : 8) : change % 9);
        const Reception r = h.receiver.poll(h.free_slots, h.now_ms);
        h.check_reply(r);
        h.check_credit();
        (void)h.receiver.check_link(h.now_ms);
        break;
      }
      default: {
        const std::size_t n = build_frame(in, wire, sent, payload);
        const std::array<std::byte, 1> delimiter{};
        (void)h.push(delimiter);
        // Save the frame: delivering it may not touch the payload buffer, but be sure.
        const std::array<std::byte, max_payload_size> expected_payload = payload;
        const std::size_t frames = h.push(std::span<const std::byte>(wire.data(), n));
        CURVESTEP_FUZZ_ASSERT(frames == 1);
        const Frame& got = h.decoder.frame();
        CURVESTEP_FUZZ_ASSERT(got.type == sent.type && got.sequence == sent.sequence);
        CURVESTEP_FUZZ_ASSERT(got.payload.size() == sent.payload.size());
        for (std::size_t i = 0; i < got.payload.size(); ++i) CURVESTEP_FUZZ_ASSERT(got.payload[i] == expected_payload[i]);
        break;
      }
    }
  }
  return 0;
}
