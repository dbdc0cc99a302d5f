// SPDX-License-Identifier: MIT
// Stm32F1Board: STM32F103C8 (Cortex-M3, 72 MHz, no FPU) bring-up: clocks, USART1, SysTick, step/dir GPIO.
//
// Pins (see README.md): USART1 TX PA9, RX PA10 (115200 8N1); STEP X/Y/Z = PA0/PA1/PA2,
// DIR X/Y/Z = PA3/PA4/PA5 (push-pull outputs). Registers from RM0008 (STM32F101/F103 reference
// manual); no vendor SDK. The same image runs on QEMU's stm32vldiscovery (STM32F100): QEMU 7.2
// models the USART and the Cortex-M core but not RCC, flash interface or GPIO (reads as 0, writes
// ignored); RCC_CR = 0 is impossible on silicon, so the board then assumes QEMU's 24 MHz core clock.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/boards/stm32/clocks.hpp>
#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/core/motion/step_generator.hpp>

namespace curvestep::boards {

using stm32::Clocks;  ///< clock frequencies after init()

/// The STM32F103C8 board ("blue pill" class, 8 MHz crystal).
class Stm32F1Board {
 public:
  using Scalar = Q16_16;                                 ///< no FPU: fixed point
  static constexpr const char* name = "stm32f1";        ///< board name in reports
  static constexpr std::size_t axes = 3;                 ///< step/dir channels
  static constexpr std::uint32_t baud = 115200;          ///< console baud rate
  static constexpr std::size_t console_buffer = 256;     ///< bytes in each console ring
  static constexpr std::uint32_t hse_hz = 8'000'000;     ///< crystal
  static constexpr std::uint32_t target_hclk_hz = 72'000'000;  ///< PLL x9 from the crystal

  /// Clocks (HSE -> PLL 72 MHz, or HSI 8 MHz fallback), GPIO and USART1 with its interrupt.
  Clocks init() noexcept;

  /// Queues console bytes; returns how many fitted in the transmit ring.
  std::size_t write(std::span<const std::uint8_t> bytes) noexcept;
  /// Queues every byte, waiting for room.
  void write_all(std::span<const std::uint8_t> bytes) noexcept;
  /// Takes one received console byte; false when none.
  bool read(std::uint8_t& byte) noexcept;
  /// Room in the transmit ring.
  [[nodiscard]] std::size_t writable() const noexcept;
  /// Received bytes lost to a full ring or a hardware overrun.
  [[nodiscard]] std::uint32_t receive_overruns() const noexcept;

  /// Starts the control tick: `callback(context)` from the SysTick interrupt `rate_hz` times a second.
  bool start_tick(std::uint32_t rate_hz, void (*callback)(void*), void* context) noexcept;
  /// Ticks since start_tick().
  [[nodiscard]] std::uint32_t ticks() const noexcept;

  /// Drives the DIR lines: bit a of `positive_mask` set = axis a moves in the positive direction.
  void set_directions(std::uint32_t positive_mask) noexcept;
  /// Raises the STEP lines of the axes in `mask` (one BSRR write).
  void raise_steps(std::uint32_t mask) noexcept;
  /// Lowers the STEP lines of the axes in `mask` (one BSRR write).
  void lower_steps(std::uint32_t mask) noexcept;

  // --- the firmware::Board concept (firmware/include/curvestep/firmware/board.hpp) ---
  static constexpr std::uint8_t axis_count = 3;                 ///< driven axes
  static constexpr std::size_t step_events_per_tick = 32;       ///< StepBatch capacity per control tick
  static constexpr std::size_t edge_ring = 64;                  ///< timed edges waiting for TIM2 (two ticks)
  /// 1 MHz step timer (TIM2), 2 µs pulses and gaps, 1 µs direction set-up and hold.
  static constexpr StepTiming step_timing() noexcept { return StepTiming{1'000'000, 2000, 2000, 1000, 1000}; }
  /// Milliseconds since init() (from SysTick, whatever its rate).
  [[nodiscard]] std::uint32_t now_ms() const noexcept;
  /// Received bytes into `into`; never blocks.
  std::size_t read(std::span<std::byte> into) noexcept;
  /// Queues what fits of `bytes` for transmission; never blocks.
  std::size_t write(std::span<const std::byte> bytes) noexcept;
  /// Queues a DIR edge at step-timer time `time_ticks` (played one control period later).
  void set_direction(std::uint64_t time_ticks, std::uint8_t axis, bool positive) noexcept;
  /// Queues a STEP edge at step-timer time `time_ticks` (played one control period later).
  void set_step(std::uint64_t time_ticks, std::uint8_t axis, bool high) noexcept;
  /// Drops every queued edge and lowers the STEP lines.
  void fault_stop() noexcept;
  /// Starts TIM2 for the edges of a control tick of `control_rate_hz`.
  void start_steps(std::uint32_t control_rate_hz) noexcept;
  /// Edges lost to a full edge ring.
  [[nodiscard]] std::uint32_t edges_dropped() const noexcept;

  /// Clocks measured by init().
  [[nodiscard]] const Clocks& clocks() const noexcept { return clocks_; }

 private:
  Clocks clocks_{8'000'000, 8'000'000, 8'000'000, false};
};

}  // namespace curvestep::boards
