// SPDX-License-Identifier: MIT
// STM32F103 vector table: 16 system entries and 60 interrupts (RM0008 §10.1.2, connectivity line has 68).
#include <curvestep/boards/stm32/startup.hpp>

extern "C" [[gnu::section(".isr_vector"), gnu::used]] constinit const curvestep::stm32::VectorTable<60> vector_table =
    curvestep::stm32::board_vector_table<60>();
