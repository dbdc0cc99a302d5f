// SPDX-License-Identifier: MIT
// PlannedPiece: one piece of motion planned ahead (by the host's MotionController) for a controller
// that only executes (PieceExecutor, no planner on board). A job is a run of pieces; each piece
// covers `ticks` consecutive control ticks and ends with the exact setpoint `end`:
//   ticks == 1   one setpoint at `end` (an exactly evaluated tick);
//   ticks == N   (a power of two, 2..HermiteChunk::max_ticks) a chunk: the N - 1 setpoints of the
//                quintic Hermite `controls` (relative to the previous setpoint's unrounded position,
//                stepped by HermiteChunk), then `end`;
//   exact_run    ticks == K (2..max_exact_run) exactly evaluated ticks in a row: controls[0..K-2],
//                then `end` (a run of exact ticks costs one queue slot and one message per K);
//   rest         ticks == R (1..max_rest_ticks) setpoints at `end`: a rest at a joint (a dwell,
//                MotionController's JointStop), one piece for up to 65535 ticks.
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
  std::uint32_t ticks = 1;             ///< control ticks covered: 1 (exact), a power of two 2..256 (chunk), 2..6 (exact run)
  MachinePoint end{};                  ///< unrounded position of the piece's last setpoint (mm)
  /// Chunk only: the Hermite control points q1..q5 relative to the previous setpoint (q0 = 0 is
  /// implied: HermiteChunk::Controls without its first point, 24 bytes less per queued piece).
  std::array<MachinePoint, 5> controls{};
  std::uint32_t segment = 0;           ///< the job segment it belongs to (setpoint.segment, error reports)
  bool exact_run = false;              ///< ticks exact setpoints: controls[0..ticks-2], then end
  bool rest = false;                   ///< ticks setpoints at end (a rest at a joint)
  bool end_of_job = false;             ///< the job's last piece

  friend constexpr bool operator==(const PlannedPiece&, const PlannedPiece&) = default;
};

/// The chunk's HermiteChunk control points (q0 = 0, then the piece's q1..q5).
[[nodiscard]] constexpr HermiteChunk::Controls chunk_controls(const PlannedPiece& piece) noexcept {
  HermiteChunk::Controls q{};
  for (std::size_t i = 0; i < piece.controls.size(); ++i) q[i + 1] = piece.controls[i];
  return q;
}

/// Most exact ticks one piece carries (its end and the five control-point slots).
inline constexpr std::uint32_t max_exact_run = 6;

/// Most ticks one rest piece covers (QueuePiece's 16-bit ticks); a longer rest is several pieces.
inline constexpr std::uint32_t max_rest_ticks = 65535;

/// True if `ticks` is a valid piece length: 1 or a power of two up to HermiteChunk::max_ticks;
/// for an exact run 2..max_exact_run; for a rest 1..max_rest_ticks.
[[nodiscard]] constexpr bool valid_piece_ticks(std::uint32_t ticks, bool exact_run = false, bool rest = false) noexcept {
  if (rest) return !exact_run && ticks >= 1 && ticks <= max_rest_ticks;
  if (exact_run) return ticks >= 2 && ticks <= max_exact_run;
  return ticks >= 1 && ticks <= HermiteChunk::max_ticks && (ticks & (ticks - 1)) == 0;
}

/// True for a chunk (Hermite-stepped ticks), false for exact ticks.
[[nodiscard]] constexpr bool is_chunk(const PlannedPiece& piece) noexcept { return piece.ticks > 1 && !piece.exact_run && !piece.rest; }

}  // namespace curvestep
