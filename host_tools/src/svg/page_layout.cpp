// SPDX-License-Identifier: MIT
// vpype-style page layout of an imported drawing (page_layout.hpp).
#include <curvestep/host/page_layout.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/host/csv.hpp>
#include <curvestep/host/load_error.hpp>

namespace curvestep::host {
namespace {

struct NamedPage {
  const char* name;
  double width_mm;
  double height_mm;
};

constexpr NamedPage named_pages[] = {{"a5", 148, 210},      {"a4", 210, 297},         {"a3", 297, 420},
                                     {"letter", 215.9, 279.4}, {"legal", 215.9, 355.6}, {"tabloid", 279.4, 431.8}};

std::string lower(std::string_view text) {
  std::string out;
  for (const char c : text) {
    if (std::isspace(static_cast<unsigned char>(c)) == 0) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return out;
}

/// "12.5" and its unit text ("mm", "" ...); invalid_argument if no number.
std::pair<double, std::string> number_and_unit(std::string_view text, std::string_view whole) {
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || !std::isfinite(value)) {
    throw std::invalid_argument("\"" + std::string(whole) + "\": expected a number, got \"" + std::string(text) + "\"");
  }
  return {value, std::string(end, text.data() + text.size())};
}

double mm_per(const std::string& unit, std::string_view whole) {
  if (unit == "mm") return 1;
  if (unit == "cm") return 10;
  if (unit == "in") return 25.4;
  throw std::invalid_argument("\"" + std::string(whole) + "\": unknown unit \"" + unit + "\" (use mm, cm or in)");
}

/// The point rounded to Q16.16 like every imported point (LoadError if outside the range).
MachinePoint on_grid(const MachinePoint& p, const std::string& file) {
  MachinePoint out{};
  for (std::size_t axis = 0; axis < motion_axes; ++axis) {
    const auto q = Q16_16::from_double(p[axis]);
    if (!q) {
      throw LoadError(SourceLocation{file, 0, 0, std::nullopt, "", "page"},
                      "the page layout puts a point at " + format_number(p[axis]) + " mm, outside the Q16.16 range",
                      Error::FixedOverflow);
    }
    out[axis] = q.value().to_double();
  }
  return out;
}

/// The largest value of `f` over [0, 1] for a smooth curve coordinate: samples, then golden-section
/// refinement around the best sample (degree <= 3 curves have at most two extrema per axis).
double curve_max(const PathSegment& segment, std::size_t axis, double sign) {
  constexpr int samples = 32;
  auto f = [&](double u) { return sign * segment.point(u)[axis]; };
  int best = 0;
  double best_value = f(0);
  for (int k = 1; k <= samples; ++k) {
    const double v = f(static_cast<double>(k) / samples);
    if (v > best_value) {
      best = k;
      best_value = v;
    }
  }
  double a = std::max(0, best - 1) / static_cast<double>(samples);
  double b = std::min(samples, best + 1) / static_cast<double>(samples);
  const double ratio = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i < 80; ++i) {
    const double c = b - ratio * (b - a);
    const double d = a + ratio * (b - a);
    if (f(c) > f(d)) b = d;
    else a = c;
  }
  return std::max(best_value, f((a + b) / 2));
}

/// A length for messages: six significant digits ("47", "1.9", "148.5"); below 10 nm (under the
/// Q16.16 grid's 15 nm) it is rounding noise of the layout and printed as 0 (a fitted drawing's
/// edge printed "x -2.10693e-06 .. 210").
std::string mm(double value) {
  std::ostringstream out;
  out << std::setprecision(6) << (std::fabs(value) < 1e-5 ? 0.0 : value);
  return out.str();
}

}  // namespace

PageSize parse_page_size(std::string_view text) {
  const std::string spec = lower(text);
  for (const auto& page : named_pages) {
    if (spec == page.name) return {page.width_mm, page.height_mm, page.name};
  }
  const auto x = spec.find('x');
  if (x == std::string::npos) {
    throw std::invalid_argument("page \"" + std::string(text) + "\": expected a5, a4, a3, letter, legal, tabloid or WxH with a unit "
                                "(e.g. 210x297mm, 8.5x11in)");
  }
  auto [width, width_unit] = number_and_unit(std::string_view(spec).substr(0, x), text);
  auto [height, height_unit] = number_and_unit(std::string_view(spec).substr(x + 1), text);
  if (height_unit.empty()) throw std::invalid_argument("page \"" + std::string(text) + "\": the size needs a unit (mm, cm or in)");
  if (width_unit.empty()) width_unit = height_unit;
  const double w = width * mm_per(width_unit, text);
  const double h = height * mm_per(height_unit, text);
  if (!(w > 0 && h > 0)) throw std::invalid_argument("page \"" + std::string(text) + "\": width and height must be positive");
  return {w, h, spec};
}

