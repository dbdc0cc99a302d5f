// SPDX-License-Identifier: MIT
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <curvestep/host/report.hpp>

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
  const std::vector<double>* values = nullptr;
  double limit = 0;        ///< drawn as a red dashed line; 0: none
  std::string limit_note;  ///< shown after the title when there is no limit line
};

/// Exceeds as the simulator counts it: by more than 1%.
bool exceeds(double measured, double limit) { return limit > 0 && measured > limit * 1.01; }

std::string chart_svg(const Chart& chart, const std::vector<double>& time) {
  constexpr double width = 800, height = 230, left = 72, right = 24, top = 30, bottom = 38;
  constexpr double plot_width = width - left - right, plot_height = height - top - bottom;
  const std::vector<double>& v = *chart.values;
  const double t0 = time.front();
  const double t1 = std::max(time.back(), t0 + 1e-9);
  double peak = 0;
  for (const double x : v) peak = std::max(peak, x);
  double y_max = std::max(peak * 1.05, chart.limit * 1.15);
  if (!(y_max > 0)) y_max = 1;
  auto sx = [&](double t) { return left + (t - t0) / (t1 - t0) * plot_width; };
  auto sy = [&](double y) { return top + (1 - y / y_max) * plot_height; };

  std::ostringstream out;
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
  const auto columns = static_cast<std::size_t>(plot_width);
  std::size_t i = 0;
  for (std::size_t column = 0; column < columns && i < v.size(); ++column) {
    const double column_end = t0 + (t1 - t0) * static_cast<double>(column + 1) / static_cast<double>(columns);
    std::size_t lo = i, hi = i;
    for (; i < v.size() && (time[i] <= column_end || column + 1 == columns); ++i) {
      if (v[i] < v[lo]) lo = i;
      if (v[i] > v[hi]) hi = i;
    }
    const std::size_t first = std::min(lo, hi), second = std::max(lo, hi);
    out << pixel(sx(time[first])) << "," << pixel(sy(v[first])) << " ";
    if (second != first) out << pixel(sx(time[second])) << "," << pixel(sy(v[second])) << " ";
  }
  out << "\"/>\n";
  if (chart.limit > 0) {
    out << "<line class=\"limit\" x1=\"" << left << "\" x2=\"" << width - right << "\" y1=\"" << pixel(sy(chart.limit)) << "\" y2=\""
        << pixel(sy(chart.limit)) << "\" stroke=\"#d62728\" stroke-width=\"1.5\" stroke-dasharray=\"8 4\"/>"
        << "<text x=\"" << width - right - 4 << "\" y=\"" << pixel(sy(chart.limit) - 5) << "\" text-anchor=\"end\" fill=\"#d62728\">limit "
        << figure(chart.limit, 6) << "</text>\n";
  }
  out << "</svg>\n";
  return out.str();
}

void summary_row(std::ostringstream& out, const std::string& name, const std::string& value, const std::string& limit,
                 const std::string& status) {
  out << "<tr><th>" << escape(name) << "</th><td>" << value << "</td><td>" << limit << "</td><td class=\""
      << (status == "exceeds" ? "bad" : "good") << "\">" << status << "</td></tr>\n";
}

void limited_row(std::ostringstream& out, const std::string& name, double measured, double limit, const std::string& unit) {
  summary_row(out, name, figure(measured, 6) + " " + unit, figure(limit, 6) + " " + unit, exceeds(measured, limit) ? "exceeds" : "ok");
}

}  // namespace

std::string html_report(const ReportInput& input) {
  if (input.job == nullptr || input.machine == nullptr || input.result == nullptr) {
    throw std::invalid_argument("html_report: job, machine and result are required");
  }
  const Job& job = *input.job;
  const MachineLimits& machine = *input.machine;
  const SimulationResult& result = *input.result;
  if (result.setpoints.empty()) throw std::invalid_argument("html_report: the simulation has no setpoints");
  const SimulationSummary& s = result.summary;
  const MotionProfile profile = motion_profile(result.setpoints, machine, input.fixed_point);
  const std::string title = input.title.empty() ? job.name : input.title;

  std::ostringstream out;
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
  out << "<p class=\"note\">" << job.sources.size() << " job segments, " << job.segments.size() << " path segments; setpoints in "
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
  out << path_plot_svg(job, &result.setpoints, plot);

  out << "<h2>Motion over time</h2>\n";
  const Chart charts[] = {
      {"chart-speed", "Speed", "mm/s", &profile.speed_mm_per_s, machine.v_max_mm_per_s, ""},
      {"chart-acceleration", "Acceleration", "mm/s²", &profile.acceleration_mm_per_s2, machine.a_max_mm_per_s2, ""},
      {"chart-jerk", "Jerk", "mm/s³", &profile.jerk_mm_per_s3, machine.jerk_limited ? machine.j_max_mm_per_s3 : 0.0,
       machine.jerk_limited ? "" : ", not limited (trapezoidal)"},
  };
  for (const auto& chart : charts) out << chart_svg(chart, profile.time_s);
  out << "<p class=\"note\">Speed: the planned path speed of each setpoint. Acceleration and jerk: magnitudes of the second and "
         "third differences of the setpoint positions";
  if (profile.stride > 1) {
    out << " taken " << profile.stride << " setpoints apart (" << figure(static_cast<double>(profile.stride) / machine.rate_hz * 1000)
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
  return out.str();
}

void write_html_report(const std::string& file, const ReportInput& input) {
  const std::string html = html_report(input);
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file);
  out << html;
  out.close();
  if (!out) throw std::runtime_error("error writing " + file);
}

}  // namespace curvestep::host
