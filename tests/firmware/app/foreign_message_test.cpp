// SPDX-License-Identifier: MIT
// App<FakeBoard>: what the controller answers for messages it does not take (the controller's
// own messages sent back to it, and a command type this protocol version does not define).
#include <catch2/catch.hpp>

#include <array>
#include <cstdint>
#include <span>

#include <curvestep/firmware/app.hpp>
#include <curvestep/protocol/frame.hpp>

#include "fake_board.hpp"

using namespace curvestep;
using namespace curvestep::firmware;
using namespace curvestep::protocol;
using namespace curvestep::firmware::testing;

namespace {

/// Puts the frame of `type`, `sequence` and `message` on the line toward the App.
void send_raw(FakeBoard& board, std::uint8_t type, std::uint8_t sequence, std::span<const std::byte> message) {
  std::array<std::byte, max_encoded_frame_size> frame{};
  const auto size = encode_frame(type, sequence, message, frame);
  REQUIRE(size.has_value());
  for (std::size_t i = 0; i < size.value(); ++i) board.incoming.push_back(frame[i]);
}

/// Puts the frame of message struct `m` on the line toward the App.
template <class M>
void send_raw(FakeBoard& board, const M& m, std::uint8_t sequence) {
  std::array<std::byte, max_message_size> payload{};
  const auto size = encode(m, payload);
  REQUIRE(size.has_value());
  send_raw(board, static_cast<std::uint8_t>(M::type), sequence, std::span<const std::byte>(payload.data(), size.value()));
}

}  // namespace

TEST_CASE("firmware: the controller's own messages sent to it are ignored without an answer", "[firmware][app]") {
  FakeBoard board;
  App<FakeBoard> app{board};
  Host<App<FakeBoard>> host{board, app};
  REQUIRE(host.connect());
  const Received before = host.received;
  SetpointBatch batch;
  batch.axis_count = 3;
  batch.count = 1;
  send_raw(board, Capabilities{}, 0);
  send_raw(board, StatusReport{}, 0);
  send_raw(board, batch, 0);
  send_raw(board, ErrorReport{Error::BadPayload, 3, 0}, 0);
  app.poll();
  host.take_output();
  CHECK(host.received.errors.empty());
  CHECK(host.received.acks.size() == before.acks.size());
  CHECK(host.received.naks.size() == before.naks.size());
  CHECK(host.received.status.size() == before.status.size());
  CHECK(host.received.capabilities == before.capabilities);
  CHECK(app.state() == MachineState::Idle);
  CHECK(app.last_error() == 0);
}

TEST_CASE("firmware: a command type the controller does not know is acknowledged and answered UnknownMessage",
          "[firmware][app]") {
  FakeBoard board;
  App<FakeBoard> app{board};
  Host<App<FakeBoard>> host{board, app};
  REQUIRE(host.connect());
  const std::array<std::byte, 2> payload{std::byte{0x12}, std::byte{0x34}};
  send_raw(board, 0x17, 0, payload);  // the first command of the session: sequence 0
  app.poll();
  host.take_output();
  REQUIRE(host.received.errors.size() == 1);
  CHECK(host.received.errors[0].code == Error::UnknownMessage);
  CHECK(host.received.errors[0].index == 0x17);
  CHECK(host.received.errors[0].sequence == 0);
  REQUIRE_FALSE(host.received.acks.empty());
  CHECK(host.received.acks.back().next_expected == 1);  // it took its sequence number like any command
  CHECK(app.last_error() == static_cast<std::uint8_t>(Error::UnknownMessage));
}
