// SPDX-License-Identifier: MIT
// Path smoothing (path_smoothing.hpp): a whole job through the SmoothingStream, and the report.
#include <curvestep/host/smoothing/path_smoothing.hpp>

#include <sstream>
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
    if (report != nullptr) *report = figures;
    return job;
  }
  SmoothingStream stream(options);
  Job rest = feed_job(std::move(job), stream);
  return stream.finish(std::move(rest), report);
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
  if (r.corners_stopped > 0) out << " (" << r.corners_stopped << " kept: the planner passes them faster as programmed)";
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
