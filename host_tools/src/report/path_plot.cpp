// SPDX-License-Identifier: MIT
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <functional>
#include <ostream>
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
  return source_type(job, source) == SegmentType::Rapid;
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

/// The bounding box of the points drawn, in millimetres.
struct Extent {
  double min_x = std::numeric_limits<double>::max(), min_y = min_x;
  double max_x = std::numeric_limits<double>::lowest(), max_y = max_x;
  void add(const Point2& p) {
    min_x = std::min(min_x, p[0]);
    max_x = std::max(max_x, p[0]);
    min_y = std::min(min_y, p[1]);
    max_y = std::max(max_y, p[1]);
  }
};

/// Where the drawing goes on the page: the extent scaled to fit the options' size.
class Frame {
 public:
  Frame(const Extent& e, const PathPlotOptions& options) : min_x_(e.min_x), max_y_(e.max_y) {
    const double extent_x = e.max_x - e.min_x;
    const double extent_y = e.max_y - e.min_y;
    extent = std::max({extent_x, extent_y, 1e-6});
    width = std::max(options.width_px, 200.0);
    top_ = options.title.empty() ? margin : margin + 24;
    // Fit the longer side; a tall path may use up to max_height_px (1.25 × the width) in height.
    const double area_height = options.max_height_px > 0 ? std::max(options.max_height_px, 50.0) : 1.25 * width - top_ - footer;
    scale = std::min((width - 2 * margin) / std::max(extent_x, extent * 1e-3), area_height / std::max(extent_y, extent * 1e-3));
    height = top_ + extent_y * scale + footer;
    offset_x_ = (width - extent_x * scale) / 2;
  }
  static constexpr double margin = 30;
  static constexpr double footer = 60;
  double extent = 0, width = 0, height = 0, scale = 0;
  [[nodiscard]] double x(double mm) const { return offset_x_ + (mm - min_x_) * scale; }
  [[nodiscard]] double y(double mm) const { return top_ + (max_y_ - mm) * scale; }

 private:
  double min_x_, max_y_, top_ = 0, offset_x_ = 0;
};

/// Writes polylines point by point. Points closer than half a pixel to the last one drawn are left
/// out (a stroke's last point never is): the point before is held until the next one shows
/// whether it was the last.
class PolylineWriter {
 public:
  PolylineWriter(std::ostream& out, const Frame& frame) : out_(out), frame_(frame) {}
  void begin(const std::string& colour, bool rapid) {
    out_ << "<polyline class=\"" << (rapid ? "rapid" : "feed") << "\" fill=\"none\" stroke=\"" << colour
         << "\" stroke-width=\"" << (rapid ? "1.2" : "2") << "\" stroke-linejoin=\"round\" stroke-linecap=\"round\""
         << (rapid ? " stroke-dasharray=\"6 4\"" : "") << " points=\"";
    last_x_ = last_y_ = std::numeric_limits<double>::max();
    has_pending_ = false;
  }
  void add(const Point2& p) {
    if (has_pending_) emit(false);
    pending_ = p;
    has_pending_ = true;
  }
  void end() {
    if (has_pending_) emit(true);
    out_ << "\"/>\n";
  }

 private:
  void emit(bool last) {
    const double x = frame_.x(pending_[0]);
    const double y = frame_.y(pending_[1]);
    if (!last && std::hypot(x - last_x_, y - last_y_) < 0.5) return;
    out_ << pixel(x) << "," << pixel(y) << " ";
    last_x_ = x;
    last_y_ = y;
  }
  std::ostream& out_;
  const Frame& frame_;
  double last_x_ = 0, last_y_ = 0;
  Point2 pending_{};
  bool has_pending_ = false;
};

/// What the first pass over a simulation's setpoints learns: extent, peak feed speed, ends.
struct SetpointSurvey {
  Extent extent;
  double peak_speed = 0;
  Point2 first{}, last{};
  std::size_t count = 0;
};

SetpointSurvey survey(const PlottedJob& job, const SetpointReplay& replay) {
  SetpointSurvey s;
  replay([&](const SetpointRecord& r) {
    const Point2 p{r.position_mm[0], r.position_mm[1]};
    if (s.count++ == 0) s.first = p;
    s.last = p;
    s.extent.add(p);
    if (!job.rapid_source(r.segment)) s.peak_speed = std::max(s.peak_speed, r.speed_mm_per_s);
  });
  return s;
}

