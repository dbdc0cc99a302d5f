// SPDX-License-Identifier: MIT
// Fuzz harness: SVG import (host_tools/src/svg parse_svg) on arbitrary text.
//
// LoadError and the other std::exception types are the documented refusal and are caught. A crash,
// sanitizer report, contract violation or another exception is a finding. For a drawing that
// imports, every PathSegment's ends are finite and inside the Q16.16 range, consecutive segments
// connect, every coordinate, weight and feed is finite and on the Q16.16 grid the wire carries,
// and the travel figures are finite and not negative.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string_view>

#include <curvestep/host/svg_import.hpp>

#include "fuzz_support.hpp"
#include "wire_grid.hpp"

using curvestep::fuzz::inside;
using curvestep::fuzz::wire_exact;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  curvestep::contract_handler = curvestep::fuzz::report_contract;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  curvestep::host::SvgOptions options;
  options.optimize = size > 0 && (data[0] & 1) != 0;
  if (size > 0 && (data[0] & 2) != 0) {  // a feed and a start off the grid, to be rounded
    options.feed_mm_per_s = 12.345;
    options.start = curvestep::MachinePoint{{0.1, 0.3, 0.7}};
  }
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
  // Coordinates, weights and feeds are rounded to Q16.16 on loading (the wire's format), so the
  // simulator and a device see the same numbers.
  for (const auto& s : job.segments) CURVESTEP_FUZZ_ASSERT(wire_exact(s));
  for (const auto& source : job.sources) CURVESTEP_FUZZ_ASSERT(wire_exact(source));
  CURVESTEP_FUZZ_ASSERT(std::isfinite(imported.travel_mm) && imported.travel_mm >= 0);
  CURVESTEP_FUZZ_ASSERT(std::isfinite(imported.travel_document_mm) && imported.travel_document_mm >= 0);
  return 0;
}
