// SPDX-License-Identifier: MIT
// App<FakeBoard>: handshake, configuration, every segment kind, bit-identical setpoints, safety.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include <curvestep/core/motion/motion_controller.hpp>
#include <curvestep/firmware/app.hpp>
#include <curvestep/firmware/conversions.hpp>
#include <curvestep/protocol/frame.hpp>
#include <curvestep/protocol/segment_curves.hpp>

#include <support/numeric.hpp>

#include "fake_board.hpp"

using namespace curvestep;
using namespace curvestep::firmware;
using namespace curvestep::protocol;
using namespace curvestep::firmware::testing;  // fake_board.hpp: the board, the host, the wire helpers

namespace {

using TestApp = App<FakeBoard>;

MachineConfiguration machine() { return curvestep::firmware::testing::machine(50); }

/// A FakeBoard, an App on it and the scripted host (a fixture: the test sees board, app and host).
template <class AppType, class BoardType = FakeBoard>
struct Rig {
  BoardType board;
  AppType app{board};
  Host<AppType> host{board, app};

  /// Connects, sends `config` (without waiting for its acknowledgement) and streams `job` to its end.
  void stream(const MachineConfiguration& config, const std::vector<QueueSegment>& job) {
    REQUIRE(host.connect());
    REQUIRE(host.send(Message(config)));
    stream_job(host, app, board, job);
  }
};
using Bench = Rig<TestApp>;
using SmallBench = Rig<App<FakeBoard, Q16_16, 16, 2>>;  // a queue of 16 slots, look-ahead 2
using FloatBench = Rig<App<FakeBoard, float>>;           // float setpoints

/// A board that buffers edges and can lose them (as the STM32 edge ring does when it is full).
struct LossyBoard : FakeBoard {
  std::uint32_t dropped = 0;  ///< edges lost so far (set by the test)
  [[nodiscard]] std::uint32_t edges_dropped() const { return dropped; }
};
using LossyBench = Rig<App<LossyBoard>, LossyBoard>;

/// The segment (or the job with its last segment) marked as the end of the job.
QueueSegment ending(QueueSegment s) {
  s.end_of_job = true;
  return s;
}
std::vector<QueueSegment> ending(std::vector<QueueSegment> job) {
  job.back().end_of_job = true;
  return job;
}

/// Line, arc, cubic Bézier, rational quadratic and a line with its own feed ending the job.
std::vector<QueueSegment> mixed_job() {
  std::vector<QueueSegment> job;
  job.push_back(line(p(0, 0), p(5, 0)));
  job.push_back(arc(p(5, 0), p(5, 4), p(5, 2), ArcDirection::CounterClockwise));
  job.push_back(cubic(p(5, 4), p(4, 5), p(2, 5, 1), p(1, 4, 1)));
  QueueSegment rational;
  rational.kind = protocol::SegmentKind::RationalBezier;
  rational.axis_count = 3;
  rational.degree = 2;
  rational.points[0] = p(1, 4, 1);
  rational.points[1] = p(0, 4, 1);
  rational.points[2] = p(0, 3, 1);
  rational.weights = {65536, 46341, 65536};
  job.push_back(rational);
  QueueSegment last = line(p(0, 3, 1), p(0, 0, 0));
  last.has_feed = true;
  last.feed_mm_per_s = q(20);
  last.end_of_job = true;
  job.push_back(last);
  return job;
}

/// The reference: MotionController<Q16_16> run directly on the same segments, as curvestep sim does.
std::vector<std::pair<std::uint32_t, WirePoint>> reference(const MachineConfiguration& config,
                                                           const std::vector<QueueSegment>& job) {
  return curvestep::firmware::testing::controller_reference<MotionController<Q16_16, 32, 16>>(config, job);
}

/// The host received no error and the reference's stream for `job`, bit for bit; returns what it received.
template <class AppType>
std::vector<std::pair<std::uint32_t, WirePoint>> require_reference_stream(const Host<AppType>& host, const MachineConfiguration& config,
                                                                          const std::vector<QueueSegment>& job) {
  const auto expected = reference(config, job);
  const auto got = host.setpoints();
  REQUIRE(host.received.errors.empty());
  check_same_stream(got, expected);
  return got;
}

}  // namespace

TEST_CASE_METHOD(Bench, "firmware: the handshake answers Capabilities with the App's limits", "[firmware][app]") {
  REQUIRE(host.connect());
  const Capabilities& c = host.received.last_capabilities;
  CHECK(c.version == protocol_version);
  CHECK(c.session == 0x1234);
  CHECK(c.queue_capacity == 32);
  CHECK(c.fixed_total_bits == 32);
  CHECK(c.fixed_fraction_bits == 16);
  CHECK(c.axis_count == 3);
  CHECK(c.max_degree == 7);
  CHECK(c.tick_rate_hz == 1000000);
  CHECK(c.lookahead == 16);  // App<FakeBoard>'s default window
  CHECK(c.credit_end == 0);  // no credit before a configuration
  CHECK(app.state() == MachineState::Idle);
}

