// SPDX-License-Identifier: MIT
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <curvestep/host/flatten.hpp>
#include <curvestep/host/report.hpp>

#include "svg_text.hpp"

namespace curvestep::host {
namespace {

using report_detail::escape;
using report_detail::figure;
using report_detail::pixel;

using Point2 = std::array<double, 2>;

/// One polyline of the drawing, in millimetres.
struct Stroke {
  std::vector<Point2> points;
  std::string colour;
  bool rapid = false;
};

constexpr const char* rapid_colour = "#888888";
constexpr std::size_t speed_buckets = 32;

bool is_rapid_source(const Job& job, std::size_t source) {
  return source < job.sources.size() && job.sources[source].type == SegmentType::Rapid;
}

/// Strokes from the flattened segments, one per PathSegment, coloured by file segment.
std::vector<Stroke> strokes_by_segment(const Job& job) {
  // A coarse pass finds the size; the fine pass stays within 1/4000 of it (a fraction of a pixel).
  auto size_of = [](const std::vector<MachinePoint>& points) {
    double lo_x = std::numeric_limits<double>::max(), lo_y = lo_x, hi_x = std::numeric_limits<double>::lowest(), hi_y = hi_x;
    for (const auto& p : points) {
      lo_x = std::min(lo_x, p[0]);
      hi_x = std::max(hi_x, p[0]);
      lo_y = std::min(lo_y, p[1]);
      hi_y = std::max(hi_y, p[1]);
    }
    return std::max(hi_x - lo_x, hi_y - lo_y);
  };
  const double coarse = size_of(flatten_path(job.segments, 0.5));
  const double tolerance = std::max(coarse / 4000.0, 1e-4);
  std::vector<Stroke> strokes;
  for (std::size_t i = 0; i < job.segments.size(); ++i) {
    const std::size_t source = job.source_index.empty() ? i : job.source_index[i];
    std::vector<MachinePoint> points{job.segments[i].start()};
    flatten_segment(job.segments[i], tolerance, points);
    Stroke s;
    s.rapid = job.segments[i].rapid() || is_rapid_source(job, source);
    s.colour = s.rapid ? rapid_colour : report_detail::segment_colour(source);
    for (const auto& p : points) s.points.push_back({p[0], p[1]});
    strokes.push_back(std::move(s));
  }
  return strokes;
}

/// Strokes from the setpoints: runs of equal speed colour, rapids apart. Returns the peak feed speed.
std::vector<Stroke> strokes_by_speed(const Job& job, const std::vector<SetpointRecord>& setpoints, double& peak_speed) {
  peak_speed = 0;
  for (const auto& r : setpoints) {
    if (!is_rapid_source(job, r.segment)) peak_speed = std::max(peak_speed, r.speed_mm_per_s);
  }
  auto bucket_of = [&](const SetpointRecord& r) -> std::size_t {
    if (!(peak_speed > 0)) return 0;
    const double f = std::clamp(r.speed_mm_per_s / peak_speed, 0.0, 1.0);
    return std::min(static_cast<std::size_t>(f * speed_buckets), speed_buckets - 1);
  };
  std::vector<Stroke> strokes;
  std::size_t current_bucket = 0;
  for (std::size_t i = 0; i < setpoints.size(); ++i) {
    const auto& r = setpoints[i];
    const bool rapid = is_rapid_source(job, r.segment);
    const std::size_t bucket = rapid ? speed_buckets : bucket_of(r);
    const Point2 p{r.position_mm[0], r.position_mm[1]};
    if (strokes.empty() || bucket != current_bucket) {
      Stroke s;
      s.rapid = rapid;
      s.colour = rapid ? rapid_colour
                       : report_detail::speed_colour((static_cast<double>(bucket) + 0.5) / static_cast<double>(speed_buckets));
      if (!strokes.empty()) s.points.push_back(strokes.back().points.back());  // joined to the previous run
      strokes.push_back(std::move(s));
      current_bucket = bucket;
    }
    strokes.back().points.push_back(p);
  }
  return strokes;
}

}  // namespace

std::string path_plot_svg(const Job& job, const std::vector<SetpointRecord>* setpoints, const PathPlotOptions& options) {
  if (job.segments.empty()) throw std::invalid_argument(job.name + ": the job has no segments");
  const bool by_speed = setpoints != nullptr && !setpoints->empty();
  double peak_speed = 0;
  const std::vector<Stroke> strokes = by_speed ? strokes_by_speed(job, *setpoints, peak_speed) : strokes_by_segment(job);

  double min_x = std::numeric_limits<double>::max(), min_y = min_x;
  double max_x = std::numeric_limits<double>::lowest(), max_y = max_x;
  for (const auto& s : strokes) {
    for (const auto& p : s.points) {
      min_x = std::min(min_x, p[0]);
      max_x = std::max(max_x, p[0]);
      min_y = std::min(min_y, p[1]);
      max_y = std::max(max_y, p[1]);
    }
  }
  const double extent_x = max_x - min_x;
  const double extent_y = max_y - min_y;
  const double extent = std::max({extent_x, extent_y, 1e-6});
  const double width = std::max(options.width_px, 200.0);
  const double margin = 30;
  const double top = options.title.empty() ? margin : margin + 24;
  const double footer = 60;
  // Fit the longer side; a tall path may use up to max_height_px (1.25 × the width) in height.
  const double area_height = options.max_height_px > 0 ? std::max(options.max_height_px, 50.0) : 1.25 * width - top - footer;
  const double scale = std::min((width - 2 * margin) / std::max(extent_x, extent * 1e-3), area_height / std::max(extent_y, extent * 1e-3));
  const double plot_width = extent_x * scale;
  const double height = top + extent_y * scale + footer;
  const double offset_x = (width - plot_width) / 2;
  auto sx = [&](double x) { return offset_x + (x - min_x) * scale; };
  auto sy = [&](double y) { return top + (max_y - y) * scale; };

  std::ostringstream out;
  if (options.standalone) out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"path-plot\" width=\"" << pixel(width) << "\" height=\"" << pixel(height)
      << "\" viewBox=\"0 0 " << pixel(width) << " " << pixel(height) << "\" font-family=\"sans-serif\">\n";
  out << "<title>" << escape(options.title.empty() ? job.name : options.title) << "</title>\n";
  if (by_speed) {
    out << "<defs><linearGradient id=\"speed-scale\" x1=\"0\" x2=\"1\" y1=\"0\" y2=\"0\">";
    for (int i = 0; i <= 8; ++i) {
      const double f = i / 8.0;
      out << "<stop offset=\"" << figure(f) << "\" stop-color=\"" << report_detail::speed_colour(f) << "\"/>";
    }
    out << "</linearGradient></defs>\n";
  }
  out << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  if (!options.title.empty()) {
    out << "<text x=\"" << pixel(margin) << "\" y=\"" << pixel(margin) << "\" font-size=\"16\">" << escape(options.title) << "</text>\n";
  }
  for (const auto& s : strokes) {
    if (s.points.empty()) continue;
    out << "<polyline class=\"" << (s.rapid ? "rapid" : "feed") << "\" fill=\"none\" stroke=\"" << s.colour
        << "\" stroke-width=\"" << (s.rapid ? "1.2" : "2") << "\" stroke-linejoin=\"round\" stroke-linecap=\"round\""
        << (s.rapid ? " stroke-dasharray=\"6 4\"" : "") << " points=\"";
    // Points closer than half a pixel to the last one drawn are left out (the last point never is).
    double last_x = std::numeric_limits<double>::max(), last_y = last_x;
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      const double x = sx(s.points[i][0]);
      const double y = sy(s.points[i][1]);
      if (i + 1 < s.points.size() && std::hypot(x - last_x, y - last_y) < 0.5) continue;
      out << pixel(x) << "," << pixel(y) << " ";
      last_x = x;
      last_y = y;
    }
    out << "\"/>\n";
  }
  // Start and end of the path: the first and last point drawn.
  const Point2 start = strokes.front().points.front();
  const Point2 end = strokes.back().points.back();
  out << "<circle class=\"start-marker\" cx=\"" << pixel(sx(start[0])) << "\" cy=\"" << pixel(sy(start[1]))
      << "\" r=\"6\" fill=\"none\" stroke=\"#2ca02c\" stroke-width=\"3\"><title>start (" << figure(start[0]) << ", "
      << figure(start[1]) << ") mm</title></circle>\n";
  out << "<rect class=\"end-marker\" x=\"" << pixel(sx(end[0]) - 5) << "\" y=\"" << pixel(sy(end[1]) - 5)
      << "\" width=\"10\" height=\"10\" fill=\"none\" stroke=\"#d62728\" stroke-width=\"3\"><title>end (" << figure(end[0]) << ", "
      << figure(end[1]) << ") mm</title></rect>\n";

