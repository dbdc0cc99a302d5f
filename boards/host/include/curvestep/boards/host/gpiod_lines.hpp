// SPDX-License-Identifier: MIT
// GpiodLineSet: numbered output lines on one GPIO chip through libgpiod v1, for the machine
// outputs (machine_outputs.hpp). Opening requests every named line as an output, low, and fails
// with a GpioError naming the chip, or the line and its role ("GPIO line \"GPIO5\" (spindle
// enable) not found on chip \"gpiochip0\""), before anything moves. set() on a line that is not
// wired does nothing; a failed write is counted, never thrown. Lines may be set from different
// threads (libgpiod v1 requests each line with its own file descriptor).
#pragma once

#include <atomic>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <curvestep/boards/host/gpio_output.hpp>  // GpioError

struct gpiod_chip;
struct gpiod_line;

namespace curvestep::boards::host {

/// Output lines on one chip, numbered in the order given.
class GpiodLineSet {
 public:
  /// Opens `chip` and requests each named line of `lines` (name, role; an empty name: not wired).
  /// Throws GpioError.
  GpiodLineSet(const std::string& chip, const std::vector<std::pair<std::string, std::string>>& lines);
  /// Every line low, then released.
  ~GpiodLineSet();
  GpiodLineSet(const GpiodLineSet&) = delete;
  GpiodLineSet& operator=(const GpiodLineSet&) = delete;

  /// Drives line `index` (no-op for a line that is not wired or out of range).
  void set(std::size_t index, bool high) noexcept;
  /// Line writes that failed.
  [[nodiscard]] std::size_t write_errors() const noexcept { return write_errors_.load(std::memory_order_relaxed); }

 private:
  gpiod_chip* chip_ = nullptr;
  std::vector<gpiod_line*> lines_;
  std::atomic<std::size_t> write_errors_{0};
};

}  // namespace curvestep::boards::host
