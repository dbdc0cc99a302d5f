// SPDX-License-Identifier: MIT
// GpiodStepOutput: step/dir edges on Linux GPIO lines through libgpiod v1 (Debian 12: 1.6).
//
// It satisfies the core's StepOutput concept (set_direction, set_step with absolute step-timer
// times), the same interface as RecordingStepOutput, so the waveform the firmware produces is
// tested with the recorder and only the pin writes differ. Each edge is written at its time:
// the output sleeps (clock_nanosleep, absolute CLOCK_MONOTONIC deadline) until the EdgeClock's
// deadline (epoch + time, re-based after a pause: edge_clock.hpp), then sets the line; in fast
// mode (tests) it does not sleep. Opening fails with a GpioError
// naming the chip or the line that was not found; a failed write in the tick path is counted,
// never thrown.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <ctime>
#include <stdexcept>
#include <string>

#include <curvestep/boards/host/edge_clock.hpp>

struct gpiod_chip;
struct gpiod_line;

namespace curvestep::boards::host {

/// A GPIO chip or line could not be opened; the message names it.
class GpioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Which lines drive the axes: a chip (name, path or number as gpiod_chip_open_lookup takes
/// it) and, per axis, the names of its step and direction lines (empty: axis not wired).
struct GpioLines {
  std::string chip;                       ///< "gpiochip0", "/dev/gpiochip0" or "0"
  std::array<std::string, 3> step{};      ///< step line names of x, y, z
  std::array<std::string, 3> direction{};  ///< direction line names of x, y, z
  bool invert_direction[3] = {false, false, false};  ///< positive = low on this axis
  std::array<std::string, 3> min_switch{};  ///< limit switch input line names at x, y, z min (empty: none)
  std::array<std::string, 3> max_switch{};  ///< limit switch input line names at x, y, z max (empty: none)
  bool switches_active_low = false;         ///< a closed switch reads low (a switch to ground with a pull-up)
};

/// Step/dir output on GPIO lines.
class GpiodStepOutput {
 public:
  /// Opens the chip and requests every named line as an output, low. Throws GpioError. An edge
  /// more than `late_limit_ns` late re-bases the edge clock (EdgeClock).
  GpiodStepOutput(const GpioLines& lines, std::uint32_t timer_hz,
                  std::int64_t late_limit_ns = EdgeClock::default_late_limit_ns);
  ~GpiodStepOutput();
  GpiodStepOutput(const GpiodStepOutput&) = delete;
  GpiodStepOutput& operator=(const GpiodStepOutput&) = delete;

  /// Sets the direction line of `axis` at `time_ticks`.
  void set_direction(std::uint64_t time_ticks, std::uint8_t axis, bool positive) noexcept;
  /// Sets the step line of `axis` at `time_ticks`.
  void set_step(std::uint64_t time_ticks, std::uint8_t axis, bool high) noexcept;
  /// Step lines low at once (abort, fault).
  void fault_stop() noexcept;
  /// The limit switches closed now (bit 2 x axis min, 2 x axis + 1 max; firmware/limit_switches.hpp).
  /// A failed read counts as closed: a switch that cannot be read cannot be trusted to be open.
  [[nodiscard]] std::uint8_t limit_switches() noexcept;
  /// Step-timer time 0 is `epoch` (CLOCK_MONOTONIC); fast: write edges without waiting.
  void set_epoch(const timespec& epoch, bool fast) noexcept;
  /// Line writes that failed.
  [[nodiscard]] std::size_t write_errors() const noexcept { return write_errors_; }
  /// Times the edge clock was re-based (an edge came late: after a pause, or the loop fell behind).
  [[nodiscard]] std::size_t rebases() const noexcept { return clock_.rebases(); }

 private:
  void wait_until(std::uint64_t time_ticks) noexcept;
  void write(gpiod_line* line, bool level) noexcept;

  gpiod_chip* chip_ = nullptr;
  std::array<gpiod_line*, 3> step_{};
  std::array<gpiod_line*, 3> direction_{};
  std::array<bool, 3> invert_{};
  std::array<gpiod_line*, 6> switch_{};  ///< input lines by switch bit (null: no switch)
  bool switches_active_low_ = false;
  EdgeClock clock_;
  bool fast_ = false;
  std::size_t write_errors_ = 0;
};

}  // namespace curvestep::boards::host
