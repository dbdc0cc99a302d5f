// SPDX-License-Identifier: MIT
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include <curvestep/host/report.hpp>

#include "running_profile.hpp"
#include "svg_text.hpp"

namespace curvestep::host {
namespace {

using report_detail::escape;
using report_detail::figure;
using report_detail::pixel;

/// One time series chart.
struct Chart {
  std::string css_class;   ///< e.g. "chart-speed"
  std::string title;       ///< "Speed"
  std::string unit;        ///< "mm/s"
  double limit = 0;        ///< drawn as a red dashed line; 0: none
  std::string limit_note;  ///< shown after the title when there is no limit line
};

/// A chart's time series as drawn: the time range, the peak, and per pixel column its smallest and
/// largest value in time order (so peaks survive), as (time, value).
struct ChartSeries {
  double t0 = 0, t1 = 0, peak = 0;
  std::vector<std::pair<double, double>> points;
};

/// Reduces a series as it comes to ChartSeries::points: a sample belongs to the first column whose
/// end it does not pass (the last column takes the rest); a column without samples shows the next
/// sample. At most two points per column are kept.
class ColumnReducer {
 public:
  ColumnReducer(double t0, double t1, std::size_t columns) : t0_(t0), t1_(t1), columns_(columns) {}
  void push(double t, double v) {
    while (column_ + 1 < columns_ && !(t <= column_end(column_))) {
      if (count_ == 0) points_.emplace_back(t, v);
      else emit();
      ++column_;
      count_ = 0;
    }
    if (count_ == 0) {
      lo_ = hi_ = Sample{count_total_, t, v};
    } else {
      if (v < lo_.v) lo_ = Sample{count_total_, t, v};
      if (v > hi_.v) hi_ = Sample{count_total_, t, v};
    }
    ++count_;
    ++count_total_;
  }
  /// The points, after the last sample.
  [[nodiscard]] std::vector<std::pair<double, double>> finish() {
    if (count_ > 0) emit();
    count_ = 0;
    return std::move(points_);
  }

