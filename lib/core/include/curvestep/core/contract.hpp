// SPDX-License-Identifier: MIT
// CURVESTEP_EXPECTS: contract checks for programmer errors (index past size, wrong call order).
#pragma once

namespace curvestep {

/// Called on a contract violation. A board installs one that stops the machine safely; the
/// test build installs one that throws so Catch2 can observe it. If it returns (or none is
/// installed) the program traps. Input errors never come here: they return Result.
using ContractHandler = void (*)(const char* condition, const char* file, int line);

/// The installed handler (nullptr: trap at once).
inline ContractHandler contract_handler = nullptr;

namespace detail {
[[noreturn]] inline void contract_failed(const char* condition, const char* file, int line) {
  if (contract_handler != nullptr) contract_handler(condition, file, line);
  __builtin_trap();
}
}  // namespace detail

}  // namespace curvestep

/// Checks a precondition. In a constant expression a violated contract is a compile error.
#define CURVESTEP_EXPECTS(condition)                                                     \
  ((condition) ? static_cast<void>(0)                                                    \
               : ::curvestep::detail::contract_failed(#condition, __FILE__, __LINE__))