TEST_CASE_METHOD(Bench, "firmware: a configuration is applied and opens the credit", "[firmware][app]") {
  REQUIRE(host.connect());
  REQUIRE(host.send(Message(machine())));
  host.pump(5);
  CHECK(app.configured());
  CHECK(app.control_rate_hz() == 1000);
  CHECK(app.controller().machine().a_max_mm_per_s2 == 1000.0);
  CHECK(app.controller().machine().axes[1].steps_per_mm == 80.0);
  CHECK(host.received.errors.empty());
  // 32 slots, 7 per wire segment in the worst case: credit for 4 segments.
  CHECK(host.sender().credit() == 4);
}

TEST_CASE_METHOD(Bench, "firmware: an invalid configuration is answered with its error and index", "[firmware][app]") {
  REQUIRE(host.connect());
  MachineConfiguration bad = machine();
  bad.control_rate_hz = 50;  // below 100 Hz
  REQUIRE(host.send(Message(bad)));
  host.pump(5);
  REQUIRE(host.received.errors.size() == 1);
  CHECK(host.received.errors[0].code == Error::InvalidRate);
  CHECK(host.received.errors[0].index == static_cast<std::uint16_t>(LimitField::RateHz));
  CHECK(host.received.errors[0].sequence == 0);
  CHECK_FALSE(app.configured());
  bad = machine();
  bad.max_jerk_mm_per_s3 = 0;
  REQUIRE(host.send(Message(bad)));
  host.pump(5);
  REQUIRE(host.received.errors.size() == 2);
  CHECK(host.received.errors[1].code == Error::InvalidLimit);
  CHECK(host.received.errors[1].index == static_cast<std::uint16_t>(LimitField::JMax));
  CHECK(host.received.errors[1].sequence == 1);
}

TEST_CASE_METHOD(Bench, "firmware: segments of every kind stream setpoints bit-identical to the motion controller",
          "[firmware][app]") {
  const auto job = mixed_job();
  stream(machine(), job);
  const auto got = require_reference_stream(host, machine(), job);
  CHECK(app.statistics().dropped_setpoints == 0);
  // The last setpoint is the job's end, and the step counts are the end position in steps.
  CHECK(got.back().second == p(0, 0, 0));
  CHECK(board.steps == std::array<std::int64_t, 3>{0, 0, 0});
  REQUIRE_FALSE(host.received.status.empty());
  CHECK(host.received.status.back().state == MachineState::Idle);
}

TEST_CASE_METHOD(Bench, "firmware: a job longer than the queue is topped up while running and stays bit-identical",
          "[firmware][app]") {
  std::vector<QueueSegment> job;
  for (int k = 0; k < 60; ++k) {
    const double x0 = k * 1.0;
    const double y0 = (k % 2 == 0) ? 0.0 : 0.5;
    const double y1 = (k % 2 == 0) ? 0.5 : 0.0;
    job.push_back(line(p(x0, y0), p(x0 + 1.0, y1)));
  }
  job.back().end_of_job = true;
  stream(machine(), job);
  require_reference_stream(host, machine(), job);
  CHECK(board.steps == std::array<std::int64_t, 3>{60 * 80, 0, 0});
}

namespace {

/// Connects, configures and returns once the configuration is acknowledged.
template <class AppType>
void connect_and_configure(Host<AppType>& host, const MachineConfiguration& config = machine()) {
  REQUIRE(host.connect());
  REQUIRE(host.send(Message(config)));
  host.pump(5);
  REQUIRE(host.received.errors.empty());
}

/// Queues `job` (as far as the credit allows, pumping) and sends Start.
template <class AppType>
void queue_and_start(Host<AppType>& host, const std::vector<QueueSegment>& job) {
  for (const auto& s : job) REQUIRE(host.send(Message(s)));
  REQUIRE(host.send(Message(Start{})));
  host.pump(5);
}

std::int64_t steps_of(double mm) { return static_cast<std::int64_t>(mm * 80.0); }

/// The whole job is uploaded and the App stands idle with every setpoint acknowledged.
template <class AppType>
bool job_finished(const JobUpload& upload, const AppType& app) {
  return upload.all_sent() && app.state() == MachineState::Idle && !app.moving() && app.setpoint_sender().idle();
}

/// Every setpoint arrived once and in order: the reference's stream, checked setpoint by setpoint.
void require_each_setpoint(const std::vector<std::pair<std::uint32_t, WirePoint>>& got,
                           const std::vector<std::pair<std::uint32_t, WirePoint>>& expected) {
  REQUIRE(got.size() == expected.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    INFO("setpoint " << i);
    REQUIRE(got[i] == expected[i]);
  }
}

}  // namespace

TEST_CASE_METHOD(Bench, "firmware: a two-axis job is bit-identical to the motion controller too", "[firmware][app]") {
  MachineConfiguration config = machine();
  config.axis_count = 2;
  const auto job = ending(std::vector<QueueSegment>{line(p(0, 0), p(3, 0), 2),
                                                     arc(p(3, 0), p(3, 2), p(3, 1), ArcDirection::Clockwise, 2),
                                                     line(p(3, 2), p(0, 2), 2)});
  stream(config, job);
  require_reference_stream(host, config, job);
  CHECK(board.steps == std::array<std::int64_t, 3>{0, steps_of(2), 0});
}

