// SPDX-License-Identifier: MIT
// Stm32F1Board: STM32F103C8 (Cortex-M3, 72 MHz, no FPU) bring-up: clocks, USART1, SysTick, step/dir GPIO.
//
// Pins (see README.md): USART1 TX PA9, RX PA10 (115200 8N1); STEP X/Y/Z = PA0/PA1/PA2,
// DIR X/Y/Z = PA3/PA4/PA5 (push-pull outputs); machine outputs PB8..PB15, spindle PWM PA6 (TIM3),
// servo pen PB6 (TIM4) (stm32_common/.../machine_outputs.hpp). Registers from RM0008 (STM32F101/F103 reference
// manual); no vendor SDK. The same image runs on QEMU's stm32vldiscovery (STM32F100): QEMU 7.2
// models the USART and the Cortex-M core but not RCC, flash interface or GPIO (reads as 0, writes
// ignored); RCC_CR = 0 is impossible on silicon, so the board then assumes QEMU's 24 MHz core clock.
#pragma once

#include <cstddef>
#include <cstdint>

#include <curvestep/boards/stm32/board.hpp>
#include <curvestep/core/fixed/fixed.hpp>

namespace curvestep::boards {

using stm32::Clocks;  ///< clock frequencies after init()

/// What is particular to the STM32F103C8 (RM0008); the rest is stm32::Board.
struct Stm32F1Chip {
  using Scalar = Q16_16;                                       ///< no FPU: fixed point
  static constexpr const char* name = "stm32f1";              ///< board name in reports
  static constexpr std::uint32_t hse_hz = 8'000'000;           ///< crystal
  static constexpr std::uint32_t target_hclk_hz = 72'000'000;  ///< PLL x9 from the crystal
  static constexpr std::uintptr_t usart1 = 0x40013800;         ///< USART1 (APB2)
  static constexpr unsigned usart1_irq = 37;                   ///< its interrupt number
  static constexpr std::uintptr_t gpioa_bsrr = 0x40010800 + 0x10;  ///< GPIOA bit set/reset register
  static constexpr std::uintptr_t gpiob_bsrr = 0x40010C00 + 0x10;  ///< GPIOB bit set/reset register (machine outputs)
  static constexpr std::size_t step_events_per_tick = 32;      ///< StepBatch capacity per control tick
  static constexpr std::size_t edge_ring = 64;                 ///< timed edges waiting for TIM2 (two ticks)
  static constexpr std::size_t setpoint_window = 2;            ///< setpoint frames in flight (8 KiB of RAM: not 4)
  static constexpr std::size_t setpoint_buffer = 28;           ///< setpoints waiting for a batch (one batch and a sixth)
  static constexpr std::size_t console_tx_buffer = 128;        ///< USART1 transmit ring (the App buffers whole frames)
  static constexpr Clocks fallback_clocks{8'000'000, 8'000'000, 8'000'000, false};  ///< HSI 8 MHz

  /// HSE 8 MHz -> PLL 72 MHz, or HSI 8 MHz if a ready flag does not come; QEMU: 24 MHz.
  static Clocks setup_clocks() noexcept;
  /// GPIOA, GPIOB, AFIO, USART1, TIM3 and TIM4 clocks; PA0..PA5 outputs, PA9 TX, PA10 RX; the
  /// machine outputs: PB8..PB15 outputs, PA6 (TIM3_CH1) and PB6 (TIM4_CH1) alternate function.
  static void setup_gpio() noexcept;
  /// TIM2 clock on (APB1).
  static void enable_step_timer() noexcept;
};

/// The STM32F103C8 board ("blue pill" class, 8 MHz crystal).
using Stm32F1Board = stm32::Board<Stm32F1Chip>;

}  // namespace curvestep::boards
