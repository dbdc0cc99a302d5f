// SPDX-License-Identifier: MIT
// Helpers for the SVG importer tests: a millimetre page, drawn pieces, point comparison.
#pragma once

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/motion/path_segment.hpp>
#include <curvestep/host/svg_import.hpp>

namespace curvestep::testing {

/// One Q16.16 step: imported points lie within half of it of the exact value.
inline constexpr double grid_mm = 1.0 / 65536.0;

/// True if `value` is finite and on the Q16.16 grid (value · 65536 is an integer).
inline bool on_q16_grid(double value) { return std::isfinite(value) && value * 65536.0 == std::round(value * 65536.0); }

/// The middle weight of the quarter arcs of circles, ellipses and rounded corners as the wire
/// carries it: √2/2 · 65536 = 46340.950 rounds to 46341 (worked out by hand, not by the importer).
inline constexpr double quarter_weight = 46341.0 / 65536.0;

/// How far off its ellipse a conic arc with a rounded middle weight can be, in the ellipse's unit
/// frame (where the ellipse is the unit circle; rational Béziers are affine invariant, so an
/// ellipse piece is the affine image of a unit-circle piece with the same weights).
///
/// The unit-circle piece of sweep δ has P0, P2 on the circle and P1 = (the middle direction) / c,
/// c = cos(δ/2), so |P1|² = 1/c², P0·P1 = P2·P1 = 1 and P0·P2 = 2c² − 1. With weight w instead of c,
/// b0 = (1 − t)², b1 = 2t(1 − t), b2 = t², s = t(1 − t) and D = b0 + w b1 + b2 = 1 − 2(1 − w)s,
/// expanding |b0 P0 + w b1 P1 + b2 P2|² − D² gives exactly
///     |P(t)|² − 1 = 4 s² (1 − c²)(w² − c²) / (c² D²),
/// which is 0 for w = c. For w ≤ 1, s/D grows with s, so 4s²/D² is largest at s = 1/4, where it is
/// 1/(1 + w)²: ||P|² − 1| ≤ (1 − c²)|w² − c²| / (c² (1 + w)²). For the quarter (c² = 1/2) and
/// w = 46341/65536 that is 3.70e-7, i.e. |P| within 1.85e-7 of 1: the documented 1.9e-7·r.
inline double conic_off_circle_bound(double c, double w) {
  return (1 - c * c) * std::fabs(w * w - c * c) / (c * c * (1 + w) * (1 + w));
}

inline std::filesystem::path svg_data(const std::string& name) { return std::filesystem::path(CURVESTEP_SVG_TEST_DATA) / name; }
inline std::filesystem::path svg_example(const std::string& name) { return std::filesystem::path(CURVESTEP_SVG_EXAMPLES) / name; }

/// A 100 mm x 100 mm page whose user unit is 1 mm: machine (x, y) = (x_user, 100 - y_user).
inline std::string page(const std::string& body) {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100mm\" height=\"100mm\" viewBox=\"0 0 100 100\">\n" + body + "\n</svg>\n";
}

/// Imports a page body.
inline host::SvgImport import_page(const std::string& body, const host::SvgOptions& options = {}) {
  return host::parse_svg(page(body), "test.svg", options);
}

/// The machine point of user point (x, y) on page().
inline MachinePoint on_page(double x, double y) { return MachinePoint{{x, 100 - y, 0.0}}; }

/// The drawn (non-rapid) source segments, in job order.
inline std::vector<host::SourceSegment> drawn(const host::Job& job) {
  std::vector<host::SourceSegment> out;
  for (const auto& s : job.sources) {
    if (s.type != host::SegmentType::Rapid) out.push_back(s);
  }
  return out;
}

inline bool near(const MachinePoint& a, const MachinePoint& b, double tolerance = grid_mm) {
  for (std::size_t i = 0; i < 3; ++i) {
    if (!(std::fabs(a[i] - b[i]) <= tolerance)) return false;
  }
  return true;
}

/// Checks that `segment` has exactly `expected` control points (within one grid step).
inline void check_points(const host::SourceSegment& segment, const std::vector<MachinePoint>& expected) {
  REQUIRE(segment.points.size() == expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    INFO("point " << i << ": got (" << segment.points[i][0] << ", " << segment.points[i][1] << "), expected (" << expected[i][0]
                  << ", " << expected[i][1] << ")");
    CHECK(near(segment.points[i], expected[i]));
  }
}

/// Every PathSegment starts where the previous one ended; drawing segments are not rapid.
inline void check_connected(const host::Job& job) {
  REQUIRE(job.segments.size() == job.source_index.size());
  for (std::size_t i = 1; i < job.segments.size(); ++i) {
    INFO("segment " << i);
    CHECK(job.segments[i].start() == job.segments[i - 1].end());
  }
  for (std::size_t i = 0; i < job.segments.size(); ++i) {
    CHECK(job.segments[i].rapid() == (job.sources[job.source_index[i]].type == host::SegmentType::Rapid));
  }
}

}  // namespace curvestep::testing
