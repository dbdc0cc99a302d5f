// SPDX-License-Identifier: MIT
// ConsoleSession: the idle interactive session of `curvestep console` on one controller. It reads
// the console keys (link::ConsoleKeyDecoder) from the operator's console (link::OperatorConsole,
// whose terminal mode and signal handlers it shares with the moves it starts) and acts on each in
// turn: a jog key moves the axis by the jog step (ControllerMoves::jog: the machine's limits, the
// travel as soft limits, refused before anything moves if it would leave it), `h` runs the homing
// cycle (homing_cycle.hpp), `?` prints the controller's state, position and switches, `q` quits.
// While a jog or the homing runs, Esc and Ctrl-X abort it (the controller stops at once) and the
// session goes on; Ctrl-C and SIGTERM abort it too and end the session (exit 6). At rest, Ctrl-C,
// SIGTERM, `q`, Ctrl-D and the end of the keys (a pipe with --keys) end it.
#pragma once

#include <array>
#include <cstddef>
#include <deque>
#include <exception>
#include <ostream>
#include <string>

#include <curvestep/host/link/console_keys.hpp>
#include <curvestep/host/machine_file.hpp>

#include "controller_moves.hpp"
#include "operator_session.hpp"

namespace curvestep::host {

/// One idle session: keys in, moves out.
class ConsoleSession {
 public:
  /// `feed_mm_per_s`: the jogs' feed (0: the machine file's feed); results go to `out`.
  ConsoleSession(ControllerMoves& moves, const MachineFile& machine_file, OperatorSession& operator_session, double feed_mm_per_s,
                 std::ostream& out);
  /// Serves keys until the operator quits; returns the exit status (0, or exit_aborted after a
  /// signal stopped a move). Throws LinkError or TransportError if the controller stops answering.
  [[nodiscard]] int run();

 private:
  /// The next key, none yet (waits a little), or Quit once the keys have ended or a signal came.
  [[nodiscard]] link::ConsoleKey next_key();
  void jog(link::ConsoleKey key);
  void home();
  void print_status();
  /// After a move: a StreamError or a switch that misbehaved is reported, the session goes on.
  void report_failure(const std::exception& e);
  [[nodiscard]] double console_step() const noexcept { return link::console_jog_steps_mm[step_index_]; }

  ControllerMoves& moves_;
  const MachineFile& machine_file_;
  OperatorSession& operator_session_;
  double feed_mm_per_s_;
  std::ostream& out_;
  link::ConsoleKeyDecoder decoder_;
  std::deque<link::ConsoleKey> keys_;
  std::size_t step_index_ = 1;  // console_jog_steps_mm: 1 mm
  bool stopped_by_signal_ = false;
};

/// The controller's status as a grbl-style line: `<Idle|MPos:2,0,0|Setpoint:512|Switches:x-,y+|Step:1>`.
[[nodiscard]] std::string format_console_status(const protocol::StatusReport& status, double step_mm);

}  // namespace curvestep::host