/// The second pass: runs of equal speed colour (rapids apart) drawn as they come, each run joined
/// to the previous one's last setpoint.
void write_strokes_by_speed(std::ostream& out, const Frame& frame, const PlottedJob& job, const SetpointReplay& replay, double peak_speed) {
  auto bucket_of = [&](const SetpointRecord& r) -> std::size_t {
    if (!(peak_speed > 0)) return 0;
    const double f = std::clamp(r.speed_mm_per_s / peak_speed, 0.0, 1.0);
    return std::min(static_cast<std::size_t>(f * speed_buckets), speed_buckets - 1);
  };
  PolylineWriter writer(out, frame);
  bool drawing = false;
  std::size_t current_bucket = 0;
  Point2 previous{};
  replay([&](const SetpointRecord& r) {
    const bool rapid = job.rapid_source(r.segment);
    const std::size_t bucket = rapid ? speed_buckets : bucket_of(r);
    const Point2 p{r.position_mm[0], r.position_mm[1]};
    if (!drawing || bucket != current_bucket) {
      if (drawing) writer.end();
      writer.begin(rapid ? rapid_colour
                         : report_detail::speed_colour((static_cast<double>(bucket) + 0.5) / static_cast<double>(speed_buckets)),
                   rapid);
      if (drawing) writer.add(previous);
      drawing = true;
      current_bucket = bucket;
    }
    writer.add(p);
    previous = p;
  });
  if (drawing) writer.end();
}

void write_header(std::ostream& out, const Frame& frame, const std::string& job_name, const PathPlotOptions& options, bool by_speed) {
  if (options.standalone) out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"path-plot\" width=\"" << pixel(frame.width) << "\" height=\""
      << pixel(frame.height) << "\" viewBox=\"0 0 " << pixel(frame.width) << " " << pixel(frame.height) << "\" font-family=\"sans-serif\">\n";
  out << "<title>" << escape(options.title.empty() ? job_name : options.title) << "</title>\n";
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
    out << "<text x=\"" << pixel(Frame::margin) << "\" y=\"" << pixel(Frame::margin) << "\" font-size=\"16\">" << escape(options.title)
        << "</text>\n";
  }
}

/// Start and end markers, scale bar and colour key.
void write_footer(std::ostream& out, const Frame& frame, const Point2& start, const Point2& end, bool by_speed, double peak_speed) {
  const double margin = Frame::margin;
  out << "<circle class=\"start-marker\" cx=\"" << pixel(frame.x(start[0])) << "\" cy=\"" << pixel(frame.y(start[1]))
      << "\" r=\"6\" fill=\"none\" stroke=\"#2ca02c\" stroke-width=\"3\"><title>start (" << figure(start[0]) << ", "
      << figure(start[1]) << ") mm</title></circle>\n";
  out << "<rect class=\"end-marker\" x=\"" << pixel(frame.x(end[0]) - 5) << "\" y=\"" << pixel(frame.y(end[1]) - 5)
      << "\" width=\"10\" height=\"10\" fill=\"none\" stroke=\"#d62728\" stroke-width=\"3\"><title>end (" << figure(end[0]) << ", "
      << figure(end[1]) << ") mm</title></rect>\n";
  // Footer: scale bar, then the colour key.
  const double bar_mm = report_detail::nice_step_below(frame.extent / 4);
  const double bar_y = frame.height - Frame::footer + 24;
  out << "<g class=\"scale-bar\"><line x1=\"" << pixel(margin) << "\" y1=\"" << pixel(bar_y) << "\" x2=\""
      << pixel(margin + bar_mm * frame.scale) << "\" y2=\"" << pixel(bar_y) << "\" stroke=\"black\" stroke-width=\"3\"/>"
      << "<text x=\"" << pixel(margin + bar_mm * frame.scale + 8) << "\" y=\"" << pixel(bar_y + 5) << "\" font-size=\"13\">"
      << figure(bar_mm) << " mm</text></g>\n";
  const double key_x = frame.width / 2 - 40;
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
}

