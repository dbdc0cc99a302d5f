// SPDX-License-Identifier: MIT
#include "svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace curvestep::host {

void write_svg_plot(const std::string& path, const std::vector<PlotPolyline>& lines, const std::string& title) {
  double min_x = std::numeric_limits<double>::max();
  double min_y = min_x;
  double max_x = std::numeric_limits<double>::lowest();
  double max_y = max_x;
  for (const auto& line : lines) {
    for (const auto& p : line.points) {
      min_x = std::min(min_x, p[0]);
      max_x = std::max(max_x, p[0]);
      min_y = std::min(min_y, p[1]);
      max_y = std::max(max_y, p[1]);
    }
  }
  if (min_x > max_x) min_x = max_x = min_y = max_y = 0;
  const double width = std::max(max_x - min_x, 1e-9);
  const double height = std::max(max_y - min_y, 1e-9);
  const double canvas = 800.0;
  const double margin = 40.0;
  const double scale = (canvas - 2 * margin) / std::max(width, height);
  const double canvas_height = height * scale + 2 * margin + 30;
  auto sx = [&](double x) { return margin + (x - min_x) * scale; };
  auto sy = [&](double y) { return margin + (max_y - y) * scale; };  // y up

  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << canvas << "\" height=\"" << canvas_height
      << "\" viewBox=\"0 0 " << canvas << " " << canvas_height << "\">\n";
  out << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  out << "<text x=\"" << margin << "\" y=\"24\" font-family=\"sans-serif\" font-size=\"16\">" << title << "</text>\n";
  for (const auto& line : lines) {
    if (line.points.empty()) continue;
    out << "<polyline fill=\"none\" stroke=\"" << line.colour << "\" stroke-width=\"1.5\""
        << (line.dashed ? " stroke-dasharray=\"6 4\"" : "") << " points=\"";
    for (const auto& p : line.points) out << sx(p[0]) << "," << sy(p[1]) << " ";
    out << "\"/>\n";
  }
  if (!lines.empty() && !lines.front().points.empty()) {
    const auto& s = lines.front().points.front();
    out << "<circle cx=\"" << sx(s[0]) << "\" cy=\"" << sy(s[1]) << "\" r=\"5\" fill=\"green\"><title>start</title></circle>\n";
    const auto& e = lines.back().points.back();
    out << "<circle cx=\"" << sx(e[0]) << "\" cy=\"" << sy(e[1]) << "\" r=\"5\" fill=\"red\"><title>end</title></circle>\n";
  }
  // Scale bar: the largest power of ten no longer than a quarter of the drawing.
  const double bar_mm = std::pow(10.0, std::floor(std::log10(std::max(width, height) / 4)));
  const double bar_y = canvas_height - 15;
  out << "<line x1=\"" << margin << "\" y1=\"" << bar_y << "\" x2=\"" << margin + bar_mm * scale << "\" y2=\"" << bar_y
      << "\" stroke=\"black\" stroke-width=\"3\"/>\n";
  out << "<text x=\"" << margin + bar_mm * scale + 8 << "\" y=\"" << bar_y + 5
      << "\" font-family=\"sans-serif\" font-size=\"13\">" << bar_mm << " mm</text>\n";
  out << "</svg>\n";
  if (!out) throw std::runtime_error("error writing " + path);
}

}  // namespace curvestep::host
