// SPDX-License-Identifier: MIT
// App<FakeBoard, Q16_16, 16, 0> (no planner): capabilities, refused commands, credit, piece replay, start rule, stalls,
// a hold the host planned.
#include <catch2/catch.hpp>

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include <curvestep/firmware/app.hpp>
#include <curvestep/protocol/frame.hpp>
#include <curvestep/protocol/messages.hpp>

#include "fake_board.hpp"

using namespace curvestep;
using namespace curvestep::firmware;
using namespace curvestep::protocol;
using namespace curvestep::firmware::testing;  // fake_board.hpp: the board, the host, the wire helpers

namespace {

using ExecutorApp = App<FakeBoard, Q16_16, 16, 0>;

/// The test machine of fake_board.hpp with 8 steps/mm: the executor checks no speed, and the
/// FakeBoard's batch of 64 edges allows at most 10 steps per tick and axis (3 × (1 + 2 × 10)),
/// so the pieces below (at most 0.5 mm = 4 steps a tick) stay well inside it. Travel ±100 mm.
MachineConfiguration executor_machine() {
  MachineConfiguration c = curvestep::firmware::testing::machine(50);
  for (auto& axis : c.axes) axis.steps_per_mm = 8;
  return c;
}

/// A FakeBoard, an executor App on it and the scripted host.
struct ExecutorRig {
  explicit ExecutorRig(AppSettings settings = {}) : app(board, settings), host(board, app) {}

  /// Connects and sends the configuration; returns once it is applied and acknowledged.
  void connect_and_configure(const MachineConfiguration& config = executor_machine()) {
    REQUIRE(host.connect());
    REQUIRE(host.send(Message(config)));
    host.pump(5);
    REQUIRE(app.configured());
    REQUIRE(host.received.errors.empty());
  }

  /// Sends `m` and lets the App take it.
  void send(const Message& m) {
    REQUIRE(host.send(m));
    host.pump(3);
  }

  /// Runs control ticks (one ms each) until the App is idle and every setpoint batch went out,
  /// at most `max_ticks`.
  void run_to_idle(int max_ticks = 100) {
    for (int t = 0; t < max_ticks; ++t) {
      if (!app.moving() && app.state() == MachineState::Idle && app.setpoint_sender().idle()) break;
      host.run_ticks(1);
    }
    host.pump(3);
    REQUIRE(app.state() == MachineState::Idle);
    REQUIRE_FALSE(app.moving());
  }

  FakeBoard board;
  ExecutorApp app;
  Host<ExecutorApp> host;
};

/// An exact piece: one setpoint at (x, y, z).
QueuePiece exact(double x, double y, double z = 0, bool end_of_job = false, std::uint32_t segment = 0) {
  QueuePiece m;
  m.axis_count = 3;
  m.ticks = 1;
  m.segment = segment;
  m.end_of_job = end_of_job;
  m.end = {x, y, z};
  return m;
}

/// A chunk of `ticks` ticks from the previous setpoint `from` to `to` along a straight line at
/// constant speed: the quintic's Bézier control points relative to `from` are q_i = i/5 (to - from),
/// i = 1..5 (equally spaced control points give B(σ) = σ (to - from) exactly), so the stepped
/// setpoints are from + k/ticks (to - from).
QueuePiece straight_chunk(const std::array<double, 3>& from, const std::array<double, 3>& to, std::uint16_t ticks,
                          std::uint32_t segment = 0) {
  QueuePiece m;
  m.axis_count = 3;
  m.ticks = ticks;
  m.segment = segment;
  m.end = to;
  for (std::size_t i = 0; i < 5; ++i) {
    for (std::size_t a = 0; a < 3; ++a) m.controls[i][a] = static_cast<double>(i + 1) / 5.0 * (to[a] - from[a]);
  }
  return m;
}

/// Setpoint k (index k) of a run of exact pieces at x = k/8 mm (one step of 8 steps/mm each).
WirePoint staircase(std::uint32_t k) { return p(k / 8.0, 0); }

/// Queues exact pieces k = first..last (inclusive) at staircase(k), none ending the job.
void queue_staircase(ExecutorRig& rig, std::uint32_t first, std::uint32_t last) {
  for (std::uint32_t k = first; k <= last; ++k) REQUIRE(rig.host.send(Message(exact(k / 8.0, 0, 0, false, k))));
  rig.host.pump(3);
}

/// The expected stream of staircase setpoints 0..count-1.
Setpoints staircase_stream(std::uint32_t count) {
  Setpoints out;
  for (std::uint32_t k = 0; k < count; ++k) out.emplace_back(k, staircase(k));
  return out;
}

void require_each_setpoint(const Setpoints& got, const Setpoints& expected) {
  REQUIRE(got.size() == expected.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    INFO("setpoint " << i);
    CHECK(got[i].first == expected[i].first);
    CHECK(got[i].second == expected[i].second);
  }
}

}  // namespace

