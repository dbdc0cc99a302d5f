// SPDX-License-Identifier: MIT
// A small SVG writer for path plots: polylines in millimetres, a frame and a scale bar.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace curvestep::host {

/// One polyline to draw.
struct PlotPolyline {
  std::vector<std::array<double, 2>> points;  ///< millimetres
  std::string colour = "#1f77b4";             ///< SVG colour
  bool dashed = false;                        ///< rapids are dashed
};

/// Writes the polylines to an SVG file scaled to fit; markers on start and end; a scale bar.
/// Throws std::runtime_error naming the file if it cannot be written.
void write_svg_plot(const std::string& path, const std::vector<PlotPolyline>& lines, const std::string& title);

}  // namespace curvestep::host
