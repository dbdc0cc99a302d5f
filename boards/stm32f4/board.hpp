// SPDX-License-Identifier: MIT
// Stm32F4Board: STM32F405 (Cortex-M4F, 168 MHz, single-precision FPU) bring-up: clocks, USART1, SysTick, step/dir GPIO.
//
// Pins (see README.md): USART1 TX PA9, RX PA10 (115200 8N1); STEP X/Y/Z = PA0/PA1/PA2,
// DIR X/Y/Z = PA3/PA4/PA5 (push-pull outputs); machine outputs PB8..PB15, spindle PWM PA6 (TIM3),
// servo pen PB6 (TIM4) (stm32_common/.../machine_outputs.hpp). Registers from RM0090 (STM32F405/F407 reference
// manual); no vendor SDK. The same image runs on QEMU's netduinoplus2 (STM32F405): QEMU 7.2
// models the USART and the Cortex-M core but not RCC, flash interface or GPIO (reads as 0, writes
// ignored); RCC_CR = 0 is impossible on silicon, so the board then assumes QEMU's 168 MHz core clock.
#pragma once

#include <cstddef>
#include <cstdint>

#include <curvestep/boards/stm32/board.hpp>

namespace curvestep::boards {

using stm32::Clocks;  ///< clock frequencies after init()

/// What is particular to the STM32F405 (RM0090); the rest is stm32::Board.
struct Stm32F4Chip {
  using Scalar = float;                                         ///< FPv4-SP: float (Q16_16 also builds)
  static constexpr const char* name = "stm32f4";               ///< board name in reports
  static constexpr std::uint32_t hse_hz = 25'000'000;           ///< crystal
  static constexpr std::uint32_t target_hclk_hz = 168'000'000;  ///< PLL from the crystal
  static constexpr std::uintptr_t usart1 = 0x40011000;          ///< USART1 (APB2)
  static constexpr unsigned usart1_irq = 37;                    ///< its interrupt number
  static constexpr std::uintptr_t gpioa_bsrr = 0x40020000 + 0x18;  ///< GPIOA bit set/reset register
  static constexpr std::uintptr_t gpiob_bsrr = 0x40020400 + 0x18;  ///< GPIOB bit set/reset register (machine outputs)
  static constexpr std::size_t step_events_per_tick = 128;      ///< StepBatch capacity per control tick
  static constexpr std::size_t edge_ring = 256;                 ///< timed edges waiting for TIM2 (two ticks)
  static constexpr std::size_t setpoint_window = 4;             ///< setpoint frames in flight (firmware::App)
  static constexpr std::size_t setpoint_buffer = 48;            ///< setpoints waiting for a batch (two batches)
  static constexpr std::size_t console_tx_buffer = 256;         ///< USART1 transmit ring
  static constexpr Clocks fallback_clocks{16'000'000, 16'000'000, 16'000'000, false};  ///< HSI 16 MHz

  /// HSE 25 MHz -> PLL 168 MHz, or HSI 16 MHz if a ready flag does not come; QEMU: 168 MHz.
  static Clocks setup_clocks() noexcept;
  /// GPIOA, GPIOB, USART1, TIM3 and TIM4 clocks; PA0..PA5 outputs, PA9/PA10 AF7 (USART1); the
  /// machine outputs: PB8..PB15 outputs, PA6 AF2 (TIM3_CH1), PB6 AF2 (TIM4_CH1).
  static void setup_gpio() noexcept;
  /// TIM2 clock on (APB1).
  static void enable_step_timer() noexcept;
};

/// The STM32F405 board (Netduino Plus 2 class, 25 MHz crystal).
using Stm32F4Board = stm32::Board<Stm32F4Chip>;

}  // namespace curvestep::boards
