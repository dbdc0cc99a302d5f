// SPDX-License-Identifier: MIT
// Internal: the machine file's "homing" section (machine_file.hpp, HomingCycle).
#pragma once

#include <curvestep/host/machine_file.hpp>

#include "json_document.hpp"

namespace curvestep::host::detail {

/// {"order": ["z", "x", "y"], "x": {"switch": "min", "seek": MM/S, "locate": MM/S, "pull_off": MM,
/// "position": MM, "distance": MM}, ...}: speeds > 0 with locate <= seek, pull-off > 0, lengths
/// inside the Q16.16 range, the distance given or derived from the axis's `travel`. LoadError
/// naming the field otherwise.
[[nodiscard]] HomingCycle parse_homing(const Reader& reader, const Node& homing, const MachineTravel& travel);

}  // namespace curvestep::host::detail
