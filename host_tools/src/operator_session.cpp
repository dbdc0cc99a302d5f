// SPDX-License-Identifier: MIT
#include "operator_session.hpp"

#include <cstdio>
#include <iostream>
#include <sstream>
#include <utility>
#include <unistd.h>

#include <curvestep/host/csv.hpp>
#include <curvestep/host/link/tick_timing_text.hpp>

namespace curvestep::host {
namespace {

/// "40/400", or "120/?" while the total is not known (pieces after a hold or override changed the plan).
std::string sent_of_total(const link::StreamProgress& p) {
  return std::to_string(p.sent) + "/" + (p.total > 0 ? std::to_string(p.total) : std::string("?"));
}

}  // namespace

OperatorSession::OperatorSession(std::string command, bool keys_from_stdin)
    : command_(std::move(command)), console_(keys_from_stdin), terminal_(isatty(STDERR_FILENO) != 0) {
  if (console_.reads_keys() && terminal_) std::cerr << command_ << ": " << link::OperatorConsole::key_help() << "\n";
}

void OperatorSession::attach(link::StreamOptions& options) {
  options.operator_command = [this] { return next_command(); };
  options.progress = [this](const link::StreamProgress& p) { draw(p); };
}

link::StreamOptions OperatorSession::abortable_moves(unsigned link_timeout_ms) {
  console_.set_interrupt_aborts(true);
  link::StreamOptions options;
  options.link.link_timeout_ms = link_timeout_ms;
  options.warn = [command = command_](const std::string& text) { std::cerr << command << ": warning: " << text << "\n"; };
  attach(options);
  return options;
}

link::OperatorCommand OperatorSession::next_command() {
  const link::OperatorCommand command = console_.poll();
  if (command != link::OperatorCommand::Status) return command;
  // grbl's status line: <State|MPos:x,y,z|Setpoint:n>
  std::ostringstream line;
  line << "<" << last_.state;
  if (last_.have_status) {
    line << "|MPos:" << format_number(last_.position_mm[0]) << "," << format_number(last_.position_mm[1]) << ","
         << format_number(last_.position_mm[2]) << "|Setpoint:" << last_.setpoint_index << "|Controller:" << last_.machine_state;
    if (last_.tick_overruns != 0) line << "|Overruns:" << last_.tick_overruns;
  }
  line << "|Ov:" << last_.override_percent.feed_percent << "," << last_.override_percent.rapid_percent;
  line << "|" << last_.unit << ":" << sent_of_total(last_) << ">";
  end_line();
  std::cerr << line.str() << "\n" << std::flush;
  return link::OperatorCommand::None;
}

void OperatorSession::draw(const link::StreamProgress& p) {
  last_ = p;
  if (!terminal_) return;
  std::cerr << "\r  " << p.state << "  feed " << p.override_percent.feed_percent << "% rapid " << p.override_percent.rapid_percent
            << "%  " << p.unit << " " << sent_of_total(p) << "  setpoints " << p.setpoints_received
            << "  elapsed " << format_seconds(p.elapsed_s) << "  ETA " << format_seconds(p.eta_s);
  if (p.tick_overruns != 0) std::cerr << "  tick overruns " << p.tick_overruns;
  std::cerr << "   " << std::flush;
}

void OperatorSession::warn_tick_overruns(const link::StreamResult& result, double rate_hz) const {
  std::cerr << link::tick_overrun_warning(command_, result.tick_overruns, result.worst_tick_us, rate_hz);
}

void OperatorSession::end_line() const {
  if (terminal_) std::cerr << "\n";
}

void add_start_override_options(CLI::App& command, StartOverride& start) {
  command
      .add_option("--feed-override", start.feed_percent,
                  "Feed override at the start, percent of the programmed feed (10..200; keys change it while the job runs)")
      ->check(CLI::Range(FeedOverride::min_feed_percent, FeedOverride::max_feed_percent));
  command.add_option("--rapid-override", start.rapid_percent, "Rapid override at the start, percent of the rapid speed (10..100)")
      ->check(CLI::Range(FeedOverride::min_rapid_percent, FeedOverride::max_rapid_percent));
}

std::string format_seconds(double s) {
  if (s < 0) return "--:--";
  const long total = static_cast<long>(s + 0.5);
  char text[32];
  std::snprintf(text, sizeof text, "%ld:%02ld", total / 60, total % 60);
  return text;
}

std::string format_operator_summary(const link::StreamResult& result, double rate_hz) {
  std::ostringstream out;
  out << link::format_tick_timing(result.tick_overruns, result.worst_tick_us, rate_hz);
  if (!result.holds.empty()) {
    out << "  feed holds:          " << result.holds.size();
    for (const link::StreamHold& hold : result.holds) {
      out << "\n                       " << (hold.tick == 0 ? "before the job began moving" : "before setpoint " + std::to_string(hold.tick));
      if (hold.standing_ticks) {
        out << ", stood " << *hold.standing_ticks << " ticks, resumed";
      } else {
        out << ", not resumed";
      }
    }
    out << "\n";
  }
  if (!result.overrides.empty()) {
    out << "  overrides:           " << result.overrides.size();
    for (const link::StreamOverride& o : result.overrides) {
      out << "\n                       feed " << o.value.feed_percent << " %, rapid " << o.value.rapid_percent << " % "
          << (o.tick == 0 ? "from the start" : "before setpoint " + std::to_string(o.tick));
    }
    out << "\n";
  }
  std::string replay = link::hold_at_option(result.holds, rate_hz);
  const std::string overrides = link::override_at_option(result.overrides, rate_hz);
  if (!overrides.empty()) replay += (replay.empty() ? "" : " ") + overrides;
  if (!replay.empty() && !result.aborted) out << "  replay:              curvestep sim " << replay << " gives the same setpoints\n";
  if (result.aborted) {
    out << "  aborted:             by the operator at setpoint " << result.final_setpoint_index << ", position ";
    for (std::size_t a = 0; a < 3; ++a) out << (a == 0 ? "" : " ") << "xyz"[a] << " " << format_number(result.final_position_q16[a] / 65536.0);
    out << " mm\n";
  }
  return out.str();
}

}  // namespace curvestep::host
