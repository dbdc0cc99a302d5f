// SPDX-License-Identifier: MIT
// STM32F4 bring-up image: clocks, console, 1 kHz tick, then the line monitor (bringup.hpp).
#include <curvestep/boards/stm32/bringup.hpp>
#include <curvestep/boards/stm32/mmio.hpp>
#include <curvestep/boards/stm32/startup.hpp>

#include "board.hpp"

extern "C" [[noreturn]] void curvestep_main() {
  static curvestep::boards::Stm32F4Board board;
  board.init();
  board.start_tick(1000, nullptr, nullptr);
  static curvestep::stm32::BringUp<curvestep::boards::Stm32F4Board> monitor(board);
  monitor.banner();
  for (;;) {
    monitor.poll();
    curvestep::stm32::wait_for_interrupt();
  }
}
