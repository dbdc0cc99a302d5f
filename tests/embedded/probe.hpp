// SPDX-License-Identifier: MIT
// Each probe_<area>.cpp instantiates one area's templates for Q16.16 and float and writes the
// results to `sink`, so the linker keeps the code. Add a declaration and a call for a new area.
#pragma once

#include <cstdint>

namespace curvestep::probe {

/// Where probes store results so that nothing is optimised away.
inline volatile std::int32_t sink = 0;

void probe_core_curves();
void probe_bspline();
void probe_interpolation();
void probe_motion();
void probe_protocol();
void probe_stepgen();
void probe_sampling();
void probe_firmware();
void probe_gcode();

/// Runs every probe (called from Reset_Handler).
inline void run_all() {
  probe_core_curves();
  probe_bspline();
  probe_interpolation();
  probe_motion();
  probe_protocol();
  probe_stepgen();
  probe_sampling();
  probe_firmware();
  probe_gcode();
}

}  // namespace curvestep::probe
