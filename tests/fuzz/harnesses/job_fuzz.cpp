// SPDX-License-Identifier: MIT
// Fuzz harness: the JSON job loader (parse_job) on arbitrary text.
//
// LoadError and the other std::exception types are the loader's documented way to refuse a file,
// so they are caught. Anything else (a crash, a sanitizer report, a contract violation, another
// exception) is a finding. For a file that loads, the promises of job.hpp are checked: every
// PathSegment's ends are finite and inside the Q16.16 range, consecutive segments connect, every
// coordinate, weight and feed (of the PathSegments and of the file's segments) is finite and on the
// Q16.16 grid the wire carries, and every file segment evaluates at both ends of its domain.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>
#include <string_view>

#include <curvestep/host/job.hpp>

#include "fuzz_support.hpp"
#include "wire_grid.hpp"

namespace {

bool in_q16_range(const curvestep::MachinePoint& p) {
  for (std::size_t a = 0; a < curvestep::motion_axes; ++a) {
    if (!std::isfinite(p[a]) || p[a] < -32768.0 || p[a] >= 32768.0) return false;
  }
  return true;
}

}  // namespace

using curvestep::fuzz::wire_exact;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  curvestep::contract_handler = curvestep::fuzz::report_contract;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  curvestep::host::Job job;
  try {
    job = curvestep::host::parse_job(text, "fuzz.json");
  } catch (const std::exception&) {
    return 0;  // refused with a message: the intended outcome for a bad file
  }
  CURVESTEP_FUZZ_ASSERT(job.segments.size() == job.source_index.size());
  for (std::size_t i = 0; i < job.segments.size(); ++i) {
    const auto& s = job.segments[i];
    CURVESTEP_FUZZ_ASSERT(in_q16_range(s.start()) && in_q16_range(s.end()));
    CURVESTEP_FUZZ_ASSERT(in_q16_range(s.point(0.5)));
    if (i > 0) {
      const auto gap = s.start() - job.segments[i - 1].end();
      for (std::size_t a = 0; a < curvestep::motion_axes; ++a) CURVESTEP_FUZZ_ASSERT(std::fabs(gap[a]) <= 1.0 / 65536);
    }
  }
  // Coordinates, weights and feeds are rounded to Q16.16 on loading (the wire's format), so the
  // simulator and a device see the same numbers.
  for (const auto& s : job.segments) CURVESTEP_FUZZ_ASSERT(wire_exact(s));
  for (const auto& source : job.sources) CURVESTEP_FUZZ_ASSERT(wire_exact(source));
  for (std::size_t i = 0; i < job.sources.size(); ++i) {
    const auto [lo, hi] = job.sources[i].domain();
    // Both ends of the domain are inside it: evaluate_segment must not refuse them.
    CURVESTEP_FUZZ_ASSERT(in_q16_range(curvestep::host::evaluate_segment(job, i, lo)));
    CURVESTEP_FUZZ_ASSERT(in_q16_range(curvestep::host::evaluate_segment(job, i, hi)));
  }
  return 0;
}
