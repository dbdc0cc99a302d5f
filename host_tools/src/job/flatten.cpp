// SPDX-License-Identifier: MIT
// Flattening of PathSegments into polylines within a tolerance (see flatten.hpp for the bounds).
#include <curvestep/host/flatten.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <curvestep/core/error_text.hpp>
#include <curvestep/core/sampling/flatten.hpp>

namespace curvestep::host {
namespace {

constexpr double pi = 3.14159265358979323846;

/// Appends the vertices of a (rational) Bézier after its start, through the core's flatten.
template <class Curve>
void flatten_curve(const Curve& curve, double tolerance, std::vector<MachinePoint>& out) {
  bool first = true;
  const auto flattened = flatten(curve, tolerance, [&](const FlattenVertex<double, motion_axes>& vertex) {
    if (!first) out.push_back(vertex.point);
    first = false;
  });
  if (!flattened) {
    throw std::invalid_argument(std::string("cannot flatten a curve to tolerance ") + std::to_string(tolerance) + " mm: " +
                                std::string(describe(flattened.error())));
  }
  out.back() = curve.back();  // the end exactly, so the next segment starts on it
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
    case SegmentKind::Bezier: flatten_curve(segment.polynomial(), tolerance_mm, out); break;
    case SegmentKind::RationalBezier: flatten_curve(segment.rational(), tolerance_mm, out); break;
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
