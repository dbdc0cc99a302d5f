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
#include "wire_job.hpp"

using namespace curvestep;
using namespace curvestep::firmware;
using namespace curvestep::protocol;
using namespace curvestep::firmware::testing;  // fake_board.hpp: the board, the host, the wire helpers
using curvestep::sim_testing::to_host_job;

namespace {

using F1App = App<FakeBoard, Q16_16, 16, 8>;      // boards/stm32f1: 16 slots, look-ahead 8
using WindowApp = App<FakeBoard, Q16_16, 17, 9>;  // the smallest queue that keeps a window of 9

MachineConfiguration machine() { return curvestep::firmware::testing::machine(100); }

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
  job.push_back(arc(p(x, 0), p(x, 4), p(x, 2), ArcDirection::CounterClockwise));
  job.push_back(line(p(x, 4), p(0, 4)));
  job.back().end_of_job = true;
  return job;
}

using RawStream = curvestep::firmware::testing::Setpoints;

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
  return curvestep::firmware::testing::controller_reference<MotionController<Q16_16, 16, 9>>(machine(), wire);
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
  stream_job(host, app, board, job);
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
    check_same_stream(device, sim9);
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
