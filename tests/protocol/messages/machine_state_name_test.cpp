// SPDX-License-Identifier: MIT
// machine_state_name: the log names of the controller states (docs/protocol.md, StatusReport).
#include <catch2/catch.hpp>

#include <cstring>

#include <curvestep/protocol/messages.hpp>

using namespace curvestep::protocol;

TEST_CASE("messages: every machine state has its log name", "[protocol][messages]") {
  STATIC_REQUIRE(machine_state_name(MachineState::Idle)[0] == 'i');
  CHECK(std::strcmp(machine_state_name(MachineState::Idle), "idle") == 0);
  CHECK(std::strcmp(machine_state_name(MachineState::Running), "running") == 0);
  CHECK(std::strcmp(machine_state_name(MachineState::Holding), "holding") == 0);
  CHECK(std::strcmp(machine_state_name(MachineState::Fault), "fault") == 0);
  // A byte that is no state (a StatusReport decoder refuses it; the name still answers).
  CHECK(std::strcmp(machine_state_name(static_cast<MachineState>(7)), "unknown") == 0);
}
