// SPDX-License-Identifier: MIT
// STM32F405 vector table: 16 system entries and 82 interrupts (RM0090 §12.2, table 61).
#include <curvestep/boards/stm32/startup.hpp>

extern "C" [[gnu::section(".isr_vector"), gnu::used]] constinit const curvestep::stm32::VectorTable<82> vector_table =
    curvestep::stm32::board_vector_table<82>();