TEST_CASE("executor app: Hello is answered with Capabilities of queue 16 and lookahead 0 and max_degree 0",
          "[firmware][app][executor]") {
  ExecutorRig rig;
  REQUIRE(rig.host.connect());
  REQUIRE(rig.host.received.capabilities == 1);
  const Capabilities& c = rig.host.received.last_capabilities;
  CHECK(c.version == protocol_version);
  CHECK(c.session == 0x1234);
  CHECK(c.queue_capacity == 16);
  CHECK(c.lookahead == 0);   // no planner: the host sends QueuePiece
  CHECK(c.max_degree == 0);  // no segments
  CHECK(c.axis_count == 3);
  CHECK(c.fixed_total_bits == 32);
  CHECK(c.fixed_fraction_bits == 16);
  CHECK(c.tick_rate_hz == 1000000);
  CHECK(c.credit_end == 0);  // no credit before a configuration
  CHECK(rig.app.state() == MachineState::Idle);
}

TEST_CASE("executor app: QueueSegment is an unknown message and FeedHold without a job changes nothing",
          "[firmware][app][executor]") {
  ExecutorRig rig;
  rig.connect_and_configure();
  rig.send(Message(line(p(0, 0), p(1, 0))));
  REQUIRE(rig.host.received.errors.size() == 1);
  CHECK(rig.host.received.errors[0].code == Error::UnknownMessage);
  CHECK(rig.host.received.errors[0].index == 0x11);
  CHECK(rig.app.controller().queued() == 0);
  CHECK(rig.app.state() == MachineState::Idle);

  rig.send(Message(FeedHold{}));
  CHECK(rig.host.received.errors.size() == 1);  // taken, as by a planner's App (docs/protocol.md, state table)
  CHECK(rig.app.state() == MachineState::Idle);  // unchanged
  CHECK_FALSE(rig.app.moving());
}

TEST_CASE("executor app: FeedOverride is not supported (the host plans the override into the pieces)",
          "[firmware][app][executor][override]") {
  ExecutorRig rig;
  rig.connect_and_configure();
  rig.send(Message(protocol::FeedOverride{50, 100}));
  REQUIRE(rig.host.received.errors.size() == 1);
  CHECK(rig.host.received.errors[0].code == Error::NotSupported);
  CHECK(rig.app.state() == MachineState::Idle);
}

TEST_CASE("executor app: after FeedHold the App runs the queued pieces and stands where they end, past the stall timeout, until Resume",
          "[firmware][app][executor]") {
  // The host planned the braking into the pieces before FeedHold (here: a staircase that simply
  // ends at staircase(15)); without FeedHold the same dry queue is a QueueUnderrun fault after
  // 20 ms (the stall test below).
  AppSettings settings;
  settings.stall_timeout_ms = 20;
  ExecutorRig rig(settings);
  rig.connect_and_configure();
  queue_staircase(rig, 0, 15);  // a full queue, no end of job
  rig.send(Message(Start{}));
  rig.host.run_ticks(4);
  REQUIRE(rig.app.moving());
  const std::size_t reports = rig.host.received.status.size();
  rig.send(Message(FeedHold{}));
  CHECK(rig.host.received.errors.empty());
  CHECK(rig.app.state() == MachineState::Holding);
  REQUIRE(rig.host.received.status.size() == reports + 1);  // at once, as a planner's App
  CHECK(rig.host.received.status.back().state == MachineState::Holding);

  rig.host.run_ticks(12 + 50);  // the 12 pieces left, then 50 ms standing: more than the stall timeout
  CHECK(rig.host.received.errors.empty());
  CHECK(rig.app.state() == MachineState::Holding);
  CHECK(rig.app.moving());
  CHECK(rig.app.statistics().stalled_ticks == 0);  // standing in a hold is no stall
  CHECK(rig.app.position() == staircase(15));
  CHECK(rig.board.steps == std::array<std::int64_t, 3>{15, 0, 0});
  rig.host.pump(3);
  require_each_setpoint(rig.host.setpoints(), staircase_stream(16));  // the short batch is not held back

  rig.send(Message(Resume{}));
  CHECK(rig.app.state() == MachineState::Running);
  for (std::uint32_t k = 16; k <= 18; ++k) REQUIRE(rig.host.send(Message(exact(k / 8.0, 0, 0, k == 18, k))));
  rig.run_to_idle();
  CHECK(rig.host.received.errors.empty());
  // The indices go on without a gap: a held executor does not tick (sim --hold-at T:0).
  require_each_setpoint(rig.host.setpoints(), staircase_stream(19));
  CHECK(rig.board.steps == std::array<std::int64_t, 3>{18, 0, 0});
  CHECK(rig.board.fault_stops == 0);
  CHECK(rig.app.state() == MachineState::Idle);
}

