// SPDX-License-Identifier: MIT
// OperatorSession: the operator's side of a job streamed by `stream`, `gpio` and `jog`: keys and
// signals (link::OperatorConsole) into stream_job, the state on the progress line, a status line
// on `?`, and the summary lines of the controller's tick timing, holds and an abort.
#pragma once

#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

#include <curvestep/host/link/operator_keys.hpp>
#include <curvestep/host/link/streamer.hpp>

namespace curvestep::host {

/// Exit status of a job the operator aborted (Ctrl-X, Esc, a second Ctrl-C, SIGTERM).
constexpr int exit_aborted = 6;

/// Keys and signals for one streamed job; restores the terminal when it goes.
class OperatorSession {
 public:
  /// `command` names the program in messages ("curvestep stream"); keys are read from a terminal on
  /// stdin, or from any stdin with `keys_from_stdin` (--keys). The progress line is drawn on stderr
  /// if it is a terminal.
  OperatorSession(std::string command, bool keys_from_stdin);
  /// Sets options.operator_command and options.progress (the line with the state, the status on `?`).
  void attach(link::StreamOptions& options);
  /// Options for moves the operator stops at once (`jog`, `home`, `console`: nothing to resume, so
  /// Ctrl-C aborts instead of holding): attached, the link timeout set, warnings on stderr.
  [[nodiscard]] link::StreamOptions abortable_moves(unsigned link_timeout_ms);
  /// The keys and signals (ask() is the hook for a program pause that waits for the operator).
  [[nodiscard]] link::OperatorConsole& console() noexcept { return console_; }
  /// Ends the progress line (before other output).
  void end_line() const;
  /// Warns on stderr if the controller's ticks overran (StreamResult::tick_overruns), else nothing.
  void warn_tick_overruns(const link::StreamResult& result, double rate_hz) const;

 private:
  link::OperatorCommand next_command();
  void draw(const link::StreamProgress& p);

  std::string command_;
  link::OperatorConsole console_;
  bool terminal_ = false;
  link::StreamProgress last_{};
};

/// `--feed-override P` and `--rapid-override R` of `stream` and `gpio`: the override a job starts with.
struct StartOverride {
  unsigned feed_percent = 100;   ///< percent of the programmed feed, 10..200
  unsigned rapid_percent = 100;  ///< percent of the rapid speed, 10..100
  [[nodiscard]] FeedOverride value() const noexcept {
    return FeedOverride{static_cast<std::uint16_t>(feed_percent), static_cast<std::uint16_t>(rapid_percent)};
  }
};
/// Adds --feed-override and --rapid-override (range-checked) to `command`.
void add_start_override_options(CLI::App& command, StartOverride& start);
/// The help footer's line on the override keys.
inline constexpr const char* override_keys_footer =
    "feed override ] [ +/-10 %, } { +/-1 %, = 100 %; rapid override ( 25 %, * 50 %, ) 100 % (shown on the progress line;\n"
    "the summary prints the curvestep sim --override-at that replays them);\n";

/// "--:--" or "m:ss".
[[nodiscard]] std::string format_seconds(double s);

/// The summary lines of the controller's tick timing (always: "  tick overruns:       0 (worst
/// tick 42 us of the 1000 us period)\n") and of the operator's holds, overrides and abort (if any),
/// with the `curvestep sim` options that replay them ("  replay:              curvestep sim
/// --hold-at 1.234:0 gives the same setpoints").
[[nodiscard]] std::string format_operator_summary(const link::StreamResult& result, double rate_hz);

}  // namespace curvestep::host
