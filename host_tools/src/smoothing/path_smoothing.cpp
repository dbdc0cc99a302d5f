// SPDX-License-Identifier: MIT
// Path smoothing (path_smoothing.hpp): line runs fitted, then corners blended.
#include <curvestep/host/smoothing/path_smoothing.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include <curvestep/host/smoothing/corner_blend.hpp>
#include <curvestep/host/smoothing/line_run_fit.hpp>
#include <curvestep/host/smoothing/segment_geometry.hpp>

namespace curvestep::host::smoothing {
namespace {

constexpr double pi = 3.14159265358979323846;
/// A joint counts as a corner above this deflection (rad); below it, a curvature jump above
/// `curvature_jump_per_mm` still makes it one.
constexpr double corner_deflection_rad = 1e-7;
constexpr double curvature_jump_per_mm = 1e-9;
/// Deflections above this are reversals: kept, the planner stops there.
constexpr double reversal_deflection_deg = 179;

/// One piece of the path between smoothing steps.
struct Item {
  PathSegment segment;
  std::size_t source = 0;   ///< Job::source_index of the programmed segment it comes from
  double length_mm = 0;     ///< arc length (before any cut)
  bool fitted = false;      ///< part of a fitted run
  bool run_inside_next = false;  ///< the joint to the next item is inside a fitted run (smooth)
  double joint_tolerance_mm = 0; ///< tolerance at the joint to the next item (0: keep the joint)
  double start_u = 0;       ///< cut by the blend before it
  double end_u = 1;         ///< cut by the blend after it
  MachinePoint start_point{};
  MachinePoint end_point{};
};

double deflection_cos(const PathSegment& a, const PathSegment& b) {
  return dot(local_frame(a, 1.0).tangent, local_frame(b, 0.0).tangent);
}

/// The tolerance of joint k (between programmed segments k-1 and k), 0 if it must stay.
double joint_tolerance(const Job& job, const SmoothingOptions& options, const std::set<std::size_t>& event_joints, std::size_t k) {
  if (event_joints.count(k) != 0) return 0;
  const PathSegment& a = job.segments[k - 1];
  const PathSegment& b = job.segments[k];
  if (a.rapid() || b.rapid()) return 0;
  double tolerance = options.tolerance_mm;
  if (job.blend_tolerance_mm.size() == job.segments.size()) {
    const double programmed = job.blend_tolerance_mm[k];
    if (programmed < 0) return 0;
    if (programmed > 0) tolerance = programmed;
  }
  return tolerance;
}

/// Time to change speed by v from or to rest: S-curve v/a + a/j (or 2√(v/j) below a²/j), trapezoid v/a.
double speed_change_time(double v, double a, double j) {
  if (!(j < 1e11)) return v / a;
  return v > a * a / j ? v / a + a / j : 2 * std::sqrt(v / j);
}

/// Whether passing the blend (at its curvature speed) beats stopping at the corner and starting
/// again from that speed: at sharp corners under a jerk limit, a tolerance-sized blend is so tight
/// that it must be crawled through for longer than a stop takes.
bool blend_pays(const CornerBlend& blend, const SmoothingOptions& options) {
  const double v = blend.speed_cap_mm_per_s;
  if (!std::isfinite(v)) return true;
  const double through = length_between(blend.curve, 0, 1) / v;
  const double stop_and_go = 2 * speed_change_time(v, options.a_max_mm_per_s2, options.j_max_mm_per_s3);
  return through < stop_and_go;
}

bool fittable_line(const PathSegment& s, const SmoothingOptions& options) {
  return s.kind() == SegmentKind::Line && !s.rapid() && norm(s.end() - s.start()) <= options.fit_max_line_mm;
}

}  // namespace

SmoothingOptions options_for(const MachineLimits& machine, double tolerance_mm) {
  SmoothingOptions options;
  options.tolerance_mm = tolerance_mm;
  options.a_max_mm_per_s2 = machine.a_max_mm_per_s2;
  options.j_max_mm_per_s3 = machine.jerk_limited ? machine.j_max_mm_per_s3 : 1e12;
  return options;
}

Job smooth_job(Job job, const SmoothingOptions& options, SmoothingReport* report) {
  SmoothingReport figures;
  figures.tolerance_mm = options.tolerance_mm;
  figures.segments_before = job.segments.size();
  const std::size_t n = job.segments.size();
  if (!(options.tolerance_mm > 0) || n == 0) {
    figures.segments_after = n;
    if (report != nullptr) *report = figures;
    return job;
  }
  std::set<std::size_t> event_joints;
  for (const auto& e : job.events) event_joints.insert(e.before_segment);
  std::vector<double> tolerance(n + 1, 0.0);  // tolerance[k]: joint between k-1 and k
  for (std::size_t k = 1; k < n; ++k) tolerance[k] = joint_tolerance(job, options, event_joints, k);

  // 1. Runs of short lines -> splines.
  std::vector<Item> items;
  std::vector<std::size_t> first_item(n + 1, 0);  // programmed segment k starts at items[first_item[k]]
  items.reserve(n);  // room for one item per segment: the vector never moves them while it grows
  const double cos_max_run_deflection = std::cos(options.fit_max_deflection_deg * pi / 180);
  const auto make_item = [&](const PathSegment& s, std::size_t source, bool fitted) {
    Item item;
    item.segment = s;
    item.source = source;
    item.length_mm = length_between(s, 0, 1);
    item.fitted = fitted;
    item.start_point = s.start();
    item.end_point = s.end();
    return item;
  };
  for (std::size_t k = 0; k < n;) {
    std::size_t end = k + 1;  // the run is [k, end)
    if (options.fit_line_runs && fittable_line(job.segments[k], options)) {
      while (end < n && fittable_line(job.segments[end], options) && tolerance[end] > 0 && tolerance[end] == tolerance[k + 1 < n ? k + 1 : k] &&
             job.segments[end].feed_mm_per_s() == job.segments[k].feed_mm_per_s() &&
             deflection_cos(job.segments[end - 1], job.segments[end]) >= cos_max_run_deflection) {
        ++end;
      }
    }
    std::optional<LineRunFit> fit;
    if (end - k >= 3) {
      std::vector<MachinePoint> vertices{job.segments[k].start()};
      for (std::size_t i = k; i < end; ++i) vertices.push_back(job.segments[i].end());
      fit = fit_line_run(vertices, 0.5 * tolerance[k + 1], job.segments[k].feed_mm_per_s());
    }
    if (fit) {
      for (std::size_t i = k; i < end; ++i) first_item[i] = items.size();
      for (std::size_t p = 0; p < fit->pieces.size(); ++p) {
        items.push_back(make_item(fit->pieces[p], job.source_index[k], true));
        items.back().run_inside_next = p + 1 < fit->pieces.size();
      }
      ++figures.runs_fitted;
      figures.lines_fitted += end - k;
      figures.fitted_pieces += fit->pieces.size();
      figures.max_deviation_mm = std::fmax(figures.max_deviation_mm, fit->deviation_mm);
      if (end < n) items.back().joint_tolerance_mm = tolerance[end];
      k = end;
    } else {
      first_item[k] = items.size();
      items.push_back(make_item(job.segments[k], job.source_index[k], false));
      if (k + 1 < n) items.back().joint_tolerance_mm = tolerance[k + 1];
      ++k;
    }
  }
  first_item[n] = items.size();
  std::vector<PathSegment>().swap(job.segments);  // the items hold what is left of them

  // 2. Corners -> blends.
  std::vector<std::optional<CornerBlend>> blends(items.size());
  for (std::size_t i = 0; i + 1 < items.size(); ++i) {
    Item& a = items[i];
    Item& b = items[i + 1];
    if (a.run_inside_next || !(a.joint_tolerance_mm > 0)) continue;
    const double cos_theta = deflection_cos(a.segment, b.segment);
    const double deflection = std::acos(std::clamp(cos_theta, -1.0, 1.0));
    const double curvature_jump = norm(local_frame(a.segment, 1.0).curvature - local_frame(b.segment, 0.0).curvature);
    if (deflection <= corner_deflection_rad && curvature_jump <= curvature_jump_per_mm) continue;
    ++figures.corners;
    if (!options.blend_corners || deflection * 180 / pi > reversal_deflection_deg) continue;
    if (!can_cut(a.segment) || !can_cut(b.segment)) continue;
    CornerRequest request;
    request.incoming = &a.segment;
    request.incoming_length_mm = a.length_mm;
    request.incoming_available_mm = options.blend_max_share * a.length_mm;
    request.outgoing = &b.segment;
    request.outgoing_length_mm = b.length_mm;
    request.outgoing_available_mm = options.blend_max_share * b.length_mm;
    request.tolerance_mm = (a.fitted || b.fitted) ? 0.5 * a.joint_tolerance_mm : a.joint_tolerance_mm;
    request.a_max_mm_per_s2 = options.a_max_mm_per_s2;
    request.j_max_mm_per_s3 = options.j_max_mm_per_s3;
    auto blend = blend_corner(request);
    if (!blend) continue;
    if (!blend_pays(*blend, options)) {
      ++figures.corners_stopped;
      continue;
    }
    a.end_u = blend->incoming_u;
    a.end_point = blend->curve.start();
    b.start_u = blend->outgoing_u;
    b.start_point = blend->curve.end();
    ++figures.corners_blended;
    const double fitted_share = (a.fitted || b.fitted) ? 0.5 * a.joint_tolerance_mm : 0.0;
    figures.max_deviation_mm = std::fmax(figures.max_deviation_mm, blend->deviation_mm + fitted_share);
    blends[i] = std::move(blend);
  }

  // 3. The smoothed job: each item cut to what the blends left, then its blend.
  Job out;
  out.version = job.version;
  out.name = job.name;
  out.sources = std::move(job.sources);
  std::vector<std::size_t> first_output(items.size() + 1, 0);
  for (std::size_t i = 0; i < items.size(); ++i) {
    const Item& item = items[i];
    first_output[i] = out.segments.size();
    if (item.start_u == 0 && item.end_u == 1) {
      out.segments.push_back(item.segment);
      out.source_index.push_back(item.source);
    } else if (item.start_u < item.end_u && item.start_point != item.end_point) {
      auto piece = piece_between(item.segment, item.start_u, item.end_u, item.start_point, item.end_point);
      if (piece) {
        out.segments.push_back(*piece);
        out.source_index.push_back(item.source);
      } else if (item.start_point != item.end_point) {
        // A piece that cannot be cut stays a straight connection between the cut points.
        auto line = PathSegment::make_line(item.start_point, item.end_point);
        if (line) {
          line.value().set_feed_mm_per_s(item.segment.feed_mm_per_s());
          out.segments.push_back(line.value());
          out.source_index.push_back(item.source);
        }
      }
    }
    if (blends[i]) {
      out.segments.push_back(blends[i]->curve);
      out.source_index.push_back(items[i + 1].source);
    }
  }
  first_output[items.size()] = out.segments.size();
  out.events = std::move(job.events);
  for (auto& e : out.events) e.before_segment = first_output[first_item[std::min(e.before_segment, n)]];
  figures.segments_after = out.segments.size();
  if (report != nullptr) *report = figures;
  return out;
}

std::string format_smoothing(const SmoothingReport& r) {
  std::ostringstream out;
  if (!(r.tolerance_mm > 0)) {
    out << "  smoothing:           off (machine file \"blend_tolerance\" or --blend-tolerance)\n";
    return out.str();
  }
  out << "  smoothing:           tolerance " << r.tolerance_mm * 1000 << " um; " << r.segments_before << " segments -> "
      << r.segments_after << "\n";
  out << "  corners blended:     " << r.corners_blended << " of " << r.corners;
  if (r.corners_stopped > 0) out << " (" << r.corners_stopped << " sharp ones stop: faster than their blend)";
  out << "\n";
  out << "  line runs fitted:    " << r.runs_fitted << " (" << r.lines_fitted << " lines -> " << r.fitted_pieces << " curves)\n";
  out << "  path deviation:      " << r.max_deviation_mm * 1000 << " um from the programmed path (tolerance "
      << r.tolerance_mm * 1000 << " um)\n";
  return out.str();
}

std::vector<std::array<std::string, 3>> smoothing_rows(const SmoothingReport& r) {
  const auto um = [](double mm) {
    std::ostringstream text;
    text << mm * 1000 << " µm";
    return text.str();
  };
  if (!(r.tolerance_mm > 0)) return {{"path smoothing", "off", ""}};
  return {{"path smoothing", std::to_string(r.segments_before) + " segments → " + std::to_string(r.segments_after), ""},
          {"corners blended", std::to_string(r.corners_blended) + " of " + std::to_string(r.corners), ""},
          {"line runs fitted", std::to_string(r.runs_fitted) + " (" + std::to_string(r.lines_fitted) + " lines → " +
                                   std::to_string(r.fitted_pieces) + " curves)",
           ""},
          {"deviation from the programmed path", um(r.max_deviation_mm), um(r.tolerance_mm)}};
}

}  // namespace curvestep::host::smoothing
