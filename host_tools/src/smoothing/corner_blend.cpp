// SPDX-License-Identifier: MIT
// Corner blends (corner_blend.hpp): G2 quintics within a tolerance of the programmed corner.
#include <curvestep/host/smoothing/corner_blend.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <curvestep/core/motion/segment_plan.hpp>
#include <curvestep/host/smoothing/segment_geometry.hpp>

namespace curvestep::host::smoothing {
namespace {

/// Blend speeds λ = β d tried; the one the planner can pass fastest is kept (1.3 suits sharp
/// corners, 2.1 gentle ones: measured on line–line corners of 10° to 135°).
constexpr std::array<double, 2> shape_factors{1.3, 2.1};
/// Deviations are measured on sampled curves: accept up to this share of the tolerance.
constexpr double tolerance_margin = 0.97;
constexpr std::size_t blend_samples = 32;
constexpr std::size_t programmed_samples = 16;

struct Candidate {
  CornerBlend blend;
  bool valid = false;
};

/// Arc-length maps of the two neighbours, built once per corner.
struct Maps {
  LengthMap incoming;
  LengthMap outgoing;
};

/// The blend of cut lengths d_a, d_b and shape factor β (not yet checked against the tolerance).
Candidate make_candidate(const CornerRequest& r, const Maps& maps, double d_a, double d_b, double beta) {
  Candidate c;
  const double u_a = maps.incoming.parameter_at(maps.incoming.total() - d_a);
  const double u_b = maps.outgoing.parameter_at(d_b);
  if (!(u_a > 0 && u_a < 1 && u_b > 0 && u_b < 1)) return c;
  const auto p_a = on_grid(r.incoming->point(u_a));
  const auto p_b = on_grid(r.outgoing->point(u_b));
  if (!p_a || !p_b || *p_a == *p_b) return c;
  const LocalFrame f_a = local_frame(*r.incoming, u_a);
  const LocalFrame f_b = local_frame(*r.outgoing, u_b);
  if (!(norm(f_a.tangent) > 0.5) || !(norm(f_b.tangent) > 0.5)) return c;
  const double l_a = beta * d_a;
  const double l_b = beta * d_b;
  std::array<MachinePoint, 6> control{
      *p_a,
      *p_a + f_a.tangent * (l_a / 5),
      *p_a + f_a.tangent * (2 * l_a / 5) + f_a.curvature * (l_a * l_a / 20),
      *p_b - f_b.tangent * (2 * l_b / 5) + f_b.curvature * (l_b * l_b / 20),
      *p_b - f_b.tangent * (l_b / 5),
      *p_b,
  };
  for (std::size_t i = 1; i + 1 < control.size(); ++i) {
    const auto q = on_grid(control[i]);
    if (!q) return c;
    control[i] = *q;
  }
  auto made = PathSegment::make_bezier(control);
  if (!made) return c;
  c.blend.curve = made.value();
  c.blend.curve.set_rapid(r.outgoing->rapid());
  c.blend.incoming_u = u_a;
  c.blend.outgoing_u = u_b;
  c.blend.incoming_cut_mm = d_a;
  c.blend.outgoing_cut_mm = d_b;
  c.valid = true;
  return c;
}

/// Largest distance between the blend and the programmed path of the corner, both ways, and
/// whether the blend's velocity stays away from zero (no cusp).
double deviation(const CornerRequest& r, const CornerBlend& b) {
  std::vector<MachinePoint> programmed = sample(*r.incoming, b.incoming_u, 1.0, programmed_samples);
  const auto after = sample(*r.outgoing, 0.0, b.outgoing_u, programmed_samples);
  programmed.insert(programmed.end(), after.begin() + 1, after.end());
  const auto curve = sample(b.curve, 0.0, 1.0, blend_samples);
  double worst = 0;
  for (const auto& p : curve) worst = std::fmax(worst, distance_to_polyline(p, programmed));
  for (const auto& p : programmed) worst = std::fmax(worst, distance_to_polyline(p, curve));
  return worst;
}

/// The speed the planner allows on the blend by its curvature (plan_segment's caps, from samples).
double curvature_speed_cap(const CornerRequest& r, const PathSegment& curve) {
  double max_kappa = 0;
  double max_rate = 0;
  MachinePoint previous_point = curve.start();
  MachinePoint previous_curvature{};
  for (std::size_t k = 0; k <= blend_samples; ++k) {
    const double u = static_cast<double>(k) / blend_samples;
    const LocalFrame f = local_frame(curve, u);
    const MachinePoint p = curve.point(u);
    const double kappa = norm(f.curvature);
    if (!(norm(f.tangent) > 0.5)) return 0;  // a cusp
    max_kappa = std::fmax(max_kappa, kappa);
    if (k > 0) {
      const double ds = norm(p - previous_point);
      if (ds > 0) max_rate = std::fmax(max_rate, norm(f.curvature - previous_curvature) / ds);
    }
    previous_point = p;
    previous_curvature = f.curvature;
  }
  if (!(max_kappa > 0)) return std::numeric_limits<double>::infinity();
  const double centripetal = std::sqrt(0.5 * r.a_max_mm_per_s2 / max_kappa);
  const double jerk = curvature_jerk_speed_cap(r.j_max_mm_per_s3, max_kappa, 1.25 * max_rate);
  return std::fmin(centripetal, jerk);
}

/// The largest blend of shape β within the tolerance: cut lengths s (each capped by what its
/// segment makes available), found by bisection on s.
Candidate largest_blend(const CornerRequest& r, const Maps& maps, double beta) {
  const double s_max = std::fmax(r.incoming_available_mm, r.outgoing_available_mm);
  const auto at = [&](double s) {
    Candidate c = make_candidate(r, maps, std::fmin(s, r.incoming_available_mm), std::fmin(s, r.outgoing_available_mm), beta);
    if (c.valid) c.blend.deviation_mm = deviation(r, c.blend);
    return c;
  };
  const double limit = tolerance_margin * r.tolerance_mm;
  Candidate best = at(s_max);
  if (best.valid && best.blend.deviation_mm <= limit) return best;
  best = Candidate{};
  double low = 0;
  double high = s_max;
  for (int i = 0; i < 16 && high - low > 1e-5 * s_max; ++i) {
    const double mid = (low + high) / 2;
    Candidate c = at(mid);
    if (c.valid && c.blend.deviation_mm <= limit) {
      low = mid;
      best = c;
    } else {
      high = mid;
    }
  }
  return best;
}

}  // namespace

std::optional<CornerBlend> blend_corner(const CornerRequest& request) {
  if (request.incoming == nullptr || request.outgoing == nullptr || !(request.tolerance_mm > 0)) return std::nullopt;
  if (!(request.incoming_available_mm > 0) || !(request.outgoing_available_mm > 0)) return std::nullopt;
  const Maps maps{LengthMap(*request.incoming), LengthMap(*request.outgoing)};
  std::optional<CornerBlend> best;
  for (const double beta : shape_factors) {
    Candidate c = largest_blend(request, maps, beta);
    if (!c.valid) continue;
    c.blend.speed_cap_mm_per_s = curvature_speed_cap(request, c.blend.curve);
    if (!(c.blend.speed_cap_mm_per_s > 0)) continue;
    if (!best || c.blend.speed_cap_mm_per_s > best->speed_cap_mm_per_s) best = c.blend;
  }
  return best;
}

}  // namespace curvestep::host::smoothing
