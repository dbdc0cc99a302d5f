// SPDX-License-Identifier: MIT
// STM32F1 firmware images: App<Stm32F1Board> (firmware/include/curvestep/firmware/app.hpp) on USART1;
// CURVESTEP_LOOKAHEAD_SEGMENTS 0 builds the executor (no planner: it replays host-planned pieces).
#include <curvestep/boards/stm32/firmware_loop.hpp>
#include <curvestep/boards/stm32/startup.hpp>
#include <curvestep/firmware/app.hpp>

#include "board.hpp"

#ifndef CURVESTEP_QUEUE_SEGMENTS
#define CURVESTEP_QUEUE_SEGMENTS 32
#endif
#ifndef CURVESTEP_LOOKAHEAD_SEGMENTS
#define CURVESTEP_LOOKAHEAD_SEGMENTS 16
#endif

namespace {
using Board = curvestep::boards::Stm32F1Board;
#ifndef CURVESTEP_MACHINE_EVENTS
#define CURVESTEP_MACHINE_EVENTS CURVESTEP_QUEUE_SEGMENTS
#endif
using App = curvestep::firmware::App<Board, curvestep::Q16_16, CURVESTEP_QUEUE_SEGMENTS, CURVESTEP_LOOKAHEAD_SEGMENTS,
                                     CURVESTEP_MACHINE_EVENTS>;
}  // namespace

extern "C" [[noreturn]] void curvestep_main() {
  static Board board;
  board.init();
  static App app(board, curvestep::stm32::firmware_settings(board));
  curvestep::stm32::run_firmware(board, app);
}
