// SPDX-License-Identifier: MIT
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <unistd.h>

#include <curvestep/host/report.hpp>

namespace curvestep::host {

std::string format_progress_line(double fraction, double elapsed_s) {
  const double f = std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0);
  constexpr int width = 40;
  const int filled = static_cast<int>(f * width);
  std::string line = "  [" + std::string(static_cast<std::size_t>(filled), '#') + std::string(static_cast<std::size_t>(width - filled), ' ') +
                     "] " + std::to_string(static_cast<int>(f * 100)) + "%";
  if (f >= 0.01 && f < 1.0 && elapsed_s >= 0) {
    const double remaining = elapsed_s * (1.0 - f) / f;
    char eta[48];
    if (remaining < 60) {
      std::snprintf(eta, sizeof eta, "  ETA %.0f s", std::ceil(remaining));
    } else {
      const long total = std::lround(std::ceil(remaining));
      std::snprintf(eta, sizeof eta, "  ETA %ld min %02ld s", total / 60, total % 60);
    }
    line += eta;
  }
  return line;
}

std::function<void(double)> make_terminal_progress() {
  if (isatty(STDERR_FILENO) == 0) return {};
  const auto started = std::chrono::steady_clock::now();
  return [started](double fraction) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    // Pad so that a shorter line overwrites a longer one.
    std::cerr << "\r" << format_progress_line(fraction, elapsed) << "          " << std::flush;
  };
}

void finish_terminal_progress() {
  if (isatty(STDERR_FILENO) != 0) std::cerr << "\r" << std::string(72, ' ') << "\r" << std::flush;
}

}  // namespace curvestep::host
