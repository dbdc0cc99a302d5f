// SPDX-License-Identifier: MIT
// Running the real curvestep program and reading files, for the plot and report tests.
#pragma once

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>

namespace report_test {

/// Exit status and everything the command printed (stdout and stderr).
struct Run {
  int status = -1;
  std::string output;
};

/// Runs a shell command line; stderr goes to the same pipe as stdout.
inline Run run_command(const std::string& command) {
  Run r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  REQUIRE(pipe != nullptr);
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) r.output += buffer;
  const int raw = pclose(pipe);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

/// Runs `curvestep <arguments>`.
inline Run run_curvestep(const std::string& arguments) { return run_command(std::string(CURVESTEP_BINARY) + " " + arguments); }

/// A file of the source tree.
inline std::string source(const std::string& relative) { return std::string(CURVESTEP_SOURCE_DIR) + "/" + relative; }

/// A scratch path for this suite, unique to this process: CTest runs test cases in parallel.
inline std::string scratch(const std::string& name) {
  return "/tmp/curvestep_report_test_" + std::to_string(::getpid()) + "_" + name;
}

/// The whole content of a file ("" if it cannot be read).
inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Number of times `needle` occurs in `text`.
inline std::size_t count(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (auto at = text.find(needle); at != std::string::npos; at = text.find(needle, at + needle.size())) ++n;
  return n;
}

}  // namespace report_test
