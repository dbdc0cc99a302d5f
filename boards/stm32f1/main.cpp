// SPDX-License-Identifier: MIT
// STM32F1 bring-up image: clocks, console, 1 kHz tick, then the line monitor (bringup.hpp).
#include <curvestep/boards/stm32/bringup.hpp>

#include "board.hpp"

extern "C" [[noreturn]] void curvestep_main() { curvestep::stm32::run_bringup<curvestep::boards::Stm32F1Board>(); }
