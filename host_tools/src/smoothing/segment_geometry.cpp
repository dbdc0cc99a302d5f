// SPDX-License-Identifier: MIT
// Arc length, cutting and distances of single PathSegments for the host's path smoothing.
#include <curvestep/host/smoothing/segment_geometry.hpp>

#include <algorithm>
#include <array>
#include <cmath>

#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/core/motion/segment_plan.hpp>
#include <curvestep/host/wire_value.hpp>

namespace curvestep::host::smoothing {
namespace {

/// 8-point Gauss-Legendre nodes on [-1, 1] (positive half) and weights.
constexpr std::array<double, 4> gauss_nodes{0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
constexpr std::array<double, 4> gauss_weights{0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

double gauss_length(const PathSegment& segment, double a, double b) {
  const double half = (b - a) / 2;
  const double mid = (a + b) / 2;
  double sum = 0;
  for (std::size_t i = 0; i < gauss_nodes.size(); ++i) {
    sum += gauss_weights[i] * (norm(segment.derivative(mid - half * gauss_nodes[i], 1)) + norm(segment.derivative(mid + half * gauss_nodes[i], 1)));
  }
  return sum * half;
}

}  // namespace

std::optional<MachinePoint> on_grid(const MachinePoint& p) {
  MachinePoint q{};
  for (std::size_t axis = 0; axis < motion_axes; ++axis) {
    const auto fixed = Q16_16::from_double(p[axis]);
    if (!fixed) return std::nullopt;
    q[axis] = fixed.value().to_double();
  }
  return q;
}

double length_between(const PathSegment& segment, double u0, double u1) {
  if (!(u1 > u0)) return 0;
  if (segment.kind() == SegmentKind::Line) return norm(segment.end() - segment.start()) * (u1 - u0);
  constexpr int pieces = 16;
  double total = 0;
  for (int k = 0; k < pieces; ++k) {
    const double a = u0 + (u1 - u0) * k / pieces;
    const double b = u0 + (u1 - u0) * (k + 1) / pieces;
    total += gauss_length(segment, a, b);
  }
  return total;
}

namespace {
constexpr std::size_t map_pieces = 64;
}

LengthMap::LengthMap(const PathSegment& segment) : segment_(&segment), cumulative_(map_pieces + 1, 0.0) {
  for (std::size_t k = 0; k < map_pieces; ++k) {
    const double a = static_cast<double>(k) / map_pieces;
    const double b = static_cast<double>(k + 1) / map_pieces;
    cumulative_[k + 1] = cumulative_[k] + (segment.kind() == SegmentKind::Line ? norm(segment.end() - segment.start()) / map_pieces
                                                                                : gauss_length(segment, a, b));
  }
}

double LengthMap::parameter_at(double s_mm) const {
  if (s_mm <= 0) return 0;
  if (s_mm >= total()) return 1;
  if (segment_->kind() == SegmentKind::Line) return s_mm / total();
  const auto above = std::upper_bound(cumulative_.begin(), cumulative_.end(), s_mm);
  const std::size_t k = static_cast<std::size_t>(above - cumulative_.begin()) - 1;
  const double base = static_cast<double>(k) / map_pieces;
  double low = base;
  double high = static_cast<double>(k + 1) / map_pieces;
  const double wanted = s_mm - cumulative_[k];
  for (int i = 0; i < 44; ++i) {
    const double mid = (low + high) / 2;
    if (gauss_length(*segment_, base, mid) < wanted) {
      low = mid;
    } else {
      high = mid;
    }
  }
  return (low + high) / 2;
}

LocalFrame local_frame(const PathSegment& segment, double u) {
  LocalFrame frame;
  curvestep::detail::tangent_and_curvature(segment.derivative(u, 1), segment.derivative(u, 2), frame.tangent, frame.curvature);
  return frame;
}

bool can_cut(const PathSegment& segment) {
  if (segment.kind() != SegmentKind::Arc) return true;
  return std::fabs(segment.arc_sweep_rad()) <= 2 * 3.14159265358979323846 + 1e-9;
}

std::optional<PathSegment> piece_between(const PathSegment& segment, double u0, double u1, const MachinePoint& start,
                                         const MachinePoint& end) {
  if (!(u1 > u0) || start == end) return std::nullopt;
  std::optional<PathSegment> piece;
  switch (segment.kind()) {
    case SegmentKind::Line: {
      auto made = PathSegment::make_line(start, end);
      if (!made) return std::nullopt;
      piece = made.value();
      break;
    }
    case SegmentKind::Arc: {
      const ArcDirection direction = segment.arc_sweep_rad() >= 0 ? ArcDirection::CounterClockwise : ArcDirection::Clockwise;
      const double r_start = norm(MachinePoint{{segment.start()[0] - segment.arc_center()[0], segment.start()[1] - segment.arc_center()[1], 0}});
      const double r_end = norm(MachinePoint{{segment.end()[0] - segment.arc_center()[0], segment.end()[1] - segment.arc_center()[1], 0}});
      const double tolerance = std::fabs(r_end - r_start) + 1e-4;
      auto made = PathSegment::make_arc(start, end, segment.arc_center(), direction, 0, tolerance);
      if (!made) return std::nullopt;
      piece = made.value();
      break;
    }
    case SegmentKind::Bezier:
    case SegmentKind::RationalBezier: {
      PathSegment rest = segment;
      PathSegment left;
      if (u1 < 1) {
        if (!rest.split_off(u1, left)) return std::nullopt;
        rest = left;  // the piece on [0, u1]
      }
      if (u0 > 0) {
        const double at = u0 / u1;  // u0 within [0, u1]
        if (!(at > 0 && at < 1) || !rest.split_off(at, left)) return std::nullopt;
      }
      const bool rational = rest.kind() == SegmentKind::RationalBezier;
      const auto control = rational ? rest.rational().control_points() : rest.polynomial().control_points();
      std::vector<MachinePoint> points(control.begin(), control.end());
      for (auto& p : points) {
        const auto q = on_grid(p);
        if (!q) return std::nullopt;
        p = *q;
      }
      points.front() = start;
      points.back() = end;
      if (rational) {
        std::vector<double> weights;
        for (std::size_t i = 0; i < points.size(); ++i) {
          const auto w = round_for_wire(rest.rational().weight(i), WireQuantity::Weight);
          if (!w) return std::nullopt;
          weights.push_back(w.value);
        }
        auto made = PathSegment::make_rational_bezier(points, weights);
        if (!made) return std::nullopt;
        piece = made.value();
      } else {
        auto made = PathSegment::make_bezier(points);
        if (!made) return std::nullopt;
        piece = made.value();
      }
      break;
    }
  }
  piece->set_rapid(segment.rapid());
  piece->set_feed_mm_per_s(segment.feed_mm_per_s());
  return piece;
}

std::vector<MachinePoint> sample(const PathSegment& segment, double u0, double u1, std::size_t samples) {
  std::vector<MachinePoint> points;
  points.reserve(samples + 1);
  for (std::size_t k = 0; k <= samples; ++k) {
    const double u = k == samples ? u1 : u0 + (u1 - u0) * static_cast<double>(k) / static_cast<double>(samples);
    points.push_back(segment.point(std::clamp(u, 0.0, 1.0)));
  }
  return points;
}

double distance_to_chord(const MachinePoint& p, const MachinePoint& a, const MachinePoint& b) {
  const MachinePoint ab = b - a;
  const double length2 = dot(ab, ab);
  double t = length2 > 0 ? dot(p - a, ab) / length2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return norm(p - (a + ab * t));
}

double distance_to_polyline(const MachinePoint& p, const std::vector<MachinePoint>& points) {
  if (points.size() == 1) return norm(p - points.front());
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < points.size(); ++i) best = std::fmin(best, distance_to_chord(p, points[i - 1], points[i]));
  return best;
}

}  // namespace curvestep::host::smoothing
