// SPDX-License-Identifier: MIT
// stream_job against a firmware App in this process (in_process_device.hpp): the real upload loop,
// link and App, without a pseudo-terminal. The reference is the simulator: the captured setpoints
// equal simulate()'s raw Q16.16 stream with the device's window, bit for bit.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/firmware/app.hpp>
#include <curvestep/host/csv.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/link/streamer.hpp>
#include <curvestep/host/link/wire.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/simulator.hpp>

#include "in_process_device.hpp"

using namespace curvestep;
namespace hl = curvestep::host::link;

namespace {

const std::filesystem::path examples = CURVESTEP_EXAMPLE_JOBS;

/// Same number of setpoints, the same raw Q16.16 positions at the same index.
void require_same_setpoints(const std::vector<host::SetpointRecord>& got, const std::vector<host::SetpointRecord>& expected) {
  REQUIRE(got.size() == expected.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    const bool same = got[i].raw_q16 == expected[i].raw_q16 && got[i].time_s == expected[i].time_s;
    if (!same && differing++ == 0) {
      INFO("first difference at setpoint " << i);
      CHECK(same);
    }
  }
  CHECK(differing == 0);
}

}  // namespace

namespace {

/// seed_cubic.json streamed to a planning App with look-ahead 9, and what curvestep sim
/// --lookahead 9 makes of the job as the device sees it.
struct WindowNineRun {
  hl::StreamResult result;
  std::vector<host::SetpointRecord> expected;
};

WindowNineRun stream_to_window_nine(const hl::StreamOptions& options) {
  using WindowApp = firmware::App<firmware::testing::FakeBoard, Q16_16, 17, 9>;
  const auto machine = host::load_machine(examples / "machine.json");
  const auto job = host::load_job(examples / "seed_cubic.json");
  hl::testing::InProcessDevice<WindowApp> device;
  WindowNineRun run{hl::stream_job(device, job, machine, options), {}};
  host::SimulationOptions nine;
  nine.lookahead = 9;
  const auto [device_job, device_machine] = hl::as_device_sees(job, machine);
  run.expected = host::simulate(device_job, device_machine, nine).setpoints;
  return run;
}

}  // namespace

TEST_CASE("stream in process: a planning App with look-ahead 9 streams curvestep sim --lookahead 9 bit for bit",
          "[host_tools][stream]") {
  std::vector<std::string> warnings;
  hl::StreamOptions options;
  options.warn = [&warnings](const std::string& text) { warnings.push_back(text); };
  const WindowNineRun run = stream_to_window_nine(options);
  CHECK(warnings.empty());
  CHECK(run.result.lookahead == 9);
  CHECK(run.result.pieces_sent == 0);
  CHECK(run.result.standing_ticks == 0);
  require_same_setpoints(run.result.setpoints, run.expected);
}

namespace {

/// The executor App of the STM32F1 image's size: 16 pieces, no planner.
using ExecutorApp = firmware::App<firmware::testing::FakeBoard, Q16_16, 16, 0>;

}  // namespace

TEST_CASE("stream in process: an App without a planner replays the pieces planned here as curvestep sim bit for bit",
          "[host_tools][stream][pieces]") {
  // The example machine with 4 steps/mm: at 80 the App refuses every_type.json's segment 8
  // (StepRateTooHigh, a planning App on this fake board alike). Steps per mm do not change the
  // planned setpoints.
  auto machine = host::load_machine(examples / "machine.json");
  for (auto& axis : machine.axes) axis.steps_per_mm = 4;
  std::size_t jobs = 0;
  for (const auto& entry : std::filesystem::directory_iterator(examples)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "machine.json") continue;
    INFO(entry.path().filename().string());
    const auto job = host::load_job(entry.path());
    hl::testing::InProcessDevice<ExecutorApp> device;
    std::vector<hl::StreamProgress> progress;
    hl::StreamOptions options;
    options.progress = [&progress](const hl::StreamProgress& p) { progress.push_back(p); };
    const hl::StreamResult result = hl::stream_job(device, job, machine, options);
    CHECK(result.lookahead == 0);
    CHECK(result.planned_lookahead == host::SimulationOptions::max_lookahead);
    CHECK(result.pieces_sent == host::plan_pieces(job, machine).size());
    CHECK(result.standing_ticks == 0);
    CHECK(result.duplicate_setpoints == 0);
    REQUIRE_FALSE(progress.empty());
    CHECK(std::string(progress.back().unit) == "pieces");
    CHECK(progress.back().sent == result.pieces_sent);
    CHECK(progress.back().total == result.pieces_sent);
    // The reference: the simulator on the job and machine as loaded (nothing is rounded for the
    // wire: the pieces travel as binary64).
    require_same_setpoints(result.setpoints, host::simulate(job, machine).setpoints);
    CHECK(device.app().statistics().dropped_setpoints == 0);
    ++jobs;
  }
  CHECK(jobs >= 4);
}

