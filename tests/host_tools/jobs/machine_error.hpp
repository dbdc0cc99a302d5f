// SPDX-License-Identifier: MIT
// Test helpers for a machine file's optional sections ("gpio", "homing", ...): a valid machine
// file's text with a section added, the LoadError a text raises (the test fails if it loads), and
// a table of bad sections checked for the file, line, key and cause their errors name.
#pragma once

#include <cstddef>
#include <span>
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/core/error.hpp>
#include <curvestep/host/machine_file.hpp>

namespace curvestep::host::testing {

/// The "axes" object machine_text uses unless told: x and y at 80 steps/mm.
inline constexpr const char* xy_axes = R"({"x": {"steps_per_mm": 80}, "y": {"steps_per_mm": 80}})";

/// A valid machine file: lines 1..5 the limits, line 6 `"axes": ` + `axes`, then `extra` root
/// members (from line 7; `extra` may hold line breaks).
inline std::string machine_text(const std::string& extra, const std::string& axes = xy_axes) {
  return "{\n"
         "  \"version\": 1,\n"
         "  \"v_max\": 200, \"a_max\": 2000, \"j_max\": 50000,\n"
         "  \"feed\": 50, \"tolerance\": 0.01, \"rate_hz\": 1000,\n"
         "  \"max_step_rate\": 40000, \"rapid\": 150, \"profile\": \"trapezoid\",\n"
         "  \"axes\": " +
         axes + std::string(extra.empty() ? "" : ",\n  " + extra) + "\n}\n";
}

/// The LoadError of parsing `text` as the machine file `name`.
inline LoadError machine_error_of(const std::string& text, const std::string& name) {
  try {
    (void)parse_machine_file(text, name);
  } catch (const LoadError& e) {
    return e;
  }
  FAIL("the machine file loaded:\n" << text);
  return LoadError({}, "", Error::InvalidArgument);
}

/// One bad section and what its error names.
struct BadSection {
  std::string section;  ///< the root member(s) added to machine_text
  std::size_t line;     ///< the line the error names
  std::string field;    ///< the key path it names ("gpio"."x"."step")
  std::string cause;    ///< a part of its message
};

/// Each case, added to machine_text(`axes`) and parsed as `file`, is an InvalidMachine error naming
/// the file, the line and the field at the start of its message ("file:line: field: ") and the cause.
inline void check_bad_sections(std::span<const BadSection> cases, const std::string& file, const std::string& axes = xy_axes) {
  for (const auto& c : cases) {
    const LoadError e = machine_error_of(machine_text(c.section, axes), file);
    const std::string what = e.what();
    INFO(what);
    CHECK(e.code() == Error::InvalidMachine);
    CHECK(e.location().file == file);
    CHECK(e.location().line == c.line);
    CHECK(e.location().field == c.field);
    CHECK(what.rfind(file + ":" + std::to_string(c.line) + ": " + c.field + ": ", 0) == 0);
    CHECK(what.find(c.cause) != std::string::npos);
  }
}

}  // namespace curvestep::host::testing
