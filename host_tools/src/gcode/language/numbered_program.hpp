// SPDX-License-Identifier: MIT
// Fanuc-style numbered programs as LinuxCNC reads them (docs/gcode.md, "Numbered programs"): what an
// M98 line calls and how often, and why an M99 of the main program is refused. The reader
// (program_reader.cpp) runs them: a call frame per M98, a pass per M99.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>

#include "line_parser.hpp"
#include "program_structure.hpp"

namespace curvestep::host::gcode::detail {

/// Subroutine and numbered program labels: 0 .. 999999999.
inline constexpr double max_label = 1e9;

/// `number` as a whole number in [0, limit) when it is within `tolerance` of one, else nullopt.
[[nodiscard]] std::optional<long long> whole_number(double number, double limit, double tolerance);

/// An M98, checked: the numbered program's O line and how many times it runs.
struct NumberedCall {
  std::size_t body = no_line;
  long long passes = 1;
};

/// `M98 P- [L-]` of `line` (values computed by `value`): the numbered program of the file it calls
/// (`structure`, the file named `file`) and its passes. LinuxCNC's rules: P within 0.0001 of a whole
/// number, L rounded, at most `max_passes`; only a numbered program (a sub's label names the call it
/// needs). A G code that reads P or L may not share the line. Throws LineError at the word at fault.
[[nodiscard]] NumberedCall numbered_call(const ParsedLine& line, const WordValue& m98, const std::function<double(NodeIndex)>& value,
                                         const ProgramStructure& structure, const std::string& file, double max_passes);

/// The LineError for an M99 of the main program (LinuxCNC's endless program), with a hint when the
/// program's first line is a number (a subprogram run on its own).
[[noreturn]] void fail_main_program_m99(const ProgramStructure& structure, const WordValue& m99);

}  // namespace curvestep::host::gcode::detail
