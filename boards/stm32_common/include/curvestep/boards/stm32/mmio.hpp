// SPDX-License-Identifier: MIT
// Memory-mapped register access and the Cortex-M core peripherals (SysTick, NVIC, SCB) shared by every STM32.
#pragma once

#include <cstdint>

namespace curvestep::stm32 {

/// The 32-bit peripheral register at `address`.
[[nodiscard]] inline volatile std::uint32_t& reg(std::uintptr_t address) noexcept {
  return *reinterpret_cast<volatile std::uint32_t*>(address);
}

/// Cortex-M system control space addresses (ARMv7-M Architecture Reference Manual, B3).
namespace scs {
inline constexpr std::uintptr_t systick_csr = 0xE000E010;  ///< SysTick control and status
inline constexpr std::uintptr_t systick_rvr = 0xE000E014;  ///< SysTick reload value
inline constexpr std::uintptr_t systick_cvr = 0xE000E018;  ///< SysTick current value
inline constexpr std::uintptr_t nvic_iser = 0xE000E100;    ///< NVIC interrupt set-enable (array of 32-bit words)
inline constexpr std::uintptr_t nvic_ispr = 0xE000E200;    ///< NVIC interrupt set-pending (array of 32-bit words)
inline constexpr std::uintptr_t nvic_ipr = 0xE000E400;     ///< NVIC priority bytes
inline constexpr std::uintptr_t icsr = 0xE000ED04;         ///< interrupt control and state
inline constexpr std::uintptr_t vtor = 0xE000ED08;         ///< vector table offset
inline constexpr std::uintptr_t aircr = 0xE000ED0C;        ///< application interrupt and reset control
inline constexpr std::uintptr_t shcsr = 0xE000ED24;        ///< system handler control and state
inline constexpr std::uintptr_t cfsr = 0xE000ED28;         ///< configurable fault status
inline constexpr std::uintptr_t hfsr = 0xE000ED2C;         ///< hard fault status
inline constexpr std::uintptr_t mmfar = 0xE000ED34;        ///< memory-management fault address
inline constexpr std::uintptr_t bfar = 0xE000ED38;         ///< bus fault address
inline constexpr std::uintptr_t cpacr = 0xE000ED88;        ///< coprocessor access control (FPU enable)
}  // namespace scs

/// Disables interrupts (PRIMASK = 1).
inline void disable_interrupts() noexcept { asm volatile("cpsid i" ::: "memory"); }
/// Enables interrupts (PRIMASK = 0).
inline void enable_interrupts() noexcept { asm volatile("cpsie i" ::: "memory"); }
/// Sleeps until the next interrupt.
inline void wait_for_interrupt() noexcept { asm volatile("wfi" ::: "memory"); }
/// Data and instruction barriers after a configuration write that must take effect now.
inline void barrier() noexcept { asm volatile("dsb\n\tisb" ::: "memory"); }

/// Saves PRIMASK and disables interrupts for the lifetime of the object.
class CriticalSection {
 public:
  /// Enters the critical section.
  CriticalSection() noexcept {
    asm volatile("mrs %0, primask" : "=r"(saved_));
    disable_interrupts();
  }
  /// Restores the saved PRIMASK.
  ~CriticalSection() { asm volatile("msr primask, %0" ::"r"(saved_) : "memory"); }
  CriticalSection(const CriticalSection&) = delete;             ///< not copyable
  CriticalSection& operator=(const CriticalSection&) = delete;  ///< not copyable

 private:
  std::uint32_t saved_ = 0;
};

/// Enables external interrupt `irq` in the NVIC with priority `priority` (0 = highest, upper bits used).
inline void nvic_enable(unsigned irq, std::uint8_t priority) noexcept {
  *reinterpret_cast<volatile std::uint8_t*>(scs::nvic_ipr + irq) = priority;
  reg(scs::nvic_iser + 4 * (irq / 32)) = std::uint32_t{1} << (irq % 32);
}

/// Marks external interrupt `irq` pending (its handler runs as soon as priorities allow).
inline void nvic_set_pending(unsigned irq) noexcept { reg(scs::nvic_ispr + 4 * (irq / 32)) = std::uint32_t{1} << (irq % 32); }

/// Bounded wait: true once (reg(address) & mask) == expected, false after `attempts` reads.
[[nodiscard]] inline bool wait_for_bits(std::uintptr_t address, std::uint32_t mask, std::uint32_t expected,
                                        std::uint32_t attempts) noexcept {
  for (std::uint32_t i = 0; i < attempts; ++i) {
    if ((reg(address) & mask) == expected) return true;
  }
  return false;
}

}  // namespace curvestep::stm32
