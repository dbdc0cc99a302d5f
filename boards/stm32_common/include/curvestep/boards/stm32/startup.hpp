// SPDX-License-Identifier: MIT
// Cortex-M start-up shared by the STM32 boards: vector table layout, reset, fault and tick handlers.
//
// Each board's startup.cpp places one VectorTable<IrqCount> in section .isr_vector (the linker
// script puts it at the start of flash) and implements the three hooks declared below. The
// reset handler runs the early hook (F4: FPU on), copies .data, clears .bss, runs static
// constructors, then curvestep_main(). Unexpected interrupts and every fault end in a report written
// by polling the board's console UART (interrupts cannot be relied on inside a fault).
#pragma once

#include <cstddef>
#include <cstdint>

namespace curvestep::stm32 {

/// An exception or interrupt handler.
using Handler = void (*)();

/// The Cortex-M vector table: initial stack pointer, 15 system exceptions, IrqCount interrupts.
template <std::size_t IrqCount>
struct VectorTable {
  const void* initial_stack;                ///< loaded into MSP at reset
  Handler system[15];                       ///< Reset, NMI, HardFault, ..., SysTick (exceptions 1-15)
  Handler interrupts[IrqCount];             ///< external interrupts 0..IrqCount-1
};

/// Ticks counted by the SysTick handler since start_systick().
[[nodiscard]] std::uint32_t systick_count() noexcept;

/// Milliseconds counted by the SysTick handler (exact for any tick rate: 1000/rate per tick).
[[nodiscard]] std::uint32_t systick_milliseconds() noexcept;

/// Processor clocks since start_systick(), from the SysTick count and counter (wraps at 2^32;
/// call with interrupts enabled: a wrap whose interrupt is pending reads one period short).
/// The tick timer of an emulator, whose DWT has no cycle counter.
[[nodiscard]] std::uint32_t systick_cycles() noexcept;

/// Starts SysTick on the processor clock `hclk_hz` at `rate_hz` interrupts per second; each one
/// increments systick_count() and then calls `callback(context)` when a callback is set.
/// False when the reload value does not fit the 24-bit counter.
bool start_systick(std::uint32_t hclk_hz, std::uint32_t rate_hz, void (*callback)(void*) = nullptr,
                   void* context = nullptr) noexcept;

/// Reads the stacked fault frame and the fault status registers and writes one report line
/// ("HardFault pc=0x... lr=0x... xpsr=0x... cfsr=0x... hfsr=0x... mmfar=0x... bfar=0x...")
/// through the board's polled console, then stops.
[[noreturn]] void report_fault(const char* name, const std::uint32_t* frame) noexcept;

}  // namespace curvestep::stm32

extern "C" {
/// The application entry (instead of main, which C++ forbids calling), after static initialisation.
[[noreturn]] void curvestep_main();
/// Board hook, first thing after reset, before .data/.bss exist (must not touch globals).
void curvestep_board_early_init();
/// Board hook: writes one byte to the console by polling (used by fault reports).
void curvestep_board_fault_putc(char c);
/// The exception handlers defined by the shared start-up code (for the boards' vector tables).
[[noreturn]] void Reset_Handler();
void Default_Handler();
void HardFault_Handler();
void MemManage_Handler();
void BusFault_Handler();
void UsageFault_Handler();
void SysTick_Handler();
/// Linker-script symbols: stack top and the data/bss/init-array boundaries.
extern std::uint32_t _estack;
}

/// Fills the 15 system-exception slots with the shared handlers.
#define CURVESTEP_STM32_SYSTEM_VECTORS                                                                           \
  {                                                                                                              \
    Reset_Handler, Default_Handler, HardFault_Handler, MemManage_Handler, BusFault_Handler, UsageFault_Handler, \
        nullptr, nullptr, nullptr, nullptr, Default_Handler, Default_Handler, nullptr, Default_Handler,         \
        SysTick_Handler                                                                                          \
  }

extern "C" void TIM2_IRQHandler();    ///< the board's step-timer handler (board.cpp)
extern "C" void USART1_IRQHandler();  ///< the board's console handler (board.cpp)

namespace curvestep::stm32 {

/// The vector table of an STM32 board with IrqCount interrupts: the shared system handlers, TIM2
/// (IRQ 28) and USART1 (IRQ 37), whose numbers are the same on the F1, F2 and F4 (RM0008 §10.1.2,
/// RM0090 §12.2), and Default_Handler for every other interrupt.
template <std::size_t IrqCount>
consteval VectorTable<IrqCount> board_vector_table() {
  static_assert(IrqCount > 37, "TIM2 and USART1 must be in the table");
  VectorTable<IrqCount> table{&_estack, CURVESTEP_STM32_SYSTEM_VECTORS, {}};
  for (auto& handler : table.interrupts) handler = Default_Handler;
  table.interrupts[28] = TIM2_IRQHandler;
  table.interrupts[37] = USART1_IRQHandler;
  return table;
}

}  // namespace curvestep::stm32
