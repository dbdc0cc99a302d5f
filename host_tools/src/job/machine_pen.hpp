// SPDX-License-Identifier: MIT
// Internal: the machine file's "pen" section (machine_file.hpp, PenModel).
#pragma once

#include <curvestep/host/machine_file.hpp>

#include "json_document.hpp"

namespace curvestep::host::detail {

/// {"axis": "z", "up": MM, "down": MM, "feed": MM/S}: heights finite, on the Q16.16 grid and
/// different, feed > 0 and carried by the wire. LoadError naming the field otherwise.
[[nodiscard]] PenModel parse_pen(const Reader& reader, const Node& pen);

}  // namespace curvestep::host::detail
