// SPDX-License-Identifier: MIT
// PieceRecorder: turns a MotionController's setpoint stream into the PlannedPieces a PieceExecutor
// replays (planned_piece.hpp). Call record() after every next_setpoint() of a job and finish()
// after its last: each exact tick becomes a piece of one tick, each chunk the controller begins a
// piece of its length (its stepped setpoints and its exact end), so the pieces reproduce the
// controller's setpoints bit for bit. Consecutive exact ticks of one segment are merged into
// exact runs of up to max_exact_run ticks, and the ticks of a rest at a joint (the controller's
// resting()) into rest pieces of up to max_rest_ticks. The sink is called with each finished piece, in order;
// the last one (finish) carries end_of_job. A recorder that plans on demand (PiecePlanner, host
// tools) may change the controller's course between two setpoints (a feed hold): revise() then
// forgets a chunk the controller no longer follows, and flush() hands over the braking's last piece.
#pragma once

#include <cstddef>
#include <cstdint>

#include <curvestep/core/motion/planned_piece.hpp>
#include <curvestep/core/motion/setpoint.hpp>

namespace curvestep {

class PieceRecorder {
 public:
  /// Records the setpoint `setpoint` that `controller` (a MotionController) just produced.
  template <class Controller, class S, class Sink>
  void record(const Controller& controller, const Setpoint<S>& setpoint, Sink&& sink) {
    const bool inside_chunk = covered_ && setpoint.tick <= covered_until_;
    if (controller.resting()) {
      if (pending_ && last_.rest && last_.ticks < max_rest_ticks && last_.segment == setpoint.segment) {
        ++last_.ticks;
      } else {
        PlannedPiece rest;
        rest.rest = true;
        rest.end = controller.last_unrounded_position();
        rest.segment = setpoint.segment;
        hand_over(rest, sink);
      }
      return;
    }
    if (!inside_chunk) {
      const bool extends =
          pending_ && !is_chunk(last_) && !last_.rest && last_.ticks < max_exact_run && last_.segment == setpoint.segment;
      if (extends) {
        last_.controls[last_.ticks - 1] = last_.end;  // the run's earlier ticks, in order
        last_.end = controller.last_unrounded_position();
        ++last_.ticks;
        last_.exact_run = true;
      } else {
        PlannedPiece exact;
        exact.end = controller.last_unrounded_position();
        exact.segment = setpoint.segment;
        hand_over(exact, sink);
      }
    }
    if (controller.chunk_begins_at_last_setpoint()) {
      PlannedPiece chunk;
      chunk.ticks = controller.chunk_ticks();
      const auto& q = controller.chunk_controls();  // q[0] is 0 (relative to the last setpoint)
      for (std::size_t i = 0; i < chunk.controls.size(); ++i) chunk.controls[i] = q[i + 1];
      chunk.end = controller.chunk_end_position();
      chunk.segment = setpoint.segment;
      hand_over(chunk, sink);
      covered_ = true;
      covered_until_ = setpoint.tick + chunk.ticks;
    }
  }

  /// Between two setpoints, after something changed the controller's plan (a hold() that abandoned
  /// the chunk it had begun at its last setpoint, MotionController::begin_stop): forgets that
  /// chunk's piece, which was not handed over yet and none of whose setpoints were made. Nothing
  /// otherwise (a chunk it still follows, as after a hold it defers, stays).
  template <class Controller>
  void revise(const Controller& controller) {
    const bool chunk_not_begun = pending_ && is_chunk(last_) && covered_ && covered_until_ + 1 == controller.tick() + last_.ticks;
    if (chunk_not_begun && !controller.chunk_begins_at_last_setpoint()) {
      pending_ = false;
      covered_ = false;
    }
  }

  /// Hands over the piece recorded last now (not marked end_of_job): the controller stands and the
  /// setpoints so far must reach the executor before more are planned (a feed hold planned on the
  /// host). The next setpoint begins a new piece. Nothing if none is pending.
  template <class Sink>
  void flush(Sink&& sink) {
    if (!pending_) return;
    sink(static_cast<const PlannedPiece&>(last_));
    pending_ = false;
  }

  /// The job ended: hands over the last piece, marked end_of_job. Nothing if nothing was recorded.
  template <class Sink>
  void finish(Sink&& sink) {
    if (!pending_) return;
    last_.end_of_job = true;
    sink(static_cast<const PlannedPiece&>(last_));
    pending_ = false;
    covered_ = false;
  }

 private:
  template <class Sink>
  void hand_over(const PlannedPiece& piece, Sink& sink) {
    if (pending_) sink(static_cast<const PlannedPiece&>(last_));
    last_ = piece;
    pending_ = true;
  }

  PlannedPiece last_{};
  std::uint64_t covered_until_ = 0;  ///< the last tick of the latest chunk
  bool covered_ = false;
  bool pending_ = false;
};

}  // namespace curvestep
