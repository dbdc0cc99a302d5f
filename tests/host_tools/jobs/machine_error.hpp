// SPDX-License-Identifier: MIT
// Test helper: the LoadError a machine file's text raises (the test fails if it loads).
#pragma once

#include <string>

#include <catch2/catch.hpp>

#include <curvestep/core/error.hpp>
#include <curvestep/host/machine_file.hpp>

namespace curvestep::host::testing {

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

}  // namespace curvestep::host::testing
