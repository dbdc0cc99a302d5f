// SPDX-License-Identifier: MIT
// STM32F4 benchmark image: runs the setpoint benchmark regions, prints the checksums, then "bench done".
#include <span>
#include <string_view>

#include <curvestep/boards/stm32/mmio.hpp>
#include <curvestep/boards/stm32/startup.hpp>

#include "board.hpp"
#include "setpoint_benchmark.hpp"

extern "C" [[noreturn]] void curvestep_main() {
  static curvestep::boards::Stm32F4Board board;
  board.init();  // no SysTick: nothing interrupts the counted regions
  const auto say = [](std::string_view text) {
    board.write_all(std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
  };
  curvestep::bench::run<float>(1, "float", say);
  curvestep::bench::run<curvestep::Q16_16>(2, "q16.16", say);
  say("bench done\r\n");
  for (;;) curvestep::stm32::wait_for_interrupt();
}