TEST_CASE("stream in process: the window the pieces are planned with is StreamOptions::lookahead",
          "[host_tools][stream][pieces]") {
  // 40 collinear lines of 0.25 mm at 50 mm/s: braking takes about 1.6 mm, so a window of 1
  // segment plans slower than the default 16 (checked on the simulator first).
  const auto machine = host::load_machine(examples / "machine.json");
  host::Job job;
  job.name = "short lines";
  for (int k = 0; k < 40; ++k) {
    const auto line = PathSegment::make_line(MachinePoint{0.25 * k, 0, 0}, MachinePoint{0.25 * (k + 1), 0, 0});
    REQUIRE(line.has_value());
    job.segments.push_back(line.value());
  }
  host::SimulationOptions one;
  one.lookahead = 1;
  const auto narrow = host::simulate(job, machine, one).setpoints;
  REQUIRE(narrow.size() != host::simulate(job, machine).setpoints.size());
  hl::testing::InProcessDevice<ExecutorApp> device;
  hl::StreamOptions options;
  options.lookahead = 1;
  const hl::StreamResult result = hl::stream_job(device, job, machine, options);
  CHECK(result.planned_lookahead == 1);
  require_same_setpoints(result.setpoints, narrow);
}

TEST_CASE("stream in process: a window outside 1..16 for a controller without a planner is refused with one line",
          "[host_tools][stream][pieces]") {
  const auto machine = host::load_machine(examples / "machine.json");
  const auto job = host::load_job(examples / "seed_cubic.json");
  hl::testing::InProcessDevice<ExecutorApp> device;
  hl::StreamOptions options;
  options.lookahead = 17;
  try {
    (void)hl::stream_job(device, job, machine, options);
    FAIL("accepted look-ahead 17");
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    CHECK(what.find("between 1 and 16") != std::string::npos);
    CHECK(what.find('\n') == std::string::npos);
  }
}

TEST_CASE("stream in process: the machine file's travel reaches the controller, which refuses a segment beyond it",
          "[host_tools][stream][travel]") {
  using WindowApp = firmware::App<firmware::testing::FakeBoard, Q16_16, 17, 9>;
  const auto machine = host::load_machine(examples / "machine.json");
  const auto job = host::load_job(examples / "seed_cubic.json");
  double high_x = 0;
  for (const auto& s : job.segments) high_x = std::max({high_x, s.start()[0], s.end()[0]});
  REQUIRE(high_x > 2);
  hl::StreamOptions options;
  options.travel[0] = host::AxisTravel{-1.0, 1.0};  // far less than the job needs: the device must refuse
  hl::testing::InProcessDevice<WindowApp> device;
  try {
    (void)hl::stream_job(device, job, machine, options);
    FAIL("the controller ran a job beyond its travel");
  } catch (const hl::StreamError& e) {
    INFO(e.what());
    CHECK(e.code() == Error::OutsideTravel);
  }
  // With the travel the job needs, it runs.
  options.travel[0] = host::AxisTravel{-1.0, high_x + 1.0};
  hl::testing::InProcessDevice<WindowApp> roomy;
  const hl::StreamResult result = hl::stream_job(roomy, job, machine, options);
  CHECK_FALSE(result.setpoints.empty());
}

