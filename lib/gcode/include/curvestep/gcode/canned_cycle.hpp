// SPDX-License-Identifier: MIT
// Canned cycles (G73 G81 G82 G83 G85 G86 G89 in the XY plane): one block -> its elementary moves.
//
// The interpreter resolves a cycle block into a CannedCycle in machine coordinates (the holes, the
// R plane, the bottom, the clear level of G98/G99); expand_cycle() turns it into the moves LinuxCNC
// describes, so the host and a firmware that runs G-code expand cycles the same way. No heap.
//
// The moves (LinuxCNC g-code reference, "Canned Cycles"):
//   preliminary  once: if the tool is below the R plane, a rapid in Z up to R. Then for each of the
//                L repeats: a rapid in XY to the hole at the current height, a rapid in Z to R.
//   G81          feed to the bottom; rapid to the clear level.
//   G82          feed to the bottom; dwell P; rapid to the clear level.
//   G83 (peck)   feed down by Q (or to the bottom); rapid out to R; rapid down to the depth reached
//                plus the backoff; repeat until the bottom; rapid to the clear level.
//   G73 (chip)   feed down by Q (or to the bottom); rapid up by the backoff; repeat until the bottom;
//                rapid to the clear level.
//   G85          feed to the bottom; feed out to R; rapid to the clear level (if above R).
//   G86          feed to the bottom; dwell P; spindle stop; rapid to the clear level; spindle
//                restarts in its direction.
//   G89          feed to the bottom; dwell P; feed out to R; rapid to the clear level (if above R).
// The clear level is R with G99, and the higher of R and the Z before the block with G98.
// The backoff is 0.010 inch (0.254 mm), LinuxCNC's figure, in both unit systems.
#pragma once

#include <cmath>
#include <cstdint>

#include <curvestep/core/geometry/vec.hpp>

namespace curvestep::gcode {

/// A point in machine space, mm.
using CyclePoint = Vec<double, 3>;

/// One canned-cycle block, resolved to machine coordinates (mm, seconds).
struct CannedCycle {
  std::int32_t code = 81;             ///< 73, 81, 82, 83, 85, 86 or 89
  CyclePoint first_hole{};            ///< x, y of the first hole (z unused)
  CyclePoint step{};                  ///< x, y added per repeat (G91 with L > 1), else 0
  /// G91 with polar words (@ ^): each repeat adds step_radius_mm to the hole's distance and
  /// step_angle_rad to its angle about polar_origin (the XY origin of the coordinate system in
  /// force), LinuxCNC's polar increments; the first hole is at first_radius_mm, first_angle_rad.
  bool polar_steps = false;
  CyclePoint polar_origin{};
  double first_radius_mm = 0;
  double first_angle_rad = 0;
  double step_radius_mm = 0;
  double step_angle_rad = 0;
  std::uint32_t repeats = 1;          ///< L
  double r_z = 0;                     ///< the R plane
  double bottom_z = 0;                ///< the Z of the hole's bottom
  double clear_z = 0;                 ///< where each hole ends (R or the initial level)
  double peck_mm = 0;                 ///< Q (G73, G83)
  double dwell_s = 0;                 ///< P (G82, G86, G89)
  double backoff_mm = 0.254;          ///< G73 retract, G83 rapid-down stop short
};

/// What one elementary move of a cycle does.
enum class CycleStepKind : std::uint8_t {
  Rapid,         ///< straight traverse to `end`
  Feed,          ///< straight feed to `end`
  Dwell,         ///< wait `seconds`
  SpindleStop,   ///< G86: the spindle stops
  SpindleStart,  ///< G86: the spindle restarts in its direction
};

/// One elementary move.
struct CycleStep {
  CycleStepKind kind = CycleStepKind::Rapid;
  CyclePoint end{};     ///< Rapid / Feed: the end point, mm
  double seconds = 0;   ///< Dwell: seconds
};

/// x, y of hole `index` (0-based) of `cycle` (z unused).
[[nodiscard]] inline CyclePoint cycle_hole(const CannedCycle& cycle, std::uint32_t index) noexcept {
  const double k = static_cast<double>(index);
  if (!cycle.polar_steps) return CyclePoint{{cycle.first_hole[0] + k * cycle.step[0], cycle.first_hole[1] + k * cycle.step[1], 0.0}};
  const double radius = cycle.first_radius_mm + k * cycle.step_radius_mm;
  const double angle = cycle.first_angle_rad + k * cycle.step_angle_rad;
  return CyclePoint{{cycle.polar_origin[0] + radius * std::cos(angle), cycle.polar_origin[1] + radius * std::sin(angle), 0.0}};
}

/// Calls visit(CycleStep) for each move of `cycle` starting at `start`, in order. Moves of zero
/// length are skipped. Returns where the tool ends.
template <typename Visit>
constexpr CyclePoint expand_cycle(const CannedCycle& cycle, const CyclePoint& start, Visit&& visit) {
  CyclePoint at = start;
  const auto move = [&](CycleStepKind kind, CyclePoint to) {
    if (to == at) return;
    at = to;
    visit(CycleStep{kind, to, 0.0});
  };
  const auto z_to = [&](CycleStepKind kind, double z) { move(kind, CyclePoint{{at[0], at[1], z}}); };
  if (at[2] < cycle.r_z) z_to(CycleStepKind::Rapid, cycle.r_z);
  for (std::uint32_t repeat = 0; repeat < cycle.repeats; ++repeat) {
    const CyclePoint hole = cycle_hole(cycle, repeat);
    move(CycleStepKind::Rapid, CyclePoint{{hole[0], hole[1], at[2]}});
    z_to(CycleStepKind::Rapid, cycle.r_z);
    switch (cycle.code) {
      case 73:
      case 83: {
        double depth = cycle.r_z;
        while (true) {
          const double next = depth - cycle.peck_mm > cycle.bottom_z ? depth - cycle.peck_mm : cycle.bottom_z;
          z_to(CycleStepKind::Feed, next);
          depth = next;
          if (depth <= cycle.bottom_z) break;
          const double resume = depth + cycle.backoff_mm < cycle.r_z ? depth + cycle.backoff_mm : cycle.r_z;
          if (cycle.code == 83) z_to(CycleStepKind::Rapid, cycle.r_z);
          z_to(CycleStepKind::Rapid, resume);
        }
        z_to(CycleStepKind::Rapid, cycle.clear_z);
        break;
      }
      case 85:
      case 89:
        z_to(CycleStepKind::Feed, cycle.bottom_z);
        if (cycle.code == 89) visit(CycleStep{CycleStepKind::Dwell, at, cycle.dwell_s});
        z_to(CycleStepKind::Feed, cycle.r_z);
        z_to(CycleStepKind::Rapid, cycle.clear_z);
        break;
      case 86:
        z_to(CycleStepKind::Feed, cycle.bottom_z);
        visit(CycleStep{CycleStepKind::Dwell, at, cycle.dwell_s});
        visit(CycleStep{CycleStepKind::SpindleStop, at, 0.0});
        z_to(CycleStepKind::Rapid, cycle.clear_z);
        visit(CycleStep{CycleStepKind::SpindleStart, at, 0.0});
        break;
      default:  // 81, 82
        z_to(CycleStepKind::Feed, cycle.bottom_z);
        if (cycle.code == 82) visit(CycleStep{CycleStepKind::Dwell, at, cycle.dwell_s});
        z_to(CycleStepKind::Rapid, cycle.clear_z);
        break;
    }
  }
  return at;
}

}  // namespace curvestep::gcode
