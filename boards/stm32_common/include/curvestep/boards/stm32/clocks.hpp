// SPDX-License-Identifier: MIT
// The clock frequencies a board's clock set-up reached (drivers compute their dividers from them).
#pragma once

#include <cstdint>

namespace curvestep::stm32 {

/// The clocks after a board's init(): HCLK (core, SysTick), PCLK1 (APB1), PCLK2 (APB2, USART1).
struct Clocks {
  std::uint32_t hclk_hz;   ///< core and SysTick clock
  std::uint32_t pclk1_hz;  ///< APB1 peripheral clock
  std::uint32_t pclk2_hz;  ///< APB2 peripheral clock (USART1)
  bool external;           ///< true when running from the crystal through the PLL, false on HSI
  bool emulated = false;   ///< RCC absent (RCC_CR reads 0, impossible on silicon): an emulator's fixed clock
};

}  // namespace curvestep::stm32
