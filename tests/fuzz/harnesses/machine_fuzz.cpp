// SPDX-License-Identifier: MIT
// Fuzz harness: the JSON machine loader (parse_machine) on arbitrary text.
//
// LoadError and the other std::exception types are the documented refusal and are caught; a crash,
// sanitizer report or contract violation is a finding. A file that loads must give limits that
// MachineLimits::validate accepts (machine_file.hpp promises a validated result).
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string_view>

#include <curvestep/host/machine_file.hpp>

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  curvestep::contract_handler = curvestep::fuzz::report_contract;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const curvestep::MachineLimits limits = curvestep::host::parse_machine(text, "machine.json");
    CURVESTEP_FUZZ_ASSERT(limits.validate().has_value());
  } catch (const std::exception&) {
    return 0;
  }
  return 0;
}
