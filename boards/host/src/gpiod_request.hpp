// SPDX-License-Identifier: MIT
// Opening a GPIO chip and requesting a named line as an output through libgpiod v1: the one place
// that words the errors (GpiodStepOutput, GpiodLineSet).
#pragma once

#include <string>

#include <gpiod.h>

namespace curvestep::boards::host::detail {

/// Opens `chip` (name, path or number, as gpiod_chip_open_lookup takes it); throws GpioError naming it.
[[nodiscard]] gpiod_chip* open_chip(const std::string& chip);

/// Requests the line named `name` on `chip` (opened from `chip_name`) as an output, low; throws
/// GpioError naming the line, its `role` ("x step", "spindle enable") and the chip.
[[nodiscard]] gpiod_line* request_output_line(gpiod_chip* chip, const std::string& chip_name, const std::string& name,
                                              const std::string& role);

}  // namespace curvestep::boards::host::detail
