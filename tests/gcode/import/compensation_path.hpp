// SPDX-License-Identifier: MIT
// Checks for compensated paths: expected segment ends and arcs, and the tool centre's distance from
// the programmed contour, computed here from the contour's own geometry.
#pragma once

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <curvestep/host/gcode_import.hpp>

namespace curvestep::host::testing {

/// One expected segment: a line (or rapid) to (x, y), or an arc to (x, y) about (cx, cy) passing
/// through (mx, my) at its middle (which fixes the direction).
struct Expected {
  bool arc;
  double x, y;
  double cx = 0, cy = 0, mx = 0, my = 0;
};
inline Expected to(double x, double y) { return {false, x, y}; }
inline Expected arc(double x, double y, double cx, double cy, double mx, double my) { return {true, x, y, cx, cy, mx, my}; }

/// Tool 1 has diameter 4 (radius 2).
inline GcodeOptions tool_table() {
  GcodeOptions options;
  options.tool_diameter_mm[1] = 4.0;
  return options;
}

inline Job load_compensated(const std::string& text) { return parse_gcode_job(text, "comp.ngc", tool_table()); }

/// A refused program: what() of its LoadError contains `where` (file:line:column: word) and `says`.
struct Refusal {
  const char* text;
  const char* where;
  const char* says;
};
inline void check_refusals(const std::vector<Refusal>& cases) {
  for (const auto& c : cases) {
    INFO(c.text);
    std::string message;
    try {
      (void)load_compensated(c.text);
    } catch (const LoadError& e) {
      message = e.what();
    }
    INFO(message);
    CHECK(message.find(c.where) != std::string::npos);
    CHECK(message.find(c.says) != std::string::npos);
  }
}

/// Checks the segments' ends (and arcs' centres and middles) and that each starts where the last ended.
inline void check_path(const Job& job, const std::vector<Expected>& expected) {
  REQUIRE(job.segments.size() == expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    INFO("segment " << i);
    const auto& s = job.segments[i];
    const auto end = s.end();
    CHECK(end[0] == Approx(expected[i].x).margin(1e-4));
    CHECK(end[1] == Approx(expected[i].y).margin(1e-4));
    if (i > 0) {
      CHECK(s.start()[0] == Approx(job.segments[i - 1].end()[0]).margin(1e-4));
      CHECK(s.start()[1] == Approx(job.segments[i - 1].end()[1]).margin(1e-4));
    }
    CHECK((s.kind() == SegmentKind::Arc) == expected[i].arc);
    if (expected[i].arc && s.kind() == SegmentKind::Arc) {
      CHECK(s.arc_center()[0] == Approx(expected[i].cx).margin(1e-4));
      CHECK(s.arc_center()[1] == Approx(expected[i].cy).margin(1e-4));
      const auto middle = s.point(0.5);
      CHECK(middle[0] == Approx(expected[i].mx).margin(1e-3));
      CHECK(middle[1] == Approx(expected[i].my).margin(1e-3));
    }
  }
}

/// The distance from (u, v) to the segment from a to b.
inline double distance_to_segment(double u, double v, const std::array<double, 2>& a, const std::array<double, 2>& b) {
  const double du = b[0] - a[0];
  const double dv = b[1] - a[1];
  const double t = std::clamp(((u - a[0]) * du + (v - a[1]) * dv) / (du * du + dv * dv), 0.0, 1.0);
  return std::hypot(u - a[0] - t * du, v - a[1] - t * dv);
}

/// The distance from (u, v) to the closed polygon through `corners` (its sides, corners included).
inline double distance_to_polygon(double u, double v, const std::vector<std::array<double, 2>>& corners) {
  double best = 1e300;
  for (std::size_t i = 0; i < corners.size(); ++i) best = std::min(best, distance_to_segment(u, v, corners[i], corners[(i + 1) % corners.size()]));
  return best;
}

/// The distance from (u, v) to the counter-clockwise arc about `center` of radius `radius` from
/// angle `from` to angle `to` (radians; to > from).
inline double distance_to_ccw_arc(double u, double v, const std::array<double, 2>& center, double radius, double from, double to) {
  constexpr double two_pi = 6.283185307179586;
  double angle = std::atan2(v - center[1], u - center[0]);
  while (angle < from) angle += two_pi;
  if (angle <= to) return std::fabs(std::hypot(u - center[0], v - center[1]) - radius);
  const auto at = [&](double a) { return std::hypot(u - center[0] - radius * std::cos(a), v - center[1] - radius * std::sin(a)); };
  return std::min(at(from), at(to));
}

}  // namespace curvestep::host::testing
