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
  send_raw(board, 0x1c, 0, payload);  // the first command of the session: sequence 0
  app.poll();
  host.take_output();
  REQUIRE(host.received.errors.size() == 1);
  CHECK(host.received.errors[0].code == Error::UnknownMessage);
  CHECK(host.received.errors[0].index == 0x1c);
  CHECK(host.received.errors[0].sequence == 0);
  REQUIRE_FALSE(host.received.acks.empty());
  CHECK(host.received.acks.back().next_expected == 1);  // it took its sequence number like any command
  CHECK(app.last_error() == static_cast<std::uint8_t>(Error::UnknownMessage));
}
