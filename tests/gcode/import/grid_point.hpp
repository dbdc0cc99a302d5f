// SPDX-License-Identifier: MIT
// Checks an imported point against hand-computed coordinates within the Q16.16 grid.
#pragma once

#include <catch2/catch.hpp>

#include <curvestep/host/gcode_import.hpp>

namespace curvestep::host::testing {

/// Q16.16 quantisation moves a coordinate by at most 2^-17 mm.
inline constexpr double grid_tolerance = 1.0 / 131072.0;

/// `p` is (x, y, z) within the grid tolerance.
inline void check_grid_point(const MachinePoint& p, double x, double y, double z) {
  CHECK(p[0] == Approx(x).margin(grid_tolerance));
  CHECK(p[1] == Approx(y).margin(grid_tolerance));
  CHECK(p[2] == Approx(z).margin(grid_tolerance));
}

}  // namespace curvestep::host::testing
