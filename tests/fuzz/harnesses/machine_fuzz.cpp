// SPDX-License-Identifier: MIT
// Fuzz harness: the JSON machine loader (parse_machine_file, with its "gpio" section) on arbitrary text.
//
// LoadError and the other std::exception types are the documented refusal and are caught; a crash,
// sanitizer report or contract violation is a finding. A file that loads must give limits that
// MachineLimits::validate accepts (machine_file.hpp promises a validated result) and, if it has a
// "gpio" section, the wiring docs/job_format.md promises: a non-empty chip, at least one axis,
// non-empty step and direction names and no line used twice.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

#include <curvestep/host/machine_file.hpp>

#include "fuzz_support.hpp"

namespace {

bool wiring_valid(const curvestep::host::GpioWiring& gpio) {
  if (gpio.chip.empty()) return false;
  std::vector<std::string> lines;
  for (const auto& axis : gpio.axes) {
    if (!axis) continue;
    if (axis->step.empty() || axis->dir.empty()) return false;
    for (const std::string* line : {&axis->step, &axis->dir}) {
      for (const auto& used : lines) {
        if (used == *line) return false;
      }
      lines.push_back(*line);
    }
  }
  return !lines.empty();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  curvestep::contract_handler = curvestep::fuzz::report_contract;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const curvestep::host::MachineFile file = curvestep::host::parse_machine_file(text, "machine.json");
    CURVESTEP_FUZZ_ASSERT(file.limits.validate().has_value());
    if (file.gpio) CURVESTEP_FUZZ_ASSERT(wiring_valid(*file.gpio));
  } catch (const std::exception&) {
    return 0;
  }
  return 0;
}
