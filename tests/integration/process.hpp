// SPDX-License-Identifier: MIT
// Test helper: runs `curvestep` subcommands as child processes (stdout through a pipe, stderr to
// a file), reads the first line a server prints, waits with a time limit and stops only its own
// children (by pid).
#pragma once

#include <chrono>
#include <csignal>
#include <cstdio>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <poll.h>
#include <sstream>
#include <stdexcept>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace curvestep::test {

/// A scratch directory unique to this process, removed at exit.
inline const std::filesystem::path& scratch_dir() {
  static const struct Dir {
    std::filesystem::path path;
    Dir() : path(std::filesystem::temp_directory_path() / ("curvestep-hil-" + std::to_string(::getpid()))) {
      std::filesystem::create_directories(path);
    }
    ~Dir() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  } dir;
  return dir.path;
}

/// One child process running `curvestep` with `arguments`.
class Process {
 public:
  /// `stdin_fd` >= 0 becomes the child's standard input (a pty's slave: a terminal to type keys
  /// into); otherwise it reads /dev/null.
  explicit Process(const std::vector<std::string>& arguments, const std::string& stderr_name, int stdin_fd = -1) {
    stderr_path_ = scratch_dir() / stderr_name;
    // Everything the child needs is made here: between fork and exec a child of a threaded process
    // (a test's relay thread) may only make async-signal-safe calls, no allocation (with the
    // sanitizers' allocator a child that allocated there died at once, now and then).
    std::string program = CURVESTEP_PROGRAM;
    std::vector<std::string> copy = arguments;
    std::vector<char*> argv;
    argv.push_back(program.data());
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    const std::string stderr_file = stderr_path_.string();
    int out[2];
    if (::pipe(out) != 0) throw std::runtime_error("pipe failed");
    pid_ = ::fork();
    if (pid_ < 0) throw std::runtime_error("fork failed");
    if (pid_ == 0) {
      ::dup2(out[1], STDOUT_FILENO);
      const int err = ::open(stderr_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (err >= 0) ::dup2(err, STDERR_FILENO);
      // Never the test runner's terminal: a child that reads operator keys would take it over.
      const int in = stdin_fd >= 0 ? stdin_fd : ::open("/dev/null", O_RDONLY);
      if (in >= 0) ::dup2(in, STDIN_FILENO);
      ::close(out[0]);
      ::execv(program.c_str(), argv.data());
      ::_exit(127);
    }
    ::close(out[1]);
    stdout_fd_ = out[0];
  }
  ~Process() {
    if (pid_ > 0 && !exited_) {
      ::kill(pid_, SIGTERM);
      wait(std::chrono::seconds(5));
      if (!exited_) {
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, nullptr, 0);
      }
    }
    if (stdout_fd_ >= 0) ::close(stdout_fd_);
  }
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;

  /// The first line the child prints on stdout (waits up to `limit`).
  std::string first_line(std::chrono::milliseconds limit = std::chrono::seconds(10)) {
    const auto end = std::chrono::steady_clock::now() + limit;
    std::string line;
    while (std::chrono::steady_clock::now() < end) {
      pollfd p{stdout_fd_, POLLIN, 0};
      if (::poll(&p, 1, 50) <= 0) continue;
      char c = 0;
      if (::read(stdout_fd_, &c, 1) != 1) break;
      if (c == '\n') return line;
      line += c;
    }
    throw std::runtime_error("no first line from curvestep (stderr: " + stderr_text() + ")");
  }
  /// Waits up to `limit` for the exit; returns the exit status (-1 if still running).
  int wait(std::chrono::milliseconds limit) {
    const auto end = std::chrono::steady_clock::now() + limit;
    while (!exited_) {
      int status = 0;
      const pid_t r = ::waitpid(pid_, &status, WNOHANG);
      if (r == pid_) {
        exited_ = true;
        status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        break;
      }
      if (std::chrono::steady_clock::now() >= end) return -1;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return status_;
  }
  /// Asks the child to stop (SIGTERM) and waits.
  int stop() {
    if (!exited_) ::kill(pid_, SIGTERM);
    return wait(std::chrono::seconds(10));
  }
  /// The child's process id.
  [[nodiscard]] pid_t pid() const noexcept { return pid_; }
  /// Everything the child wrote to stderr so far.
  [[nodiscard]] std::string stderr_text() const {
    std::ifstream in(stderr_path_);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  /// The rest of stdout (after exit).
  std::string rest_of_stdout() {
    std::string text;
    char buffer[4096];
    for (;;) {
      pollfd p{stdout_fd_, POLLIN, 0};
      if (::poll(&p, 1, 0) <= 0) break;
      const ssize_t n = ::read(stdout_fd_, buffer, sizeof buffer);
      if (n <= 0) break;
      text.append(buffer, static_cast<std::size_t>(n));
    }
    return text;
  }

 private:
  pid_t pid_ = -1;
  int stdout_fd_ = -1;
  bool exited_ = false;
  int status_ = -1;
  std::filesystem::path stderr_path_;
};

/// Runs `curvestep` with `arguments` to the end (at most `limit`); returns the exit status, and
/// stderr in `error_text`.
inline int run_program(const std::vector<std::string>& arguments, std::string& error_text, const std::string& name,
                       std::chrono::milliseconds limit = std::chrono::seconds(120), std::string* output = nullptr) {
  Process p(arguments, name + ".stderr");
  const int status = p.wait(limit);
  error_text = p.stderr_text();
  if (output != nullptr) *output = p.rest_of_stdout();
  return status;
}

}  // namespace curvestep::test
