// SPDX-License-Identifier: MIT
// STM32F4 firmware image: App<Stm32F4Board> (firmware/include/curvestep/firmware/app.hpp) on USART1.
#include <curvestep/boards/stm32/firmware_loop.hpp>
#include <curvestep/boards/stm32/startup.hpp>
#include <curvestep/firmware/app.hpp>

#include <type_traits>

#include "board.hpp"

#ifndef CURVESTEP_QUEUE_SEGMENTS
#define CURVESTEP_QUEUE_SEGMENTS 32
#endif
#ifndef CURVESTEP_LOOKAHEAD_SEGMENTS
#define CURVESTEP_LOOKAHEAD_SEGMENTS 16
#endif

// Float setpoints on the Cortex-M4F; built for a Cortex-M3 STM32F2, Q16.16 with the STM32F1
// firmware's queue and look-ahead (CMakeLists.txt).
#ifndef CURVESTEP_FIXED_POINT_SETPOINTS
#define CURVESTEP_FIXED_POINT_SETPOINTS 0
#endif

namespace {
using Board = curvestep::boards::Stm32F4Board;
using Scalar = std::conditional_t<CURVESTEP_FIXED_POINT_SETPOINTS != 0, curvestep::Q16_16, float>;
using App = curvestep::firmware::App<Board, Scalar, CURVESTEP_QUEUE_SEGMENTS, CURVESTEP_LOOKAHEAD_SEGMENTS>;
}  // namespace

extern "C" [[noreturn]] void curvestep_main() {
  static Board board;
  board.init();
  static App app(board, curvestep::stm32::firmware_settings(board));
  curvestep::stm32::run_firmware(board, app);
}
