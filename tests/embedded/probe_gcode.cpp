// SPDX-License-Identifier: MIT
// Probe: the G-code line parser and modal interpreter (lines, arcs, G5, G5.1, a NURBS block).
#include <array>
#include <cstdint>
#include <string_view>

#include <curvestep/gcode.hpp>

#include "probe.hpp"

namespace curvestep::probe {

void probe_gcode() {
  static constexpr std::array<std::string_view, 12> program{
      "N10 G21 G90 G17 (mm) F600", "G0 X10 Y0", "G3 X0 Y10 I-10 J0", "G2 X10 Y0 R10", "G5 I0 J3 P0 Q-3 X11 Y1",
      "G5 P0 Q-3 X12 Y2",          "G5.1 I1 J2 X14 Y2", "G5.2 P1 L3", "X14 Y4", "X16 Y4 P2", "G5.3", "M2 ; end"};
  gcode::Interpreter<8> interpreter;
  // `sink` decides where to start, so the compiler cannot fold the program away.
  const auto first = static_cast<std::size_t>(sink) % 2;
  for (std::size_t i = first; i < program.size(); ++i) {
    const auto block = gcode::parse_line(program[i]);
    if (!block) {
      sink = sink + static_cast<std::int32_t>(block.where());
      continue;
    }
    const auto motion = interpreter.execute(block.value());
    if (!motion) {
      sink = sink + static_cast<std::int32_t>(motion.error());
      continue;
    }
    sink = sink + static_cast<std::int32_t>(motion.value().kind) + static_cast<std::int32_t>(motion.value().end[0]);
  }
  sink = sink + static_cast<std::int32_t>(interpreter.nurbs_points().size());
}

}  // namespace curvestep::probe
