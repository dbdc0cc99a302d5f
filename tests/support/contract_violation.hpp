// SPDX-License-Identifier: MIT
// The exception the test build's contract handler throws.
#pragma once

#include <stdexcept>
#include <string>

#include <curvestep/core/contract.hpp>

namespace curvestep::testing {

struct ContractViolation : std::logic_error {
  ContractViolation(const char* condition, const char* file, int line)
      : std::logic_error(std::string("contract violated: ") + condition + " at " + file + ":" + std::to_string(line)) {}
};

}  // namespace curvestep::testing
