// SPDX-License-Identifier: MIT
// (DEBUG,...) and (PRINT,...) text with #number and #<name> replaced by their values.
#pragma once

#include <string>
#include <string_view>

#include "expression.hpp"

namespace curvestep::host::gcode::detail {

/// `text` with each #123 and #<name> replaced by the value written with six decimals ("1.500000");
/// a reference to an undefined named parameter or a number outside 1..5602 is left as written.
[[nodiscard]] std::string substitute_parameters(std::string_view text, const ParameterSource& parameters);

}  // namespace curvestep::host::gcode::detail
