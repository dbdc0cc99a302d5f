// SPDX-License-Identifier: MIT
// Limit switches and homing through App<Board> and its serial link: a hard limit is a fault with
// the switch named, a seek ends the job where its switch closes, SetPosition sets the coordinates.
// The switch closes when the test says (a board with limit_switches()), not by the App's state.
#include <catch2/catch.hpp>

#include <cstdint>

#include <curvestep/firmware/app.hpp>

#include "fake_board.hpp"
#include "line_job_rig.hpp"

using namespace curvestep;
using namespace curvestep::firmware;
using namespace curvestep::protocol;
using namespace curvestep::firmware::testing;

namespace {

/// A FakeBoard whose limit switches the test closes.
struct SwitchBoard : FakeBoard {
  std::uint8_t closed = 0;
  std::uint8_t limit_switches() const { return closed; }
};
static_assert(Board<SwitchBoard>);

/// The App on a SwitchBoard moving along a 40 mm line along +x.
using SwitchRig = LineJobRig<SwitchBoard>;

}  // namespace

TEST_CASE("firmware: the x max switch closing while x moves up is a HardLimit fault naming switch 1", "[firmware][app][limits]") {
  SwitchRig rig;
  rig.ticks(50);
  REQUIRE(rig.host.received.errors.empty());
  rig.board.closed = 0b10;  // x max
  rig.ticks(3);
  REQUIRE(rig.host.received.errors.size() == 1);
  CHECK(rig.host.received.errors[0].code == Error::HardLimit);
  CHECK(rig.host.received.errors[0].index == 1);
  CHECK(rig.app.state() == MachineState::Fault);
  CHECK(rig.board.fault_stops > 0);
  REQUIRE_FALSE(rig.host.received.status.empty());
  CHECK(rig.host.received.status.back().limit_switches == 0b10);
  CHECK(rig.host.received.status.back().setpoint_index == 50);  // the first tick after the switch closed
}

TEST_CASE("firmware: a switch on the side x moves away from does not stop the job", "[firmware][app][limits]") {
  SwitchRig rig;
  rig.board.closed = 0b01;  // x min: x moves up, away from it
  rig.ticks(50);
  CHECK(rig.host.received.errors.empty());
  CHECK(rig.app.state() == MachineState::Running);
}

TEST_CASE("firmware: a seek ends the job where its switch closes, no fault, and SetPosition renames the spot",
          "[firmware][app][limits][homing]") {
  SwitchRig rig({}, Message(SeekSwitch{1}));  // seek x max
  rig.ticks(50);
  const int stops_before = rig.board.fault_stops;
  rig.board.closed = 0b10;
  rig.ticks(3);
  CHECK(rig.host.received.errors.empty());
  REQUIRE(rig.host.received.switches.size() == 1);
  const SwitchReport report = rig.host.received.switches[0];
  CHECK(report.limit_switch == 1);
  CHECK(report.setpoint_index == 50);
  CHECK(rig.app.state() == MachineState::Idle);
  CHECK_FALSE(rig.app.moving());
  CHECK(rig.board.fault_stops == stops_before);  // the edges handed over are kept
  CHECK(rig.app.position() == WirePoint{report.x, report.y, report.z});
  CHECK(report.x > 0);
  CHECK(report.x < q(40));
  REQUIRE(rig.host.send(Message(SetPosition{0b001, q(-2), 0, 0})));
  REQUIRE(rig.host.send(Message(StatusRequest{})));
  rig.host.pump(5);
  CHECK(rig.host.received.errors.empty());
  CHECK(rig.app.position() == WirePoint{q(-2), report.y, report.z});
  CHECK(rig.host.received.status.back().position == WirePoint{q(-2), report.y, report.z});
}

TEST_CASE("firmware: SeekSwitch and SetPosition are refused where the state table says", "[firmware][app][limits][homing]") {
  SwitchRig rig;  // running
  REQUIRE(rig.host.send(Message(SeekSwitch{1})));
  REQUIRE(rig.host.send(Message(SetPosition{0b001, q(1), 0, 0})));
  rig.host.pump(5);
  REQUIRE(rig.host.received.errors.size() == 2);
  CHECK(rig.host.received.errors[0].code == Error::InvalidState);
  CHECK(rig.host.received.errors[1].code == Error::PlannerBusy);
  REQUIRE(rig.host.send(Message(Abort{})));
  REQUIRE(rig.host.send(Message(SeekSwitch{6})));                  // 3 axes: switches 0 .. 5
  REQUIRE(rig.host.send(Message(SetPosition{0b1000, q(1), 0, 0})));  // axis 3 does not exist
  rig.host.pump(5);
  REQUIRE(rig.host.received.errors.size() == 4);
  CHECK(rig.host.received.errors[2].code == Error::InvalidArgument);
  CHECK(rig.host.received.errors[3].code == Error::InvalidArgument);
}
