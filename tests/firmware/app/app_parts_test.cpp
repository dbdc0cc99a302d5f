// SPDX-License-Identifier: MIT
// The App's parts on their own (link_watch.hpp, next_start.hpp, switch_seek.hpp, machine_events.hpp).
// Expected values are the rules of docs/firmware.md ("Safety states", "Homing", "What a host must
// do") and hand-counted times, not the App's output; the App tests drive the same parts through
// the serial bytes.
#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

#include <curvestep/firmware/link_watch.hpp>
#include <curvestep/firmware/machine_events.hpp>
#include <curvestep/firmware/next_start.hpp>
#include <curvestep/firmware/switch_seek.hpp>

using namespace curvestep;
using namespace curvestep::firmware;
using protocol::MachineEventKind;
using protocol::QueueEvent;
using protocol::WirePoint;

namespace {

struct Clock {
  std::uint32_t ms = 0;
  std::uint32_t now_ms() const { return ms; }
};

/// A board with the spindle and coolant hooks: records each call.
struct HookBoard {
  struct Call {
    char hook;  // 's' spindle, 'c' coolant
    bool spindle_on;
    bool mist;
    bool flood;
    std::uint32_t setpoint;
  };
  std::vector<Call> calls;
  void spindle(bool on, bool, std::uint32_t, std::uint32_t setpoint) { calls.push_back({'s', on, false, false, setpoint}); }
  void coolant(bool mist, bool flood, std::uint32_t setpoint) { calls.push_back({'c', false, mist, flood, setpoint}); }
};

QueueEvent event(MachineEventKind kind, std::uint32_t segment) {
  QueueEvent e{};
  e.kind = kind;
  e.segment = segment;
  return e;
}

}  // namespace

TEST_CASE("link watch: a lost link is acted on once per silence, and a frame re-arms it", "[firmware][parts]") {
  LinkWatch watch;
  int asked = 0;
  const auto lost = [&] {
    ++asked;
    return false;
  };
  CHECK_FALSE(watch.newly_lost([] { return true; }));  // the link is fine
  CHECK(watch.newly_lost(lost));
  CHECK_FALSE(watch.newly_lost(lost));  // acted on: not again, and the link is not asked
  CHECK(asked == 1);
  watch.heard(5);
  CHECK(watch.newly_lost(lost));
}

TEST_CASE("link watch: a stall expires after its timeout, once, and its fault names what the host did", "[firmware][parts]") {
  Clock clock{1000};
  LinkWatch watch;
  watch.stalled_tick(clock);
  clock.ms = 1300;
  watch.stalled_tick(clock);  // the stall began at 1000, not 1300
  CHECK(watch.stalled());
  CHECK_FALSE(watch.stall_expired(1499, 500));
  CHECK_FALSE(watch.stall_expired(9999, 0));  // timeout 0: never
  REQUIRE(watch.stall_expired(1500, 500));
  CHECK_FALSE(watch.stalled());
  CHECK_FALSE(watch.stall_expired(1600, 500));  // reported once
  // Silent host: LinkTimeout; index = the stall's length in ms (1600 - 1000).
  CHECK(watch.stall_fault(1600, false).code == Error::LinkTimeout);
  CHECK(watch.stall_fault(1600, false).index == 600);
  CHECK(watch.stall_fault(1600, true).code == Error::QueueUnderrun);
  watch.heard(1200);  // heard during the stall: the host talks but takes no setpoints
  CHECK(watch.stall_fault(1600, false).code == Error::RetransmitLimit);
}

TEST_CASE("link watch: stall times are taken modulo 2^32 across the clock's wrap", "[firmware][parts]") {
  Clock clock{0xFFFFFF00u};
  LinkWatch watch;
  watch.stalled_tick(clock);
  CHECK_FALSE(watch.stall_expired(0x0000003Fu, 0x140));  // 0x13F ms later
  REQUIRE(watch.stall_expired(0x00000040u, 0x140));      // 0x140 ms later
  CHECK(watch.stall_fault(0x00000040u, false).index == 0x140);
  watch.heard(0x00000010u);  // after the stall began, across the wrap
  CHECK(watch.stall_fault(0x00000040u, false).code == Error::RetransmitLimit);
}

