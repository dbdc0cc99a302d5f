// SPDX-License-Identifier: MIT
// TickWatch: each control tick's start and duration against its period, on the board's cycle clock.
//
// The board counts cycles (DWT CYCCNT on the STM32 boards, microseconds on the host board); a tick
// is due one period after the one before. The watch keeps the due time of the next tick: a tick
// that starts before it re-anchors the schedule there (the board's timer is the truth, and the
// first tick of a motion may start anywhere in its period), one that starts after it is late.
//   * overrun: a tick that starts more than one period late (the work before it took the period
//     it was due in) or runs longer than one period; counted, never more than once a tick;
//   * missed deadline: a tick that starts more than `tolerated_periods` periods late. The step
//     edges of a tick are played one period after it (the board's edge ring holds two ticks), so
//     with 1 a tick can be late by one period before its edges are. App faults with
//     TickDeadlineMissed. 0 tolerates anything (count only: an emulator, whose clock is not real).
// Cycle counts are 32-bit and wrap; only differences are used, so a tick and its lateness must
// stay below 2^31 cycles (30 s at 72 MHz).
#pragma once

#include <cstdint>

namespace curvestep::firmware {

/// Overruns and the worst tick, from a free-running 32-bit cycle counter.
class TickWatch {
 public:
  /// Ticks of `period_cycles` cycles; a tick more than `tolerated_periods` late is a missed deadline.
  void configure(std::uint32_t period_cycles, std::uint32_t tolerated_periods) noexcept {
    period_ = period_cycles;
    tolerated_periods_ = static_cast<std::uint16_t>(tolerated_periods < 0xFFFF ? tolerated_periods : 0xFFFF);
    restart();
  }
  /// The next tick starts a new schedule (motion starts or resumes after a pause of the ticks).
  void restart() noexcept { anchored_ = false; }

  /// A tick starts at cycle `now`. Returns how many whole periods late it is if that is more than
  /// tolerated (a missed deadline), else 0.
  [[nodiscard]] std::uint32_t on_start(std::uint32_t now) noexcept {
    start_ = now;
    if (period_ == 0) return 0;
    if (!anchored_) {
      due_ = now;
      anchored_ = true;
    }
    const auto late = static_cast<std::int32_t>(now - due_);
    if (late < 0) due_ = now;  // early: the board's timer started this period later than thought
    const std::uint32_t late_cycles = late > 0 ? static_cast<std::uint32_t>(late) : 0;
    due_ += period_;
    late_ = late_cycles > period_;
    if (late_) ++overruns_;
    if (tolerated_periods_ == 0 || late_cycles <= std::uint64_t{tolerated_periods_} * period_) return 0;
    return late_cycles / period_;
  }

  /// The tick that started last ends at cycle `now`.
  void on_end(std::uint32_t now) noexcept {
    const std::uint32_t cycles = now - start_;
    if (cycles > worst_cycles_) worst_cycles_ = cycles;
    if (!late_ && period_ != 0 && cycles > period_) ++overruns_;
  }

  /// Ticks that started more than a period late or ran longer than a period.
  [[nodiscard]] std::uint32_t overruns() const noexcept { return overruns_; }
  /// The longest tick so far, in cycles.
  [[nodiscard]] std::uint32_t worst_cycles() const noexcept { return worst_cycles_; }
  /// The longest tick so far in microseconds on a clock of `cycles_per_second` (whole MHz on every
  /// board: 72, 168, 1; a fraction of a MHz is dropped, which rounds the figure up). 0 below 1 MHz.
  [[nodiscard]] std::uint32_t worst_microseconds(std::uint32_t cycles_per_second) const noexcept {
    const std::uint32_t cycles_per_us = cycles_per_second / 1'000'000u;
    return cycles_per_us == 0 ? 0 : worst_cycles_ / cycles_per_us;
  }
  /// The period in cycles (0: not configured).
  [[nodiscard]] std::uint32_t period_cycles() const noexcept { return period_; }
  /// Forgets the counts (a new session).
  void clear() noexcept {
    overruns_ = 0;
    worst_cycles_ = 0;
  }

 private:
  std::uint32_t period_ = 0;
  std::uint32_t due_ = 0;
  std::uint32_t start_ = 0;
  std::uint32_t overruns_ = 0;
  std::uint32_t worst_cycles_ = 0;
  std::uint16_t tolerated_periods_ = 0;  // 16 bits: the F1 executor's 8 KiB count every word
  bool anchored_ = false;
  bool late_ = false;  // the current tick was counted as an overrun at its start
};

}  // namespace curvestep::firmware
