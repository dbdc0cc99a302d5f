// SPDX-License-Identifier: MIT
// PieceExecutor: the setpoints of a job planned elsewhere, for a controller without a planner
// (the STM32F1 executor image). It queues PlannedPieces (planned_piece.hpp) and replays them one
// tick at a time: an exact piece is its end point, a chunk steps HermiteChunk from the previous
// setpoint's unrounded position and ends on its end point, a rest piece repeats its end point. The pieces a PieceRecorder took from a
// MotionController give that controller's setpoints bit for bit (the same HermiteChunk code on the
// same doubles, the same rounding to S); no curve, profile or look-ahead code is linked.
//
// It has the MotionController's interface where a firmware App uses one (configure, start, abort,
// reset, next_setpoint, state, fault, queued), with these differences:
//   * the queue holds pieces, not segments; the job's first piece must be exact (one tick or an
//     exact run): a chunk needs the setpoint before it; the job ends with the piece flagged
//     end_of_job (there is no end_of_job() call);
//   * it cannot brake: hold() is refused (NotSupported) and an empty queue before the job's last
//     piece is a fault (QueueUnderrun), an immediate stop, not a controlled one. The host keeps
//     the queue filled (docs/firmware.md, "Executing host-planned motion");
//   * Setpoint::speed_mm_per_s is 0 (the planned speed stays on the host).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include <curvestep/core/container/ring_buffer.hpp>
#include <curvestep/core/motion/hermite_chunk.hpp>
#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/core/motion/controller_state.hpp>
#include <curvestep/core/motion/planned_piece.hpp>
#include <curvestep/core/motion/setpoint.hpp>
#include <curvestep/core/result.hpp>
#include <curvestep/core/scalar.hpp>

namespace curvestep {

/// Queue and replay of planned pieces; S is the position scalar of the setpoints.
template <Scalar S, std::size_t Capacity = 16>
class PieceExecutor {
  static_assert(Capacity >= 1, "the queue needs a slot");

 public:
  /// Checks the machine (MachineLimits::validate: InvalidLimit, InvalidRate); InvalidState while moving.
  [[nodiscard]] Result<void> configure(const MachineLimits& machine) noexcept {
    if (!stopped()) return fail(Error::InvalidState);
    CURVESTEP_CHECK(machine.validate());
    configured_ = true;
    return ok();
  }

  /// Queues a piece. ConfigurationMissing before configure; InvalidState after the job's last
  /// piece, an abort or a fault; QueueFull; InvalidArgument with index 2 (the byte offset of
  /// QueuePiece's ticks, the field at fault) for ticks that are not 1 or a power of two up to
  /// HermiteChunk::max_ticks (an exact run: not 2..max_exact_run; a rest: not 1..max_rest_ticks)
  /// and for a chunk as the job's first piece;
  /// NotFinite for a NaN or infinite coordinate. A refused piece leaves the queue unchanged.
  [[nodiscard]] Result<void> push(const PlannedPiece& piece) noexcept {
    if (!configured_) return fail(Error::ConfigurationMissing, piece.segment);
    if (end_of_job_ || state_ == ControllerState::Aborted || state_ == ControllerState::Fault) {
      return fail(Error::InvalidState, piece.segment);
    }
    if (queue_.full()) return fail(Error::QueueFull, piece.segment);
    constexpr std::uint16_t ticks_field = 2;  // QueuePiece's byte offset of ticks (docs/protocol.md)
    if (!valid_piece_ticks(piece.ticks, piece.exact_run, piece.rest)) return fail(Error::InvalidArgument, ticks_field);
    if (is_chunk(piece) && first_of_job()) return fail(Error::InvalidArgument, ticks_field);
    if (!finite(piece)) return fail(Error::NotFinite, piece.segment);
    [[maybe_unused]] const bool pushed = queue_.try_push(piece);  // room checked above
    if (piece.end_of_job) end_of_job_ = true;
    return ok();
  }

  /// Starts replaying the queue. ConfigurationMissing, InvalidState (not idle), NothingQueued.
  [[nodiscard]] Result<void> start() noexcept {
    if (!configured_) return fail(Error::ConfigurationMissing);
    if (state_ != ControllerState::Idle) return fail(Error::InvalidState);
    if (queue_.empty()) return fail(Error::NothingQueued);
    tick_ = 0;
    stepped_left_ = 0;
    end_pending_ = false;
    state_ = ControllerState::Running;
    return ok();
  }

  /// A feed hold needs a plan to brake along: not possible here (NotSupported, state unchanged).
  [[nodiscard]] Result<void> hold() noexcept { return fail(Error::NotSupported); }
  /// Nothing to resume (see hold): InvalidState.
  [[nodiscard]] Result<void> resume() noexcept { return fail(Error::InvalidState); }

