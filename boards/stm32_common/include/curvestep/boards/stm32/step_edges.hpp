// SPDX-License-Identifier: MIT
// Step/dir edge replay: a ring of timed GPIO edges played by TIM2 compare interrupts (STM32F1 and F4).
//
// App<Board> hands the edges of control tick k with absolute step-timer times in [kP, (k+1)P)
// while tick k is being computed, so they are played one period late: the first edge after an
// idle ring fixes offset = now + P - time, and every edge then goes to the pins at time + offset.
// TIM2 runs free at timer_hz (1 MHz) with a 16-bit period on both families (TIM2 is 16-bit on
// F1, 32-bit on F4; the update interrupt extends it to 64 bits). The handler plays every due
// edge (one BSRR write each) and sets CCR1 to the next one. Registers: RM0008 §15.4 (F1),
// RM0090 §18.4 (F4), identical for CR1, DIER, SR, CNT, PSC, ARR, CCR1.
//
// A full ring on silicon loses the edge: edges_dropped() counts it and App faults (StepsLost), as
// a lost edge is a lost step. In an emulator (RCC absent: Clocks::emulated) the timer does not
// keep time — QEMU 7.2's F100 has no TIM2; its F2/F4 timer model never raises the compare
// interrupt and raises the update interrupt late (docs/boards.md, "Step edges in QEMU") — so
// there a full ring plays its oldest edge at once instead: order and counts stay exact, timing
// is meaningless anyway. The setpoint stream does not depend on it.
#pragma once

#include <cstddef>
#include <cstdint>

#include <curvestep/boards/stm32/mmio.hpp>

namespace curvestep::stm32 {

/// Timed edges for three axes on one GPIO port (`Bsrr` = its bit set/reset register), TIM2 at `Timer`.
template <std::uintptr_t Timer, std::uintptr_t Bsrr, std::size_t Capacity>
class StepEdges {
  static_assert(Capacity >= 2 && (Capacity & (Capacity - 1)) == 0, "capacity must be a power of two");

 public:
  static constexpr unsigned irq = 28;  ///< TIM2 global interrupt (F1 and F4)

  /// Starts TIM2 at `timer_hz` from its kernel clock `timer_clock_hz`; `period_ticks` = P.
  /// Step pins `step_pins[a]`, direction pins `dir_pins[a]` (pin numbers on the port).
  /// `emulated`: an emulator's timer that does not keep time (a full ring plays, never drops).
  void start(std::uint32_t timer_clock_hz, std::uint32_t timer_hz, std::uint32_t period_ticks,
             const std::uint8_t (&step_pins)[3], const std::uint8_t (&dir_pins)[3], bool emulated) noexcept {
    play_when_full_ = emulated;
    for (std::size_t a = 0; a < 3; ++a) {
      step_bits_[a] = static_cast<std::uint16_t>(1u << step_pins[a]);
      dir_bits_[a] = static_cast<std::uint16_t>(1u << dir_pins[a]);
    }
    period_ = period_ticks;
    reg(Timer + cr1) = 0;
    reg(Timer + psc) = timer_clock_hz / timer_hz - 1;
    reg(Timer + arr) = 0xFFFF;
    reg(Timer + egr) = 1;  // UG: load the prescaler
    reg(Timer + sr) = 0;
    reg(Timer + dier) = dier_uie;
    reg(Timer + cr1) = 1;  // CEN
    nvic_enable(irq, 0x00);  // edges first
  }

  /// Sets the play-out latency P (step-timer ticks per control tick).
  void set_period(std::uint32_t period_ticks) noexcept { period_ = period_ticks; }

