// SPDX-License-Identifier: MIT
#include "gpio_wiring.hpp"

#include <stdexcept>

#include <curvestep/host/csv.hpp>

namespace curvestep::host {

boards::host::GpioLines step_lines(const GpioWiring& gpio, const std::string& chip) {
  boards::host::GpioLines lines;
  lines.chip = chip.empty() ? gpio.chip : chip;
  for (std::size_t a = 0; a < motion_axes; ++a) {
    if (!gpio.axes[a]) continue;
    lines.step[a] = gpio.axes[a]->step;
    lines.direction[a] = gpio.axes[a]->dir;
    lines.invert_direction[a] = gpio.axes[a]->invert_dir;
  }
  return lines;
}

boards::host::MachineOutputLines output_lines(const GpioWiring& gpio, const std::optional<PenModel>& pen, const std::string& chip) {
  boards::host::MachineOutputLines lines;
  lines.chip = chip.empty() ? gpio.chip : chip;
  lines.spindle_enable = gpio.spindle_enable;
  lines.spindle_direction = gpio.spindle_direction;
  lines.coolant_mist = gpio.coolant_mist;
  lines.coolant_flood = gpio.coolant_flood;
  lines.outputs = gpio.outputs;
  if (pen && pen->servo) lines.servo = pen->line;
  return lines;
}

void check_digital_outputs(const Job& job, const GpioWiring& gpio) {
  for (const JobEvent& event : job.events) {
    if (event.kind != JobEventKind::DigitalOutput || event.value < static_cast<double>(gpio.outputs.size())) continue;
    const std::string wired = gpio.outputs.empty() ? "none (\"gpio\".\"outputs\" is absent)"
                                                   : "0 .. " + std::to_string(gpio.outputs.size() - 1);
    throw std::runtime_error(job.name + (event.line > 0 ? ":" + std::to_string(event.line) : std::string{}) + ": " + event.text +
                             ": digital output " + format_number(event.value) + " has no line in the machine file (wired: " +
                             wired + ")");
  }
}

}  // namespace curvestep::host