TEST_CASE_METHOD(Bench, "firmware: feed hold stops on the path and resume finishes the job", "[firmware][app]") {
  connect_and_configure(host);
  queue_and_start(host, {ending(line(p(0, 0), p(40, 0)))});
  host.run_ticks(200);
  REQUIRE(app.moving());
  REQUIRE(host.send(Message(FeedHold{})));
  host.pump();
  CHECK(app.state() == MachineState::Holding);
  host.run_ticks(500);
  REQUIRE(app.controller().state() == ControllerState::Held);
  const auto held_at = app.position();
  const auto held_steps = board.steps;
  CHECK(held_at[0] > q(5));
  CHECK(held_at[0] < q(40));
  host.run_ticks(200);
  CHECK(app.position() == held_at);
  CHECK(board.steps == held_steps);
  REQUIRE(host.send(Message(Resume{})));
  host.run_ticks(3000);
  CHECK(app.state() == MachineState::Idle);
  CHECK(app.position() == p(40, 0));
  CHECK(board.steps == std::array<std::int64_t, 3>{steps_of(40), 0, 0});
  CHECK(host.received.errors.empty());
}

TEST_CASE_METHOD(Bench, "firmware: abort stops at once, flushes the queue and allows a new job", "[firmware][app]") {
  connect_and_configure(host);
  const auto job = ending(std::vector<QueueSegment>{line(p(0, 0), p(20, 0)), line(p(20, 0), p(20, 20))});
  queue_and_start(host, job);
  host.run_ticks(150);
  REQUIRE(app.moving());
  REQUIRE(host.send(Message(Abort{})));
  host.pump();
  CHECK(board.fault_stops == 1);
  CHECK(app.state() == MachineState::Idle);
  CHECK_FALSE(app.moving());
  CHECK(app.controller().queued() == 0);
  const auto stopped_at = app.position();
  const auto steps = board.steps;
  host.run_ticks(50);
  CHECK(app.position() == stopped_at);
  CHECK(board.steps == steps);
  // A job from elsewhere is refused: the machine stands where the abort left it.
  REQUIRE(host.send(Message(line(p(0, 0), p(1, 0)))));
  host.pump();
  REQUIRE(host.received.errors.size() == 1);
  CHECK(host.received.errors[0].code == Error::SegmentsNotConnected);
  host.received.errors.clear();
  // A new job from where the machine stopped runs to its end.
  queue_and_start(host, {ending(line(stopped_at, p(0, 0)))});
  host.run_ticks(2000);
  CHECK(app.state() == MachineState::Idle);
  CHECK(board.steps == std::array<std::int64_t, 3>{0, 0, 0});
  CHECK(host.received.errors.empty());
}

TEST_CASE("firmware: losing the host link holds the machine and Resume continues", "[firmware][app]") {
  FakeBoard board;
  AppSettings settings;
  settings.link_timeout_ms = 50;
  settings.stream_setpoints = false;  // a silent host would not acknowledge setpoints either (next test)
  TestApp app(board, settings);
  Host<TestApp> host(board, app);
  connect_and_configure(host);
  queue_and_start(host, {ending(line(p(0, 0), p(30, 0)))});
  REQUIRE(app.moving());
  host.run_ticks(49);  // the host sends nothing while the job runs
  CHECK(app.state() == MachineState::Running);
  host.run_ticks(600);
  CHECK(app.state() == MachineState::Holding);
  CHECK(app.controller().state() == ControllerState::Held);
  REQUIRE(host.received.errors.size() == 1);
  CHECK(host.received.errors[0].code == Error::LinkTimeout);
  REQUIRE(host.send(Message(Resume{})));
  for (int t = 0; t < 3000 && app.state() != MachineState::Idle; ++t) {
    if (t % 40 == 0) REQUIRE(host.send(Message(StatusRequest{})));
    host.run_ticks(1);
  }
  CHECK(app.state() == MachineState::Idle);
  CHECK(app.position() == p(30, 0));
}

TEST_CASE_METHOD(Bench, "firmware: a corrupted frame is Nak-ed and the queue is not disturbed", "[firmware][app]") {
  connect_and_configure(host);
  REQUIRE(host.sender().submit(Message(line(p(0, 0), p(1, 0)))).has_value());
  std::array<std::byte, max_encoded_frame_size> frame{};
  const auto size = host.sender().poll(board.clock_ms, frame);
  REQUIRE(size.has_value());
  REQUIRE(size.value() > 10);
  frame[8] = frame[8] == std::byte{0x55} ? std::byte{0x56} : std::byte{0x55};  // one damaged data byte
  board.put_incoming(std::span<const std::byte>(frame.data(), size.value()));
  app.poll();
  host.take_output();
  REQUIRE(host.received.naks.size() == 1);
  CHECK((host.received.naks[0].reason == Error::BadCrc || host.received.naks[0].reason == Error::BadFraming));
  CHECK(app.controller().queued() == 0);
  host.pump(5);  // the Nak made the host resend at once
  CHECK(app.controller().queued() == 1);
  CHECK(host.sender().idle());
  CHECK(host.received.errors.empty());
}