  /// Queues one edge: `direction` true = DIR line of `axis`, else STEP line; `high` its level.
  void push(std::uint64_t time_ticks, std::uint8_t axis, bool direction, bool high) noexcept {
    if (axis >= 3) return;
    const CriticalSection guard;
    const std::uint32_t count = head_ - tail_;
    if (count == 0) offset_ = now() + period_ - time_ticks;
    if (count == Capacity) {
      if (!play_when_full_) {
        edges_dropped_ = edges_dropped_ + 1;
        return;
      }
      reg(Bsrr) = ring_[tail_ % Capacity].bsrr;  // emulator: the oldest edge goes out now
      tail_ = tail_ + 1;
    }
    const std::uint16_t bit = direction ? dir_bits_[axis] : step_bits_[axis];
    ring_[head_ % Capacity] = Edge{time_ticks + offset_, high ? bit : static_cast<std::uint32_t>(bit) << 16};
    head_ = head_ + 1;
    if (count == 0) arm();
  }

  /// Forgets every edge not yet played and lowers the step lines.
  void stop() noexcept {
    const CriticalSection guard;
    tail_ = head_;
    reg(Timer + dier) = dier_uie;
    reg(Bsrr) = static_cast<std::uint32_t>(step_bits_[0] | step_bits_[1] | step_bits_[2]) << 16;
  }

  /// The timer interrupt body.
  void on_interrupt() noexcept {
    const std::uint32_t status = reg(Timer + sr);
    reg(Timer + sr) = ~status & 0x1FFFu;  // rc_w0: clear what was seen
    if ((status & 1u) != 0) overflows_ = overflows_ + 1;
    arm();
  }

  /// Edges lost because the ring was full.
  [[nodiscard]] std::uint32_t edges_dropped() const noexcept { return edges_dropped_; }
  /// Edges waiting to be played.
  [[nodiscard]] std::size_t pending() const noexcept { return head_ - tail_; }

  /// The 64-bit step-timer time (16-bit counter extended by the update interrupts).
  [[nodiscard]] std::uint64_t now() const noexcept {
    const CriticalSection guard;
    std::uint32_t high = overflows_;
    std::uint32_t low = reg(Timer + cnt) & 0xFFFFu;
    if ((reg(Timer + sr) & 1u) != 0) {  // an overflow not yet counted
      low = reg(Timer + cnt) & 0xFFFFu;
      ++high;
    }
    return (static_cast<std::uint64_t>(high) << 16) | low;
  }

 private:
  struct Edge {
    std::uint64_t time;
    std::uint32_t bsrr;
  };
  static constexpr std::uintptr_t cr1 = 0x00, dier = 0x0C, sr = 0x10, egr = 0x14, cnt = 0x24, psc = 0x28,
                                  arr = 0x2C, ccr1 = 0x34;
  static constexpr std::uint32_t dier_uie = 1u << 0, dier_cc1ie = 1u << 1;

  /// Plays every due edge, then programs CCR1 for the next one (the update interrupt covers the rest).
  void arm() noexcept {
    for (;;) {
      if (head_ == tail_) {
        reg(Timer + dier) = dier_uie;
        return;
      }
      const Edge& edge = ring_[tail_ % Capacity];
      const std::uint64_t current = now();
      if (edge.time <= current) {
        reg(Bsrr) = edge.bsrr;
        tail_ = tail_ + 1;
        continue;
      }
      if (edge.time - current < 0x10000u) {
        reg(Timer + ccr1) = static_cast<std::uint32_t>(edge.time & 0xFFFFu);
        reg(Timer + dier) = dier_uie | dier_cc1ie;
        if (edge.time > now()) return;  // else it passed while arming: play it now
      } else {
        reg(Timer + dier) = dier_uie;
        return;
      }
    }
  }

  Edge ring_[Capacity] = {};
  volatile std::uint32_t head_ = 0;
  volatile std::uint32_t tail_ = 0;
  volatile std::uint32_t overflows_ = 0;
  volatile std::uint32_t edges_dropped_ = 0;
  std::uint64_t offset_ = 0;
  std::uint32_t period_ = 0;
  bool play_when_full_ = false;  ///< emulator: a full ring plays its oldest edge instead of dropping one
  std::uint16_t step_bits_[3] = {};
  std::uint16_t dir_bits_[3] = {};
};

}  // namespace curvestep::stm32
