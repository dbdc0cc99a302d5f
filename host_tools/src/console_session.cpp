// SPDX-License-Identifier: MIT
#include "console_session.hpp"

#include <chrono>
#include <iostream>
#include <string>
#include <thread>

#include <curvestep/host/csv.hpp>
#include <curvestep/host/link/streamer.hpp>
#include <curvestep/host/load_error.hpp>

#include "homing_cycle.hpp"

namespace curvestep::host {
namespace {

/// "X+1"-style name of a jog.
std::string jog_name(const link::JogDirection& d, double step_mm) {
  return std::string(1, "XYZ"[d.axis]) + (d.sign > 0 ? "+" : "-") + format_number(step_mm);
}

}  // namespace

ConsoleSession::ConsoleSession(ControllerMoves& moves, const MachineFile& machine_file, OperatorSession& operator_session,
                               double feed_mm_per_s, std::ostream& out)
    : moves_(moves), machine_file_(machine_file), operator_session_(operator_session), feed_mm_per_s_(feed_mm_per_s), out_(out) {}

int ConsoleSession::run() {
  out_ << "  at " << format_position(moves_.position_mm()) << " mm, jog step " << format_number(console_step()) << " mm" << std::endl;
  for (;;) {
    const link::ConsoleKey key = next_key();
    if (stopped_by_signal_) return exit_aborted;
    switch (key) {
      case link::ConsoleKey::Quit: return 0;
      case link::ConsoleKey::Status: print_status(); break;
      case link::ConsoleKey::NextStep:
        step_index_ = (step_index_ + 1) % std::size(link::console_jog_steps_mm);
        out_ << "  jog step " << format_number(console_step()) << " mm" << std::endl;
        break;
      case link::ConsoleKey::Home: home(); break;
      case link::ConsoleKey::Abort: out_ << "  nothing to abort: the controller stands" << std::endl; break;
      default: jog(key); break;
    }
    if (stopped_by_signal_) return exit_aborted;
  }
}

link::ConsoleKey ConsoleSession::next_key() {
  link::OperatorConsole& console = operator_session_.console();
  for (;;) {
    if (console.poll_signals() != link::OperatorCommand::None) {
      out_ << "  interrupted: the controller stands; bye" << std::endl;
      return link::ConsoleKey::Quit;
    }
    if (keys_.empty()) {
      for (const link::ConsoleKey key : decoder_.decode(console.read_bytes())) keys_.push_back(key);
    }
    if (!keys_.empty()) {
      const link::ConsoleKey key = keys_.front();
      keys_.pop_front();
      return key;
    }
    if (!console.reads_keys()) return link::ConsoleKey::Quit;  // the keys ended
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

void ConsoleSession::jog(link::ConsoleKey key) {
  const link::JogDirection direction = link::jog_direction(key);
  std::array<double, 3> distance{};
  distance[direction.axis] = direction.sign * console_step();
  const std::string name = "jog " + jog_name(direction, console_step());
  try {
    const link::StreamResult result = moves_.jog(distance, feed_mm_per_s_);
    operator_session_.end_line();
    if (result.aborted) {
      out_ << "  " << name << " aborted: the controller stopped at once at " << format_position(moves_.position_mm()) << " mm" << std::endl;
      stopped_by_signal_ = operator_session_.console().signalled();
      return;
    }
    out_ << "  " << name << ": at " << format_position(moves_.position_mm()) << " mm" << std::endl;
  } catch (const LoadError& e) {
    out_ << "  " << name << " refused, nothing moved: " << e.what() << std::endl;
  } catch (const link::StreamError& e) {
    report_failure(e);
  }
}

void ConsoleSession::home() {
  if (!machine_file_.homing) {
    out_ << "  no homing: " << machine_file_.name << " has no \"homing\" section (docs/job_format.md)" << std::endl;
    return;
  }
  out_ << "  homing" << std::endl;
  try {
    run_homing_cycle(moves_, *machine_file_.homing, {true, true, true}, out_);
    out_ << "  homed: at " << format_position(moves_.position_mm()) << " mm" << std::endl;
  } catch (const HomingAborted& e) {
    operator_session_.end_line();
    out_ << "  " << e.what() << std::endl;
    stopped_by_signal_ = operator_session_.console().signalled();
  } catch (const link::StreamError& e) {
    report_failure(e);
  } catch (const HomingSwitchError& e) {
    report_failure(e);
  }
}

void ConsoleSession::report_failure(const std::exception& e) {
  operator_session_.end_line();
  out_ << "  failed: " << e.what() << std::endl;
  moves_.refresh();  // a new session clears a fault; where it stands now
  out_ << "  at " << format_position(moves_.position_mm()) << " mm" << std::endl;
}

void ConsoleSession::print_status() {
  moves_.refresh();
  out_ << format_console_status(moves_.status(), console_step()) << std::endl;
}

std::string format_console_status(const protocol::StatusReport& status, double step_mm) {
  std::string state = protocol::machine_state_name(status.state);
  if (!state.empty()) state[0] = static_cast<char>(state[0] - 'a' + 'A');
  std::string line = "<" + state + "|MPos:";
  for (std::size_t a = 0; a < 3; ++a) line += (a == 0 ? "" : ",") + format_number(static_cast<double>(status.position[a]) / 65536.0);
  line += "|Setpoint:" + std::to_string(status.setpoint_index) + "|Switches:";
  std::string closed;
  for (unsigned bit = 0; bit < 6; ++bit) {
    if ((status.limit_switches & (1u << bit)) == 0) continue;
    closed += std::string(closed.empty() ? "" : ",") + "xyz"[bit / 2] + (bit % 2 == 0 ? "-" : "+");
  }
  return line + (closed.empty() ? "none" : closed) + "|Step:" + format_number(step_mm) + ">";
}

}  // namespace curvestep::host
