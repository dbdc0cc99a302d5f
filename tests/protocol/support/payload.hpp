// SPDX-License-Identifier: MIT
// Test helper for the protocol suites: the payload bytes of a message (the all-types encoder).
#pragma once

#include <catch2/catch.hpp>

#include <cstddef>
#include <vector>

#include <curvestep/protocol/limits.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::protocol::testing {

/// The payload `m` encodes to; an encoding error fails the test.
inline std::vector<std::byte> payload_of(const Message& m) {
  std::vector<std::byte> out(max_payload_size);
  const auto r = encode(m, out);
  REQUIRE(r.has_value());
  out.resize(r.value());
  return out;
}

}  // namespace curvestep::protocol::testing