TEST_CASE_METHOD(Bench, "firmware: a segment beyond the granted credit is refused with QueueFull", "[firmware][app]") {
  connect_and_configure(host);
  std::uint8_t sequence = 1;  // the configuration took sequence 0
  double x = 0;
  while (host.sender().credit() > 0) {
    REQUIRE(host.send(Message(line(p(x, 0), p(x + 1, 0)))));
    x += 1;
    ++sequence;
    host.pump(3);
  }
  const std::size_t queued = app.controller().queued();
  // Credit lasts while 7 slots (the worst-case split) are free: 32 - 7 + 1 = 26 one-slot segments.
  CHECK(queued == 26);
  send_raw(board, line(p(x, 0), p(x + 1, 0)), sequence);
  app.poll();
  host.take_output();
  REQUIRE_FALSE(host.received.naks.empty());
  CHECK(host.received.naks.back().reason == Error::QueueFull);
  CHECK(host.received.naks.back().expected == sequence);
  CHECK(app.controller().queued() == queued);
}

TEST_CASE_METHOD(Bench, "firmware: a step rate the drivers cannot follow faults with its error and axis", "[firmware][app]") {
  MachineConfiguration config = machine();
  config.axes[0].steps_per_mm = 2000;  // 100 mm/s would need 200 000 steps/s
  connect_and_configure(host, config);
  // The App lowered the step-rate limit until the busiest tick fits the board's 64-edge batch.
  const auto fitted = StepConfig::create(app.controller().machine(), FakeBoard::step_timing());
  REQUIRE(fitted.has_value());
  CHECK(fitted.value().max_events_per_tick() <= FakeBoard::step_events_per_tick);
  CHECK(app.controller().machine().max_step_rate_hz < 100000.0);
  QueueSegment s = line(p(0, 0), p(50, 0));
  s.has_feed = true;
  s.feed_mm_per_s = q(100);
  s.end_of_job = true;
  queue_and_start(host, {s});
  host.run_ticks(1000);
  CHECK(app.state() == MachineState::Fault);
  CHECK_FALSE(app.moving());
  CHECK(board.fault_stops == 1);
  REQUIRE(host.received.errors.size() == 1);
  CHECK(host.received.errors[0].code == Error::StepRateTooHigh);
  CHECK(host.received.errors[0].index == 0);
  REQUIRE_FALSE(host.received.status.empty());
  CHECK(host.received.status.back().state == MachineState::Fault);
  CHECK(host.received.status.back().error == static_cast<std::uint8_t>(Error::StepRateTooHigh));
  // Fault refuses new work until Abort.
  REQUIRE(host.send(Message(Start{})));
  host.pump();
  REQUIRE(host.received.errors.size() == 2);
  CHECK(host.received.errors[1].code == Error::InvalidState);
  REQUIRE(host.send(Message(Abort{})));
  host.pump();
  CHECK(app.state() == MachineState::Idle);
}

TEST_CASE_METHOD(LossyBench, "firmware: step edges the board lost are a StepsLost fault naming the segment",
                 "[firmware][app]") {
  connect_and_configure(host);
  queue_and_start(host, {line(p(0, 0), p(10, 0)), ending(line(p(10, 0), p(40, 0)))});
  host.run_ticks(100);  // well inside the first segment (10 mm at 50 mm/s take over 200 ticks)
  REQUIRE(app.moving());
  REQUIRE(host.received.errors.empty());
  board.dropped = 1;  // the edge ring overflowed
  host.run_ticks(1);
  CHECK(app.state() == MachineState::Fault);
  CHECK_FALSE(app.moving());
  CHECK(board.fault_stops == 1);
  REQUIRE(host.received.errors.size() == 1);
  CHECK(host.received.errors[0].code == Error::StepsLost);
  CHECK(host.received.errors[0].index == 0);
  // After Abort the next job runs: the loss was reported once, not again.
  REQUIRE(host.send(Message(Abort{})));
  host.pump(5);
  REQUIRE(app.state() == MachineState::Idle);
  const WirePoint here = app.position();
  queue_and_start(host, {ending(line(here, p(0, 0)))});
  host.run_ticks(3000);
  CHECK(app.state() == MachineState::Idle);
  CHECK(host.received.errors.size() == 1);
  CHECK(board.steps == std::array<std::int64_t, 3>{0, 0, 0});  // back at the origin: 0 steps
}

TEST_CASE("firmware: edges a board lost before the App was built are not a fault", "[firmware][app]") {
  LossyBoard board;
  board.dropped = 5;  // e.g. an earlier image or App on the same static edge ring
  App<LossyBoard> app(board);
  Host<App<LossyBoard>> host(board, app);
  connect_and_configure(host);
  queue_and_start(host, {ending(line(p(0, 0), p(5, 0)))});
  host.run_ticks(2000);
  CHECK(host.received.errors.empty());
  CHECK(app.state() == MachineState::Idle);
  CHECK(board.steps == std::array<std::int64_t, 3>{400, 0, 0});  // 5 mm at 80 steps/mm
}

