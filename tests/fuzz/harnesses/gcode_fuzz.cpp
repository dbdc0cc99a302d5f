// SPDX-License-Identifier: MIT
// Fuzz harness: G-code (lib/gcode parse_line + Interpreter, and the host import parse_gcode_job).
//
// The text is cut into lines; each goes through parse_line and, when it parses, the modal
// Interpreter, exactly as a controller would run a program line by line. Then the whole text goes
// through the host import, whose LoadError/std::exception is the documented refusal. Properties:
// no crash, sanitizer report or contract violation; every motion the interpreter returns has
// finite end points within max_coordinate_mm; a job that imports has every PathSegment end inside
// the Q16.16 range and connected to the previous one, and every coordinate, weight and feed finite
// and on the Q16.16 grid the wire carries.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string_view>

#include <curvestep/gcode/interpreter.hpp>
#include <curvestep/gcode/parser.hpp>
#include <curvestep/host/gcode_import.hpp>

#include "fuzz_support.hpp"
#include "wire_grid.hpp"

using curvestep::fuzz::inside;
using curvestep::fuzz::wire_exact;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  curvestep::contract_handler = curvestep::fuzz::report_contract;
  const std::string_view text(reinterpret_cast<const char*>(data), size);

  curvestep::gcode::Interpreter<16> interpreter;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const auto block = curvestep::gcode::parse_line<24>(text.substr(start, end - start));
    if (block) {
      const auto motion = interpreter.execute(block.value());
      if (motion && motion.value().kind != curvestep::gcode::MotionKind::None) {
        CURVESTEP_FUZZ_ASSERT(inside(motion.value().end, curvestep::gcode::max_coordinate_mm));
      }
    }
    start = end + 1;
  }

  curvestep::host::Job job;
  try {
    job = curvestep::host::parse_gcode_job(text, "fuzz.ngc");
  } catch (const std::exception&) {
    return 0;
  }
  for (std::size_t i = 0; i < job.segments.size(); ++i) {
    const auto& s = job.segments[i];
    CURVESTEP_FUZZ_ASSERT(inside(s.start(), 32768.0) && inside(s.end(), 32768.0) && inside(s.point(0.5), 32768.0));
    if (i > 0) CURVESTEP_FUZZ_ASSERT(inside(s.start() - job.segments[i - 1].end(), 1.0 / 65536));
  }
  // Coordinates, weights and feeds are rounded to Q16.16 on loading (the wire's format), so the
  // simulator and a device see the same numbers.
  for (const auto& s : job.segments) CURVESTEP_FUZZ_ASSERT(wire_exact(s));
  for (const auto& source : job.sources) CURVESTEP_FUZZ_ASSERT(wire_exact(source));
  return 0;
}