 private:
  struct Sample {
    std::size_t index = 0;
    double t = 0, v = 0;
  };
  [[nodiscard]] double column_end(std::size_t column) const {
    return t0_ + (t1_ - t0_) * static_cast<double>(column + 1) / static_cast<double>(columns_);
  }
  void emit() {
    const Sample& first = lo_.index <= hi_.index ? lo_ : hi_;
    const Sample& second = lo_.index <= hi_.index ? hi_ : lo_;
    points_.emplace_back(first.t, first.v);
    if (second.index != first.index) points_.emplace_back(second.t, second.v);
  }
  double t0_, t1_;
  std::size_t columns_;
  std::size_t column_ = 0, count_ = 0, count_total_ = 0;
  Sample lo_{}, hi_{};
  std::vector<std::pair<double, double>> points_;
};

constexpr double chart_width = 800, chart_height = 230, chart_left = 72, chart_right = 24, chart_top = 30, chart_bottom = 38;
constexpr double chart_plot_width = chart_width - chart_left - chart_right;
constexpr auto chart_columns = static_cast<std::size_t>(chart_plot_width);

/// Exceeds as the simulator counts it: by more than 1%.
bool exceeds(double measured, double limit) { return limit > 0 && measured > limit * 1.01; }

void write_chart(std::ostream& out, const Chart& chart, const ChartSeries& series) {
  constexpr double width = chart_width, height = chart_height, left = chart_left, right = chart_right, top = chart_top, bottom = chart_bottom;
  constexpr double plot_width = chart_plot_width, plot_height = height - top - bottom;
  const double t0 = series.t0, t1 = series.t1, peak = series.peak;
  double y_max = std::max(peak * 1.05, chart.limit * 1.15);
  if (!(y_max > 0)) y_max = 1;
  auto sx = [&](double t) { return left + (t - t0) / (t1 - t0) * plot_width; };
  auto sy = [&](double y) { return top + (1 - y / y_max) * plot_height; };

  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"chart " << chart.css_class << "\" width=\"" << width << "\" height=\""
      << height << "\" viewBox=\"0 0 " << width << " " << height << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  out << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  out << "<text x=\"" << left << "\" y=\"18\" font-size=\"14\" font-weight=\"bold\">" << escape(chart.title) << " ("
      << escape(chart.unit) << ")</text>";
  out << "<text x=\"" << width - right << "\" y=\"18\" text-anchor=\"end\" fill=\"#555\">peak " << figure(peak, 5)
      << (chart.limit > 0 ? ", limit " + figure(chart.limit, 6) : std::string()) << escape(chart.limit_note) << "</text>\n";
  // Grid and ticks.
  const double y_step = report_detail::nice_step_below(y_max / 4);
  for (double y = 0; y <= y_max + 1e-12 * y_max; y += y_step) {
    out << "<line x1=\"" << left << "\" x2=\"" << width - right << "\" y1=\"" << pixel(sy(y)) << "\" y2=\"" << pixel(sy(y))
        << "\" stroke=\"#e4e4e4\"/><text x=\"" << left - 6 << "\" y=\"" << pixel(sy(y) + 4) << "\" text-anchor=\"end\">"
        << figure(y, 6) << "</text>\n";
  }
  const double t_step = report_detail::nice_step_below((t1 - t0) / 6);
  for (double t = std::ceil(t0 / t_step) * t_step; t <= t1 + 1e-12 * t1; t += t_step) {
    out << "<line x1=\"" << pixel(sx(t)) << "\" x2=\"" << pixel(sx(t)) << "\" y1=\"" << top << "\" y2=\"" << top + plot_height
        << "\" stroke=\"#e4e4e4\"/><text x=\"" << pixel(sx(t)) << "\" y=\"" << top + plot_height + 16 << "\" text-anchor=\"middle\">"
        << figure(t) << "</text>\n";
  }
  out << "<text x=\"" << width - right << "\" y=\"" << height - 4 << "\" text-anchor=\"end\" fill=\"#555\">time (s)</text>\n";
  out << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << plot_width << "\" height=\"" << plot_height
      << "\" fill=\"none\" stroke=\"#999\"/>\n";
  // The series: per pixel column its smallest and largest value, in time order, so peaks survive.
  out << "<polyline class=\"series\" fill=\"none\" stroke=\"#1f77b4\" stroke-width=\"1.3\" points=\"";
  for (const auto& [t, v] : series.points) out << pixel(sx(t)) << "," << pixel(sy(v)) << " ";
  out << "\"/>\n";
  if (chart.limit > 0) {
    out << "<line class=\"limit\" x1=\"" << left << "\" x2=\"" << width - right << "\" y1=\"" << pixel(sy(chart.limit)) << "\" y2=\""
        << pixel(sy(chart.limit)) << "\" stroke=\"#d62728\" stroke-width=\"1.5\" stroke-dasharray=\"8 4\"/>"
        << "<text x=\"" << width - right - 4 << "\" y=\"" << pixel(sy(chart.limit) - 5) << "\" text-anchor=\"end\" fill=\"#d62728\">limit "
        << figure(chart.limit, 6) << "</text>\n";
  }
  out << "</svg>\n";
}

void summary_row(std::ostream& out, const std::string& name, const std::string& value, const std::string& limit,
                 const std::string& status) {
  out << "<tr><th>" << escape(name) << "</th><td>" << value << "</td><td>" << limit << "</td><td class=\""
      << (status == "exceeds" ? "bad" : "good") << "\">" << status << "</td></tr>\n";
}

void limited_row(std::ostream& out, const std::string& name, double measured, double limit, const std::string& unit) {
  summary_row(out, name, figure(measured, 6) + " " + unit, figure(limit, 6) + " " + unit, exceeds(measured, limit) ? "exceeds" : "ok");
}

}  // namespace

namespace {

/// The three charts' series: a first replay finds the time range and the peaks, a second reduces
/// the samples per pixel column.
std::array<ChartSeries, 3> chart_series(const MachineLimits& machine, bool fixed_point, const SetpointReplay& replay,
                                        std::size_t& stride) {
  std::array<ChartSeries, 3> series;
  std::size_t count = 0;
  double first_time = 0, last_time = 0;
  {
    report_detail::RunningProfile profile(machine, fixed_point);
    stride = profile.stride();
    replay([&](const SetpointRecord& r) {
      const report_detail::ProfileSample p = profile.push(r);
      if (count++ == 0) first_time = p.time_s;
      last_time = p.time_s;
      series[0].peak = std::max(series[0].peak, p.speed_mm_per_s);
      series[1].peak = std::max(series[1].peak, p.acceleration_mm_per_s2);
      series[2].peak = std::max(series[2].peak, p.jerk_mm_per_s3);
    });
  }
  if (count == 0) throw std::invalid_argument("html_report: the simulation has no setpoints");
  for (auto& c : series) {
    c.t0 = first_time;
    c.t1 = std::max(last_time, first_time + 1e-9);
  }
  std::array<ColumnReducer, 3> reducers{ColumnReducer(series[0].t0, series[0].t1, chart_columns),
                                        ColumnReducer(series[1].t0, series[1].t1, chart_columns),
                                        ColumnReducer(series[2].t0, series[2].t1, chart_columns)};
  report_detail::RunningProfile profile(machine, fixed_point);
  replay([&](const SetpointRecord& r) {
    const report_detail::ProfileSample p = profile.push(r);
    reducers[0].push(p.time_s, p.speed_mm_per_s);
    reducers[1].push(p.time_s, p.acceleration_mm_per_s2);
    reducers[2].push(p.time_s, p.jerk_mm_per_s3);
  });
  for (std::size_t k = 0; k < 3; ++k) series[k].points = reducers[k].finish();
  return series;
}

/// The report, the setpoints handed over by `replay` (four times: two for the charts, two for
/// the path plot), none kept.
void write_report(std::ostream& out, const ReportInput& input, const SetpointReplay& replay) {
  if (input.job == nullptr || input.machine == nullptr || input.result == nullptr) {
    throw std::invalid_argument("html_report: job, machine and result are required");
  }
  const Job& job = *input.job;
  const MachineLimits& machine = *input.machine;
  const SimulationResult& result = *input.result;
  const SimulationSummary& s = result.summary;
  std::size_t stride = 1;
  const std::array<ChartSeries, 3> series = chart_series(machine, input.fixed_point, replay, stride);
  const std::string title = input.title.empty() ? job.name : input.title;

  out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>curvestep report: " << escape(title)
      << "</title>\n<style>\n"
      << "body{font-family:sans-serif;margin:24px;color:#222;max-width:860px}\n"
      << "h1{font-size:22px}h2{font-size:17px;margin-top:28px}\n"
      << "table{border-collapse:collapse}th,td{padding:3px 10px;text-align:left;border-bottom:1px solid #ddd}\n"
      << "td.good{color:#2ca02c}td.bad{color:#d62728;font-weight:bold}\n"
      << ".warnings li{color:#d62728}.none{color:#2ca02c}.note{color:#555;font-size:13px}\n"
      << "svg{display:block;margin:8px 0}\n"
      << "</style>\n</head>\n<body>\n";
  out << "<h1>curvestep report: " << escape(title) << "</h1>\n";
  const std::size_t path_segments = input.rapid_source ? input.path_segments : job.segments.size();
  out << "<p class=\"note\">" << source_count(job) << " job segments, " << path_segments << " path segments; setpoints in "
      << (input.fixed_point ? "Q16.16" : "double") << " at " << figure(machine.rate_hz) << " Hz; "
      << (machine.jerk_limited ? "S-curve" : "trapezoidal") << " profiles.</p>\n";

  out << "<h2>Warnings</h2>\n";
  if (s.violations.empty()) {
    out << "<p class=\"none\" id=\"warnings\">No limit exceeded.</p>\n";
  } else {
    out << "<ul class=\"warnings\" id=\"warnings\">\n";
    for (const auto& v : s.violations) out << "<li>" << escape(v) << "</li>\n";
    out << "</ul>\n";
  }

  out << "<h2>Summary</h2>\n<table class=\"summary\">\n<tr><th></th><th>measured</th><th>limit</th><th></th></tr>\n";
  summary_row(out, "setpoints", std::to_string(s.setpoints), "", "");
  summary_row(out, "duration", figure(s.duration_s, 6) + " s", "", "");
  summary_row(out, "distance", figure(s.distance_mm, 6) + " mm", "", "");
  limited_row(out, "peak speed", s.peak_speed_mm_per_s, machine.v_max_mm_per_s, "mm/s");
  limited_row(out, "peak acceleration", s.peak_acceleration_mm_per_s2, machine.a_max_mm_per_s2, "mm/s²");
  if (machine.jerk_limited) {
    limited_row(out, "peak jerk", s.peak_jerk_mm_per_s3, machine.j_max_mm_per_s3, "mm/s³");
  } else {
    summary_row(out, "peak jerk", figure(s.peak_jerk_mm_per_s3, 6) + " mm/s³", "not limited (trapezoidal)", "");
  }
  limited_row(out, "chord deviation", s.max_chord_deviation_mm * 1000, machine.tolerance_mm * 1000, "µm");
  summary_row(out, "Q16.16 rounding", figure(s.max_quantisation_mm * 1000, 6) + " µm", "", "");
  const char* axis_names[] = {"x", "y", "z"};
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if (machine.axes[axis].steps_per_mm <= 0) continue;
    const bool over = s.peak_step_rate_hz[axis] > machine.max_step_rate_hz;
    summary_row(out, std::string("step rate ") + axis_names[axis], figure(s.peak_step_rate_hz[axis], 6) + " Hz",
                figure(machine.max_step_rate_hz, 6) + " Hz", over ? "exceeds" : "ok");
  }
  for (const auto& row : input.extra_rows) summary_row(out, row[0], row[1], row[2], "");
  out << "</table>\n";