TEST_CASE("executor app: the credit counts one per piece", "[firmware][app][executor]") {
  ExecutorRig rig;
  rig.connect_and_configure();
  // 16 free slots, one per piece (a planner's App would grant 16 / 7 = 2).
  REQUIRE_FALSE(rig.host.received.acks.empty());
  CHECK(rig.host.received.acks.back().credit_end == 16);
  CHECK(rig.host.sender().credit() == 16);
  for (std::uint32_t k = 0; k < 5; ++k) REQUIRE(rig.host.send(Message(exact(k / 8.0, 0, 0, k == 4, k))));
  rig.host.pump(3);
  CHECK(rig.app.controller().queued() == 5);
  CHECK(rig.app.free_segments() == 11);
  CHECK(rig.host.sender().credit() == 11);  // credit_end 5 accepted + 11 free = 16, 5 sent
  rig.send(Message(Start{}));
  rig.run_to_idle();
  CHECK(rig.host.received.errors.empty());
  // The queue is empty again: credit_end = 5 accepted + 16 free.
  CHECK(rig.app.free_segments() == 16);
  CHECK(rig.host.received.acks.back().credit_end == 21);
  CHECK(rig.host.sender().credit() == 16);
}

TEST_CASE("executor app: an exact piece and a straight chunk and an exact run stream the hand-computed setpoints",
          "[firmware][app][executor]") {
  ExecutorRig rig;
  rig.connect_and_configure();
  REQUIRE(rig.host.send(Message(exact(0, 0, 0, false, 0))));
  // (0, 0) to (1, 2) in 4 ticks: setpoints at 1/4, 1/2, 3/4 of the way, then the end.
  REQUIRE(rig.host.send(Message(straight_chunk({0, 0, 0}, {1, 2, 0}, 4, 1))));
  QueuePiece run;  // three exact ticks: controls[0], controls[1], then end; the job's last piece
  run.axis_count = 3;
  run.ticks = 3;
  run.exact_run = true;
  run.segment = 2;
  run.controls[0] = {1.25, 2, 0};
  run.controls[1] = {1.5, 2, 0};
  run.end = {1.75, 2, 0};
  run.end_of_job = true;
  REQUIRE(rig.host.send(Message(run)));
  rig.host.pump(3);
  REQUIRE(rig.host.received.errors.empty());
  CHECK(rig.app.controller().queued() == 3);
  rig.send(Message(Start{}));
  rig.run_to_idle();
  CHECK(rig.host.received.errors.empty());

  // Q16.16 raw values: 0.25 mm = 16384, 0.5 mm = 32768, 1 mm = 65536, ...
  const Setpoints expected{
      {0, WirePoint{0, 0, 0}},
      {1, WirePoint{16384, 32768, 0}},   // (0.25, 0.5)
      {2, WirePoint{32768, 65536, 0}},   // (0.5, 1)
      {3, WirePoint{49152, 98304, 0}},   // (0.75, 1.5)
      {4, WirePoint{65536, 131072, 0}},  // (1, 2): the chunk's end
      {5, WirePoint{81920, 131072, 0}},  // (1.25, 2)
      {6, WirePoint{98304, 131072, 0}},  // (1.5, 2)
      {7, WirePoint{114688, 131072, 0}}, // (1.75, 2): the job's end
  };
  require_each_setpoint(rig.host.setpoints(), expected);
  CHECK(rig.app.position() == (WirePoint{114688, 131072, 0}));
  CHECK(rig.board.steps == std::array<std::int64_t, 3>{14, 16, 0});  // (1.75, 2) mm at 8 steps/mm
  REQUIRE_FALSE(rig.host.received.status.empty());
  const StatusReport& s = rig.host.received.status.back();
  CHECK(s.state == MachineState::Idle);
  CHECK(s.position == (WirePoint{114688, 131072, 0}));
  CHECK(s.queue_depth == 0);
  CHECK(rig.board.fault_stops == 0);
}

