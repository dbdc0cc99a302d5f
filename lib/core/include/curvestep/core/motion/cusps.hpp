// SPDX-License-Identifier: MIT
// find_cusps: interior parameters where a Bézier segment's velocity vanishes (cusps).
//
// A path can only pass a cusp by stopping, because the direction of motion reverses there, and
// the curvature is unbounded next to it. The controller therefore splits a segment at its cusps;
// the reversal junction between the pieces then forces a stop. |p'(u)| is sampled at 257 points;
// each local minimum below 1e-3 of the largest speed is refined by golden-section search and
// counts as a cusp if the refined speed is below 1e-7 of the largest speed (a true cusp reaches 0
// up to rounding; a tight loop or a near-cusp keeps a clearly positive speed and is slowed down
// by its curvature instead).
#pragma once

#include <array>
#include <cstddef>

#include <curvestep/core/detail/golden_section.hpp>
#include <curvestep/core/motion/path_segment.hpp>

namespace curvestep {

/// Up to MaxCusps interior cusp parameters in increasing order, and how many were found.
template <std::size_t MaxCusps = 6>
struct CuspList {
  static constexpr std::size_t capacity = MaxCusps;
  std::array<double, MaxCusps> parameters{};
  std::size_t count = 0;
};

/// The cusps of a Bézier or rational Bézier segment (none for lines and arcs).
template <std::size_t MaxCusps = 6>
[[nodiscard]] CuspList<MaxCusps> find_cusps(const PathSegment& segment) {
  CuspList<MaxCusps> cusps;
  if (segment.kind() == SegmentKind::Line || segment.kind() == SegmentKind::Arc) return cusps;
  constexpr std::size_t samples = 256;
  // Two passes over the samples instead of a table of 257 speeds (2 KiB of stack on a
  // microcontroller): the largest speed first, then the local minima from a sliding window of
  // three. The speeds are recomputed identically (a pure function of the segment).
  const auto speed_at = [&segment](std::size_t k) { return norm(segment.derivative(static_cast<double>(k) / samples, 1)); };
  double largest = 0;
  for (std::size_t k = 0; k <= samples; ++k) {
    const double speed = speed_at(k);
    if (speed > largest) largest = speed;
  }
  if (!(largest > 0)) return cusps;
  double before = speed_at(0);
  double here = speed_at(1);
  for (std::size_t k = 1; k < samples && cusps.count < MaxCusps; ++k) {
    const double after = speed_at(k + 1);
    const bool minimum_here = here <= before && here <= after && !(here > 1e-3 * largest);
    before = here;
    here = after;
    if (!minimum_here) continue;
    // golden-section search for the minimum of |p'| on [u_{k-1}, u_{k+1}]
    const auto minimum = detail::golden_section_minimum([&](double x) { return norm(segment.derivative(x, 1)); },
                                                        static_cast<double>(k - 1) / samples, static_cast<double>(k + 1) / samples, 80);
    const double u = minimum.x;
    const bool is_new = cusps.count == 0 || u - cusps.parameters[cusps.count - 1] > 1e-6;
    if (u > 1e-6 && u < 1 - 1e-6 && norm(segment.derivative(u, 1)) <= 1e-7 * largest && is_new) {
      cusps.parameters[cusps.count++] = u;
    }
  }
  return cusps;
}

}  // namespace curvestep