TEST_CASE("stream in process: with a setpoint sink the setpoints arrive there in order, bit for bit as curvestep sim, and none is kept",
          "[host_tools][stream][capture]") {
  // What `stream --capture` does to keep memory independent of the job's length (issue 19.7).
  std::vector<host::SetpointRecord> sunk;
  hl::StreamOptions options;
  options.setpoint_sink = [&sunk](const host::SetpointRecord& r) { sunk.push_back(r); };
  const WindowNineRun run = stream_to_window_nine(options);
  CHECK(run.result.setpoints.empty());
  CHECK(run.result.setpoints_received == sunk.size());
  CHECK(run.result.duplicate_setpoints == 0);
  CHECK(run.result.standing_ticks == 0);
  require_same_setpoints(sunk, run.expected);
}

TEST_CASE("stream in process: the start override reaches a planning App and is planned into an executor's pieces, as sim replays it",
          "[host_tools][stream][override]") {
  const auto machine = host::load_machine(examples / "machine.json");
  const auto job = host::load_job(examples / "inch_square.json");
  hl::StreamOptions options;
  options.feed_override = FeedOverride{60, 50};
  host::SimulationOptions replay;
  replay.overrides = {{0, FeedOverride{60, 50}}};
  {
    using PlanningApp = firmware::App<firmware::testing::FakeBoard, Q16_16, 32, 16>;
    hl::testing::InProcessDevice<PlanningApp> device;
    const hl::StreamResult result = hl::stream_job(device, job, machine, options);
    REQUIRE(result.overrides.size() == 1);
    CHECK(result.overrides[0].tick == 0);
    CHECK(result.overrides[0].value == FeedOverride{60, 50});
    CHECK(hl::override_at_option(result.overrides, 1000) == "--override-at 0:60:50");
    replay.lookahead = 16;
    const auto [device_job, device_machine] = hl::as_device_sees(job, machine);
    const auto expected = host::simulate(device_job, device_machine, replay).setpoints;
    CHECK(expected.size() != host::simulate(device_job, device_machine).setpoints.size());  // the override matters
    require_same_setpoints(result.setpoints, expected);
  }
  {
    hl::testing::InProcessDevice<ExecutorApp> device;
    const hl::StreamResult result = hl::stream_job(device, job, machine, options);
    REQUIRE(result.overrides.size() == 1);
    CHECK(result.overrides[0].value == FeedOverride{60, 50});
    replay.lookahead = host::SimulationOptions::max_lookahead;
    require_same_setpoints(result.setpoints, host::simulate(job, machine, replay).setpoints);
  }
}

