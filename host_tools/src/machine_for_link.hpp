// SPDX-License-Identifier: MIT
// The machine file as a command that talks to a controller over the link reads it (stream, jog).
#pragma once

#include <string>

#include <curvestep/host/machine_file.hpp>

namespace curvestep::host {

/// The machine file without its "gpio" section (the device's wiring, not planning data).
[[nodiscard]] MachineFile load_machine_for_link(const std::string& path);

}  // namespace curvestep::host
