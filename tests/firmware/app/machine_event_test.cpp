// SPDX-License-Identifier: MIT
// QueueEvent on the App: machine events reach the board's optional hooks when the motion reaches
// their joint (the first setpoint of the segment they precede, or ticks into the rest there), in
// the order they were queued; the events after the last move come at the job's end. The expected
// setpoint indices come from the setpoint stream itself (the rest is the run of setpoints at the
// joint), not from the App's bookkeeping.
#include <cstdint>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "fake_board.hpp"

using namespace curvestep;
using namespace curvestep::firmware;
using namespace curvestep::protocol;
using namespace curvestep::firmware::testing;

namespace {

/// A FakeBoard with every hook, recording "hook(arguments)@setpoint".
struct HookBoard : FakeBoard {
  std::vector<std::string> calls;
  std::vector<std::uint32_t> at;
  void record(std::string call, std::uint32_t setpoint) {
    calls.push_back(std::move(call));
    at.push_back(setpoint);
  }
  void spindle(bool on, bool counter_clockwise, std::uint32_t rpm, std::uint32_t setpoint) {
    record("spindle(" + std::to_string(on) + "," + std::to_string(counter_clockwise) + "," + std::to_string(rpm) + ")", setpoint);
  }
  void coolant(bool mist, bool flood, std::uint32_t setpoint) {
    record("coolant(" + std::to_string(mist) + "," + std::to_string(flood) + ")", setpoint);
  }
  void digital_output(std::uint32_t number, bool on, std::uint32_t setpoint) {
    record("output(" + std::to_string(number) + "," + std::to_string(on) + ")", setpoint);
  }
  void tool_change(std::uint32_t tool, std::uint32_t setpoint) { record("tool(" + std::to_string(tool) + ")", setpoint); }
  void pen(bool down, std::uint32_t pulse_us, std::uint32_t setpoint) {
    record("pen(" + std::to_string(down) + "," + std::to_string(pulse_us) + ")", setpoint);
  }
};
static_assert(Board<HookBoard>);

QueueEvent event(std::uint32_t segment, std::uint32_t after_rest_ticks, MachineEventKind kind, bool flag = false,
                 std::uint32_t value = 0) {
  QueueEvent e;
  e.segment = segment;
  e.after_rest_ticks = after_rest_ticks;
  e.kind = kind;
  e.flag = flag;
  e.value = value;
  return e;
}

/// Streams `messages` (segments and events, in order) and runs the job to its end.
template <class AppType>
void run(Host<AppType>& host, AppType& app, HookBoard& board, const std::vector<Message>& messages) {
  std::size_t next = 0;
  bool started = false;
  for (int t = 0; t < 100000; ++t) {
    while (next < messages.size() && host.sender().can_submit(messages[next].type())) {
      REQUIRE(host.sender().submit(messages[next]).has_value());
      ++next;
    }
    if (!started && next > 0 && host.sender().can_submit(MessageType::Start)) {
      REQUIRE(host.sender().submit(Message(Start{})).has_value());
      started = true;
    }
    app.on_tick();
    ++board.clock_ms;
    host.pump();
    if (started && next == messages.size() && !app.moving() && app.state() == MachineState::Idle && host.sender().idle()) return;
  }
  FAIL("the job did not finish");
}

}  // namespace

TEST_CASE("firmware: M3 S1000, M8, G4 P0.5, M62 P1, M5, M9 reach the board's hooks at their setpoints in order",
          "[firmware][app][events]") {
  HookBoard board;
  App<HookBoard> app{board};
  Host<App<HookBoard>> host{board, app};
  REQUIRE(host.connect());
  REQUIRE(host.send(Message(machine(50))));
  // G1 X10 / M3 S1000 / M8 / G4 P0.5 / M62 P1 / G1 X20 / M5 / M9 (end): the two lines, the second
  // after a 500-tick rest at 1 kHz; M62 after the dwell.
  QueueSegment first = line(p(0, 0), p(10, 0));
  QueueSegment second = line(p(10, 0), p(20, 0));
  second.stop_before = true;
  second.rest_ticks = 500;
  second.end_of_job = true;
  const std::vector<Message> messages{Message(first),
                                      Message(event(1, 0, MachineEventKind::SpindleOn, false, 1000)),
                                      Message(event(1, 0, MachineEventKind::CoolantFlood)),
                                      Message(event(1, 500, MachineEventKind::DigitalOutput, true, 1)),
                                      Message(event(2, 0, MachineEventKind::SpindleOff)),
                                      Message(event(2, 0, MachineEventKind::CoolantOff)),
                                      Message(second)};
  run(host, app, board, messages);
  REQUIRE(host.received.errors.empty());
  CHECK(board.calls == std::vector<std::string>{"spindle(1,0,1000)", "coolant(0,1)", "output(1,1)", "spindle(0,0,1000)",
                                                "coolant(0,0)"});
  // From the stream: the rest is inside the run of setpoints at (10, 0) (the ticks next to it
  // may round to the joint too); the job's last setpoint is its end.
  const auto setpoints = host.setpoints();
  std::size_t run_begin = 0;  // the first setpoint at the joint
  while (run_begin < setpoints.size() && setpoints[run_begin].second != p(10, 0)) ++run_begin;
  std::size_t run_end = run_begin;
  while (run_end < setpoints.size() && setpoints[run_end].second == p(10, 0)) ++run_end;
  REQUIRE(run_end - run_begin >= 500);
  REQUIRE(board.at.size() == 5);
  CHECK(board.at[0] >= setpoints[run_begin].first);     // M3 at the rest's first setpoint
  CHECK(board.at[0] + 500 <= setpoints[run_end].first);  // ... which has 500 at the joint from it
  CHECK(board.at[1] == board.at[0]);                     // M8 with it
  CHECK(board.at[2] == board.at[0] + 500);               // M62 after the dwell
  CHECK(board.at[3] == setpoints.back().first);          // M5 and M9 at the job's end
  CHECK(board.at[4] == setpoints.back().first);
}