void write_plot_by_segment(std::ostream& out, const Job& job, const PathPlotOptions& options) {
  const std::vector<Stroke> strokes = strokes_by_segment(job);
  Extent extent;
  for (const auto& s : strokes) {
    for (const auto& p : s.points) extent.add(p);
  }
  const Frame frame(extent, options);
  write_header(out, frame, job.name, options, false);
  PolylineWriter writer(out, frame);
  for (const auto& s : strokes) {
    if (s.points.empty()) continue;
    writer.begin(s.colour, s.rapid);
    for (const auto& p : s.points) writer.add(p);
    writer.end();
  }
  write_footer(out, frame, strokes.front().points.front(), strokes.back().points.back(), false, 0);
}

/// The plot of a simulation whose survey `s` found setpoints: they are replayed again for the strokes.
void write_plot_by_speed(std::ostream& out, const PlottedJob& job, const SetpointReplay& replay, const PathPlotOptions& options,
                         const SetpointSurvey& s) {
  const Frame frame(s.extent, options);
  write_header(out, frame, job.name, options, true);
  write_strokes_by_speed(out, frame, job, replay, s.peak_speed);
  write_footer(out, frame, s.first, s.last, true, s.peak_speed);
}

/// The plot of a simulation: the setpoints are replayed twice (survey, then strokes); without
/// setpoints, the plot by segment.
void write_plot_by_speed(std::ostream& out, const Job& job, const SetpointReplay& replay, const PathPlotOptions& options) {
  const PlottedJob subject = plotted(job);
  const SetpointSurvey s = survey(subject, replay);
  if (s.count == 0) {
    write_plot_by_segment(out, job, options);
    return;
  }
  write_plot_by_speed(out, subject, replay, options, s);
}

void write_file(const std::string& file, const std::function<void(std::ostream&)>& write) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file);
  write(out);
  out.close();
  if (!out) throw std::runtime_error("error writing " + file);
}

}  // namespace

std::string path_plot_svg(const Job& job, const std::vector<SetpointRecord>* setpoints, const PathPlotOptions& options) {
  std::ostringstream out;
  write_path_plot(out, job, setpoints, options);
  return out.str();
}

void write_path_plot(std::ostream& out, const Job& job, const std::vector<SetpointRecord>* setpoints, const PathPlotOptions& options) {
  if (job.segments.empty()) throw std::invalid_argument(job.name + ": the job has no segments");
  if (setpoints == nullptr || setpoints->empty()) {
    write_plot_by_segment(out, job, options);
    return;
  }
  write_plot_by_speed(out, job, [setpoints](const SetpointSink& sink) {
    for (const auto& r : *setpoints) sink(r);
  }, options);
}

void write_path_plot_streamed(std::ostream& out, const Job& job, const SetpointReplay& replay, const PathPlotOptions& options) {
  if (job.segments.empty()) throw std::invalid_argument(job.name + ": the job has no segments");
  write_plot_by_speed(out, job, replay, options);
}

PlottedJob plotted(const Job& job) {
  return PlottedJob{job.name, [&job](std::size_t source) { return is_rapid_source(job, source); }};
}

void write_path_plot_streamed(std::ostream& out, const PlottedJob& job, const SetpointReplay& replay, const PathPlotOptions& options) {
  const SetpointSurvey s = survey(job, replay);
  if (s.count == 0) throw std::invalid_argument(job.name + ": the simulation made no setpoints to plot");
  write_plot_by_speed(out, job, replay, options, s);
}

void write_path_plot_streamed(const std::string& file, const PlottedJob& job, const SetpointReplay& replay, const PathPlotOptions& options) {
  write_file(file, [&](std::ostream& out) { write_path_plot_streamed(out, job, replay, options); });
}

void write_path_plot(const std::string& file, const Job& job, const std::vector<SetpointRecord>* setpoints,
                     const PathPlotOptions& options) {
  write_file(file, [&](std::ostream& out) { write_path_plot(out, job, setpoints, options); });
}

void write_path_plot_streamed(const std::string& file, const Job& job, const SetpointReplay& replay, const PathPlotOptions& options) {
  write_file(file, [&](std::ostream& out) { write_path_plot_streamed(out, job, replay, options); });
}

}  // namespace curvestep::host
