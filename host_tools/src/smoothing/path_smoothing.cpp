// SPDX-License-Identifier: MIT
// Path smoothing (path_smoothing.hpp): a whole job through the SmoothingStream, and the report.
#include <curvestep/host/smoothing/path_smoothing.hpp>

#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <curvestep/host/smoothing/smoothing_stream.hpp>

namespace curvestep::host::smoothing {

SmoothingOptions options_for(const MachineLimits& machine, double tolerance_mm) {
  SmoothingOptions options;
  options.tolerance_mm = tolerance_mm;
  options.machine = machine;
  return options;
}

Job smooth_job(Job job, const SmoothingOptions& options, SmoothingReport* report) {
  if (!(options.tolerance_mm > 0) || job.segments.empty()) {  // the job as programmed
    SmoothingReport figures;
    figures.tolerance_mm = options.tolerance_mm;
    figures.segments_before = job.segments.size();
    figures.segments_after = job.segments.size();
    for (const double tolerance : job.blend_tolerance_mm) figures.unapplied_tolerance_mm = std::fmax(figures.unapplied_tolerance_mm, tolerance);
    if (report != nullptr) *report = figures;
    return job;
  }
  SmoothingStream stream(options);
  Job rest = feed_job(std::move(job), stream);
  return stream.finish(std::move(rest), report);
}

namespace {

/// Why corners were kept, for the summary ("" when all were blended).
std::string kept_corners(const SmoothingReport& r) {
  std::string why;
  const auto add = [&why](std::size_t count, const char* reason) {
    if (count == 0) return;
    why += (why.empty() ? "" : "; ") + std::to_string(count) + " " + reason;
  };
  add(r.corners_stopped, "kept: the planner passes them faster as programmed");
  add(r.corners_reversed, "reversals: the planner stops there");
  add(r.corners_unblendable, "kept: no blend fits (a neighbour too short for the tolerance)");
  return why;
}

std::string micrometres(double mm, const char* unit) {
  std::ostringstream text;
  text << mm * 1000 << " " << unit;
  return text.str();
}

/// The tolerance the deviation is judged against: the machine's, or with G64 P per move the range
/// and how much of the tolerance in force the deviation used where it occurred.
std::string deviation_limit(const SmoothingReport& r, const char* unit) {
  std::string limit = micrometres(r.tolerance_mm, unit);
  if (!(r.largest_tolerance_mm > r.tolerance_mm)) return limit;
  std::ostringstream share;
  share << r.max_deviation_share * 100;
  return limit + ", up to " + micrometres(r.largest_tolerance_mm, unit) + " set by G64 P; at most " + share.str() +
         " % of the tolerance in force where it occurs";
}

}  // namespace

std::string format_smoothing(const SmoothingReport& r) {
  std::ostringstream out;
  if (!(r.tolerance_mm > 0)) {
    out << "  smoothing:           off (machine file \"blend_tolerance\" or --blend-tolerance)";
    if (r.unapplied_tolerance_mm > 0) out << "; the program's G64 P (up to " << r.unapplied_tolerance_mm * 1000 << " um) is not applied";
    out << "\n";
    return out.str();
  }
  out << "  smoothing:           tolerance " << r.tolerance_mm * 1000 << " um; " << r.segments_before << " segments -> "
      << r.segments_after << "\n";
  out << "  corners blended:     " << r.corners_blended << " of " << r.corners;
  if (const std::string why = kept_corners(r); !why.empty()) out << " (" << why << ")";
  out << "\n";
  out << "  line runs fitted:    " << r.runs_fitted << " (" << r.lines_fitted << " lines -> " << r.fitted_pieces << " curves)\n";
  out << "  path deviation:      " << r.max_deviation_mm * 1000 << " um from the programmed path (tolerance " << deviation_limit(r, "um") << ")\n";
  return out.str();
}

std::vector<std::array<std::string, 3>> smoothing_rows(const SmoothingReport& r) {
  if (!(r.tolerance_mm > 0)) {
    if (r.unapplied_tolerance_mm > 0) return {{"path smoothing", "off: the program's G64 P (up to " + micrometres(r.unapplied_tolerance_mm, "µm") + ") is not applied", ""}};
    return {{"path smoothing", "off", ""}};
  }
  std::string corners = std::to_string(r.corners_blended) + " of " + std::to_string(r.corners);
  if (const std::string why = kept_corners(r); !why.empty()) corners += " (" + why + ")";
  return {{"path smoothing", std::to_string(r.segments_before) + " segments → " + std::to_string(r.segments_after), ""},
          {"corners blended", corners, ""},
          {"line runs fitted", std::to_string(r.runs_fitted) + " (" + std::to_string(r.lines_fitted) + " lines → " +
                                   std::to_string(r.fitted_pieces) + " curves)",
           ""},
          {"deviation from the programmed path", micrometres(r.max_deviation_mm, "µm"), deviation_limit(r, "µm")}};
}

}  // namespace curvestep::host::smoothing
