// SPDX-License-Identifier: MIT
// QueueSegment flag bit 4 (end of job, protocol version 2): hand-computed bytes, round trip, reserved bits.
#include <catch2/catch.hpp>

#include <array>
#include <cstddef>
#include <vector>

#include <curvestep/protocol/messages.hpp>

#include "../support/bytes.hpp"

using namespace curvestep;
using namespace curvestep::protocol;
using curvestep::protocol::testing::hex;

TEST_CASE("messages: the end-of-job flag is bit 4 of a segment's flags byte", "[protocol][messages]") {
  QueueSegment s;
  s.kind = SegmentKind::Line;
  s.axis_count = 2;
  s.end_of_job = true;
  s.points[1] = WirePoint{65536, -65536, 0};
  std::array<std::byte, max_payload_size> out{};
  const auto size = encode(s, out);
  REQUIRE(size.has_value());
  // kind 0, flags 0x10 (end of job, two axes, no feed), start (0, 0), end (1, -1) mm
  const auto expected = hex("00 10 00000000 00000000 00000100 0000ffff");
  REQUIRE(size.value() == expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) CHECK(out[i] == expected[i]);
  const auto back = decode<QueueSegment>(std::span<const std::byte>(out.data(), size.value()));
  REQUIRE(back.has_value());
  CHECK(back.value().end_of_job);
  CHECK(back.value().points[1][0] == 65536);
  CHECK(back.value().points[1][1] == -65536);
}

TEST_CASE("messages: a segment without the end-of-job flag decodes with end_of_job false", "[protocol][messages]") {
  const auto back = decode<QueueSegment>(hex("00 00 00000000 00000000 00000100 0000ffff"));
  REQUIRE(back.has_value());
  CHECK_FALSE(back.value().end_of_job);
  // bit 7 (the end-of-job flag of version 1) is now the rest flag: its count must follow and not
  // be 0, so a version-1 end of job is refused at the count (offset 2), never read as one
  const auto old_end = decode<QueueSegment>(hex("00 80 00000000 00000000 00000100 0000ffff"));
  REQUIRE_FALSE(old_end.has_value());
  CHECK(old_end.where() == 2);
  // bit 6 is the exact stop before the segment; bit 5 is for arcs only
  const auto stop = decode<QueueSegment>(hex("00 40 00000000 00000000 00000100 0000ffff"));
  REQUIRE(stop.has_value());
  CHECK(stop.value().stop_before);
  CHECK_FALSE(stop.value().end_of_job);
  CHECK(decode<QueueSegment>(hex("00 20 00000000 00000000 00000100 0000ffff")).where() == 1);
}
