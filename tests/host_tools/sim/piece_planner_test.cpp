// SPDX-License-Identifier: MIT
// PiecePlanner: pieces planned on demand for a controller without a planner, with the operator's
// holds and overrides applied at the tick it has planned up to. The reference is the simulator
// (simulate() with the same FeedHoldEvent / FeedOverrideEvent, `curvestep sim --hold-at T:0` /
// `--override-at`): a PieceExecutor<Q16_16, 16> (the executor firmware's replay), fed as its queue
// has room, gives its raw Q16.16 setpoints, indices and segments bit for bit.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/motion/piece_executor.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/piece_planner.hpp>
#include <curvestep/host/simulator.hpp>

using namespace curvestep;

namespace {

const std::filesystem::path examples = std::filesystem::path(CURVESTEP_SOURCE_DIR) / "examples" / "jobs";

/// What the operator does: called after each piece handed to the executor (with their count so far),
/// and with `standing` true when the executor has run dry at the end of a hold's braking.
using Operator = std::function<void(host::PiecePlanner& planner, std::size_t handed, bool standing)>;

/// The executor's setpoints, its 16-piece queue topped up from the planner as a streamer does; a
/// queue that runs dry must be a hold the planner stands in (the operator then resumes it).
std::vector<Setpoint<Q16_16>> replay_on_demand(host::PiecePlanner& planner, const MachineLimits& machine, const Operator& act,
                                               std::vector<PlannedPiece>* pieces = nullptr) {
  PieceExecutor<Q16_16, 16> executor;
  REQUIRE(executor.configure(machine).has_value());
  std::vector<Setpoint<Q16_16>> out;
  std::size_t handed = 0;
  std::uint64_t handed_ticks = 0;
  bool started = false;
  while (!executor.finished() && out.size() < 10000000) {
    while (!executor.queue_full()) {
      const auto piece = planner.next_piece();
      if (!piece) break;
      REQUIRE(executor.push(*piece).has_value());
      if (pieces != nullptr) pieces->push_back(*piece);
      ++handed;
      handed_ticks += piece->ticks;
      CHECK(handed_ticks <= planner.tick());  // a piece is handed out once the controller has passed it
      act(planner, handed, false);
    }
    if (!started) {
      REQUIRE(executor.start().has_value());
      started = true;
    }
    if (!executor.can_step()) {
      REQUIRE(planner.held());  // only a hold stops the pieces before the job's end
      act(planner, handed, true);
      REQUIRE_FALSE(planner.held());
      continue;
    }
    const auto setpoint = executor.next_setpoint();
    REQUIRE(setpoint.has_value());
    out.push_back(setpoint.value());
  }
  CHECK(planner.done());
  CHECK_FALSE(planner.next_piece().has_value());
  return out;
}

/// Every replayed setpoint equals simulate()'s at its index (raw Q16.16, segment), and there are as many.
void require_simulated(const std::vector<Setpoint<Q16_16>>& replayed, const host::SimulationResult& simulated) {
  REQUIRE(replayed.size() == simulated.setpoints.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < replayed.size(); ++i) {
    const auto& expected = simulated.setpoints[i];
    bool same = replayed[i].tick == expected.index && replayed[i].segment == expected.segment;
    for (std::size_t axis = 0; axis < 3; ++axis) same = same && replayed[i].position[axis].raw() == expected.raw_q16[axis];
    if (!same && differing++ == 0) {
      INFO("first difference at setpoint " << i);
      CHECK(same);
    }
  }
  CHECK(differing == 0);
}

std::vector<std::filesystem::path> example_jobs() {
  std::vector<std::filesystem::path> jobs;
  for (const auto& entry : std::filesystem::directory_iterator(examples)) {
    if (entry.path().extension() == ".json" && entry.path().filename() != "machine.json") jobs.push_back(entry.path());
  }
  REQUIRE(jobs.size() >= 4);
  return jobs;
}

const Operator nobody = [](host::PiecePlanner&, std::size_t, bool) {};

}  // namespace