TEST_CASE("firmware: pen events reach the pen hook with the servo pulse width they carry", "[firmware][app][events]") {
  struct Rig {
    HookBoard board;
    App<HookBoard> app{board};
    Host<App<HookBoard>> host{board, app};
  } rig;
  REQUIRE(rig.host.connect());
  REQUIRE(rig.host.send(Message(machine(50))));
  QueueSegment travel = line(p(0, 0), p(10, 0));
  QueueSegment stroke = line(p(10, 0), p(20, 0));
  stroke.stop_before = true;
  stroke.end_of_job = true;
  // A servo pen lifted (1000 us) before the travel, lowered (2000 us) at the joint, lifted at the end.
  const std::vector<Message> messages{Message(event(0, 0, MachineEventKind::PenUp, false, 1000)), Message(travel),
                                      Message(event(1, 0, MachineEventKind::PenDown, false, 2000)),
                                      Message(event(2, 0, MachineEventKind::PenUp, false, 1000)), Message(stroke)};
  run(rig.host, rig.app, rig.board, messages);
  REQUIRE(rig.host.received.errors.empty());
  CHECK(rig.board.calls == std::vector<std::string>{"pen(0,1000)", "pen(1,2000)", "pen(0,1000)"});
}

TEST_CASE("firmware: a QueueEvent takes a credit and waits in the App's ring", "[firmware][app][events]") {
  HookBoard board;
  App<HookBoard> app{board};
  Host<App<HookBoard>> host{board, app};
  REQUIRE(host.connect());
  CHECK(app.free_segments() == 0);  // no configuration, no credit: nothing can be queued
  REQUIRE(host.send(Message(machine(50))));
  host.pump(3);
  const auto credit = app.free_segments();
  REQUIRE(credit > 0);
  REQUIRE(host.send(Message(event(0, 0, MachineEventKind::CoolantMist))));
  host.pump(3);
  CHECK(host.received.errors.empty());
  CHECK(app.queued_events() == 1);
  CHECK(app.free_segments() == credit);  // the segment credit (32 slots / 7) is the smaller room
  CHECK(board.calls.empty());             // nothing moved: not reached yet
}

TEST_CASE("firmware: a tool change pauses the job at its joint until Resume, and the stream is the plain job's",
          "[firmware][app][events][pause]") {
  HookBoard board;
  App<HookBoard> app{board};
  Host<App<HookBoard>> host{board, app};
  REQUIRE(host.connect());
  REQUIRE(host.send(Message(machine(50))));
  QueueSegment first = line(p(0, 0), p(10, 0));
  QueueSegment second = line(p(10, 0), p(10, 10));
  second.stop_before = true;
  second.end_of_job = true;
  REQUIRE(host.send(Message(first)));
  REQUIRE(host.send(Message(event(1, 0, MachineEventKind::ToolChange, false, 2))));
  REQUIRE(host.send(Message(second)));
  REQUIRE(host.send(Message(Start{})));
  int ticks = 0;
  while (!app.paused() && ticks < 100000) {
    app.on_tick();
    ++board.clock_ms;
    host.pump();
    ++ticks;
  }
  REQUIRE(app.paused());
  REQUIRE(board.calls == std::vector<std::string>{"tool(2)"});
  const std::uint32_t paused_at = board.at[0];
  // Paused: ticks produce nothing, the state is holding, the host heard why.
  for (int t = 0; t < 300; ++t) {
    app.on_tick();
    ++board.clock_ms;
    host.pump();
  }
  CHECK(app.paused());
  CHECK(app.state() == MachineState::Holding);
  REQUIRE(host.received.pauses.size() == 1);
  CHECK(host.received.pauses[0].kind == MachineEventKind::ToolChange);
  CHECK(host.received.pauses[0].value == 2);
  CHECK(host.received.pauses[0].setpoint_index == paused_at);
  REQUIRE_FALSE(host.setpoints().empty());
  CHECK(host.setpoints().back().first == paused_at);
  REQUIRE(host.send(Message(Resume{})));
  for (int t = 0; t < 100000 && (app.moving() || app.state() != MachineState::Idle); ++t) {
    app.on_tick();
    ++board.clock_ms;
    host.pump();
  }
  CHECK_FALSE(app.paused());
  REQUIRE(host.received.errors.empty());
  // The setpoints are those of the job without the pause (a controller run straight through).
  std::vector<QueueSegment> job{first, second};
  const auto expected = controller_reference<MotionController<Q16_16, 32, 16>>(machine(50), job);
  check_same_stream(host.setpoints(), expected);
}

