// SPDX-License-Identifier: MIT
// STM32F405 vector table: 16 system entries and 82 interrupts (RM0090 §12.2, table 61).
#include <curvestep/boards/stm32/startup.hpp>

extern "C" void USART1_IRQHandler();
extern "C" void TIM2_IRQHandler();

namespace {

constexpr std::size_t irq_count = 82;

consteval curvestep::stm32::VectorTable<irq_count> make_table() {
  curvestep::stm32::VectorTable<irq_count> table{&_estack, CURVESTEP_STM32_SYSTEM_VECTORS, {}};
  for (auto& handler : table.interrupts) handler = Default_Handler;
  table.interrupts[28] = TIM2_IRQHandler;
  table.interrupts[37] = USART1_IRQHandler;
  return table;
}

}  // namespace

extern "C" [[gnu::section(".isr_vector"), gnu::used]] constinit const curvestep::stm32::VectorTable<irq_count> vector_table =
    make_table();