  /// Stops at once and flushes the queue.
  void abort() noexcept {
    queue_.clear();
    stepped_left_ = 0;
    end_pending_ = false;
    state_ = ControllerState::Aborted;
  }

  /// Back to Idle after Finished or Aborted (configuration kept); the next job starts afresh.
  void reset() noexcept {
    queue_.clear();
    state_ = ControllerState::Idle;
    end_of_job_ = false;
    tick_ = 0;
    stepped_left_ = 0;
    end_pending_ = false;
  }

  /// The next setpoint. InvalidState unless running; QueueUnderrun (a fault) if the queue ran
  /// dry before the job's last piece; OutOfRange (a fault) for a position S cannot hold.
  [[nodiscard]] Result<Setpoint<S>> next_setpoint() noexcept {
    if (state_ != ControllerState::Running) return fail(Error::InvalidState);
    // The piece being replayed stays at the queue's front until its end point is out.
    if (!end_pending_) {
      if (queue_.empty()) return fault(fail(Error::QueueUnderrun, last_segment_));
      const PlannedPiece& piece = queue_.front();
      if (is_chunk(piece)) {
        if (auto started = chunk_.start(last_position_, chunk_controls(piece), piece.ticks); !started) {
          return fault(fail(started.error(), piece.segment));
        }
      }
      stepped_left_ = piece.ticks - 1;
      end_pending_ = true;
    }
    const PlannedPiece& piece = queue_.front();
    last_segment_ = piece.segment;
    if (stepped_left_ > 0) {
      --stepped_left_;
      if (piece.exact_run) return emit(piece.controls[piece.ticks - 2 - stepped_left_]);
      if (piece.rest) return emit(piece.end);
      return emit(chunk_.next());
    }
    auto setpoint = emit(piece.end);
    if (!setpoint) return setpoint;
    end_pending_ = false;
    const bool last = piece.end_of_job;
    queue_.pop_front();
    if (last) state_ = ControllerState::Finished;
    return setpoint;
  }

  [[nodiscard]] ControllerState state() const noexcept { return state_; }
  [[nodiscard]] bool finished() const noexcept { return state_ == ControllerState::Finished; }
  /// The error that put the executor into Fault.
  [[nodiscard]] Failure fault() const noexcept { return fault_; }
  /// Pieces queued, the one being replayed included.
  [[nodiscard]] std::size_t queued() const noexcept { return queue_.size(); }
  [[nodiscard]] static constexpr std::size_t queue_capacity() noexcept { return Capacity; }
  [[nodiscard]] bool queue_full() const noexcept { return queue_.full(); }
  [[nodiscard]] std::uint64_t tick() const noexcept { return tick_; }
  /// True if the next setpoint needs no piece beyond those queued (the piece being replayed stays
  /// at the queue's front until its end point is out, so a queued piece is all it takes).
  [[nodiscard]] bool can_step() const noexcept { return !queue_.empty(); }

 private:
  [[nodiscard]] bool stopped() const noexcept { return state_ != ControllerState::Running; }

  /// True if a piece pushed now would be the job's first.
  [[nodiscard]] bool first_of_job() const noexcept { return state_ != ControllerState::Running && queue_.empty(); }

  [[nodiscard]] static bool finite(const PlannedPiece& piece) noexcept {
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      if (!std::isfinite(piece.end[axis])) return false;
      for (const MachinePoint& q : piece.controls) {
        if (!std::isfinite(q[axis])) return false;
      }
    }
    return true;
  }

  [[nodiscard]] Result<Setpoint<S>> emit(const MachinePoint& p) noexcept {
    auto sp = make_setpoint<S>(p, tick_, 0, last_segment_);
    if (!sp) return fault(sp.failure());
    last_position_ = p;
    ++tick_;
    return sp;
  }

  [[nodiscard]] Failure fault(Failure f) noexcept {
    fault_ = f;
    state_ = ControllerState::Fault;
    return f;
  }

  RingBuffer<PlannedPiece, Capacity> queue_{};
  HermiteChunk chunk_{};
  MachinePoint last_position_{};
  Failure fault_{Error::InvalidState, no_index};
  std::uint64_t tick_ = 0;
  std::uint32_t stepped_left_ = 0;
  std::uint32_t last_segment_ = 0;  ///< segment of the piece being replayed (setpoints, faults)
  ControllerState state_ = ControllerState::Idle;
  bool configured_ = false;
  bool end_of_job_ = false;
  bool end_pending_ = false;
};

}  // namespace curvestep