double parse_page_length(std::string_view text) {
  const std::string spec = lower(text);
  auto [value, unit] = number_and_unit(spec, text);
  const double mm = value * (unit.empty() ? 1.0 : mm_per(unit, text));
  if (!(mm >= 0)) throw std::invalid_argument("\"" + std::string(text) + "\": must not be negative");
  return mm;
}

std::optional<std::pair<MachinePoint, MachinePoint>> drawing_extent(const Job& job) {
  std::optional<std::pair<MachinePoint, MachinePoint>> box;
  for (const auto& segment : job.segments) {
    if (segment.rapid()) continue;
    MachinePoint low{};
    MachinePoint high{};
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      high[axis] = curve_max(segment, axis, 1);
      low[axis] = -curve_max(segment, axis, -1);
    }
    if (!box) {
      box = std::pair{low, high};
      continue;
    }
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      box->first[axis] = std::min(box->first[axis], low[axis]);
      box->second[axis] = std::max(box->second[axis], high[axis]);
    }
  }
  return box;
}

std::string page_overflow(const MachinePoint& low, const MachinePoint& high, double width_mm, double height_mm) {
  constexpr double slack = 1.0 / 65536;
  const double over[4] = {-low[0], high[0] - width_mm, -low[1], high[1] - height_mm};
  const char* sides[4] = {"left of the page", "right of the page", "below the page", "above the page"};
  std::string overflow;
  for (int i = 0; i < 4; ++i) {
    if (over[i] > slack) overflow += (overflow.empty() ? "" : ", ") + mm(over[i]) + " mm " + sides[i];
  }
  return overflow;
}