TEST_CASE("executor app: Start waits for a full queue of 16 pieces when the job end is not known",
          "[firmware][app][executor]") {
  ExecutorRig rig;
  rig.connect_and_configure();
  queue_staircase(rig, 0, 14);  // 15 pieces, none ending the job
  rig.send(Message(Start{}));
  rig.host.run_ticks(20);
  CHECK_FALSE(rig.app.moving());
  CHECK(rig.host.setpoints().empty());
  CHECK(rig.board.steps == std::array<std::int64_t, 3>{0, 0, 0});
  CHECK(rig.app.controller().queued() == 15);
  CHECK(rig.host.received.errors.empty());

  queue_staircase(rig, 15, 15);  // the 16th piece fills the queue: motion begins
  CHECK(rig.app.moving());
  rig.host.run_ticks(16);
  // The job goes on after a stall for the piece that ends it.
  REQUIRE(rig.host.send(Message(exact(16 / 8.0, 0, 0, true, 16))));
  rig.run_to_idle();
  require_each_setpoint(rig.host.setpoints(), staircase_stream(17));
  CHECK(rig.board.steps == std::array<std::int64_t, 3>{16, 0, 0});
  CHECK(rig.host.received.errors.empty());
}

TEST_CASE("executor app: a chunk as the first piece of a job is refused and nothing is queued",
          "[firmware][app][executor]") {
  ExecutorRig rig;
  rig.connect_and_configure();
  rig.send(Message(straight_chunk({0, 0, 0}, {1, 2, 0}, 4)));
  REQUIRE(rig.host.received.errors.size() == 1);
  CHECK(rig.host.received.errors[0].code == Error::InvalidArgument);
  CHECK(rig.host.received.errors[0].index == 2);  // the ticks field (index 1 would be too many axes)
  CHECK(rig.app.controller().queued() == 0);
  // An exact piece may begin the job, and a chunk may follow it.
  rig.send(Message(exact(0, 0)));
  rig.send(Message(straight_chunk({0, 0, 0}, {1, 2, 0}, 4)));
  CHECK(rig.host.received.errors.size() == 1);
  CHECK(rig.app.controller().queued() == 2);
}

TEST_CASE("executor app: a piece ending outside the travel range is refused with the axis as index",
          "[firmware][app][executor]") {
  ExecutorRig rig;
  rig.connect_and_configure();  // travel -100 .. 100 mm on every axis
  rig.send(Message(exact(150, 0)));
  rig.send(Message(exact(0, -100.5)));
  rig.send(Message(exact(0, 0, 101)));
  REQUIRE(rig.host.received.errors.size() == 3);
  for (std::uint16_t axis = 0; axis < 3; ++axis) {
    INFO("axis " << axis);
    CHECK(rig.host.received.errors[axis].code == Error::OutsideTravel);
    CHECK(rig.host.received.errors[axis].index == axis);
  }
  CHECK(rig.app.controller().queued() == 0);
  // A chunk's end is checked too.
  rig.send(Message(exact(99, 0)));
  CHECK(rig.app.controller().queued() == 1);
  rig.send(Message(straight_chunk({99, 0, 0}, {101, 0, 0}, 4)));
  REQUIRE(rig.host.received.errors.size() == 4);
  CHECK(rig.host.received.errors[3].code == Error::OutsideTravel);
  CHECK(rig.host.received.errors[3].index == 0);
  CHECK(rig.app.controller().queued() == 1);
  // So is every point of an exact run: its second point leaves the range in Y, its end does not.
  QueuePiece run;
  run.axis_count = 3;
  run.ticks = 3;
  run.exact_run = true;
  run.controls[0] = {99, 50, 0};
  run.controls[1] = {99, 100.25, 0};
  run.end = {99, 99, 0};
  rig.send(Message(run));
  REQUIRE(rig.host.received.errors.size() == 5);
  CHECK(rig.host.received.errors[4].code == Error::OutsideTravel);
  CHECK(rig.host.received.errors[4].index == 1);
  CHECK(rig.app.controller().queued() == 1);
}

