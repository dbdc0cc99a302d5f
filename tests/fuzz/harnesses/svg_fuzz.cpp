// SPDX-License-Identifier: MIT
// Fuzz harness: SVG import (host_tools/src/svg parse_svg) on arbitrary text.
//
// LoadError and the other std::exception types are the documented refusal and are caught. A crash,
// sanitizer report, contract violation or another exception is a finding. For a drawing that
// imports, every PathSegment's ends are finite and inside the Q16.16 range, consecutive segments
// connect, and the travel figures are finite and not negative.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string_view>

#include <curvestep/host/svg_import.hpp>

#include "fuzz_support.hpp"

namespace {

bool inside(const curvestep::MachinePoint& p, double limit) {
  for (std::size_t a = 0; a < curvestep::motion_axes; ++a) {
    if (!std::isfinite(p[a]) || std::fabs(p[a]) > limit) return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  curvestep::contract_handler = curvestep::fuzz::report_contract;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  curvestep::host::SvgOptions options;
  options.optimize = size > 0 && (data[0] & 1) != 0;
  curvestep::host::SvgImport imported;
  try {
    imported = curvestep::host::parse_svg(text, "fuzz.svg", options);
  } catch (const std::exception&) {
    return 0;
  }
  const auto& job = imported.job;
  for (std::size_t i = 0; i < job.segments.size(); ++i) {
    const auto& s = job.segments[i];
    CURVESTEP_FUZZ_ASSERT(inside(s.start(), 32768.0) && inside(s.end(), 32768.0) && inside(s.point(0.5), 32768.0));
    if (i > 0) CURVESTEP_FUZZ_ASSERT(inside(s.start() - job.segments[i - 1].end(), 1.0 / 65536));
  }
  CURVESTEP_FUZZ_ASSERT(std::isfinite(imported.travel_mm) && imported.travel_mm >= 0);
  CURVESTEP_FUZZ_ASSERT(std::isfinite(imported.travel_document_mm) && imported.travel_document_mm >= 0);
  return 0;
}