  // Footer: scale bar, then the colour key.
  const double bar_mm = report_detail::nice_step_below(extent / 4);
  const double bar_y = height - footer + 24;
  out << "<g class=\"scale-bar\"><line x1=\"" << pixel(margin) << "\" y1=\"" << pixel(bar_y) << "\" x2=\""
      << pixel(margin + bar_mm * scale) << "\" y2=\"" << pixel(bar_y) << "\" stroke=\"black\" stroke-width=\"3\"/>"
      << "<text x=\"" << pixel(margin + bar_mm * scale + 8) << "\" y=\"" << pixel(bar_y + 5) << "\" font-size=\"13\">"
      << figure(bar_mm) << " mm</text></g>\n";
  const double key_x = width / 2 - 40;
  if (by_speed) {
    out << "<g class=\"speed-key\"><rect x=\"" << pixel(key_x) << "\" y=\"" << pixel(bar_y - 8) << "\" width=\"160\" height=\"12\" fill=\"url(#speed-scale)\"/>"
        << "<text x=\"" << pixel(key_x - 6) << "\" y=\"" << pixel(bar_y + 3) << "\" font-size=\"12\" text-anchor=\"end\">0</text>"
        << "<text x=\"" << pixel(key_x + 166) << "\" y=\"" << pixel(bar_y + 3) << "\" font-size=\"12\">" << figure(peak_speed)
        << " mm/s (planned speed)</text></g>\n";
  } else {
    out << "<text class=\"segment-key\" x=\"" << pixel(key_x) << "\" y=\"" << pixel(bar_y + 5)
        << "\" font-size=\"12\">colour: segment of the job file</text>\n";
  }
  out << "<text x=\"" << pixel(margin) << "\" y=\"" << pixel(bar_y + 26) << "\" font-size=\"12\" fill=\"#555\">"
      << "XY view, y up. Dashed: rapids. Circle: start, square: end.</text>\n";
  out << "</svg>\n";
  return out.str();
}

void write_path_plot(const std::string& file, const Job& job, const std::vector<SetpointRecord>* setpoints,
                     const PathPlotOptions& options) {
  const std::string svg = path_plot_svg(job, setpoints, options);
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file);
  out << svg;
  out.close();
  if (!out) throw std::runtime_error("error writing " + file);
}

}  // namespace curvestep::host
