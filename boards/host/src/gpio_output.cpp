// SPDX-License-Identifier: MIT
#include <curvestep/boards/host/gpio_output.hpp>

#include <gpiod.h>

#include <curvestep/boards/host/monotonic_time.hpp>

#include "gpiod_request.hpp"

namespace curvestep::boards::host {

GpiodStepOutput::GpiodStepOutput(const GpioLines& lines, std::uint32_t timer_hz, std::int64_t late_limit_ns)
    : clock_(timer_hz, late_limit_ns) {
  chip_ = detail::open_chip(lines.chip);
  const char* axis_names[] = {"x", "y", "z"};
  const auto request = [this, &lines, &axis_names](const std::string& name, const char* role, std::size_t axis) -> gpiod_line* {
    if (name.empty()) return nullptr;
    return detail::request_output_line(chip_, lines.chip, name, std::string(axis_names[axis]) + " " + role);
  };
  try {
    for (std::size_t axis = 0; axis < 3; ++axis) {
      step_[axis] = request(lines.step[axis], "step", axis);
      direction_[axis] = request(lines.direction[axis], "direction", axis);
      invert_[axis] = lines.invert_direction[axis];
    }
  } catch (...) {
    gpiod_chip_close(chip_);  // also releases the lines requested so far
    throw;
  }
  clock_.set_epoch(to_nanoseconds(monotonic_now()));
}

GpiodStepOutput::~GpiodStepOutput() {
  fault_stop();
  gpiod_chip_close(chip_);
}

void GpiodStepOutput::set_epoch(const timespec& epoch, bool fast) noexcept {
  clock_.set_epoch(to_nanoseconds(epoch));
  fast_ = fast;
}

void GpiodStepOutput::wait_until(std::uint64_t time_ticks) noexcept {
  if (fast_) return;
  const std::int64_t now = to_nanoseconds(monotonic_now());
  const std::int64_t due = clock_.deadline_ns(time_ticks, now);
  if (due > now) sleep_until(to_timespec(due));
}

void GpiodStepOutput::write(gpiod_line* line, bool level) noexcept {
  if (line == nullptr) return;
  if (gpiod_line_set_value(line, level ? 1 : 0) != 0) ++write_errors_;
}

void GpiodStepOutput::set_direction(std::uint64_t time_ticks, std::uint8_t axis, bool positive) noexcept {
  if (axis >= 3) return;
  wait_until(time_ticks);
  write(direction_[axis], positive != invert_[axis]);
}

void GpiodStepOutput::set_step(std::uint64_t time_ticks, std::uint8_t axis, bool high) noexcept {
  if (axis >= 3) return;
  wait_until(time_ticks);
  write(step_[axis], high);
}

void GpiodStepOutput::fault_stop() noexcept {
  for (gpiod_line* line : step_) write(line, false);
}

}  // namespace curvestep::boards::host
