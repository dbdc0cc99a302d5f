// SPDX-License-Identifier: MIT
// PlannedPiece: one piece of motion planned ahead (by the host's MotionController) for a controller
// that only executes (PieceExecutor, no planner on board). A job is a run of pieces; each piece
// covers `ticks` consecutive control ticks and ends with the exact setpoint `end`:
//   ticks == 1   one setpoint at `end` (an exactly evaluated tick);
//   ticks == N   (a power of two, 2..HermiteChunk::max_ticks) a chunk: the N - 1 setpoints of the
//                quintic Hermite `controls` (relative to the previous setpoint's unrounded position,
//                stepped by HermiteChunk), then `end`.
// The planner's own stream is exactly this (MotionController::running_tick): its exact ticks and
// its chunks. Replaying the pieces gives its setpoints bit for bit (PieceRecorder records them,
// PieceExecutor replays them; tests/core/motion/piece_executor_test.cpp).
#pragma once

#include <array>
#include <cstdint>

#include <curvestep/core/motion/hermite_chunk.hpp>
#include <curvestep/core/motion/machine_limits.hpp>

namespace curvestep {

/// One planned piece of a job (see the header comment).
struct PlannedPiece {
  std::uint32_t ticks = 1;             ///< control ticks covered: 1 (exact) or a power of two 2..256 (chunk)
  MachinePoint end{};                  ///< unrounded position of the piece's last setpoint (mm)
  /// Chunk only: the Hermite control points q1..q5 relative to the previous setpoint (q0 = 0 is
  /// implied: HermiteChunk::Controls without its first point, 24 bytes less per queued piece).
  std::array<MachinePoint, 5> controls{};
  std::uint32_t segment = 0;           ///< the job segment it belongs to (setpoint.segment, error reports)
  bool end_of_job = false;             ///< the job's last piece

  friend constexpr bool operator==(const PlannedPiece&, const PlannedPiece&) = default;
};

/// The chunk's HermiteChunk control points (q0 = 0, then the piece's q1..q5).
[[nodiscard]] constexpr HermiteChunk::Controls chunk_controls(const PlannedPiece& piece) noexcept {
  HermiteChunk::Controls q{};
  for (std::size_t i = 0; i < piece.controls.size(); ++i) q[i + 1] = piece.controls[i];
  return q;
}

/// True if `ticks` is a valid piece length: 1 or a power of two up to HermiteChunk::max_ticks.
[[nodiscard]] constexpr bool valid_piece_ticks(std::uint32_t ticks) noexcept {
  return ticks >= 1 && ticks <= HermiteChunk::max_ticks && (ticks & (ticks - 1)) == 0;
}

}  // namespace curvestep