  out << "<h2>Path</h2>\n";
  PathPlotOptions plot;
  plot.standalone = false;
  plot.width_px = 800;
  plot.max_height_px = 560;
  if (input.rapid_source) {
    write_path_plot_streamed(out, PlottedJob{job.name, input.rapid_source}, replay, plot);
  } else {
    write_path_plot_streamed(out, job, replay, plot);
  }

  out << "<h2>Motion over time</h2>\n";
  const Chart charts[] = {
      {"chart-speed", "Speed", "mm/s", machine.v_max_mm_per_s, ""},
      {"chart-acceleration", "Acceleration", "mm/s²", machine.a_max_mm_per_s2, ""},
      {"chart-jerk", "Jerk", "mm/s³", machine.jerk_limited ? machine.j_max_mm_per_s3 : 0.0,
       machine.jerk_limited ? "" : ", not limited (trapezoidal)"},
  };
  for (std::size_t k = 0; k < 3; ++k) write_chart(out, charts[k], series[k]);
  out << "<p class=\"note\">Speed: the planned path speed of each setpoint. Acceleration and jerk: magnitudes of the second and "
         "third differences of the setpoint positions";
  if (stride > 1) {
    out << " taken " << stride << " setpoints apart (" << figure(static_cast<double>(stride) / machine.rate_hz * 1000)
        << " ms), so that Q16.16 rounding adds less than 1% of the limits; the summary's peaks come from the exact positions";
  }
  out << ". Drawn per pixel column as its smallest and largest value.</p>\n";

