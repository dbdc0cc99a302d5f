// SPDX-License-Identifier: MIT
// App<FakeBoard>: handshake, configuration, every segment kind, bit-identical setpoints, safety.
#include <catch2/catch.hpp>

#include <cstdint>
#include <utility>
#include <vector>

#include <curvestep/core/motion/motion_controller.hpp>
#include <curvestep/firmware/app.hpp>
#include <curvestep/firmware/conversions.hpp>
#include <curvestep/protocol/frame.hpp>
#include <curvestep/protocol/segment_curves.hpp>

#include "fake_board.hpp"

using namespace curvestep;
using namespace curvestep::firmware;
using namespace curvestep::protocol;
using curvestep::firmware::testing::FakeBoard;
using curvestep::firmware::testing::Host;

namespace {

using TestApp = App<FakeBoard>;

constexpr std::int32_t q(double mm) { return static_cast<std::int32_t>(mm * 65536.0); }

MachineConfiguration machine() {
  MachineConfiguration c;
  c.axis_count = 3;
  c.max_velocity_mm_per_s = q(100);
  c.max_acceleration_mm_per_s2 = 1000;
  c.max_jerk_mm_per_s3 = 10000;
  c.default_feed_mm_per_s = q(50);
  c.tolerance_mm = q(0.01);
  c.junction_deviation_mm = q(0.05);
  c.control_rate_hz = 1000;
  for (auto& axis : c.axes) {
    axis.steps_per_mm = q(80);
    axis.min_position_mm = q(-100);
    axis.max_position_mm = q(100);
  }
  return c;
}

WirePoint p(double x, double y, double z = 0) { return WirePoint{q(x), q(y), q(z)}; }

QueueSegment line(WirePoint a, WirePoint b, std::uint8_t axes = 3) {
  QueueSegment s;
  s.kind = protocol::SegmentKind::Line;
  s.axis_count = axes;
  s.points[0] = a;
  s.points[1] = b;
  return s;
}

/// Line, arc, cubic Bézier, rational quadratic and a line with its own feed ending the job.
std::vector<QueueSegment> mixed_job() {
  std::vector<QueueSegment> job;
  job.push_back(line(p(0, 0), p(5, 0)));
  QueueSegment arc;
  arc.kind = protocol::SegmentKind::Arc;
  arc.axis_count = 3;
  arc.degree = 2;
  arc.points[0] = p(5, 0);
  arc.points[1] = p(5, 4);
  arc.points[2] = p(5, 2);
  arc.direction = ArcDirection::CounterClockwise;
  job.push_back(arc);
  QueueSegment cubic;
  cubic.kind = protocol::SegmentKind::Bezier;
  cubic.axis_count = 3;
  cubic.degree = 3;
  cubic.points[0] = p(5, 4);
  cubic.points[1] = p(4, 5);
  cubic.points[2] = p(2, 5, 1);
  cubic.points[3] = p(1, 4, 1);
  job.push_back(cubic);
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
  MotionController<Q16_16, 32, 16> controller;
  REQUIRE(controller.configure(to_machine_limits(config).value()).has_value());
  std::size_t next = 0;
  const auto fill = [&] {
    while (next < job.size() && !controller.queue_full()) {
      const auto segment = to_path_segment(job[next]);
      REQUIRE(segment.has_value());
      const auto pushed = controller.try_push(segment.value(), static_cast<std::uint32_t>(next));
      if (!pushed && pushed.error() == Error::QueueFull) return;
      REQUIRE(pushed.has_value());
      ++next;
    }
    if (next == job.size()) controller.end_of_job();
  };
  fill();
  REQUIRE(controller.start().has_value());
  std::vector<std::pair<std::uint32_t, WirePoint>> out;
  while (!controller.finished()) {
    const auto sp = controller.next_setpoint();
    REQUIRE(sp.has_value());
    WirePoint w{};
    for (std::size_t a = 0; a < 3; ++a) w[a] = sp.value().position[a].raw();
    out.emplace_back(static_cast<std::uint32_t>(sp.value().tick), w);
    fill();
  }
  return out;
}

/// Streams `job` to the App while it runs, one submission attempt per tick, until the App is idle again.
template <class AppType>
void stream_job(Host<AppType>& host, AppType& app, FakeBoard& board, const std::vector<QueueSegment>& job,
                int max_ticks = 200000) {
  std::size_t next = 0;
  bool started = false;
  for (int t = 0; t < max_ticks; ++t) {
    while (next < job.size() && host.sender().can_submit(MessageType::QueueSegment)) {
      REQUIRE(host.sender().submit(Message(job[next])).has_value());
      ++next;
    }
    if (!started && host.sender().can_submit(MessageType::Start)) {
      REQUIRE(host.sender().submit(Message(Start{})).has_value());
      started = true;
    }
    // A host polls the status now and then; that traffic also keeps the link watchdog quiet.
    if (t % 100 == 99 && host.sender().can_submit(MessageType::StatusRequest)) {
      REQUIRE(host.sender().submit(Message(StatusRequest{})).has_value());
    }
    app.on_tick();
    ++board.clock_ms;
    host.pump();
    if (started && next == job.size() && !app.moving() && app.state() == MachineState::Idle &&
        host.sender().idle()) {
      return;
    }
  }
  INFO("state " << static_cast<int>(app.state()) << " moving " << app.moving() << " queued "
                 << app.controller().queued() << " controller " << static_cast<int>(app.controller().state())
                 << " sent " << next << " errors " << host.received.errors.size() << " credit "
                 << host.sender().credit() << " in flight " << host.sender().in_flight());
  INFO("first error " << (host.received.errors.empty() ? 0 : static_cast<int>(host.received.errors[0].code)) << " at "
                       << (host.received.errors.empty() ? 0 : host.received.errors[0].index) << " clock " << board.clock_ms);
  FAIL("the job did not finish");
}

}  // namespace