/// The App on a HookBoard, connected and configured (machine(50)), for the pause tests below.
struct PauseRig {
  explicit PauseRig(AppSettings settings = {}) : app(board, settings), host(board, app) {
    REQUIRE(host.connect());
    REQUIRE(host.send(Message(machine(50))));
  }
  /// One control tick, `ms` on the board's clock, then a link exchange.
  void tick(std::uint32_t ms = 1) {
    app.on_tick();
    board.clock_ms += ms;
    host.pump();
  }
  /// Delivers what was sent, then ticks until the App stands idle (the job over).
  void tick_until_idle() {
    host.pump(3);
    for (int t = 0; t < 100000 && (app.moving() || app.state() != MachineState::Idle); ++t) tick();
  }

  HookBoard board;
  App<HookBoard> app;
  Host<App<HookBoard>> host;
};

TEST_CASE("firmware: a pause due at the job's end is reported and ends with the job, so the next job runs without a Resume",
          "[firmware][app][events][pause]") {
  PauseRig rig;
  // M0 after the last move: the event precedes segment 1, which never comes.
  QueueSegment first = line(p(0, 0), p(10, 0));
  first.end_of_job = true;
  REQUIRE(rig.host.send(Message(event(1, 0, MachineEventKind::ProgramPause))));
  REQUIRE(rig.host.send(Message(first)));
  REQUIRE(rig.host.send(Message(Start{})));
  rig.tick_until_idle();
  REQUIRE(rig.host.received.pauses.size() == 1);
  CHECK(rig.host.received.pauses[0].kind == MachineEventKind::ProgramPause);
  REQUIRE_FALSE(rig.host.setpoints().empty());
  CHECK(rig.host.received.pauses[0].setpoint_index == rig.host.setpoints().back().first);  // at the job's last setpoint
  CHECK_FALSE(rig.app.paused());
  CHECK(rig.app.phase() == Phase::Configured);
  // The next job of the session moves at once (a pause left over from the last job would hold it).
  const std::size_t first_job_setpoints = rig.host.setpoints().size();
  QueueSegment second = line(p(10, 0), p(10, 10));
  second.end_of_job = true;
  REQUIRE(rig.host.send(Message(second)));
  REQUIRE(rig.host.send(Message(Start{})));
  for (int t = 0; t < 300; ++t) rig.tick();
  CHECK(rig.host.setpoints().size() > first_job_setpoints);
  rig.tick_until_idle();
  CHECK(rig.host.received.errors.empty());
  CHECK(rig.app.phase() == Phase::Configured);
  CHECK(rig.app.position() == p(10, 10));
}

TEST_CASE("firmware: a fault during a pause ends the pause, and Resume does not leave the fault",
          "[firmware][app][events][pause]") {
  AppSettings settings;
  settings.stall_timeout_ms = 0;  // as `curvestep device --fast`: only the setpoint sender gives up
  settings.link_timeout_ms = 0;
  PauseRig rig(settings);
  QueueSegment first = line(p(0, 0), p(0.5, 0));  // short: its setpoints fit the stream unacknowledged
  QueueSegment second = line(p(0.5, 0), p(10, 0));
  second.stop_before = true;
  second.end_of_job = true;
  REQUIRE(rig.host.send(Message(first)));
  REQUIRE(rig.host.send(Message(event(1, 0, MachineEventKind::ProgramPause))));
  REQUIRE(rig.host.send(Message(second)));
  REQUIRE(rig.host.send(Message(Start{})));
  rig.host.pump(3);
  rig.host.acknowledge_setpoints = false;  // the stream will give up (RetransmitLimit) while the job is paused
  for (int t = 0; t < 2000 && !rig.app.paused(); ++t) rig.tick();
  REQUIRE(rig.app.paused());
  for (int i = 0; i < 400 && rig.app.state() != MachineState::Fault; ++i) {
    REQUIRE(rig.host.send(Message(StatusRequest{})));  // the host talks, so the stream's failure is RetransmitLimit
    rig.tick(100);
  }
  rig.host.pump(2);
  REQUIRE(rig.app.state() == MachineState::Fault);
  REQUIRE_FALSE(rig.host.received.errors.empty());
  CHECK(rig.host.received.errors.back().code == Error::RetransmitLimit);
  CHECK_FALSE(rig.app.paused());
  const std::size_t errors = rig.host.received.errors.size();
  REQUIRE(rig.host.send(Message(Resume{})));
  rig.host.pump(3);
  REQUIRE(rig.host.received.errors.size() == errors + 1);
  CHECK(rig.host.received.errors.back().code == Error::RetransmitLimit);  // a failed stream refuses with its reason
  CHECK_FALSE(rig.app.paused());
  CHECK(rig.app.state() == MachineState::Fault);
  CHECK(rig.app.phase() == Phase::StreamFailed);
}