  // Written by the page's own script: shows (and lets a test check) that the page ran without errors.
  out << "<p class=\"note\" id=\"render-check\">script did not run</p>\n"
      << "<script>\n(function () {\n"
      << "  var drawings = document.querySelectorAll('svg').length;\n"
      << "  var marker = document.getElementById('render-check');\n"
      << "  marker.textContent = 'report rendered: ' + drawings + ' drawings';\n"
      << "  marker.setAttribute('data-drawings', String(drawings));\n"
      << "})();\n</script>\n";
  out << "</body>\n</html>\n";
}

SetpointReplay replay_of(const ReportInput& input) {
  if (input.result == nullptr) return [](const SetpointSink&) {};
  const std::vector<SetpointRecord>* setpoints = &input.result->setpoints;
  return [setpoints](const SetpointSink& sink) {
    for (const auto& r : *setpoints) sink(r);
  };
}

void write_report_file(const std::string& file, const ReportInput& input, const SetpointReplay& replay) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file);
  write_report(out, input, replay);
  out.close();
  if (!out) throw std::runtime_error("error writing " + file);
}

}  // namespace

std::string html_report(const ReportInput& input) {
  std::ostringstream out;
  write_report(out, input, replay_of(input));
  return out.str();
}

void write_html_report(const std::string& file, const ReportInput& input) { write_report_file(file, input, replay_of(input)); }

void write_html_report_streamed(const std::string& file, const ReportInput& input, const SetpointReplay& replay) {
  write_report_file(file, input, replay);
}

}  // namespace curvestep::host