TEST_CASE("firmware: the handshake answers Capabilities with the App's limits", "[firmware][app]") {
  FakeBoard board;
  TestApp app(board);
  Host<TestApp> host(board, app);
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
  CHECK(c.credit_end == 0);  // no credit before a configuration
  CHECK(app.state() == MachineState::Idle);
}

TEST_CASE("firmware: a configuration is applied and opens the credit", "[firmware][app]") {
  FakeBoard board;
  TestApp app(board);
  Host<TestApp> host(board, app);
  REQUIRE(host.connect());
  REQUIRE(host.send(Message(machine())));
  for (int i = 0; i < 5; ++i) host.pump();
  CHECK(app.configured());
  CHECK(app.control_rate_hz() == 1000);
  CHECK(app.controller().machine().a_max_mm_per_s2 == 1000.0);
  CHECK(app.controller().machine().axes[1].steps_per_mm == 80.0);
  CHECK(host.received.errors.empty());
  // 32 slots, 7 per wire segment in the worst case: credit for 4 segments.
  CHECK(host.sender().credit() == 4);
}

TEST_CASE("firmware: an invalid configuration is answered with its error and index", "[firmware][app]") {
  FakeBoard board;
  TestApp app(board);
  Host<TestApp> host(board, app);
  REQUIRE(host.connect());
  MachineConfiguration bad = machine();
  bad.control_rate_hz = 50;  // below 100 Hz
  REQUIRE(host.send(Message(bad)));
  for (int i = 0; i < 5; ++i) host.pump();
  REQUIRE(host.received.errors.size() == 1);
  CHECK(host.received.errors[0].code == Error::InvalidRate);
  CHECK(host.received.errors[0].index == static_cast<std::uint16_t>(LimitField::RateHz));
  CHECK(host.received.errors[0].sequence == 0);
  CHECK_FALSE(app.configured());
  bad = machine();
  bad.max_jerk_mm_per_s3 = 0;
  REQUIRE(host.send(Message(bad)));
  for (int i = 0; i < 5; ++i) host.pump();
  REQUIRE(host.received.errors.size() == 2);
  CHECK(host.received.errors[1].code == Error::InvalidLimit);
  CHECK(host.received.errors[1].index == static_cast<std::uint16_t>(LimitField::JMax));
  CHECK(host.received.errors[1].sequence == 1);
}

TEST_CASE("firmware: segments of every kind stream setpoints bit-identical to the motion controller",
          "[firmware][app]") {
  FakeBoard board;
  TestApp app(board);
  Host<TestApp> host(board, app);
  REQUIRE(host.connect());
  REQUIRE(host.send(Message(machine())));
  const auto job = mixed_job();
  stream_job(host, app, board, job);
  const auto expected = reference(machine(), job);
  const auto got = host.setpoints();
  REQUIRE(host.received.errors.empty());
  REQUIRE(got.size() == expected.size());
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    if (got[i] != expected[i]) ++mismatches;
  }
  CHECK(mismatches == 0);
  CHECK(app.statistics().dropped_setpoints == 0);
  // The last setpoint is the job's end, and the step counts are the end position in steps.
  CHECK(got.back().second == p(0, 0, 0));
  CHECK(board.steps == std::array<std::int64_t, 3>{0, 0, 0});
  REQUIRE_FALSE(host.received.status.empty());
  CHECK(host.received.status.back().state == MachineState::Idle);
}

TEST_CASE("firmware: a job longer than the queue is topped up while running and stays bit-identical",
          "[firmware][app]") {
  FakeBoard board;
  TestApp app(board);
  Host<TestApp> host(board, app);
  REQUIRE(host.connect());
  REQUIRE(host.send(Message(machine())));
  std::vector<QueueSegment> job;
  for (int k = 0; k < 60; ++k) {
    const double x0 = k * 1.0;
    const double y0 = (k % 2 == 0) ? 0.0 : 0.5;
    const double y1 = (k % 2 == 0) ? 0.5 : 0.0;
    job.push_back(line(p(x0, y0), p(x0 + 1.0, y1)));
  }
  job.back().end_of_job = true;
  stream_job(host, app, board, job);
  const auto expected = reference(machine(), job);
  const auto got = host.setpoints();
  REQUIRE(host.received.errors.empty());
  REQUIRE(got.size() == expected.size());
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    if (got[i] != expected[i]) ++mismatches;
  }
  CHECK(mismatches == 0);
  CHECK(board.steps == std::array<std::int64_t, 3>{60 * 80, 0, 0});
}