TEST_CASE_METHOD(Bench, "firmware: a segment that does not start at the previous end is refused", "[firmware][app]") {
  connect_and_configure(host);
  REQUIRE(host.send(Message(line(p(0, 0), p(1, 0)))));
  REQUIRE(host.send(Message(line(p(1, 0.5), p(2, 0)))));
  host.pump(5);
  REQUIRE(host.received.errors.size() == 1);
  CHECK(host.received.errors[0].code == Error::SegmentsNotConnected);
  CHECK(host.received.errors[0].index == 1);
  CHECK(host.received.errors[0].sequence == 2);
  CHECK(app.controller().queued() == 1);
}

TEST_CASE_METHOD(SmallBench, "firmware: a queue underrun stops on the path, is reported, and the job goes on", "[firmware][app]") {
  connect_and_configure(host);
  queue_and_start(host, {line(p(0, 0), p(2, 0)), line(p(2, 0), p(4, 0)), line(p(4, 0), p(6, 0))});
  REQUIRE(app.moving());
  host.run_ticks(1500);
  CHECK(app.controller().state() == ControllerState::Starved);
  CHECK(app.state() == MachineState::Running);
  CHECK(app.position() == p(6, 0));
  REQUIRE_FALSE(host.received.status.empty());
  CHECK(host.received.status.back().error == static_cast<std::uint8_t>(Error::QueueUnderrun));
  const auto rest = ending(std::vector<QueueSegment>{line(p(6, 0), p(6, 2)), line(p(6, 2), p(6, 4))});
  for (const auto& s : rest) REQUIRE(host.send(Message(s)));
  host.run_ticks(1500);
  CHECK(app.state() == MachineState::Idle);
  CHECK(app.position() == p(6, 4));
  CHECK(board.steps == std::array<std::int64_t, 3>{steps_of(6), steps_of(4), 0});
  CHECK(host.received.errors.empty());
}

TEST_CASE("firmware: wire values convert exactly to planner values", "[firmware][app]") {
  CHECK(wire_to_mm(688128) == 10.5);
  CHECK(wire_to_mm(-147456) == -2.25);
  CHECK(wire_to_mm(1) == 1.0 / 65536.0);
  const auto limits = to_machine_limits(machine());
  REQUIRE(limits.has_value());
  CHECK(limits.value().v_max_mm_per_s == 100.0);
  CHECK(limits.value().j_max_mm_per_s3 == 10000.0);
  CHECK(limits.value().rate_hz == 1000.0);
  CHECK(limits.value().tolerance_mm == 0.01);  // binary64 on the wire: the host's double exactly
  CHECK(limits.value().junction_deviation_mm == 0.05);
  CHECK(limits.value().max_step_rate_hz == 100000.0);
  CHECK(limits.value().jerk_limited);
  CHECK(limits.value().rapid_mm_per_s == 0.0);
  MachineConfiguration trapezoid = machine();
  trapezoid.profile = ProfileKind::Trapezoid;
  trapezoid.rapid_mm_per_s = q(80);
  CHECK_FALSE(to_machine_limits(trapezoid).value().jerk_limited);
  CHECK(to_machine_limits(trapezoid).value().rapid_mm_per_s == 80.0);
  QueueSegment helix;
  helix.kind = protocol::SegmentKind::Arc;
  helix.axis_count = 3;
  helix.points[0] = p(2, 0, 0);
  helix.points[1] = p(2, 0, -3);
  helix.points[2] = p(0, 0);
  helix.turns = 2;  // a full circle (start == end) plus two more turns: three turns, 3 mm down
  const auto three_turns = to_path_segment(helix);
  REQUIRE(three_turns.has_value());
  CHECK(three_turns.value().arc_sweep_rad() == Approx(6 * 3.14159265358979323846).epsilon(1e-15));
  QueueSegment arc;
  arc.kind = protocol::SegmentKind::Arc;
  arc.axis_count = 2;
  arc.points[0] = p(2, 0);
  arc.points[1] = p(0, 2);
  arc.points[2] = p(0, 0);
  const auto segment = to_path_segment(arc);
  REQUIRE(segment.has_value());
  CHECK(segment.value().arc_radius() == 2.0);
  CHECK(segment.value().end() == MachinePoint{{0.0, 2.0, 0.0}});
  CHECK(segment.value().feed_mm_per_s() == 0.0);
  QueueSegment bad = line(p(1, 1), p(1, 1));
  CHECK(to_path_segment(bad).error() == Error::DegenerateCurve);
  QueueSegment no_feed = line(p(0, 0), p(1, 0));
  no_feed.has_feed = true;
  no_feed.feed_mm_per_s = 0;
  CHECK(to_path_segment(no_feed).error() == Error::InvalidLimit);
}

TEST_CASE_METHOD(SmallBench, "firmware: a feed hold during an underrun keeps the machine still until Resume", "[firmware][app]") {
  connect_and_configure(host);
  queue_and_start(host, {line(p(0, 0), p(2, 0)), line(p(2, 0), p(4, 0)), line(p(4, 0), p(6, 0))});
  host.run_ticks(1500);
  REQUIRE(app.controller().state() == ControllerState::Starved);
  REQUIRE(host.send(Message(FeedHold{})));
  host.pump();
  CHECK(app.state() == MachineState::Holding);
  const auto rest = ending(std::vector<QueueSegment>{line(p(6, 0), p(6, 2)), line(p(6, 2), p(6, 4))});
  for (const auto& s : rest) REQUIRE(host.send(Message(s)));
  host.run_ticks(300);
  CHECK(app.position() == p(6, 0));  // held: the new segments wait
  REQUIRE(host.send(Message(Resume{})));
  host.run_ticks(1500);
  CHECK(app.state() == MachineState::Idle);
  CHECK(app.position() == p(6, 4));
  CHECK(host.received.errors.empty());
}

