// SPDX-License-Identifier: MIT
#include "svg_text.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include <curvestep/host/printable.hpp>

namespace curvestep::host::report_detail {

std::string escape(std::string_view text) {
  // Control characters and invalid UTF-8 (a file name, an SVG id) would make the XML malformed:
  // printable() writes them as \xNN first, then the XML specials are escaped.
  const std::string safe = printable(text);
  std::string out;
  out.reserve(safe.size());
  for (const char c : safe) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string pixel(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2f", value);
  return buffer;
}

std::string figure(double value, int digits) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

double nice_step_below(double limit) {
  if (!(limit > 0) || !std::isfinite(limit)) return 1.0;
  const double power = std::pow(10.0, std::floor(std::log10(limit)));
  for (const double m : {5.0, 2.0, 1.0}) {
    if (m * power <= limit) return m * power;
  }
  return power;
}

std::string speed_colour(double fraction) {
  // Five stops, linearly interpolated in RGB: dark violet, blue, teal, green, yellow.
  static constexpr std::array<std::array<double, 3>, 5> stops{{
      {68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}}};
  // The scale stops at 85% of the last stop's way: pale yellow is hard to see on white.
  const double f = std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0) * 0.85 * static_cast<double>(stops.size() - 1);
  const auto i = std::min(static_cast<std::size_t>(f), stops.size() - 2);
  const double t = f - static_cast<double>(i);
  char buffer[8];
  int rgb[3];
  for (std::size_t c = 0; c < 3; ++c) rgb[c] = static_cast<int>(std::lround(stops[i][c] + t * (stops[i + 1][c] - stops[i][c])));
  std::snprintf(buffer, sizeof buffer, "#%02x%02x%02x", rgb[0], rgb[1], rgb[2]);
  return buffer;
}

std::string segment_colour(std::size_t index) {
  static constexpr std::array<const char*, 10> palette{"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                                       "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#393b79"};
  return palette[index % palette.size()];
}

}  // namespace curvestep::host::report_detail
