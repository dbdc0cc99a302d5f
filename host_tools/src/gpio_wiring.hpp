// SPDX-License-Identifier: MIT
// From a machine file's wiring ("gpio" and a servo "pen") to the host board's line lists, and the
// job-load check that every digital output a job switches has a line (`curvestep device --gpio`,
// `curvestep gpio`).
#pragma once

#include <optional>
#include <string>

#include <curvestep/boards/host/gpio_output.hpp>
#include <curvestep/boards/host/machine_outputs.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/machine_file.hpp>

namespace curvestep::host {

/// The step/dir lines of `gpio` on `chip` (empty: gpio.chip).
[[nodiscard]] boards::host::GpioLines step_lines(const GpioWiring& gpio, const std::string& chip = {});

/// The machine-output lines of `gpio` and, for a servo pen, its "line", on `chip` (empty: gpio.chip).
[[nodiscard]] boards::host::MachineOutputLines output_lines(const GpioWiring& gpio, const std::optional<PenModel>& pen,
                                                            const std::string& chip = {});

/// Throws std::runtime_error naming the job's file:line and word if an M62-M65 switches an output
/// number that `gpio` has no line for ("gpio"."outputs" lists outputs 0 .. size - 1).
void check_digital_outputs(const Job& job, const GpioWiring& gpio);

}  // namespace curvestep::host
