// SPDX-License-Identifier: MIT
// Flattening of PathSegments into polylines within a tolerance (see flatten.hpp for the bounds).
#include <curvestep/host/flatten.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <curvestep/core/motion/deterministic_math.hpp>

namespace curvestep::host {
namespace {

constexpr int max_depth = 48;
constexpr double pi = 3.14159265358979323846;

double distance_to_chord(const MachinePoint& p, const MachinePoint& a, const MachinePoint& b) {
  const MachinePoint ab = b - a;
  const MachinePoint ap = p - a;
  const double length2 = dot(ab, ab);
  double t = length2 > 0 ? dot(ap, ab) / length2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const MachinePoint off = ap - ab * t;
  return std::sqrt(dot(off, off));
}

/// Largest distance of a control point from the chord: bounds the curve's distance from it.
double hull_deviation(std::span<const MachinePoint> control) {
  double worst = 0;
  for (std::size_t i = 1; i + 1 < control.size(); ++i) {
    worst = std::max(worst, distance_to_chord(control[i], control.front(), control.back()));
  }
  return worst;
}

template <class Curve>
void flatten_curve(const Curve& curve, double tolerance, int depth, std::vector<MachinePoint>& out) {
  if (hull_deviation(curve.control_points()) <= tolerance) {
    out.push_back(curve.back());
    return;
  }
  if (depth >= max_depth) {
    throw std::invalid_argument("tolerance too small: a curve still deviates after " + std::to_string(max_depth) +
                                " halvings");
  }
  const auto halves = curve.split(0.5);
  if (!halves) throw std::invalid_argument("cannot split a curve while flattening");
  flatten_curve(halves.value().left, tolerance, depth + 1, out);
  flatten_curve(halves.value().right, tolerance, depth + 1, out);
}

void flatten_arc(const PathSegment& arc, double tolerance, std::vector<MachinePoint>& out) {
  const double r = arc.arc_radius();
  const double sweep = std::fabs(arc.arc_sweep_rad());
  const double dz = arc.end()[2] - arc.start()[2];
  double step = pi / 2;
  if (tolerance < r) step = std::min(step, 2 * std::acos(1 - tolerance / r));
  auto count = static_cast<std::size_t>(std::ceil(sweep / step));
  count = std::max<std::size_t>(count, 1);
  auto deviation = [&](std::size_t n) {
    const double half = sweep / static_cast<double>(2 * n);
    const double sagitta = r * (1 - std::cos(half));
    return dz == 0 ? sagitta : sagitta + r * half * half * half / 8;
  };
  while (deviation(count) > tolerance) {
    if (count > (std::size_t{1} << 30)) throw std::invalid_argument("tolerance too small for an arc");
    count += std::max<std::size_t>(1, count / 8);
  }
  for (std::size_t k = 1; k <= count; ++k) {
    out.push_back(arc.point(k == count ? 1.0 : static_cast<double>(k) / static_cast<double>(count)));
  }
}

}  // namespace

void flatten_segment(const PathSegment& segment, double tolerance_mm, std::vector<MachinePoint>& out) {
  if (!(tolerance_mm > 0) || !std::isfinite(tolerance_mm)) {
    throw std::invalid_argument("the tolerance must be a positive number of mm");
  }
  switch (segment.kind()) {
    case SegmentKind::Line: out.push_back(segment.end()); break;
    case SegmentKind::Arc: flatten_arc(segment, tolerance_mm, out); break;
    case SegmentKind::Bezier: flatten_curve(segment.polynomial(), tolerance_mm, 0, out); break;
    case SegmentKind::RationalBezier: flatten_curve(segment.rational(), tolerance_mm, 0, out); break;
  }
}

std::vector<MachinePoint> flatten_path(std::span<const PathSegment> segments, double tolerance_mm) {
  std::vector<MachinePoint> points;
  for (const auto& segment : segments) {
    if (points.empty() || !(points.back() == segment.start())) points.push_back(segment.start());
    flatten_segment(segment, tolerance_mm, points);
  }
  return points;
}

}  // namespace curvestep::host