TEST_CASE("firmware: Abort switches a running spindle and the coolant off through their hooks", "[firmware][app][events][abort]") {
  HookBoard board;
  App<HookBoard> app{board};
  Host<App<HookBoard>> host{board, app};
  REQUIRE(host.connect());
  REQUIRE(host.send(Message(machine(50))));
  // M4 S800 and M7 before a 100 mm line (2 s at 50 mm/s); Abort 300 ticks into it.
  QueueSegment cut = line(p(0, 0), p(100, 0));
  cut.end_of_job = true;
  REQUIRE(host.send(Message(event(0, 0, MachineEventKind::SpindleOn, true, 800))));
  REQUIRE(host.send(Message(event(0, 0, MachineEventKind::CoolantMist))));
  REQUIRE(host.send(Message(cut)));
  REQUIRE(host.send(Message(Start{})));
  for (int t = 0; t < 300; ++t) {
    app.on_tick();
    ++board.clock_ms;
    host.pump();
  }
  REQUIRE(app.moving());
  REQUIRE(board.calls == std::vector<std::string>{"spindle(1,1,800)", "coolant(1,0)"});
  REQUIRE(host.send(Message(Abort{})));
  host.pump(3);
  CHECK_FALSE(app.moving());
  CHECK(board.calls == std::vector<std::string>{"spindle(1,1,800)", "coolant(1,0)", "spindle(0,1,800)", "coolant(0,0)"});
  // A second Abort with everything off calls no hook again.
  REQUIRE(host.send(Message(Abort{})));
  host.pump(3);
  CHECK(board.calls.size() == 4);
}

TEST_CASE("firmware: 40 events before one segment, more than the ring holds, run in order at the joint, the stream unchanged",
          "[firmware][app][events][credit]") {
  // G1 X10 / 20 x (M62 P1, M63 P1) / G1 X20 (an exact stop: more than 16 events there, joint_stops)
  // with 32 event slots: the App waits at the joint for the segment its events precede. Oracle:
  // the same job with one event there, which fits the ring and never waits: same setpoints, and
  // every one of the 40 events at the setpoint where that one happens.
  const auto job = [](std::size_t events) {
    QueueSegment first = line(p(0, 0), p(10, 0));
    QueueSegment second = line(p(10, 0), p(20, 0));
    second.stop_before = true;
    second.end_of_job = true;
    std::vector<Message> messages{Message(first)};
    for (std::size_t k = 0; k < events; ++k) messages.push_back(Message(event(1, 0, MachineEventKind::DigitalOutput, k % 2 == 0, 1)));
    messages.push_back(Message(event(2, 0, MachineEventKind::ProgramEnd)));  // M2: after the last move, sent before it
    messages.push_back(Message(second));
    return messages;
  };
  struct Run {
    HookBoard board;
    std::vector<std::pair<std::uint32_t, WirePoint>> setpoints;
    bool errors = false;
  };
  const auto run_job = [&job](std::size_t events) {
    Run r;
    App<HookBoard> app{r.board};
    Host<App<HookBoard>> host{r.board, app};
    REQUIRE(host.connect());
    REQUIRE(host.send(Message(machine(50))));
    run(host, app, r.board, job(events));
    r.setpoints = host.setpoints();
    r.errors = !host.received.errors.empty();
    return r;
  };
  const Run one = run_job(1);
  REQUIRE(one.board.at.size() == 1);  // M2 has no hook on this board
  const Run many = run_job(40);
  CHECK_FALSE(many.errors);
  REQUIRE(many.board.calls.size() == 40);
  for (std::size_t k = 0; k < 40; ++k) {
    CHECK(many.board.calls[k] == (k % 2 == 0 ? "output(1,1)" : "output(1,0)"));
    CHECK(many.board.at[k] == one.board.at[0]);
  }
  CHECK(many.setpoints == one.setpoints);
}
