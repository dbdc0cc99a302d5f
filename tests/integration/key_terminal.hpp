// SPDX-License-Identifier: MIT
// HIL helpers for operator tests: a pseudo-terminal to type keys into a streamer's stdin, a pipe
// of keys for a command run with --keys, and a wait for a line in the device's log.
#pragma once

#include <chrono>
#include <cstdlib>
#include <fcntl.h>
#include <string>
#include <termios.h>
#include <thread>
#include <unistd.h>

#include <catch2/catch.hpp>

#include "process.hpp"

namespace curvestep::test {

/// A terminal for the streamer's stdin: a pty pair in the kernel's default (cooked) mode.
class KeyTerminal {
 public:
  KeyTerminal() {
    master_ = ::posix_openpt(O_RDWR | O_NOCTTY);
    REQUIRE(master_ >= 0);
    REQUIRE(::grantpt(master_) == 0);
    REQUIRE(::unlockpt(master_) == 0);
    slave_ = ::open(::ptsname(master_), O_RDWR | O_NOCTTY);
    REQUIRE(slave_ >= 0);
  }
  ~KeyTerminal() {
    ::close(slave_);
    ::close(master_);
  }
  KeyTerminal(const KeyTerminal&) = delete;
  KeyTerminal& operator=(const KeyTerminal&) = delete;
  [[nodiscard]] int slave() const { return slave_; }
  void type(const std::string& keys) const { REQUIRE(::write(master_, keys.data(), keys.size()) == static_cast<ssize_t>(keys.size())); }
  /// The slave's local mode flags (ICANON, ECHO, ...).
  [[nodiscard]] tcflag_t local_mode() const {
    termios mode{};
    REQUIRE(::tcgetattr(slave_, &mode) == 0);
    return mode.c_lflag;
  }

 private:
  int master_ = -1;
  int slave_ = -1;
};

/// Keys for a command's standard input through a pipe (not a terminal: the command needs --keys):
/// the whole script is written at once and the pipe closed, so the command reads its end.
class KeyPipe {
 public:
  explicit KeyPipe(const std::string& keys) {
    int ends[2];
    REQUIRE(::pipe(ends) == 0);
    REQUIRE(::write(ends[1], keys.data(), keys.size()) == static_cast<ssize_t>(keys.size()));
    ::close(ends[1]);
    read_end_ = ends[0];
  }
  ~KeyPipe() { ::close(read_end_); }
  KeyPipe(const KeyPipe&) = delete;
  KeyPipe& operator=(const KeyPipe&) = delete;
  /// The end to give the command as its standard input.
  [[nodiscard]] int read_end() const { return read_end_; }

 private:
  int read_end_ = -1;
};

/// Waits up to 20 s for `text` in the device's log (its state changes: "running at tick", "holding at tick").
inline bool wait_for_log(const Process& device, const std::string& text, std::size_t after = 0) {
  for (int i = 0; i < 1000; ++i) {
    if (device.stderr_text().find(text, after) != std::string::npos) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

}  // namespace curvestep::test
