// SPDX-License-Identifier: MIT
// Fuzz harness: message payload decoding (decode_message), frame checks (parse_frame) and the
// QueueSegment -> core curve conversions, fed with arbitrary bytes.
//
// Input: byte 0 is the message type, the rest the payload. The CRC is bypassed on purpose (a fuzzer
// cannot forge CRCs); parse_frame is fed the whole input separately. Properties checked:
//   * no crash, no sanitizer report, no contract violation on any input;
//   * a payload that decodes re-encodes into at most max_payload_size bytes, and decoding that
//     encoding and encoding again gives the same bytes (encode . decode is idempotent);
//   * a decoded QueueSegment converts to a core curve or fails with a Result error.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/protocol.hpp>
#include <curvestep/protocol/segment_curves.hpp>

#include "fuzz_support.hpp"

namespace {

using namespace curvestep;
using namespace curvestep::protocol;

template <std::size_t Dim>
void convert_segment(const QueueSegment& s) {
  if (s.kind == SegmentKind::Line || s.kind == SegmentKind::Bezier) {
    auto curve = to_bezier<Dim>(s);
    if (curve) {
      auto back = bezier_segment(curve.value());
      CURVESTEP_FUZZ_ASSERT(back.has_value());
    }
  }
  if (s.kind != SegmentKind::Arc) {
    auto curve = to_rational_bezier<Dim>(s);
    if (curve) (void)curve.value().point_at(Q16_16::from_raw(1 << 15));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  curvestep::contract_handler = curvestep::fuzz::report_contract;
  const auto bytes = std::as_bytes(std::span<const std::uint8_t>(data, size));

  // parse_frame on the raw input (length and CRC checks; no decoding past them).
  if (auto frame = parse_frame(bytes)) (void)decode_message(frame.value());

  if (size == 0) return 0;
  const auto decoded = decode_message(data[0], bytes.subspan(1));
  if (!decoded) return 0;
  const Message& m = decoded.value();
  CURVESTEP_FUZZ_ASSERT(static_cast<std::uint8_t>(m.type()) == data[0]);

  std::array<std::byte, max_payload_size> first{};
  const auto first_size = encode(m, first);
  CURVESTEP_FUZZ_ASSERT(first_size.has_value());
  const auto again = decode_message(data[0], std::span<const std::byte>(first.data(), first_size.value()));
  CURVESTEP_FUZZ_ASSERT(again.has_value());
  std::array<std::byte, max_payload_size> second{};
  const auto second_size = encode(again.value(), second);
  CURVESTEP_FUZZ_ASSERT(second_size.has_value() && second_size.value() == first_size.value());
  CURVESTEP_FUZZ_ASSERT(first == second);

  // A whole frame around the payload must come back through the decoder unchanged.
  std::array<std::byte, max_encoded_frame_size> wire{};
  const auto wire_size = encode_frame(m, 7, wire);
  CURVESTEP_FUZZ_ASSERT(wire_size.has_value());
  FrameDecoder<> decoder;
  bool completed = false;
  for (std::size_t i = 0; i < wire_size.value(); ++i) {
    const auto pushed = decoder.push(wire[i]);
    CURVESTEP_FUZZ_ASSERT(pushed.has_value());
    completed = pushed.value();
  }
  CURVESTEP_FUZZ_ASSERT(completed && decoder.frame().sequence == 7 && decoder.frame().type == data[0]);

  if (m.holds<QueueSegment>()) {
    const auto& s = m.get<QueueSegment>();
    if (s.axis_count == 2) convert_segment<2>(s);
    if (s.axis_count == 3) convert_segment<3>(s);
  }
  return 0;
}