TEST_CASE("executor app: the next job must begin where the last one ended", "[firmware][app][executor]") {
  ExecutorRig rig;
  rig.connect_and_configure();
  rig.send(Message(exact(0, 0)));
  rig.send(Message(exact(0.5, 0.25, 0, true)));
  rig.send(Message(Start{}));
  rig.run_to_idle();
  REQUIRE(rig.host.received.errors.empty());
  REQUIRE(rig.app.position() == p(0.5, 0.25));

  rig.send(Message(exact(0, 0)));  // not at (0.5, 0.25)
  REQUIRE(rig.host.received.errors.size() == 1);
  CHECK(rig.host.received.errors[0].code == Error::SegmentsNotConnected);
  CHECK(rig.host.received.errors[0].index == 0);
  CHECK(rig.app.controller().queued() == 0);

  rig.send(Message(exact(0.5, 0.25)));  // where the machine stands
  CHECK(rig.host.received.errors.size() == 1);
  CHECK(rig.app.controller().queued() == 1);
}

TEST_CASE("executor app: a job that opens with an exact run begins at the run's first point", "[firmware][app][executor]") {
  ExecutorRig rig;
  rig.connect_and_configure();
  rig.send(Message(exact(0, 0)));
  rig.send(Message(exact(0.5, 0.25, 0, true)));
  rig.send(Message(Start{}));
  rig.run_to_idle();
  REQUIRE(rig.host.received.errors.empty());
  QueuePiece run;
  run.axis_count = 3;
  run.ticks = 2;
  run.exact_run = true;
  run.controls[0] = {0.5, 0.25, 0};  // the next job's first setpoint: where the machine stands
  run.end = {0.75, 0.25, 0};
  rig.send(Message(run));
  CHECK(rig.host.received.errors.empty());
  CHECK(rig.app.controller().queued() == 1);
  rig.send(Message(Abort{}));  // the machine still stands at (0.5, 0.25)
  run.controls[0] = {0.75, 0.25, 0};
  run.end = {0.5, 0.25, 0};  // ends where the machine stands, but begins elsewhere
  rig.send(Message(run));
  REQUIRE(rig.host.received.errors.size() == 1);
  CHECK(rig.host.received.errors[0].code == Error::SegmentsNotConnected);
  CHECK(rig.app.controller().queued() == 0);
}

TEST_CASE("executor app: pieces that run out before the job end stall the ticks and a long stall is a QueueUnderrun fault",
          "[firmware][app][executor]") {
  AppSettings settings;
  settings.stall_timeout_ms = 20;
  ExecutorRig rig(settings);
  rig.connect_and_configure();
  queue_staircase(rig, 0, 15);  // a full queue, no end of job
  rig.send(Message(Start{}));
  REQUIRE(rig.app.moving());
  rig.host.run_ticks(16);  // every queued piece
  REQUIRE(rig.app.position() == staircase(15));
  CHECK(rig.app.statistics().stalled_ticks == 0);

  rig.host.run_ticks(10);  // stalled for 10 ms, below the timeout
  CHECK(rig.app.statistics().stalled_ticks == 10);
  CHECK_FALSE(rig.app.ready_to_tick());
  CHECK(rig.app.moving());
  CHECK(rig.app.state() == MachineState::Running);
  CHECK(rig.app.position() == staircase(15));
  CHECK(rig.board.steps == std::array<std::int64_t, 3>{15, 0, 0});
  CHECK(rig.host.received.errors.empty());
  // While stalled, the 16 setpoints made so far (less than a 24-setpoint batch) are not held back.
  rig.host.pump(3);
  require_each_setpoint(rig.host.setpoints(), staircase_stream(16));

  rig.host.run_ticks(15);  // 25 ms: past the timeout
  REQUIRE(rig.host.received.errors.size() == 1);
  CHECK(rig.host.received.errors[0].code == Error::QueueUnderrun);
  CHECK(rig.app.state() == MachineState::Fault);
  CHECK_FALSE(rig.app.moving());
  CHECK(rig.board.fault_stops == 1);
  REQUIRE_FALSE(rig.host.received.status.empty());
  CHECK(rig.host.received.status.back().state == MachineState::Fault);
  CHECK(rig.host.received.status.back().error == static_cast<std::uint8_t>(Error::QueueUnderrun));
  CHECK(rig.app.last_error() == static_cast<std::uint8_t>(Error::QueueUnderrun));
  // Nothing moved during the stall; every setpoint before it reached the host.
  CHECK(rig.app.position() == staircase(15));
  CHECK(rig.board.steps == std::array<std::int64_t, 3>{15, 0, 0});
  rig.host.pump(3);
  require_each_setpoint(rig.host.setpoints(), staircase_stream(16));
}

