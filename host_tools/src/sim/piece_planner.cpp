// SPDX-License-Identifier: MIT
#include <curvestep/host/piece_planner.hpp>

#include <deque>
#include <stdexcept>
#include <string>
#include <tuple>

#include <curvestep/core/motion/piece_recorder.hpp>

#include "lockstep_run.hpp"

namespace curvestep::host {

struct PiecePlanner::Run {
  Run(const ReadableJob& job, const MachineLimits& machine, const SimulationOptions& options)
      : run(job.outline->name, job.segments, joint_stops(job.outline->events, job.segments, job.outline->name, machine.rate_hz), job.read(),
            machine, options) {}

  /// Plans until a piece is ready, the job's last one was recorded, or the controller stands in a hold.
  void plan_until_piece() {
    const auto keep = [this](const PlannedPiece& piece) { ready.push_back(piece); };
    if (!begun) {
      begun = true;
      if (!run.begin()) finished = true;  // no segments: no pieces
    }
    while (ready.empty() && !finished && !stands_held()) {
      if (run.finished()) {
        recorder.finish(keep);
        finished = true;
        break;
      }
      run.prepare();
      recorder.revise(run.lead());  // a hold just applied may abandon the chunk begun at the last setpoint
      const auto setpoints = run.tick();
      recorder.record(run.lead(), std::get<0>(setpoints), keep);
      if (stands_held()) recorder.flush(keep);  // the braking's last piece: the executor comes to rest at its end
    }
  }

  [[nodiscard]] bool stands_held() const { return holding && run.lead().state() == ControllerState::Held; }

  detail::LockstepRun<detail::FixedController> run;
  PieceRecorder recorder;
  std::deque<PlannedPiece> ready;  // recorded, not yet handed out
  bool begun = false;
  bool finished = false;  // the job's last piece was recorded
  bool holding = false;   // hold() without resume()
};

PiecePlanner::PiecePlanner(const Job& job, const MachineLimits& machine, const SimulationOptions& options)
    : PiecePlanner(readable(job), machine, options) {}

PiecePlanner::PiecePlanner(const ReadableJob& job, const MachineLimits& machine, const SimulationOptions& options) {
  detail::check_request(machine, options);
  run_ = std::make_unique<Run>(job, machine, options);
}

PiecePlanner::~PiecePlanner() = default;

std::optional<PlannedPiece> PiecePlanner::next_piece() {
  if (run_->ready.empty()) run_->plan_until_piece();
  if (run_->ready.empty()) return std::nullopt;
  const PlannedPiece piece = run_->ready.front();
  run_->ready.pop_front();
  return piece;
}

std::uint64_t PiecePlanner::tick() const noexcept { return run_->run.lead().tick(); }

bool PiecePlanner::done() const noexcept { return run_->finished && run_->ready.empty(); }

bool PiecePlanner::can_hold() const noexcept {
  return run_->begun && !run_->finished && !run_->holding && tick() > 0 && run_->run.lead().state() == ControllerState::Running;
}

bool PiecePlanner::held() const noexcept { return run_->stands_held() && run_->ready.empty(); }

std::uint64_t PiecePlanner::hold() {
  if (!can_hold()) throw std::logic_error("PiecePlanner::hold: the controller is not moving along the job");
  run_->run.add_hold(FeedHoldEvent{tick(), 0});
  run_->holding = true;
  return tick();
}

void PiecePlanner::resume() { run_->holding = false; }

std::uint64_t PiecePlanner::set_override(FeedOverride value) {
  if (!value.valid()) {
    throw std::runtime_error("feed override " + std::to_string(value.feed_percent) + " %, rapid " + std::to_string(value.rapid_percent) +
                             " %: " + override_range_text());
  }
  run_->run.add_override(FeedOverrideEvent{tick(), value});
  return tick();
}

}  // namespace curvestep::host
