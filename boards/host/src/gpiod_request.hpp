// SPDX-License-Identifier: MIT
// Opening a GPIO chip and requesting a named line as an output or an input through libgpiod v1:
// the one place that words the errors (GpiodStepOutput, GpiodLineSet).
#pragma once

#include <string>

#include <gpiod.h>

namespace curvestep::boards::host::detail {

/// Opens `chip` (name, path or number, as gpiod_chip_open_lookup takes it); throws GpioError naming it.
[[nodiscard]] gpiod_chip* open_chip(const std::string& chip);

/// Which way a requested line goes.
enum class LineDirection { Output, Input };

/// Requests the line named `name` on `chip` (opened from `chip_name`) as an output (low) or an
/// input; throws GpioError naming the line, its `role` ("x step", "x min switch") and the chip.
[[nodiscard]] gpiod_line* request_line(gpiod_chip* chip, const std::string& chip_name, const std::string& name,
                                       const std::string& role, LineDirection direction = LineDirection::Output);

}  // namespace curvestep::boards::host::detail