TEST_CASE("executor app: a piece arriving before the stall timeout continues the job with the right setpoint",
          "[firmware][app][executor]") {
  AppSettings settings;
  settings.stall_timeout_ms = 20;
  ExecutorRig rig(settings);
  rig.connect_and_configure();
  queue_staircase(rig, 0, 15);
  rig.send(Message(Start{}));
  rig.host.run_ticks(16);
  rig.host.run_ticks(10);  // stalled for 10 ms
  REQUIRE(rig.app.statistics().stalled_ticks == 10);
  REQUIRE_FALSE(rig.app.ready_to_tick());

  // The next piece, still no end of job: a chunk of 2 ticks from staircase(15) to staircase(17)
  // (its first setpoint halfway, at staircase(16)); a chunk continues from the last setpoint.
  REQUIRE(rig.host.send(Message(straight_chunk({15 / 8.0, 0, 0}, {17 / 8.0, 0, 0}, 2, 16))));
  rig.host.pump(3);
  CHECK(rig.host.received.errors.empty());
  CHECK(rig.app.ready_to_tick());
  rig.host.run_ticks(1);
  CHECK(rig.app.position() == staircase(16));
  CHECK(rig.board.steps == std::array<std::int64_t, 3>{16, 0, 0});
  CHECK(rig.app.statistics().stalled_ticks == 10);
  rig.host.run_ticks(1);
  CHECK(rig.app.position() == staircase(17));
  rig.host.run_ticks(12);  // a second stall, 12 ms, shorter than the timeout
  CHECK(rig.app.statistics().stalled_ticks == 22);
  CHECK(rig.app.state() == MachineState::Running);

  REQUIRE(rig.host.send(Message(exact(18 / 8.0, 0, 0, true, 17))));
  rig.run_to_idle();
  CHECK(rig.host.received.errors.empty());
  require_each_setpoint(rig.host.setpoints(), staircase_stream(19));
  CHECK(rig.board.steps == std::array<std::int64_t, 3>{18, 0, 0});
  REQUIRE_FALSE(rig.host.received.status.empty());
  CHECK(rig.host.received.status.back().state == MachineState::Idle);
  CHECK(rig.board.fault_stops == 0);
}

TEST_CASE("executor app: after an Abort during a stall the next job runs without a stale stall fault",
          "[firmware][app][executor]") {
  AppSettings settings;
  settings.stall_timeout_ms = 20;
  ExecutorRig rig(settings);
  rig.connect_and_configure();
  queue_staircase(rig, 0, 15);
  rig.send(Message(Start{}));
  rig.host.run_ticks(16);
  rig.host.run_ticks(5);  // stalled for 5 ms
  REQUIRE(rig.app.statistics().stalled_ticks == 5);
  rig.send(Message(Abort{}));
  REQUIRE(rig.app.state() == MachineState::Idle);
  REQUIRE_FALSE(rig.app.moving());
  for (int ms = 0; ms < 30; ++ms) {  // 30 ms standing idle (longer than the stall timeout)
    ++rig.board.clock_ms;
    rig.host.pump();
  }
  REQUIRE(rig.host.received.errors.empty());

  // The next job starts where the machine stands (staircase(15)) and ends one step further.
  rig.send(Message(exact(15 / 8.0, 0)));
  rig.send(Message(exact(16 / 8.0, 0, 0, true)));
  rig.send(Message(Start{}));
  INFO("first error " << (rig.host.received.errors.empty() ? 0 : static_cast<int>(rig.host.received.errors[0].code)));
  CHECK(rig.host.received.errors.empty());  // no stall happened in this job
  CHECK(rig.app.state() == MachineState::Running);
  rig.run_to_idle();
  CHECK(rig.host.received.errors.empty());
  CHECK(rig.app.position() == staircase(16));
  CHECK(rig.board.steps == std::array<std::int64_t, 3>{16, 0, 0});
  CHECK(rig.board.fault_stops == 1);  // the Abort's
}
