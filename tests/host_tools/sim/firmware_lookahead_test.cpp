// SPDX-License-Identifier: MIT
// The simulator's look-ahead window against the firmware: simulate() with lookahead 9 gives exactly
// the setpoints of a firmware App with Lookahead 9 streamed over its serial link (FakeBoard, as in
// tests/firmware/app), and of an independent MotionController<Q16_16, 16, 9>; the default window
// (16) does not (the jobs are chosen so that the window matters); invalid windows are refused.
//
// Queue depth: the App grants credit in whole worst-case segments (slots_per_segment = 7 slots),
// so its queue peaks at Queue - 6 entries, and a segment is planned just after the previous one
// left the queue, with Queue - 8 segments behind it. The full window Lookahead is therefore used
// only when Queue >= Lookahead + 8, which App's static_assert requires: App<_, _, 17, 9> is the
// simulator's --lookahead 9 stream, and the STM32F1's App<_, _, 16, 8> is --lookahead 8.
#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/motion/motion_controller.hpp>
#include <curvestep/firmware/app.hpp>
#include <curvestep/firmware/conversions.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/simulator.hpp>

#include "fake_board.hpp"  // tests/firmware/app

using namespace curvestep;
using namespace curvestep::firmware;
using namespace curvestep::protocol;
using curvestep::firmware::testing::FakeBoard;
using curvestep::firmware::testing::Host;
using curvestep::firmware::testing::JobUpload;

namespace {

using F1App = App<FakeBoard, Q16_16, 16, 8>;      // boards/stm32f1: 16 slots, look-ahead 8
using WindowApp = App<FakeBoard, Q16_16, 17, 9>;  // the smallest queue that keeps a window of 9

constexpr std::int32_t q(double mm) { return static_cast<std::int32_t>(mm * 65536.0); }

MachineConfiguration machine() {
  MachineConfiguration c;
  c.axis_count = 3;
  c.max_velocity_mm_per_s = 100;  // protocol version 2: limits travel as binary64
  c.max_acceleration_mm_per_s2 = 1000;
  c.max_jerk_mm_per_s3 = 10000;
  c.default_feed_mm_per_s = q(100);
  c.tolerance_mm = 0.01;
  c.junction_deviation_mm = 0.05;
  c.max_step_rate_hz = 100000;
  c.control_rate_hz = 1000;
  for (auto& axis : c.axes) {
    axis.steps_per_mm = 80;
    axis.min_position_mm = q(-100);
    axis.max_position_mm = q(100);
  }
  return c;
}

WirePoint p(double x, double y, double z = 0) { return WirePoint{q(x), q(y), q(z)}; }

QueueSegment line(WirePoint a, WirePoint b) {
  QueueSegment s;
  s.kind = protocol::SegmentKind::Line;
  s.axis_count = 3;
  s.points[0] = a;
  s.points[1] = b;
  return s;
}

QueueSegment cubic(WirePoint a, WirePoint b, WirePoint c, WirePoint d) {
  QueueSegment s;
  s.kind = protocol::SegmentKind::Bezier;
  s.axis_count = 3;
  s.degree = 3;
  s.points[0] = a;
  s.points[1] = b;
  s.points[2] = c;
  s.points[3] = d;
  return s;
}

/// 40 collinear lines of 0.8 mm: the braking distance from 100 mm/s (v²/2a + va/2j = 10 mm) is
/// longer than 9 segments and shorter than 16, so the window decides the cruise speed. (Segments
/// much shorter drain the 16-slot queue faster than this link refills it: the device's window
/// then shrinks and its stream is no longer the simulator's, whatever the window.)
std::vector<QueueSegment> short_lines() {
  std::vector<QueueSegment> job;
  for (int k = 0; k < 40; ++k) job.push_back(line(p(0.8 * k, 0), p(0.8 * (k + 1), 0)));
  job.back().end_of_job = true;
  return job;
}

/// Short lines and flat Béziers, a cusp loop (several queue slots), an arc and a line back.
std::vector<QueueSegment> mixed_short() {
  std::vector<QueueSegment> job;
  double x = 0;
  for (int k = 0; k < 8; ++k) {
    job.push_back(line(p(x, 0), p(x + 0.8, 0)));
    job.push_back(cubic(p(x + 0.8, 0), p(x + 1.1, 0), p(x + 1.3, 0.002), p(x + 1.6, 0.002)));
    job.push_back(line(p(x + 1.6, 0.002), p(x + 2.4, 0)));
    x += 2.4;
  }
  job.push_back(cubic(p(x, 0), p(x + 3, 3), p(x, 3), p(x + 3, 0)));  // cusp
  x += 3;
  QueueSegment arc;
  arc.kind = protocol::SegmentKind::Arc;
  arc.axis_count = 3;
  arc.degree = 2;
  arc.points[0] = p(x, 0);
  arc.points[1] = p(x, 4);
  arc.points[2] = p(x, 2);
  arc.direction = ArcDirection::CounterClockwise;
  job.push_back(arc);
  job.push_back(line(p(x, 4), p(0, 4)));
  job.back().end_of_job = true;
  return job;
}

/// The same job as the simulator loads it: the firmware's own conversion of each wire segment.
host::Job to_host_job(const std::vector<QueueSegment>& wire) {
  host::Job job;
  job.name = "wire";
  for (const auto& s : wire) {
    const auto segment = to_path_segment(s);
    REQUIRE(segment.has_value());
    job.segments.push_back(segment.value());
  }
  return job;
}

using RawStream = std::vector<std::pair<std::uint32_t, WirePoint>>;

RawStream simulated(const std::vector<QueueSegment>& wire, std::size_t lookahead) {
  host::SimulationOptions options;
  options.lookahead = lookahead;
  const auto result = host::simulate(to_host_job(wire), to_machine_limits(machine()).value(), options);
  RawStream out;
  for (std::size_t i = 0; i < result.setpoints.size(); ++i) {
    const auto& raw = result.setpoints[i].raw_q16;
    out.emplace_back(static_cast<std::uint32_t>(i), WirePoint{raw[0], raw[1], raw[2]});
  }
  return out;
}

/// An independent reference: MotionController<Q16_16, 16, 9>, fed whenever there is room.
RawStream controller_16_9(const std::vector<QueueSegment>& wire) {
  MotionController<Q16_16, 16, 9> c;
  REQUIRE(c.configure(to_machine_limits(machine()).value()).has_value());
  std::size_t next = 0;
  const auto fill = [&] {
    while (next < wire.size() && !c.queue_full()) {
      const auto pushed = c.try_push(to_path_segment(wire[next]).value(), static_cast<std::uint32_t>(next));
      if (!pushed && pushed.error() == Error::QueueFull) return;
      REQUIRE(pushed.has_value());
      ++next;
    }
    if (next == wire.size()) c.end_of_job();
  };
  fill();
  REQUIRE(c.start().has_value());
  RawStream out;
  while (!c.finished()) {
    const auto sp = c.next_setpoint();
    REQUIRE(sp.has_value());
    out.emplace_back(static_cast<std::uint32_t>(sp.value().tick),
                     WirePoint{sp.value().position[0].raw(), sp.value().position[1].raw(), sp.value().position[2].raw()});
    fill();
  }
  return out;
}

/// Streams the job to an AppType over the FakeBoard link (as tests/firmware/app does), one
/// submission attempt per tick, until the App is idle again; returns the setpoints received.
template <class AppType>
RawStream streamed(const std::vector<QueueSegment>& job) {
  FakeBoard board;
  AppType app(board);
  Host<AppType> host(board, app);
  REQUIRE(host.connect());
  REQUIRE(host.send(Message(machine())));
  JobUpload upload(job);
  bool done = false;
  for (int t = 0; t < 200000 && !done; ++t) {
    REQUIRE(upload.step(host.sender(), t));
    app.on_tick();
    ++board.clock_ms;
    host.pump();
    done = upload.all_sent() && !app.moving() && app.state() == MachineState::Idle && host.sender().idle();
  }
  REQUIRE(done);
  REQUIRE(host.received.errors.empty());
  CHECK(app.statistics().dropped_setpoints == 0);
  return host.setpoints();
}

}  // namespace