TEST_CASE("stream in process: an executor held, resumed and overridden by the operator streams sim --hold-at T:0 --override-at bit for bit",
          "[host_tools][stream][pieces][hold][override]") {
  // The host plans the braking and the override into the pieces; the App stands at the end of the
  // braking (after FeedHold) without a stall fault until Resume, and does not tick meanwhile.
  auto machine = host::load_machine(examples / "machine.json");
  for (auto& axis : machine.axes) axis.steps_per_mm = 4;  // as above: within the fake board's step batch
  const auto job = host::load_job(examples / "helix.json");
  const auto unheld = host::simulate(job, machine).setpoints;
  REQUIRE(unheld.size() > 10000);
  firmware::AppSettings settings;
  settings.stall_timeout_ms = 50;  // standing in the hold is longer: it must not count as a stall
  hl::testing::InProcessDevice<ExecutorApp> device(settings);
  std::vector<host::SetpointRecord> captured;
  int step = 0;
  int polls_standing = 0;
  hl::StreamOptions options;
  options.setpoint_sink = [&captured](const host::SetpointRecord& r) { captured.push_back(r); };
  options.operator_command = [&]() {
    const std::size_t received = captured.size();
    switch (step) {
      case 0:
        if (received < 6000) return hl::OperatorCommand::None;  // past the first queue's worth (see the end)
        step = 1;
        return hl::OperatorCommand::Hold;
      case 1: {
        const bool standing = device.app().state() == protocol::MachineState::Holding && device.app().controller().queued() == 0;
        if (!standing || ++polls_standing < 30) return hl::OperatorCommand::None;
        step = 2;
        return hl::OperatorCommand::Resume;
      }
      case 2:
        if (received < 12000) return hl::OperatorCommand::None;
        step = 3;
        return hl::OperatorCommand::FeedMinus10;
      default: return hl::OperatorCommand::None;
    }
  };
  std::vector<std::string> warnings;
  options.warn = [&warnings](const std::string& text) { warnings.push_back(text); };
  const hl::StreamResult result = hl::stream_job(device, job, machine, options);
  CHECK(warnings.empty());
  CHECK(step == 3);
  CHECK(polls_standing >= 30);  // it stood, longer than the stall timeout in wall-clock time
  REQUIRE(result.holds.size() == 1);
  CHECK(result.holds[0].tick > 0);
  REQUIRE(result.holds[0].standing_ticks.has_value());
  CHECK(*result.holds[0].standing_ticks == 0);
  REQUIRE(result.overrides.size() == 1);
  CHECK(result.overrides[0].value == FeedOverride{90, 100});
  CHECK(result.overrides[0].tick > result.holds[0].tick);
  CHECK(result.standing_ticks == 0);  // no index skipped
  CHECK(device.app().statistics().stalled_ticks == 0);
  host::SimulationOptions replay;
  replay.holds.push_back({result.holds[0].tick, 0});
  replay.overrides.push_back({result.overrides[0].tick, result.overrides[0].value});
  const auto expected = host::simulate(job, machine, replay).setpoints;
  CHECK(expected.size() != unheld.size());  // the hold and the override changed the motion
  require_same_setpoints(captured, expected);
  CHECK(hl::hold_at_option(result.holds, 1000) == "--hold-at " + host::format_number(static_cast<double>(result.holds[0].tick) / 1000.0) + ":0");
  // The in-flight bound (StreamOptions::piece_lead_s): once the device runs, the hold acts at most
  // 500 ticks plus one piece (256) and an exact run (6) after the last setpoint the host knew of
  // when the operator asked: setpoint 5999, or up to ~200 more the device had made and not yet
  // delivered. (Before it starts, the device takes a full queue, 16 pieces of up to 256 ticks.)
  CHECK(result.holds[0].tick <= 6000 + 500 + 262 + 200);
}

TEST_CASE("stream in process: a hold or override key once an executor has the whole rest of the job is answered with a warning and changes nothing",
          "[host_tools][stream][pieces][hold]") {
  const auto machine = host::load_machine(examples / "machine.json");
  // The longest line whose pieces the executor's queue (16) takes all before it starts: its
  // setpoints come in several batches, so the keys are read while it runs.
  host::Job job;
  job.name = "line";
  for (const double length : {20.0, 10.0, 5.0, 2.0, 1.0, 0.5}) {
    const auto line = PathSegment::make_line(MachinePoint{0, 0, 0}, MachinePoint{length, 0, 0});
    REQUIRE(line.has_value());
    job.segments = {line.value()};
    if (host::plan_pieces(job, machine).size() <= 16) break;
  }
  REQUIRE(host::plan_pieces(job, machine).size() <= 16);
  INFO("line of " << job.segments[0].end()[0] << " mm");
  hl::testing::InProcessDevice<ExecutorApp> device;
  std::vector<host::SetpointRecord> captured;
  int step = 0;
  hl::StreamOptions options;
  options.setpoint_sink = [&captured](const host::SetpointRecord& r) { captured.push_back(r); };
  options.operator_command = [&]() {
    if (captured.empty() || step >= 2) return hl::OperatorCommand::None;
    return ++step == 1 ? hl::OperatorCommand::Hold : hl::OperatorCommand::FeedPlus10;
  };
  std::vector<std::string> warnings;
  options.warn = [&warnings](const std::string& text) { warnings.push_back(text); };
  const hl::StreamResult result = hl::stream_job(device, job, machine, options);
  REQUIRE(step == 2);
  REQUIRE(warnings.size() == 2);
  CHECK(warnings[0].find("cannot be held now") != std::string::npos);
  CHECK(warnings[1].find("the override cannot change it now") != std::string::npos);
  CHECK(result.holds.empty());
  CHECK(result.overrides.empty());
  require_same_setpoints(captured, host::simulate(job, machine).setpoints);
}
