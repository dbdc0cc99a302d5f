// SPDX-License-Identifier: MIT
// OperatorConsole: the operator's keys and signals while a job runs (`curvestep stream`, `gpio`,
// `jog`, `home`), and the terminal and signals of the idle `curvestep console` (read_bytes,
// poll_signals: it decodes its own keys, console_keys.hpp).
//
// Keys, as grbl senders use them: `!` feed hold, `~` resume, Ctrl-X or Esc abort, `?` status line;
// feed override `]` / `[` ±10 %, `}` / `{` ±1 %, `=` 100 %; rapid override `(` 25 %, `*` 50 %, `)`
// 100 % (and grbl's real-time override bytes 0x90 .. 0x97).
// While a question is open (ask()), Enter or `r` also resume and `a` aborts. An escape sequence
// (an arrow or function key: Esc followed at once by `[` or `O`) is ignored, not taken as Esc.
// Signals: SIGINT (Ctrl-C) is a feed hold and asks whether to resume or abort; a second SIGINT
// before the answer aborts; SIGTERM aborts.
//
// Keys are read from standard input when it is a terminal (put in raw mode: no line buffering, no
// echo; Ctrl-C still raises SIGINT), or from any standard input (a pipe) when `keys_from_stdin`
// says so (`--keys`); a terminal is left alone when the process runs in the background (not its
// foreground process group). The constructor installs the signal handlers and the raw mode; the
// destructor restores both, so every way out of a command (return, exception) puts the terminal
// back. One console at a time.
#pragma once

#include <deque>
#include <string>
#include <string_view>

#include <termios.h>

#include <curvestep/host/link/operator_command.hpp>

namespace curvestep::host::link {

/// Keys and signals of the operator, polled without blocking.
class OperatorConsole {
 public:
  /// Reads keys from `input_fd` if it is a terminal or `keys_from_stdin`; writes questions to `output_fd`.
  explicit OperatorConsole(bool keys_from_stdin, int input_fd = 0, int output_fd = 2);
  ~OperatorConsole();
  OperatorConsole(const OperatorConsole&) = delete;
  OperatorConsole& operator=(const OperatorConsole&) = delete;

  /// The next request (None if nothing happened). Never blocks.
  [[nodiscard]] OperatorCommand poll();
  /// Prints `question` on its own line and takes the next Enter or `r` as Resume, `a` as Abort
  /// (the other keys keep their meaning). The hook for anything that waits for the operator (a
  /// program pause): ask, then keep the link going until poll() says Resume or Abort.
  void ask(std::string_view question);
  /// Ctrl-C (SIGINT) aborts at once instead of holding and asking (a jog: nothing to resume).
  void set_interrupt_aborts(bool aborts) noexcept { interrupt_aborts_ = aborts; }
  /// True if keys are read (a terminal, or keys_from_stdin) and the input has not ended.
  [[nodiscard]] bool reads_keys() const noexcept { return input_fd_ >= 0; }
  /// The bytes typed since the last call, not decoded (an idle session decodes its own keys:
  /// console_keys.hpp); empty if none or no keys are read. Never blocks; the end of the input
  /// makes reads_keys() false.
  [[nodiscard]] std::string read_bytes();
  /// The signals alone (what poll() would answer for them, keys left unread): Abort for SIGTERM,
  /// Hold or Abort for SIGINT as poll() does, None if none arrived since.
  [[nodiscard]] OperatorCommand poll_signals();
  /// True once a SIGINT or SIGTERM was taken (poll, poll_signals): the operator wants the program to stop.
  [[nodiscard]] bool signalled() const noexcept { return signals_seen_ > 0 || terminate_seen_; }
  /// The keys, one line, for a command's help and start-up note.
  [[nodiscard]] static std::string_view key_help() noexcept;

 private:
  void read_keys();
  std::size_t read_available(char* bytes, std::size_t capacity);
  void take_key(const char* bytes, std::size_t count, std::size_t& k);
  void write_line(std::string_view text) const;

  int input_fd_ = -1;  // -1: no keys
  int output_fd_ = 2;
  bool raw_mode_ = false;
  termios saved_mode_{};
  bool question_open_ = false;
  bool interrupt_aborts_ = false;
  int signals_seen_ = 0;  // SIGINTs acted on
  bool terminate_seen_ = false;
  std::deque<OperatorCommand> pending_;
};

}  // namespace curvestep::host::link
