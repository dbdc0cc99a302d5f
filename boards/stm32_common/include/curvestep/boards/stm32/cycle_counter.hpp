// SPDX-License-Identifier: MIT
// The Cortex-M3/M4 cycle counter (DWT CYCCNT, ARMv7-M Architecture Reference Manual C1.8): one count
// per processor clock, 32 bits, free running. It times the control ticks (firmware::TickWatch).
#pragma once

#include <cstdint>

#include <curvestep/boards/stm32/mmio.hpp>

namespace curvestep::stm32 {

namespace dwt {
inline constexpr std::uintptr_t demcr = 0xE000EDFC;   ///< debug exception and monitor control (TRCENA bit 24)
inline constexpr std::uintptr_t ctrl = 0xE0001000;    ///< DWT control (CYCCNTENA bit 0)
inline constexpr std::uintptr_t cyccnt = 0xE0001004;  ///< cycle count
}  // namespace dwt

/// Starts the cycle counter from 0.
inline void start_cycle_counter() noexcept {
  reg(dwt::demcr) = reg(dwt::demcr) | (1u << 24);
  reg(dwt::cyccnt) = 0;
  reg(dwt::ctrl) = reg(dwt::ctrl) | 1u;
}

/// Processor clocks since start_cycle_counter() (wraps at 2^32).
[[nodiscard]] inline std::uint32_t cycle_counter() noexcept { return reg(dwt::cyccnt); }

}  // namespace curvestep::stm32
