// SPDX-License-Identifier: MIT
#include <curvestep/host/link/operator_keys.hpp>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <poll.h>
#include <unistd.h>

namespace curvestep::host::link {
namespace {

std::atomic<int> interrupts_received{0};
std::atomic<bool> terminate_received{false};
struct sigaction saved_interrupt {};
struct sigaction saved_terminate {};

extern "C" void on_operator_signal(int signal_number) {
  if (signal_number == SIGINT) interrupts_received.fetch_add(1);
  if (signal_number == SIGTERM) terminate_received.store(true);
}

void install(int signal_number, struct sigaction& saved) {
  struct sigaction action {};
  action.sa_handler = on_operator_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  ::sigaction(signal_number, &action, &saved);
}

constexpr char ctrl_x = 0x18;
constexpr char escape = 0x1b;

/// The override keys: ] [ feed ±10 %, } { ±1 %, = 100 %; ( ) * rapid 25 / 100 / 50 %; and grbl's
/// real-time bytes 0x90 .. 0x97 (feed 100 %, +10, −10, +1, −1, rapid 100, 50, 25 %) a sender may pipe.
OperatorCommand override_key(char key) {
  switch (static_cast<unsigned char>(key)) {
    case ']': case 0x91: return OperatorCommand::FeedPlus10;
    case '[': case 0x92: return OperatorCommand::FeedMinus10;
    case '}': case 0x93: return OperatorCommand::FeedPlus1;
    case '{': case 0x94: return OperatorCommand::FeedMinus1;
    case '=': case 0x90: return OperatorCommand::FeedReset;
    case ')': case 0x95: return OperatorCommand::RapidFull;
    case '*': case 0x96: return OperatorCommand::RapidHalf;
    case '(': case 0x97: return OperatorCommand::RapidQuarter;
    default: return OperatorCommand::None;
  }
}

}  // namespace

OperatorConsole::OperatorConsole(bool keys_from_stdin, int input_fd, int output_fd) : output_fd_(output_fd) {
  interrupts_received.store(0);
  terminate_received.store(false);
  install(SIGINT, saved_interrupt);
  install(SIGTERM, saved_terminate);
  const bool terminal = ::isatty(input_fd) != 0;
  if (!terminal && !keys_from_stdin) return;
  // A job in the background (`curvestep stream ... &`) leaves the terminal alone: changing its
  // mode or reading it would stop the process (SIGTTOU, SIGTTIN).
  // (A terminal that is not the controlling one has no foreground group: tcgetpgrp fails.)
  const pid_t foreground = terminal ? ::tcgetpgrp(input_fd) : -1;
  if (foreground > 0 && foreground != ::getpgrp()) return;
  input_fd_ = input_fd;
  if (terminal && ::tcgetattr(input_fd, &saved_mode_) == 0) {
    termios raw = saved_mode_;
    raw.c_lflag &= ~static_cast<tcflag_t>(ICANON | ECHO);  // ISIG stays: Ctrl-C is SIGINT
    raw.c_cc[VMIN] = 0;
    raw.c_cc[VTIME] = 0;
    raw_mode_ = ::tcsetattr(input_fd, TCSANOW, &raw) == 0;
  }
}

OperatorConsole::~OperatorConsole() {
  if (raw_mode_) ::tcsetattr(input_fd_, TCSANOW, &saved_mode_);
  ::sigaction(SIGINT, &saved_interrupt, nullptr);
  ::sigaction(SIGTERM, &saved_terminate, nullptr);
}

std::string_view OperatorConsole::key_help() noexcept {
  return "keys: ! feed hold, ~ resume, Ctrl-X or Esc abort, ? status; ] [ feed +/-10 %, } { +/-1 %, = feed 100 %, "
         "( ) * rapid 25/100/50 %; Ctrl-C holds and asks, twice aborts";
}

void OperatorConsole::ask(std::string_view question) {
  question_open_ = true;
  write_line(question);
}

void OperatorConsole::write_line(std::string_view text) const {
  std::string line = "\n";
  line.append(text);
  line += "\n";
  [[maybe_unused]] const auto written = ::write(output_fd_, line.data(), line.size());
}

OperatorCommand OperatorConsole::poll() {
  const OperatorCommand signalled_command = poll_signals();
  if (signalled_command != OperatorCommand::None) return signalled_command;
  if (pending_.empty()) read_keys();
  if (pending_.empty()) return OperatorCommand::None;
  const OperatorCommand next = pending_.front();
  pending_.pop_front();
  return next;
}

OperatorCommand OperatorConsole::poll_signals() {
  if (terminate_received.load() && !terminate_seen_) {
    terminate_seen_ = true;
    return OperatorCommand::Abort;
  }
  const int interrupts = interrupts_received.load();
  if (interrupts <= signals_seen_) return OperatorCommand::None;
  signals_seen_ = interrupts;
  if (question_open_ || interrupt_aborts_) {  // a second Ctrl-C before the answer
    question_open_ = false;
    return OperatorCommand::Abort;
  }
  ask(reads_keys() ? "Feed hold (Ctrl-C). Resume: ~, r or Enter; abort: Ctrl-X, Esc, a or Ctrl-C again."
                   : "Feed hold (Ctrl-C). Abort: Ctrl-C again or SIGTERM (keys are not read: stdin is no terminal, see --keys).");
  return OperatorCommand::Hold;
}

std::string OperatorConsole::read_bytes() {
  char bytes[256];
  return std::string(bytes, read_available(bytes, sizeof bytes));
}

std::size_t OperatorConsole::read_available(char* bytes, std::size_t capacity) {
  if (input_fd_ < 0) return 0;
  pollfd p{input_fd_, POLLIN, 0};
  if (::poll(&p, 1, 0) <= 0) return 0;
  const ssize_t count = ::read(input_fd_, bytes, capacity);
  if (count == 0 || (count < 0 && errno != EAGAIN && errno != EINTR)) {
    input_fd_ = -1;  // end of input: no more keys
    return 0;
  }
  return count < 0 ? 0 : static_cast<std::size_t>(count);
}

void OperatorConsole::read_keys() {
  char bytes[64];
  const std::size_t count = read_available(bytes, sizeof bytes);
  for (std::size_t k = 0; k < count; ++k) take_key(bytes, count, k);
}

void OperatorConsole::take_key(const char* bytes, std::size_t count, std::size_t& k) {
  const char key = bytes[k];
  if (key == escape && k + 1 < count && (bytes[k + 1] == '[' || bytes[k + 1] == 'O')) {
    // An arrow or function key: skip to the sequence's final byte (0x40 .. 0x7E after the introducer).
    k += 2;
    while (k < count && !(bytes[k] >= 0x40 && bytes[k] <= 0x7e)) ++k;
    return;
  }
  OperatorCommand command = OperatorCommand::None;
  if (key == '!') command = OperatorCommand::Hold;
  if (key == '~') command = OperatorCommand::Resume;
  if (key == ctrl_x || key == escape) command = OperatorCommand::Abort;
  if (key == '?') command = OperatorCommand::Status;
  const OperatorCommand override_command = override_key(key);
  if (override_command != OperatorCommand::None) command = override_command;
  if (question_open_ && (key == '\r' || key == '\n' || key == 'r' || key == 'R')) command = OperatorCommand::Resume;
  if (question_open_ && (key == 'a' || key == 'A')) command = OperatorCommand::Abort;
  if (command == OperatorCommand::Resume || command == OperatorCommand::Abort) question_open_ = false;
  if (command != OperatorCommand::None) pending_.push_back(command);
}

}  // namespace curvestep::host::link
