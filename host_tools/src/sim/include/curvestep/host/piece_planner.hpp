// SPDX-License-Identifier: MIT
// PiecePlanner: a job planned on the host, piece by piece as they are asked for, for a controller
// without a planner (Capabilities::lookahead 0), which replays the PlannedPieces (PieceExecutor).
//
// It keeps the simulator's Q16.16 MotionController (the one simulate() runs, in a LockstepRun)
// alive and records its setpoints into pieces (PieceRecorder) only as far as next_piece() needs:
// memory stays independent of the job's length, and the operator can still change the plan.
// hold(), resume() and set_override() act on that controller between two setpoints, before setpoint
// tick(): every piece handed out so far covers setpoints before it and runs as planned. They enter
// the run as the events `curvestep sim` takes (FeedHoldEvent, FeedOverrideEvent), so the pieces
// replay to simulate()'s setpoints with the same events bit for bit:
//   * hold() at tick T: the next pieces brake to rest (the last one is handed over at once); then
//     next_piece() gives none until resume(). The executor stands between them without ticking,
//     so the hold is `sim --hold-at T:0` (FeedHoldEvent{T, 0}): no standing setpoints;
//   * set_override(v) at tick T: `sim --override-at T:F:R` (FeedOverrideEvent{T, v}).
// plan_pieces() is next_piece() until none is left.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include <curvestep/core/motion/feed_override.hpp>
#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/core/motion/planned_piece.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/readable_job.hpp>
#include <curvestep/host/simulator.hpp>

namespace curvestep::host {

/// On-demand planning of `job` into pieces (see the header comment).
class PiecePlanner {
 public:
  /// Plans `job` on `machine` with options.lookahead, options.lookahead_distance_mm and
  /// options.overrides (options.holds are not used). The job and machine must outlive it. Throws
  /// what simulate() throws for an invalid request.
  PiecePlanner(const Job& job, const MachineLimits& machine, const SimulationOptions& options);
  /// The same for a job read rather than held (its segments pulled from one job.read() as the
  /// planning needs them); the outline and machine must outlive it.
  PiecePlanner(const ReadableJob& job, const MachineLimits& machine, const SimulationOptions& options);
  ~PiecePlanner();
  PiecePlanner(const PiecePlanner&) = delete;
  PiecePlanner& operator=(const PiecePlanner&) = delete;

  /// The next piece, planned now. None while the controller stands in a hold (held(): after the
  /// braking's pieces, until resume()) and after the job's last piece (end_of_job; done()).
  /// Throws std::runtime_error as simulate() does if the controller refuses a segment or faults.
  [[nodiscard]] std::optional<PlannedPiece> next_piece();

  /// The index of the next setpoint the controller makes: the pieces handed out cover setpoints
  /// before it (the piece being recorded may cover some more); a hold or override now acts here.
  [[nodiscard]] std::uint64_t tick() const noexcept;
  /// True once the job's last piece has been handed out.
  [[nodiscard]] bool done() const noexcept;
  /// True if hold() may be called: the controller is moving along the job (it has begun, is
  /// neither holding nor braking from a hold, and has not planned the job's end).
  [[nodiscard]] bool can_hold() const noexcept;
  /// True while it stands in a hold with the braking's pieces all handed out (next_piece() gives none).
  [[nodiscard]] bool held() const noexcept;

  /// A feed hold before setpoint tick() (requires can_hold()); returns that tick (sim --hold-at T = tick / rate).
  std::uint64_t hold();
  /// Ends the hold: the controller resumes as soon as it stands (at once if it does), without a
  /// standing setpoint. Nothing without a hold.
  void resume();
  /// A feed and rapid override before setpoint tick() (std::runtime_error outside FeedOverride's
  /// ranges); returns that tick. The controller takes it at its next point of zero acceleration.
  std::uint64_t set_override(FeedOverride value);

 private:
  struct Run;
  std::unique_ptr<Run> run_;
};

}  // namespace curvestep::host
