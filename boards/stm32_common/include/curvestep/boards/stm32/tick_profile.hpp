// SPDX-License-Identifier: MIT
// TickProfile: what the control ticks and the segment work of a job cost, in cycles, for the
// real-time benchmark (benchmarks/qemu/tick_budget.py). Built into the firmware images only with
// CURVESTEP_TICK_PROFILE (the benchmark's builds); the shipped images keep only the App's
// TickWatch (overruns, worst tick).
//
// run_firmware records, with the board's cycle clock (QEMU -icount: instructions):
//   * every on_tick() while the App moves: count, sum, maximum and a histogram (4 buckets per
//     octave: bucket 4 e + m holds durations in [2^e (1 + m/4), 2^e (1 + (m+1)/4)), e >= 2);
//   * the ticks that began a segment or piece (the queue shrank: the tick planned the next one,
//     MotionController::begin_segment): count, sum, maximum;
//   * the poll() calls that accepted segments or pieces (the queue grew: decoding, cusps, caps,
//     junction speeds): segments accepted, sum, maximum.
// The benchmark reads the object `curvestep_tick_profile` from the emulator's memory (the QEMU
// monitor's xp) after the job; its layout in 32-bit words is fixed (word offsets below).
#pragma once

#include <cstddef>
#include <cstdint>

namespace curvestep::stm32 {

/// The profile's memory image (little-endian words; the benchmark reads it by these offsets).
struct TickProfile {
  static constexpr std::uint32_t magic_value = 0x6B636974;  ///< "tick"
  static constexpr std::size_t buckets = 128;               ///< histogram buckets (32 octaves x 4)
  std::uint32_t magic = magic_value;      ///< word 0
  std::uint32_t version = 1;              ///< word 1
  std::uint64_t tick_cycles_sum = 0;      ///< words 2-3: every tick while moving
  std::uint64_t start_cycles_sum = 0;     ///< words 4-5: ticks that began a segment or piece
  std::uint64_t accept_cycles_sum = 0;    ///< words 6-7: polls that accepted segments or pieces
  std::uint32_t ticks = 0;                ///< word 8
  std::uint32_t tick_cycles_max = 0;      ///< word 9
  std::uint32_t starts = 0;               ///< word 10
  std::uint32_t start_cycles_max = 0;     ///< word 11
  std::uint32_t accepted = 0;             ///< word 12: segments or pieces accepted
  std::uint32_t accept_cycles_max = 0;    ///< word 13: the longest poll that accepted any
  std::uint32_t cycles_per_second = 0;    ///< word 14: the board's cycle clock as it believes it
  std::uint32_t overruns = 0;             ///< word 15: the App's TickWatch count
  std::uint32_t histogram[buckets] = {};  ///< words 16..143

  /// The histogram bucket of a duration.
  [[nodiscard]] static constexpr std::size_t bucket(std::uint32_t cycles) noexcept {
    if (cycles < 4) return cycles;
    const int octave = 31 - __builtin_clz(cycles);
    return static_cast<std::size_t>(4 * octave) + ((cycles >> (octave - 2)) & 3u);
  }
  /// Records a tick of `cycles`; `started` if it began a segment or piece.
  void tick(std::uint32_t cycles, bool started) noexcept {
    ++ticks;
    tick_cycles_sum += cycles;
    if (cycles > tick_cycles_max) tick_cycles_max = cycles;
    ++histogram[bucket(cycles)];
    if (!started) return;
    ++starts;
    start_cycles_sum += cycles;
    if (cycles > start_cycles_max) start_cycles_max = cycles;
  }
  /// Records a poll of `cycles` that accepted `count` segments or pieces.
  void accept(std::uint32_t cycles, std::uint32_t count) noexcept {
    accepted += count;
    accept_cycles_sum += cycles;
    if (cycles > accept_cycles_max) accept_cycles_max = cycles;
  }
};

}  // namespace curvestep::stm32
