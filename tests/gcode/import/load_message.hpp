// SPDX-License-Identifier: MIT
// The LoadError message a G-code text must produce (a test failure if it loads).
#pragma once

#include <catch2/catch.hpp>

#include <string>

#include <curvestep/host/gcode_import.hpp>

namespace curvestep::host::testing {

/// what() of the LoadError that parse_gcode_job(text, file_name) throws.
inline std::string load_error_message(const std::string& text, const std::string& file_name) {
  try {
    (void)parse_gcode_job(text, file_name);
  } catch (const LoadError& e) {
    return e.what();
  }
  FAIL("no LoadError for: " << text);
  return {};
}

}  // namespace curvestep::host::testing
