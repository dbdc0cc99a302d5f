// SPDX-License-Identifier: MIT
// Board bring-up console: a line-based monitor on the console UART that exercises every driver.
//
// Commands (one per line, answers end in "\r\n"):
//   hello        -> "hello from <board> hclk=<Hz> clock=<hse-pll|hsi|emulator>"
//   echo <text>  -> "<text>"
//   tick         -> waits for 20 control ticks: "tick ok <first> <last>"
//   gpio         -> sets DIR X/Z, pulses STEP X/Y/Z: "gpio ok"
//   stats        -> "stats overruns=<n> ticks=<n>"
//   fault        -> executes an undefined instruction: the HardFault report follows
// Anything else answers "error: unknown command".
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include <curvestep/boards/stm32/mmio.hpp>
#include <curvestep/boards/stm32/text.hpp>

namespace curvestep::stm32 {

/// The bring-up monitor for any board with the Stm32F1Board interface.
template <typename Board>
class BringUp {
 public:
  /// Uses `board` (already initialised by the caller).
  explicit BringUp(Board& board) noexcept : board_(board) {}

  /// Writes the boot banner.
  void banner() noexcept {
    say("curvestep ");
    say(Board::name);
    say(" boot\r\n");
  }

  /// Handles received bytes; never blocks except while the transmit ring is full.
  void poll() noexcept {
    std::uint8_t byte = 0;
    while (board_.read(byte)) {
      if (byte == '\r' || byte == '\n') {
        if (length_ > 0) execute(std::string_view(line_, length_));
        length_ = 0;
      } else if (length_ < sizeof(line_)) {
        line_[length_++] = static_cast<char>(byte);
      }
    }
  }

 private:
  void say(std::string_view text) noexcept {
    board_.write_all(std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
  }
  void put(char c) noexcept { say(std::string_view(&c, 1)); }
  void number(std::uint64_t value) noexcept {
    put_decimal([this](char c) { put(c); }, value);
  }

  void execute(std::string_view command) noexcept {
    if (command == "hello") {
      say("hello from ");
      say(Board::name);
      say(" hclk=");
      number(board_.clocks().hclk_hz);
      say(board_.clocks().emulated ? " clock=emulator\r\n"
                                   : (board_.clocks().external ? " clock=hse-pll\r\n" : " clock=hsi\r\n"));
    } else if (command.starts_with("echo ")) {
      say(std::string_view(command.data() + 5, command.size() - 5));  // substr() could throw
      say("\r\n");
    } else if (command == "tick") {
      const std::uint32_t first = board_.ticks();
      while (board_.ticks() - first < 20) wait_for_interrupt();
      say("tick ok ");
      number(first);
      put(' ');
      number(board_.ticks());
      say("\r\n");
    } else if (command == "gpio") {
      board_.set_directions(0b101);
      board_.raise_steps(0b111);
      board_.lower_steps(0b111);
      say("gpio ok\r\n");
    } else if (command == "stats") {
      say("stats overruns=");
      number(board_.receive_overruns());
      say(" ticks=");
      number(board_.ticks());
      say("\r\n");
    } else if (command == "fault") {
      say("fault: executing udf\r\n");
      while (board_.writable() < Board::console_tx_buffer) {
      }
      asm volatile("udf #0");
    } else {
      say("error: unknown command\r\n");
    }
  }

  Board& board_;
  char line_[64] = {};
  std::size_t length_ = 0;
};

/// The bring-up image's main loop: clocks, console, a 1 kHz tick, then the monitor.
template <class Board>
[[noreturn]] void run_bringup() {
  static Board board;
  board.init();
  board.start_tick(1000, nullptr, nullptr);
  static BringUp<Board> monitor(board);
  monitor.banner();
  for (;;) {
    monitor.poll();
    wait_for_interrupt();
  }
}

}  // namespace curvestep::stm32