TEST_CASE("next start: none is required until set, then only that point connects", "[firmware][parts]") {
  NextStart next;
  CHECK_FALSE(next.known());
  CHECK(next.connects(WirePoint{7, 8, 9}));
  next.set(WirePoint{1, 2, 3});
  CHECK(next.connects(WirePoint{1, 2, 3}));
  CHECK_FALSE(next.connects(WirePoint{1, 2, 4}));
  next.stand_at(WirePoint{4, 5, 6}, false);  // the machine's position is not known
  CHECK(next.connects(WirePoint{0, 0, 0}));
  next.stand_at(WirePoint{4, 5, 6}, true);
  CHECK_FALSE(next.connects(WirePoint{1, 2, 3}));
  CHECK(next.connects(WirePoint{4, 5, 6}));
  next.forget();
  CHECK(next.connects(WirePoint{1, 2, 3}));
}

TEST_CASE("switch seek: arms a switch of the machine's axes only, meets it closed, reports where", "[firmware][parts]") {
  SwitchSeek seek;
  CHECK_FALSE(seek.met(0xFF));  // nothing armed
  CHECK_FALSE(seek.arm(4, 2));  // z min on a 2-axis machine (switches 0..3)
  CHECK_FALSE(seek.met(0xFF));
  REQUIRE(seek.arm(3, 2));  // y max: bit 2 x 1 + 1
  CHECK_FALSE(seek.met(0b0111));
  CHECK(seek.met(0b1000));
  seek.record_stop(42, WirePoint{10, 20, 30});
  CHECK(seek.report().limit_switch == 3);
  CHECK(seek.report().setpoint_index == 42);
  CHECK(seek.report().x == 10);
  CHECK(seek.report().y == 20);
  CHECK(seek.report().z == 30);
  seek.disarm();
  CHECK_FALSE(seek.met(0b1000));
  CHECK(seek.report().limit_switch == 3);  // the report stays for poll() to send
}

TEST_CASE("machine events: a stop switches a running spindle and coolant off, once", "[firmware][parts]") {
  HookBoard board;
  MachineEvents<4> events;
  CHECK_FALSE(events.act_on(board, event(MachineEventKind::SpindleOn, 0), 1));
  CHECK_FALSE(events.act_on(board, event(MachineEventKind::CoolantFlood, 0), 2));
  board.calls.clear();
  events.switch_off_spindle_and_coolant(board, 9);
  REQUIRE(board.calls.size() == 2);
  CHECK(board.calls[0].hook == 's');
  CHECK_FALSE(board.calls[0].spindle_on);
  CHECK(board.calls[0].setpoint == 9);
  CHECK(board.calls[1].hook == 'c');
  CHECK_FALSE(board.calls[1].flood);
  CHECK(board.calls[1].setpoint == 9);
  board.calls.clear();
  events.switch_off_spindle_and_coolant(board, 10);  // already off: no hook
  CHECK(board.calls.empty());
}

TEST_CASE("machine events: program pause, tool change and layer change pause, the others do not", "[firmware][parts]") {
  HookBoard board;
  MachineEvents<4> events;
  CHECK(events.act_on(board, event(MachineEventKind::ProgramPause, 0), 1));
  CHECK(events.act_on(board, event(MachineEventKind::ToolChange, 0), 1));
  CHECK(events.act_on(board, event(MachineEventKind::LayerChange, 0), 1));
  CHECK_FALSE(events.act_on(board, event(MachineEventKind::SpindleSpeed, 0), 1));
  QueueEvent tool = event(MachineEventKind::ToolChange, 3);
  tool.value = 7;
  events.hold_for(tool, 55);
  CHECK(events.pause().setpoint_index == 55);
  CHECK(events.pause().kind == MachineEventKind::ToolChange);
  CHECK(events.pause().value == 7);
}

TEST_CASE("machine events: the motion waits at the queue's end for events of the segment not yet queued", "[firmware][parts]") {
  MachineEvents<4> events;
  REQUIRE(events.push(event(MachineEventKind::CoolantMist, 2)));  // before segment 2
  std::vector<MachineEventKind> acted;
  const auto act = [&](const QueueEvent& e) { acted.push_back(e.kind); };
  bool window = false;
  const auto ready = [&] { return window; };
  CHECK_FALSE(events.wait_at_joint(false, 2, ready, act));  // not yet at the queue's end
  CHECK_FALSE(events.wait_at_joint(true, 3, ready, act));   // segment 2 is queued (3 taken): no wait
  CHECK(events.wait_at_joint(true, 2, ready, act));         // at the end, segment 2 missing: wait, act
  REQUIRE(acted.size() == 1);
  CHECK(events.size() == 0);
  CHECK(events.wait_at_joint(false, 3, ready, act));  // segment 2 came, the window is not full yet
  window = true;
  CHECK_FALSE(events.wait_at_joint(false, 3, ready, act));  // full: on
  CHECK_FALSE(events.wait_at_joint(true, 3, ready, act));   // and no longer waiting
}