TEST_CASE_METHOD(Bench, "firmware: a new configuration is refused while segments are queued", "[firmware][app]") {
  connect_and_configure(host);
  REQUIRE(host.send(Message(line(p(0, 0), p(1, 0)))));
  REQUIRE(host.send(Message(machine())));
  host.pump(5);
  REQUIRE(host.received.errors.size() == 1);
  CHECK(host.received.errors[0].code == Error::PlannerBusy);
  CHECK(app.controller().queued() == 1);
}

TEST_CASE_METHOD(Bench, "firmware: a StatusReport follows a feed hold once the machine stands", "[firmware][app]") {
  connect_and_configure(host);
  queue_and_start(host, {ending(line(p(0, 0), p(40, 0)))});
  host.run_ticks(200);
  REQUIRE(host.send(Message(FeedHold{})));
  host.pump();
  const std::size_t before = host.received.status.size();
  host.run_ticks(500);
  REQUIRE(app.controller().state() == ControllerState::Held);
  REQUIRE(host.received.status.size() == before + 1);
  CHECK(host.received.status.back().state == MachineState::Holding);
  CHECK(host.received.status.back().position == app.position());
  REQUIRE(host.send(Message(Resume{})));
  host.pump();
  CHECK(app.state() == MachineState::Running);
}

TEST_CASE_METHOD(Bench, "firmware: Resume while still braking continues from the stop", "[firmware][app]") {
  connect_and_configure(host);
  queue_and_start(host, {ending(line(p(0, 0), p(40, 0)))});
  host.run_ticks(200);
  REQUIRE(host.send(Message(FeedHold{})));
  host.pump();
  host.run_ticks(2);
  REQUIRE(app.controller().state() == ControllerState::Holding);
  REQUIRE(host.send(Message(Resume{})));
  host.pump();
  host.run_ticks(3000);
  CHECK(app.state() == MachineState::Idle);
  CHECK(app.position() == p(40, 0));
  CHECK(board.steps == std::array<std::int64_t, 3>{steps_of(40), 0, 0});
  CHECK(host.received.errors.empty());
}

TEST_CASE_METHOD(Bench, "firmware: segments that leave the travel range are refused with the axis", "[firmware][app]") {
  connect_and_configure(host);  // travel -100 .. 100 mm on every axis
  REQUIRE(host.send(Message(line(p(0, 0), p(150, 0)))));
  host.pump(3);
  REQUIRE(host.received.errors.size() == 1);
  CHECK(host.received.errors[0].code == Error::OutsideTravel);
  CHECK(host.received.errors[0].index == 0);
  // A counter-clockwise half circle about (0, 96) of radius 5 from (5, 96) passes (0, 101) ...
  QueueSegment half = arc(p(5, 96), p(-5, 96), p(0, 96), ArcDirection::CounterClockwise);
  REQUIRE(host.send(Message(half)));
  host.pump(3);
  REQUIRE(host.received.errors.size() == 2);
  CHECK(host.received.errors[1].code == Error::OutsideTravel);
  CHECK(host.received.errors[1].index == 1);
  // ... the clockwise one passes (0, 91) and stays inside: accepted.
  half.direction = ArcDirection::Clockwise;
  REQUIRE(host.send(Message(half)));
  host.pump(3);
  CHECK(host.received.errors.size() == 2);
  CHECK(app.controller().queued() == 1);
  // A reversed travel range is refused at configuration (index: byte offset of axis 1's minimum).
  MachineConfiguration reversed = machine();
  reversed.axes[1].min_position_mm = q(10);
  reversed.axes[1].max_position_mm = q(-10);
  CHECK(to_travel_limits(reversed).error() == Error::InvalidArgument);
  CHECK(to_travel_limits(reversed).where() == 62 + 32 + 24);  // header, axis 0, axis 1's three binary64 fields
}

TEST_CASE("firmware: a travel range of zero to zero leaves the axis unlimited", "[firmware][app]") {
  MachineConfiguration config = machine();
  config.axes[0].min_position_mm = 0;
  config.axes[0].max_position_mm = 0;
  const auto travel = to_travel_limits(config);
  REQUIRE(travel.has_value());
  const auto far = to_path_segment(line(p(0, 0), p(1000, 0)));
  REQUIRE(far.has_value());
  CHECK(check_travel(far.value(), travel.value()).has_value());
  const auto bounds = segment_bounds(far.value());
  CHECK(bounds.high[0] == 1000.0);
  CHECK(bounds.low[0] == 0.0);
}

