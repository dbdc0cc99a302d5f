// SPDX-License-Identifier: MIT
// Plotter pen up/down as motion: a drawing job (an SVG import, z = 0, rapids between its subpaths)
// becomes a job whose pen moves are ordinary segments, planned, simulated and streamed like the rest.
#pragma once

#include <cstddef>

#include <curvestep/host/job.hpp>
#include <curvestep/host/machine_file.hpp>

namespace curvestep::host {

/// What add_pen_moves did.
struct PenMovesReport {
  std::size_t lifts = 0;   ///< moves up to pen.up_mm
  std::size_t lowers = 0;  ///< moves down to pen.down_mm
};

/// `job` with the pen on z: every drawing segment at z = pen.down_mm, every rapid at pen.up_mm.
/// Before a rapid (and at a LayerChange, a pen change) the pen is lifted: a PenUp event, then a
/// rapid straight up to up_mm; before the first drawing segment after that, a line straight down to
/// down_mm at pen.feed_mm_per_s, then a PenDown event (so smoothing never blends the touch-down).
/// The job ends with the pen lifted. The start point keeps its z (the first move goes from it).
/// Expects one segment per source (as imports make them); std::invalid_argument otherwise, or for arcs.
[[nodiscard]] Job add_pen_moves(const Job& job, const PenModel& pen, PenMovesReport* report = nullptr);

}  // namespace curvestep::host
