// SPDX-License-Identifier: MIT
// GpiodMachineOutputs: the machine outputs (machine_outputs.hpp) on libgpiod lines (gpiod_lines.hpp),
// opened together: every named line is requested at construction (GpioError naming a missing one)
// and the servo pulse train runs while the object lives.
#pragma once

#include <curvestep/boards/host/gpiod_lines.hpp>
#include <curvestep/boards/host/machine_outputs.hpp>

namespace curvestep::boards::host {

/// Machine outputs on the lines `lines` names.
class GpiodMachineOutputs {
 public:
  /// Opens the chip and every named line; throws GpioError.
  explicit GpiodMachineOutputs(const MachineOutputLines& lines)
      : lines_(lines.chip, output_line_roles(lines)), outputs_(lines_, lines.outputs.size(), !lines.servo.empty()) {}

  /// The hooks to hand to the board (DeviceOptions::machine_outputs).
  [[nodiscard]] MachineOutputHooks& hooks() noexcept { return outputs_; }
  /// Line writes that failed.
  [[nodiscard]] std::size_t write_errors() const noexcept { return lines_.write_errors(); }
  /// Digital-output events whose number has no line.
  [[nodiscard]] std::size_t unwired_outputs() const noexcept { return outputs_.unwired_outputs(); }

 private:
  GpiodLineSet lines_;
  MachineOutputs<GpiodLineSet> outputs_;  // after lines_: stops its pulse train before the lines close
};

}  // namespace curvestep::boards::host