PageLayoutReport lay_out_on_page(Job& job, const PageLayout& layout, const MachinePoint& start) {
  if (layout.rotate_deg != 0 && layout.rotate_deg != 90 && layout.rotate_deg != 180 && layout.rotate_deg != 270) {
    throw std::invalid_argument("--rotate " + std::to_string(layout.rotate_deg) + ": use 90, 180 or 270 (clockwise)");
  }
  if ((layout.center || layout.fit) && !layout.page) throw std::invalid_argument("--center and --fit need --page");
  for (const auto& source : job.sources) {
    if (source.type != SegmentType::Line && source.type != SegmentType::Bezier && source.type != SegmentType::RationalBezier &&
        source.type != SegmentType::Rapid) {
      throw std::invalid_argument(job.name + ": page layout applies to imported drawings (lines and Béziers), not to " +
                                  std::string(segment_type_name(source.type)) + " segments");
    }
  }
  const bool layer_changes_only =
      std::all_of(job.events.begin(), job.events.end(), [](const JobEvent& e) { return e.kind == JobEventKind::LayerChange; });
  if (!layer_changes_only || !job.blend_tolerance_mm.empty()) {
    throw std::invalid_argument(job.name + ": page layout applies to imported drawings (whose only events are layer changes), "
                                           "not to jobs with other events or blend tolerances");
  }
  const auto extent = drawing_extent(job);
  if (!extent) throw std::invalid_argument(job.name + ": nothing drawn to lay out");
  const auto [low, high] = *extent;
  const double cx = (low[0] + high[0]) / 2;
  const double cy = (low[1] + high[1]) / 2;
  // Clockwise by a quarter-turn multiple on the machine (y up): (x, y) -> (x cos + y sin, -x sin + y cos).
  const int quarter = layout.rotate_deg / 90;
  const double cosine = quarter == 0 ? 1 : quarter == 2 ? -1 : 0;
  const double sine = quarter == 1 ? 1 : quarter == 3 ? -1 : 0;
  const bool sideways = quarter % 2 == 1;
  const double w = sideways ? high[1] - low[1] : high[0] - low[0];
  const double h = sideways ? high[0] - low[0] : high[1] - low[1];

  PageLayoutReport report;
  double target_x = cx;
  double target_y = cy;
  if (layout.page) {
    report.page_width_mm = layout.page->width_mm;
    report.page_height_mm = layout.page->height_mm;
    if (layout.landscape && report.page_width_mm < report.page_height_mm) std::swap(report.page_width_mm, report.page_height_mm);
    if (layout.fit) {
      const double room_w = report.page_width_mm - 2 * layout.margin_mm;
      const double room_h = report.page_height_mm - 2 * layout.margin_mm;
      if (!(room_w > 0 && room_h > 0)) throw std::invalid_argument("--margin leaves no room on the page");
      const double sx = w > 0 ? room_w / w : std::numeric_limits<double>::infinity();
      const double sy = h > 0 ? room_h / h : std::numeric_limits<double>::infinity();
      report.scale = std::min(sx, sy);
      if (!std::isfinite(report.scale)) throw std::invalid_argument(job.name + ": the drawing has no size to fit");
    }
    if (layout.fit || layout.center) {
      target_x = report.page_width_mm / 2;
      target_y = report.page_height_mm / 2;
    }
  }
  const double s = report.scale;
  auto place = [&](const MachinePoint& p) {
    const double dx = p[0] - cx;
    const double dy = p[1] - cy;
    return MachinePoint{{target_x + s * (cosine * dx + sine * dy), target_y + s * (-sine * dx + cosine * dy), p[2]}};
  };

  // The drawn pieces, moved; rapids rebuilt between them.
  Job out;
  out.version = job.version;
  out.name = job.name;
  MachinePoint at = on_grid(start, job.name);
  auto push = [&](SourceSegment source, const PathSegment& segment) {
    source.first_piece = out.segments.size();
    source.breaks = {0.0, 1.0};
    out.source_index.push_back(out.sources.size());
    out.segments.push_back(segment);
    out.sources.push_back(std::move(source));
  };
  // moved_index[k]: where the job's segment k (one per source) lands, so that events keep their place.
  std::vector<std::size_t> moved_index;
  for (const auto& source : job.sources) {
    moved_index.push_back(out.segments.size());
    if (source.type == SegmentType::Rapid) continue;
    SourceSegment moved = source;
    for (auto& p : moved.points) p = on_grid(place(p), job.name);
    if (std::all_of(moved.points.begin(), moved.points.end(), [&](const MachinePoint& p) { return p == moved.points.front(); })) {
      continue;  // vanished on the grid
    }
    if (!(moved.points.front() == at)) {
      SourceSegment rapid;
      rapid.type = SegmentType::Rapid;
      rapid.line = source.line;
      rapid.points = {at, moved.points.front()};
      rapid.degree = 1;
      auto line = PathSegment::make_line(at, moved.points.front());
      line.value().set_rapid(true);
      push(std::move(rapid), line.value());
    }
    Result<PathSegment> made = moved.type == SegmentType::Line     ? PathSegment::make_line(moved.points[0], moved.points[1])
                               : moved.type == SegmentType::Bezier ? PathSegment::make_bezier(moved.points)
                                                                   : PathSegment::make_rational_bezier(moved.points, moved.weights);
    if (!made) {
      throw LoadError(SourceLocation{job.name, source.line, 0, std::nullopt, "", "page"},
                      "a piece cannot be used after the page layout", made.error());
    }
    made.value().set_feed_mm_per_s(moved.feed_mm_per_s);
    at = moved.points.back();
    push(std::move(moved), made.value());
  }

  moved_index.push_back(out.segments.size());
  out.events = job.events;
  for (auto& event : out.events) event.before_segment = moved_index[std::min(event.before_segment, moved_index.size() - 1)];

  const auto placed = drawing_extent(out);
  report.low = placed->first;
  report.high = placed->second;
  std::ostringstream note;
  note << "page layout: drawing " << mm(w) << " x " << mm(h) << " mm";
  if (layout.rotate_deg != 0) note << ", rotated " << layout.rotate_deg << "° clockwise";
  if (std::fabs(s - 1) > 1e-12) note << ", scaled by " << mm(s);
  note << ", at x " << mm(report.low[0]) << " .. " << mm(report.high[0]) << ", y "
       << mm(report.low[1]) << " .. " << mm(report.high[1]) << " mm";
  if (layout.page) {
    note << " on " << layout.page->name << (layout.landscape ? " landscape" : "") << " (" << mm(report.page_width_mm)
         << " x " << mm(report.page_height_mm) << " mm)";
    // The machine file gives no travel range: the page is the limit.
    const std::string overflow = page_overflow(report.low, report.high, report.page_width_mm, report.page_height_mm);
    if (!overflow.empty()) {
      throw LoadError(SourceLocation{job.name, 0, 0, std::nullopt, "", "page"},
                      "the drawing does not fit the page " + layout.page->name + (layout.landscape ? " landscape" : "") + " (" +
                          mm(report.page_width_mm) + " x " + mm(report.page_height_mm) + " mm): it reaches " +
                          overflow + " (x " + mm(report.low[0]) + " .. " + mm(report.high[0]) + ", y " +
                          mm(report.low[1]) + " .. " + mm(report.high[1]) +
                          " mm); use --fit, --center or a larger --page",
                      Error::OutsideTravel);
    }
  }
  report.note = note.str();
  job = std::move(out);
  return report;
}

}  // namespace curvestep::host