TEST_CASE("piece planner: pieces pulled on demand without events are plan_pieces' and replay to curvestep sim bit for bit",
          "[host_tools][sim][pieces]") {
  const MachineLimits machine = host::load_machine(examples / "machine.json");
  for (const auto& path : example_jobs()) {
    INFO(path.filename().string());
    const host::Job job = host::load_job(path);
    host::SimulationOptions options;
    options.lookahead_distance_mm = host::lookahead_distance_for(machine);  // as `curvestep stream` plans for an executor
    host::PiecePlanner planner(job, machine, options);
    CHECK_FALSE(planner.can_hold());  // nothing planned yet: tick 0
    CHECK(planner.tick() == 0);
    std::vector<PlannedPiece> pieces;
    require_simulated(replay_on_demand(planner, machine, nobody, &pieces), host::simulate(job, machine, options));
    CHECK(pieces == host::plan_pieces(job, machine, options));
    CHECK_FALSE(planner.can_hold());  // done: nothing left to brake
    CHECK_THROWS_AS(planner.hold(), std::logic_error);
  }
}

TEST_CASE("piece planner: a hold after any piece brakes in the next pieces, waits for resume, and replays sim --hold-at T:0 bit for bit",
          "[host_tools][sim][pieces][hold]") {
  const MachineLimits machine = host::load_machine(examples / "machine.json");
  std::size_t holds = 0;
  for (const auto& path : example_jobs()) {
    const host::Job job = host::load_job(path);
    // Pieces 1..40 cover exact ticks, exact runs, chunks begun at the last setpoint (the recorder
    // must drop them: the hold abandons them) and, in dwell-free jobs, segment joints.
    for (std::size_t after = 1; after <= 40; ++after) {
      INFO(path.filename().string() << ", hold after piece " << after);
      host::PiecePlanner planner(job, machine, {});
      std::uint64_t hold_tick = 0;
      bool stood = false;
      const auto replayed = replay_on_demand(planner, machine, [&](host::PiecePlanner& p, std::size_t handed, bool standing) {
        if (standing) {
          CHECK_FALSE(p.can_hold());
          CHECK_FALSE(p.next_piece().has_value());  // none while it stands
          p.resume();
          stood = true;
        } else if (handed == after && p.can_hold()) {
          hold_tick = p.hold();
          CHECK(hold_tick > 0);
          CHECK_FALSE(p.can_hold());  // one hold at a time
        }
      });
      if (hold_tick == 0) continue;  // the job was planned to its end by then
      CHECK(stood);
      host::SimulationOptions held;
      held.holds.push_back({hold_tick, 0});
      const auto simulated = host::simulate(job, machine, held);
      require_simulated(replayed, simulated);
      CHECK(simulated.setpoints.size() > host::simulate(job, machine).setpoints.size());  // braking and starting again take time
      ++holds;
    }
  }
  CHECK(holds >= 100);
}

TEST_CASE("piece planner: overrides set while planning and while standing in a hold replay sim --override-at bit for bit",
          "[host_tools][sim][pieces][override]") {
  const MachineLimits machine = host::load_machine(examples / "machine.json");
  for (const auto& path : example_jobs()) {
    INFO(path.filename().string());
    const host::Job job = host::load_job(path);
    host::SimulationOptions start;
    start.overrides.push_back({0, FeedOverride{150, 100}});  // --feed-override 150
    host::PiecePlanner planner(job, machine, start);
    host::SimulationOptions expected = start;
    bool held = false;
    const auto replayed = replay_on_demand(planner, machine, [&](host::PiecePlanner& p, std::size_t handed, bool standing) {
      if (standing) {
        expected.overrides.push_back({p.set_override(FeedOverride{120, 50}), FeedOverride{120, 50}});  // taken after the resume
        p.resume();
      } else if (handed == 6) {
        expected.overrides.push_back({p.set_override(FeedOverride{60, 100}), FeedOverride{60, 100}});
      } else if (handed == 12 && p.can_hold()) {
        expected.holds.push_back({p.hold(), 0});
        held = true;
      }
    });
    CHECK(expected.overrides.size() == (held ? 3 : 2));
    CHECK(expected.overrides[1].tick > 0);
    require_simulated(replayed, host::simulate(job, machine, expected));
  }
  host::PiecePlanner planner(host::load_job(examples / "seed_cubic.json"), machine, {});
  CHECK_THROWS_AS(planner.set_override(FeedOverride{5, 100}), std::runtime_error);  // outside 10..200 %
}