TEST_CASE("firmware: the next job's first segment is accepted in the poll right after a job ends",
          "[firmware][app]") {
  FakeBoard board;
  AppSettings settings;
  settings.stream_setpoints = false;  // ticks without a poll in between: nothing drains a stream
  TestApp app(board, settings);
  Host<TestApp> host(board, app);
  connect_and_configure(host);
  queue_and_start(host, {ending(line(p(0, 0), p(2, 0)))});
  REQUIRE(app.moving());
  for (int t = 0; t < 5000 && app.moving(); ++t) app.on_tick();  // no poll in between
  REQUIRE_FALSE(app.moving());
  QueueSegment second = line(p(2, 0), p(2, 2));
  second.end_of_job = true;
  REQUIRE(host.sender().submit(Message(second)).has_value());
  host.pump();
  CHECK(host.received.errors.empty());
  CHECK(app.state() == MachineState::Idle);
  CHECK(app.controller().queued() == 1);
}

TEST_CASE_METHOD(Bench, "firmware: a Bézier with a cusp takes two queue slots and stays bit-identical", "[firmware][app]") {
  connect_and_configure(host);
  // B'(1/2) = 3 (1/4 (1, 1) + 1/2 (-1, 0) + 1/4 (1, -1)) = 0: a cusp in the middle.
  const QueueSegment cusp = cubic(p(0, 0), p(1, 1), p(0, 1), p(1, 0), 2);
  const QueueSegment last = ending(line(p(1, 0), p(3, 0), 2));
  REQUIRE(host.send(Message(cusp)));
  host.pump(3);
  CHECK(app.controller().queued() == 2);
  host.received = {};
  const std::vector<QueueSegment> job{cusp, last};
  stream_job(host, app, board, std::vector<QueueSegment>{last});
  const auto got = require_reference_stream(host, machine(), job);
  // independent of the reference: the job ends at (3, 0), 240 steps along x
  REQUIRE_FALSE(got.empty());
  CHECK(got.back().second == p(3, 0));
  CHECK(board.steps == std::array<std::int64_t, 3>{steps_of(3), 0, 0});
}

TEST_CASE_METHOD(Bench, "firmware: a malformed payload is answered with BadPayload at its byte offset", "[firmware][app]") {
  connect_and_configure(host);
  const std::array<std::byte, 2> payload{std::byte{4}, std::byte{0}};  // segment kind 4 does not exist
  send_raw(board, static_cast<std::uint8_t>(MessageType::QueueSegment), 1, payload);
  app.poll();
  host.take_output();
  REQUIRE(host.received.errors.size() == 1);
  CHECK(host.received.errors[0].code == Error::BadPayload);
  CHECK(host.received.errors[0].index == 0);
  CHECK(host.received.errors[0].sequence == 1);
  CHECK(app.controller().queued() == 0);
}

TEST_CASE_METHOD(Bench, "firmware: a slow transmitter gets every frame in order, later", "[firmware][app]") {
  board.write_limit = 24;  // bytes accepted per write: 24 kB/s at one poll per millisecond
  const auto job = mixed_job();
  stream(machine(), job);
  host.pump(50);
  const auto expected = reference(machine(), job);
  CHECK(host.setpoints() == expected);
  // independent of the reference: the job's end point, in position and in steps
  REQUIRE_FALSE(host.setpoints().empty());
  CHECK(host.setpoints().back().second == p(0, 0, 0));
  CHECK(board.steps == std::array<std::int64_t, 3>{0, 0, 0});
  CHECK(app.statistics().dropped_frames == 0);
  CHECK(app.statistics().dropped_setpoints == 0);
}

TEST_CASE_METHOD(FloatBench, "firmware: with float setpoints the job runs to its exact end point", "[firmware][app]") {
  const auto job = mixed_job();
  stream(machine(), job);
  const auto got = host.setpoints();
  const auto expected = reference(machine(), job);
  REQUIRE(host.received.errors.empty());
  REQUIRE(got.size() == expected.size());
  CHECK(got.back().second == p(0, 0, 0));
  // Below 8 mm a float's spacing is under 1e-6 mm (0.07 raw units), so after rounding to Q16.16
  // both scalars agree within one raw unit (15 nm).
  std::int32_t worst = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    for (std::size_t a = 0; a < 3; ++a) {
      const std::int32_t d = got[i].second[a] - expected[i].second[a];
      worst = std::max(worst, d < 0 ? -d : d);
    }
  }
  CHECK(worst <= 1);
}

TEST_CASE_METHOD(Bench, "firmware: random line noise never queues anything and the link recovers", "[firmware][app]") {
  connect_and_configure(host);
  std::mt19937 random(curvestep::testing::test_seed());
  std::uniform_int_distribution<int> byte(0, 255);
  const int count = curvestep::testing::test_count(20000);
  for (int i = 0; i < count; ++i) {
    board.incoming.push_back(static_cast<std::byte>(byte(random)));
    if (i % 64 == 63) {
      app.poll();
      host.take_output();
    }
  }
  board.incoming.push_back(std::byte{0});  // end whatever partial frame the noise left
  app.poll();
  host.take_output();
  CHECK(app.controller().queued() == 0);
  CHECK(app.state() == MachineState::Idle);
  // The host's next segment still arrives (resent if a Nak or the timer asks for it).
  REQUIRE(host.send(Message(line(p(0, 0), p(1, 0)))));
  for (int i = 0; i < 400 && app.controller().queued() == 0; ++i) {
    ++board.clock_ms;
    host.pump();
  }
  CHECK(app.controller().queued() == 1);
}