TEST_CASE("sim lookahead: simulate with lookahead 9 equals a firmware App with Lookahead 9 (Queue 17) bit for bit",
          "[host_tools][sim][lookahead]") {
  STATIC_REQUIRE(WindowApp::Controller::lookahead == 9);
  const std::vector<std::vector<QueueSegment>> jobs{short_lines(), mixed_short()};
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    INFO("job " << j);
    const auto& job = jobs[j];
    const RawStream device = streamed<WindowApp>(job);
    const RawStream sim9 = simulated(job, 9);
    REQUIRE(device.size() == sim9.size());
    std::size_t mismatches = 0;
    for (std::size_t i = 0; i < device.size(); ++i) {
      if (device[i] != sim9[i]) ++mismatches;
    }
    CHECK(mismatches == 0);
    // An independent second instantiation agrees too.
    const bool reference_agrees = controller_16_9(job) == sim9;
    CHECK(reference_agrees);
    // On the lines, the default window (16) and a window of 8 plan differently: the comparison is
    // not vacuous. (On the mixed job the curves and the cusp limit the speed more than the window;
    // it checks the slot counting of the cusp pieces and the other kinds.)
    if (j == 0) {
      const bool differs_16 = simulated(job, 16) != device;
      const bool differs_8 = simulated(job, 8) != device;
      CHECK(differs_16);
      CHECK(differs_8);
    }
  }
}

// The STM32F1's App<_, _, 16, 8> keeps at most 10 segments queued (credit = free slots / 7), so a
// segment is planned with 8 segments behind it: exactly the simulator's --lookahead 8. (With
// Lookahead 9 it planned the first segment with 9 and the rest with 8, matching neither; App now
// refuses that combination at compile time.)
TEST_CASE("sim lookahead: the STM32F1's App with Queue 16 / Lookahead 8 equals simulate with lookahead 8",
          "[host_tools][sim][lookahead]") {
  STATIC_REQUIRE(F1App::Controller::lookahead == 8);
  const auto job = short_lines();
  const bool same = streamed<F1App>(job) == simulated(job, 8);
  CHECK(same);
  const bool differs_9 = streamed<F1App>(job) != simulated(job, 9);
  CHECK(differs_9);
}

TEST_CASE("sim lookahead: the default window is 16 and out-of-range windows are refused with one line",
          "[host_tools][sim][lookahead]") {
  STATIC_REQUIRE(host::SimulationOptions::max_lookahead == 16);
  CHECK(host::SimulationOptions{}.lookahead == 16);
  const bool same = simulated(short_lines(), 16) == simulated(short_lines(), host::SimulationOptions{}.lookahead);
  CHECK(same);
  for (const std::size_t bad : {std::size_t{0}, std::size_t{17}, std::size_t{1000}}) {
    host::SimulationOptions options;
    options.lookahead = bad;
    try {
      (void)host::simulate(to_host_job(short_lines()), to_machine_limits(machine()).value(), options);
      FAIL("accepted lookahead " << bad);
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      CHECK(what.find("lookahead") != std::string::npos);
      CHECK(what.find("between 1 and 16") != std::string::npos);
      CHECK(what.find('\n') == std::string::npos);
    }
  }
}
