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

namespace {

bool inside(const curvestep::MachinePoint& p, double limit) {
  for (std::size_t a = 0; a < curvestep::motion_axes; ++a) {
    if (!std::isfinite(p[a]) || std::fabs(p[a]) > limit) return false;
  }
  return true;
}

/// Finite and on the Q16.16 grid (value · 65536, exact in double, is an integer): a number the
/// wire carries without rounding.
bool on_wire_grid(double value) { return std::isfinite(value) && value * 65536.0 == std::nearbyint(value * 65536.0); }

bool on_wire_grid(const curvestep::MachinePoint& p) {
  for (std::size_t a = 0; a < curvestep::motion_axes; ++a) {
    if (!on_wire_grid(p[a])) return false;
  }
  return true;
}

/// Every number of `s` that the wire carries (host_tools/src/link/wire.cpp): control points (the
/// end points and the XY centre of an arc), weights and the feed.
bool wire_exact(const curvestep::PathSegment& s) {
  if (!on_wire_grid(s.start()) || !on_wire_grid(s.end()) || !on_wire_grid(s.feed_mm_per_s())) return false;
  switch (s.kind()) {
    case curvestep::SegmentKind::Line:
    case curvestep::SegmentKind::Bezier:
      for (const auto& p : s.polynomial().control_points()) {
        if (!on_wire_grid(p)) return false;
      }
      return true;
    case curvestep::SegmentKind::RationalBezier:
      for (std::size_t k = 0; k <= s.rational().degree(); ++k) {
        if (!on_wire_grid(s.rational().control_points()[k]) || !on_wire_grid(s.rational().weight(k))) return false;
      }
      return true;
    case curvestep::SegmentKind::Arc: return on_wire_grid(s.arc_center()[0]) && on_wire_grid(s.arc_center()[1]);
  }
  return false;
}

/// The file's segments as loaded: points, weights and feed on the grid (knots never travel).
bool wire_exact(const curvestep::host::SourceSegment& source) {
  for (const auto& p : source.points) {
    if (!on_wire_grid(p)) return false;
  }
  for (const double w : source.weights) {
    if (!on_wire_grid(w)) return false;
  }
  return on_wire_grid(source.feed_mm_per_s);
}

}  // namespace

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