TEST_CASE_METHOD(Bench, "firmware: a new session declares the position afresh with its first job", "[firmware][app]") {
  connect_and_configure(host);
  queue_and_start(host, {ending(line(p(0, 0), p(2, 0)))});
  host.run_ticks(1000);
  REQUIRE(app.state() == MachineState::Idle);
  REQUIRE(app.position() == p(2, 0));
  Host<TestApp> second_host(board, app);
  REQUIRE(second_host.connect(0x4321));
  REQUIRE(second_host.send(Message(machine())));  // a new session starts without a configuration
  queue_and_start(second_host, {ending(line(p(10, 10), p(12, 10)))});
  second_host.run_ticks(1000);
  CHECK(second_host.received.errors.empty());
  CHECK(app.position() == p(12, 10));
  // The steps moved by the second job only: the first job's 2 mm and then 2 mm more.
  CHECK(board.steps == std::array<std::int64_t, 3>{steps_of(4), 0, 0});
}

TEST_CASE("firmware: a host that stops acknowledging setpoints pauses the interpolator and a long stall is a fault",
          "[firmware][app]") {
  FakeBoard board;
  AppSettings settings;
  settings.stall_timeout_ms = 300;
  settings.link_timeout_ms = 0;
  TestApp app(board, settings);
  Host<TestApp> host(board, app);
  connect_and_configure(host);
  queue_and_start(host, {ending(line(p(0, 0), p(30, 0)))});
  REQUIRE(app.moving());
  host.acknowledge_setpoints = false;
  host.run_ticks(200);
  // window (4 batches) and buffer (48) full: the controller stopped advancing, nothing was dropped
  const std::uint64_t tick = app.controller().tick();
  CHECK(app.statistics().stalled_ticks > 0);
  CHECK_FALSE(app.ready_to_tick());
  host.run_ticks(100);
  CHECK(app.controller().tick() == tick);
  CHECK(app.state() == MachineState::Running);
  host.run_ticks(300);  // stalled for more than 300 ms
  CHECK(app.state() == MachineState::Fault);
  REQUIRE_FALSE(host.received.errors.empty());
  CHECK(host.received.errors.back().code == Error::LinkTimeout);
  CHECK(app.statistics().dropped_setpoints == 0);
}

TEST_CASE("firmware: a slow host gets every setpoint exactly once because the App waits instead of dropping",
          "[firmware][app]") {
  FakeBoard board;
  AppSettings settings;
  settings.stall_timeout_ms = 0;  // fast mode: wait for ever
  TestApp app(board, settings);
  Host<TestApp> host(board, app);
  connect_and_configure(host);
  const auto job = mixed_job();
  const auto expected = reference(machine(), job);
  JobUpload upload(job);
  for (int t = 0; t < 400000 && !job_finished(upload, app); ++t) {
    REQUIRE(upload.step(host.sender(), t));
    host.reading = (t / 37) % 5 == 0;  // the host reads only a fifth of the time, in bursts
    app.on_tick();
    ++board.clock_ms;
    host.pump();
  }
  CHECK(app.statistics().stalled_ticks > 0);
  const auto got = host.setpoints();
  INFO("state " << static_cast<int>(app.state()) << " moving " << app.moving() << " errors " << host.received.errors.size()
                << " first error " << (host.received.errors.empty() ? 0 : static_cast<int>(host.received.errors[0].code))
                << " sender state " << static_cast<int>(app.setpoint_sender().state()) << " in flight "
                << app.setpoint_sender().in_flight() << " go-backs " << app.setpoint_sender().go_backs() << " clock "
                << board.clock_ms << " repeated " << host.repeated_batches);
  require_each_setpoint(got, expected);
}

TEST_CASE_METHOD(Bench, "firmware: a lost setpoint frame is resent after the host's Nak and the batches shrink on a noisy line",
          "[firmware][app]") {
  connect_and_configure(host);
  const auto job = mixed_job();
  const auto expected = reference(machine(), job);
  JobUpload upload(job);
  std::mt19937 rng(curvestep::testing::test_seed());
  int damaged = 0;
  for (int t = 0; t < 400000 && !job_finished(upload, app); ++t) {
    REQUIRE(upload.step(host.sender(), t));
    app.on_tick();
    ++board.clock_ms;
    app.poll();
    // damage one byte in 200 of what the App sent (setpoint frames among them)
    for (std::byte& b : board.outgoing) {
      if (b != std::byte{0} && rng() % 200 == 0) {
        b ^= std::byte{0x10};
        ++damaged;
      }
    }
    host.take_output();
    host.pump();
  }
  CHECK(damaged > 0);
  CHECK(app.statistics().setpoint_go_backs > 0);
  const auto got = host.setpoints();
  require_each_setpoint(got, expected);
  bool small = false;
  for (const auto& b : host.received.batches) small = small || b.count < max_setpoints_per_batch / 2;
  CHECK(small);
}
