// SPDX-License-Identifier: MIT
// ConsoleKeyDecoder: the keys of an idle interactive session (`curvestep console`), as grbl
// senders and bCNC pendants use them: the arrow keys jog Y+ (up), Y- (down), X+ (right), X-
// (left), Page Up / Page Down jog Z+ / Z-; letters do the same on a terminal without them (d / a
// X+ / X-, w / s Y+ / Y-, r / f Z+ / Z-); t or Tab cycle the jog step (0.1, 1, 10 mm); h homes; ?
// asks for the status; Esc or Ctrl-X abort; q or Ctrl-D quit.
//
// Arrow keys arrive as escape sequences (Esc [ A, or Esc O A in the terminal's application mode;
// Page Up Esc [ 5 ~): a sequence split between two reads is kept until its end arrives, and one
// this console does not know is skipped whole. A lone Esc (nothing after it in the same read) is
// the Esc key.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace curvestep::host::link {

/// One key of the idle console.
enum class ConsoleKey : std::uint8_t {
  JogXPlus,   ///< right arrow, d
  JogXMinus,  ///< left arrow, a
  JogYPlus,   ///< up arrow, w
  JogYMinus,  ///< down arrow, s
  JogZPlus,   ///< Page Up, r
  JogZMinus,  ///< Page Down, f
  NextStep,   ///< t or Tab: the next jog step (0.1 -> 1 -> 10 -> 0.1 mm)
  Home,       ///< h: home the axes of the machine file's "homing" section
  Status,     ///< ?: state, position and switches
  Abort,      ///< Esc or Ctrl-X: abort a running jog or homing
  Quit,       ///< q or Ctrl-D
};

/// The jog keys' axis (0 x, 1 y, 2 z) and direction (+1 or -1); axis 3 for any other key.
struct JogDirection {
  std::size_t axis = 3;  ///< 0 x, 1 y, 2 z; 3: no jog key
  int sign = 0;          ///< +1 or -1
};
/// Where a jog key moves.
[[nodiscard]] JogDirection jog_direction(ConsoleKey key) noexcept;

/// The jog steps `t` cycles through, mm.
inline constexpr double console_jog_steps_mm[] = {0.1, 1, 10};

/// Turns typed bytes into console keys; keeps an escape sequence cut between two reads.
class ConsoleKeyDecoder {
 public:
  /// The keys in `bytes` (after any sequence left open by the last call); other bytes are ignored.
  [[nodiscard]] std::vector<ConsoleKey> decode(std::string_view bytes);
  /// The keys, one line, for the command's start-up note and help.
  [[nodiscard]] static std::string_view key_help() noexcept;

 private:
  std::string open_sequence_;  // an escape sequence without its final byte yet
};

}  // namespace curvestep::host::link
