// SPDX-License-Identifier: MIT
// Job files: JSON -> checked, quantised SourceSegments and connected PathSegments.
#include <curvestep/host/job.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <curvestep/core/bspline/bezier_extraction.hpp>
#include <curvestep/core/error_text.hpp>
#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/host/csv.hpp>
#include <curvestep/host/wire_value.hpp>

#include "json_document.hpp"

namespace curvestep::host {
namespace {

using detail::Node;
using detail::Reader;

constexpr double millimetres_per_inch = 25.4;
/// Consecutive segments connect if every coordinate agrees within one Q16.16 step (needed only
/// where a start point is computed, as for an unclamped B-spline; given points compare equal).
constexpr double connection_tolerance_mm = 1.0 / 65536.0;
/// An arc's end may be this much farther from (or nearer to) the center than its start.
constexpr double arc_radius_tolerance_mm = 0.002;
/// Control points a bspline or nurbs segment may have.
constexpr std::size_t max_spline_points = 512;
constexpr std::size_t max_bezier_points = PathSegment::max_degree + 1;

using Spline = BSpline<double, motion_axes, PathSegment::max_degree, max_spline_points>;
using RationalSpline = Nurbs<double, motion_axes, PathSegment::max_degree, max_spline_points>;

std::string point_text(const MachinePoint& p) {
  return "(" + format_number(p[0]) + ", " + format_number(p[1]) + ", " + format_number(p[2]) + ")";
}

bool connected(const MachinePoint& a, const MachinePoint& b) {
  for (std::size_t axis = 0; axis < motion_axes; ++axis) {
    if (!(std::fabs(a[axis] - b[axis]) <= connection_tolerance_mm)) return false;
  }
  return true;
}

std::optional<SegmentType> parse_type(const std::string& text) {
  for (const auto type : {SegmentType::Line, SegmentType::Arc, SegmentType::Bezier, SegmentType::RationalBezier,
                          SegmentType::BSpline, SegmentType::Nurbs, SegmentType::Rapid}) {
    if (segment_type_name(type) == text) return type;
  }
  return std::nullopt;
}

/// Quantises a value in mm to Q16.16 (the grid a Q16.16 firmware uses).
std::optional<double> quantise(double mm) {
  const auto q = Q16_16::from_double(mm);
  if (!q) return std::nullopt;
  return q.value().to_double();
}

class JobParser {
 public:
  JobParser(std::string_view text, std::string name)
      : document_(text, std::move(name), Error::InvalidJob), reader_(document_, Error::InvalidJob) {}

  Job parse() {
    const Node root = reader_.root();
    reader_.check_keys(root, {"version", "units", "segments"});
    const auto version = reader_.integer(reader_.require(root, "version"), 0, 1000000);
    if (version != 1) {
      reader_.fail(root.member("version"), "unsupported version " + std::to_string(version) + " (this program reads version 1)");
    }
    job_.version = static_cast<int>(version);
    job_.name = document_.name();
    if (const auto units = reader_.optional(root, "units")) {
      const std::string text = reader_.string(*units);
      if (text == "mm") {
        scale_ = 1;
      } else if (text == "in") {
        scale_ = millimetres_per_inch;
      } else {
        reader_.fail(*units, "unknown units \"" + text + "\" (expected \"mm\" or \"in\")");
      }
    }
    const auto segments = reader_.array(reader_.require(root, "segments"), 1, static_cast<std::size_t>(-1));
    for (std::size_t i = 0; i < segments.size(); ++i) {
      const Node segment = reader_.enter_segment(i, segments[i]);
      parse_segment(i, segment);
      reader_.leave_segment();
    }
    return std::move(job_);
  }

 private:
  /// A coordinate in the file's units -> mm on the Q16.16 grid.
  double coordinate(const Node& node) {
    const double value = reader_.number(node);
    const auto mm = quantise(value * scale_);
    if (!mm) {
      std::string text = "value " + format_number(value);
      if (scale_ != 1) text += " in (= " + format_number(value * scale_) + " mm)";
      reader_.fail(node, text + " is outside the Q16.16 range (-32768 to 32768 mm)", Error::FixedOverflow);
    }
    return *mm;
  }

  MachinePoint point(const Node& node) {
    const auto entries = reader_.array(node, 2, 3);
    MachinePoint p{};
    for (std::size_t axis = 0; axis < entries.size(); ++axis) p[axis] = coordinate(entries[axis]);
    return p;
  }

  std::vector<MachinePoint> points(const Node& node, std::size_t min_count, std::size_t max_count) {
    std::vector<MachinePoint> result;
    for (const auto& entry : reader_.array(node, min_count, max_count)) result.push_back(point(entry));
    return result;
  }

  std::vector<double> weights(const Node& segment, std::size_t count) {
    std::vector<double> result;
    for (const auto& entry : reader_.array(reader_.require(segment, "weights"), count, count)) {
      result.push_back(wire_positive(entry, WireQuantity::Weight));
    }
    return result;
  }

  /// A weight or feed: a finite number > 0, rounded to the nearest Q16.16 value as the wire
  /// carries it (so the simulator sees what a device receives). Out of range, or rounding to 0, is
  /// an error naming the value.
  double wire_positive(const Node& node, WireQuantity quantity) {
    const auto rounded = round_for_wire(reader_.positive(node), quantity);
    if (!rounded) reader_.fail(node, rounded.problem, rounded.code);
    return rounded.value;
  }

  /// Fails with the core's description of `failure`, at `node`.
  [[noreturn]] void fail_core(const Node& node, Failure failure, const std::string& context = "") {
    std::string text(describe(failure.code));
    if (!context.empty()) text = context + ": " + text;
    reader_.fail(node, text, failure.code);
  }

  void parse_segment(std::size_t index, const Node& segment) {
    reader_.expect_object(segment);
    const Node type_node = reader_.require(segment, "type");
    const std::string type_text = reader_.string(type_node);
    const auto type = parse_type(type_text);
    if (!type) {
      reader_.fail(type_node,
                   "unknown segment type \"" + type_text + "\" (expected line, arc, bezier, rational_bezier, bspline, nurbs or rapid)",
                   Error::UnknownSegmentType);
    }
    reader_.set_segment_type(type_text);
    SourceSegment source;
    source.type = *type;
    source.line = document_.line_of(segment.pointer);
    std::vector<PathSegment> pieces;
    const Node points_node = reader_.require(segment, "points");
    switch (*type) {
      case SegmentType::Line:
        reader_.check_keys(segment, {"type", "points", "feed"});
        source.points = points(points_node, 2, 2);
        source.degree = 1;
        if (!(source.points[0] == source.points[1])) pieces.push_back(line(points_node, source.points[0], source.points[1]));
        break;
      case SegmentType::Rapid:
        reader_.check_keys(segment, {"type", "points"});
        parse_rapid(points_node, source, pieces);
        break;
      case SegmentType::Arc:
        reader_.check_keys(segment, {"type", "points", "center", "radius", "direction", "turns", "feed"});
        pieces.push_back(parse_arc(segment, points_node, source));
        break;
      case SegmentType::Bezier: {
        reader_.check_keys(segment, {"type", "points", "feed"});
        source.points = points(points_node, 2, max_bezier_points);
        source.degree = source.points.size() - 1;
        const auto made = PathSegment::make_bezier(source.points);
        if (!made) fail_bezier(segment, points_node, made.failure());
        pieces.push_back(made.value());
        break;
      }
      case SegmentType::RationalBezier: {
        reader_.check_keys(segment, {"type", "points", "weights", "feed"});
        source.points = points(points_node, 2, max_bezier_points);
        source.degree = source.points.size() - 1;
        source.weights = weights(segment, source.points.size());
        const auto made = PathSegment::make_rational_bezier(source.points, source.weights);
        if (!made) fail_bezier(segment, points_node, made.failure());
        pieces.push_back(made.value());
        break;
      }
      case SegmentType::BSpline:
      case SegmentType::Nurbs:
        if (*type == SegmentType::BSpline) {
          reader_.check_keys(segment, {"type", "points", "degree", "knots", "feed"});
        } else {
          reader_.check_keys(segment, {"type", "points", "weights", "degree", "knots", "feed"});
        }
        parse_spline(segment, points_node, source, pieces);
        break;
    }
    if (source.breaks.empty() && !pieces.empty()) source.breaks = {0.0, 1.0};
    if (const auto feed = reader_.optional(segment, "feed")) {
      source.feed_mm_per_s = wire_positive(*feed, WireQuantity::Feed);
      for (auto& piece : pieces) piece.set_feed_mm_per_s(source.feed_mm_per_s);
    }

    const MachinePoint start = pieces.empty() ? source.points.front() : pieces.front().start();
    if (*type != SegmentType::Rapid && previous_end_ && !connected(start, *previous_end_)) {
      const Node at = *type == SegmentType::BSpline || *type == SegmentType::Nurbs ? points_node : points_node.element(0);
      reader_.fail(at,
                   "starts at " + point_text(start) + ", but segment " + std::to_string(previous_index_) + " ended at " +
                       point_text(*previous_end_),
                   Error::SegmentsNotConnected);
    }
    if (*type == SegmentType::Rapid) {
      // A rapid may start anywhere: travel there first from where the previous segment ended.
      if (previous_end_ && !(start == *previous_end_)) {
        pieces.insert(pieces.begin(), rapid(points_node, *previous_end_, start));
        source.first_piece = 1;
      }
    }
    source.first_piece += job_.segments.size();
    if (!pieces.empty()) previous_end_ = pieces.back().end();
    else if (!previous_end_) previous_end_ = source.points.back();
    previous_index_ = index;
    for (auto& piece : pieces) {
      job_.segments.push_back(piece);
      job_.source_index.push_back(index);
    }
    job_.sources.push_back(std::move(source));
  }

  PathSegment line(const Node& node, const MachinePoint& a, const MachinePoint& b) {
    const auto made = PathSegment::make_line(a, b);
    if (!made) fail_core(node, made.failure());
    return made.value();
  }

  PathSegment rapid(const Node& node, const MachinePoint& a, const MachinePoint& b) {
    PathSegment move = line(node, a, b);
    move.set_rapid(true);
    return move;
  }

  void parse_rapid(const Node& points_node, SourceSegment& source, std::vector<PathSegment>& pieces) {
    source.points = points(points_node, 1, 2);
    source.degree = 1;
    if (source.points.size() == 1) source.points.insert(source.points.begin(), previous_end_.value_or(MachinePoint{}));
    if (!(source.points[0] == source.points[1])) pieces.push_back(rapid(points_node, source.points[0], source.points[1]));
  }

  PathSegment parse_arc(const Node& segment, const Node& points_node, SourceSegment& source) {
    source.points = points(points_node, 2, 2);
    const MachinePoint start = source.points[0];
    const MachinePoint end = source.points[1];
    const Node direction_node = reader_.require(segment, "direction");
    const std::string direction_text = reader_.string(direction_node);
    if (direction_text != "cw" && direction_text != "ccw") {
      reader_.fail(direction_node, "unknown direction \"" + direction_text + "\" (expected \"cw\" or \"ccw\")");
    }
    const ArcDirection direction = direction_text == "cw" ? ArcDirection::Clockwise : ArcDirection::CounterClockwise;
    std::uint32_t turns = 0;
    if (const auto turns_node = reader_.optional(segment, "turns")) {
      turns = static_cast<std::uint32_t>(reader_.integer(*turns_node, 0, 100000));
    }
    const auto center_node = reader_.optional(segment, "center");
    const auto radius_node = reader_.optional(segment, "radius");
    if (center_node && radius_node) reader_.fail(*radius_node, "give either \"center\" or \"radius\", not both");
    if (!center_node && !radius_node) reader_.fail(segment.member("center"), "missing: an arc needs \"center\" or \"radius\"");
    MachinePoint center{};
    Node center_at = center_node ? *center_node : *radius_node;
    if (center_node) {
      const auto entries = reader_.array(*center_node, 2, 2);
      center = MachinePoint{{coordinate(entries[0]), coordinate(entries[1]), 0.0}};
    } else {
      center = center_from_radius(*radius_node, start, end, direction);
    }
    source.points.push_back(center);  // points = start, end, center
    const auto made = PathSegment::make_arc(start, end, center, direction, turns, arc_radius_tolerance_mm);
    if (!made) {
      const double r_start = std::hypot(start[0] - center[0], start[1] - center[1]);
      const double r_end = std::hypot(end[0] - center[0], end[1] - center[1]);
      switch (made.error()) {
        case Error::DegenerateCurve: reader_.fail(center_at, "zero radius: the center is the start point", Error::DegenerateCurve);
        case Error::InvalidArgument:
          reader_.fail(points_node.element(1),
                       "the end is " + format_number(r_end) + " mm from the center but the start is " + format_number(r_start) +
                           " mm (the radii may differ by " + format_number(arc_radius_tolerance_mm) + " mm)",
                       Error::InvalidArgument);
        default: fail_core(segment, made.failure());
      }
    }
    return made.value();
  }

  /// G-code's R form: |r| is the radius; r > 0 takes the arc of at most half a turn, r < 0 the longer one.
  MachinePoint center_from_radius(const Node& node, const MachinePoint& start, const MachinePoint& end, ArcDirection direction) {
    const double value = reader_.number(node);
    const auto r_quantised = quantise(value * scale_);
    if (!r_quantised) reader_.fail(node, "value " + format_number(value) + " is outside the Q16.16 range", Error::FixedOverflow);
    const double r = *r_quantised;
    if (r == 0) reader_.fail(node, "the radius must not be zero", Error::DegenerateCurve);
    const double dx = end[0] - start[0];
    const double dy = end[1] - start[1];
    const double chord = std::hypot(dx, dy);
    if (chord == 0) reader_.fail(node, "start and end coincide: a full circle needs \"center\"");
    const double half = chord / 2;
    const double radius = std::fabs(r);
    if (radius < half - arc_radius_tolerance_mm) {
      reader_.fail(node, "radius " + format_number(radius) + " mm is smaller than half the distance from start to end (" +
                             format_number(half) + " mm)");
    }
    const double height = radius > half ? std::sqrt(radius * radius - half * half) : 0.0;
    // The center lies left of the chord for a counter-clockwise arc of at most half a turn.
    double side = direction == ArcDirection::CounterClockwise ? 1.0 : -1.0;
    if (r < 0) side = -side;
    const double cx = start[0] + dx / 2 - side * height * dy / chord;
    const double cy = start[1] + dy / 2 + side * height * dx / chord;
    const auto qx = quantise(cx);
    const auto qy = quantise(cy);
    if (!qx || !qy) reader_.fail(node, "the arc's center is outside the Q16.16 range", Error::FixedOverflow);
    return MachinePoint{{*qx, *qy, 0.0}};
  }

  [[noreturn]] void fail_bezier(const Node& segment, const Node& points_node, Failure failure) {
    switch (failure.code) {
      case Error::DegenerateCurve: reader_.fail(points_node, "all control points are the same point", failure.code);
      case Error::NonPositiveWeight:
      case Error::NotFinite:
        if (failure.index != no_index) {
          reader_.fail(segment.member("weights").element(failure.index), std::string(describe(failure.code)), failure.code);
        }
        fail_core(segment, failure);
      default: fail_core(points_node, failure);
    }
  }

  void parse_spline(const Node& segment, const Node& points_node, SourceSegment& source, std::vector<PathSegment>& pieces) {
    const bool rational = source.type == SegmentType::Nurbs;
    const Node degree_node = reader_.require(segment, "degree");
    source.degree = static_cast<std::size_t>(reader_.integer(degree_node, 1, static_cast<std::int64_t>(PathSegment::max_degree)));
    const std::size_t p = source.degree;
    const Node points_array = reader_.require(segment, "points");
    if (points_array.json->is_array() && points_array.json->size() < p + 1) {
      reader_.fail(points_array, "a curve of degree " + std::to_string(p) + " needs at least " + std::to_string(p + 1) +
                                     " control points, got " + std::to_string(points_array.json->size()),
                   Error::TooFewPoints);
    }
    source.points = points(points_node, p + 1, max_spline_points);
    const std::size_t n = source.points.size();
    if (rational) source.weights = weights(segment, n);
    const Node knots_node = reader_.require(segment, "knots");
    if (!knots_node.json->is_array()) reader_.fail(knots_node, "expected an array");
    const std::size_t expected = n + p + 1;
    if (knots_node.json->size() != expected) {
      reader_.fail(knots_node,
                   "expected " + std::to_string(expected) + " knots (points + degree + 1 = " + std::to_string(n) + " + " +
                       std::to_string(p) + " + 1), got " + std::to_string(knots_node.json->size()),
                   Error::WrongKnotCount);
    }
    for (const auto& entry : reader_.array(knots_node, expected, expected)) {
      const double knot = reader_.number(entry);
      if (!source.knots.empty() && knot < source.knots.back()) {
        reader_.fail(entry,
                     "knot " + format_number(knot) + " is smaller than the knot before it (" + format_number(source.knots.back()) +
                         "): knots must not decrease",
                     Error::KnotsNotNondecreasing);
      }
      source.knots.push_back(knot);
    }
    auto fail_spline = [&](Failure failure) {
      switch (failure.code) {
        case Error::InvalidInterval:
          reader_.fail(knots_node,
                       "empty domain: knot " + std::to_string(p) + " equals knot " + std::to_string(n) + " (" +
                           format_number(source.knots[p]) + ")",
                       failure.code);
        case Error::KnotMultiplicityTooHigh:
          reader_.fail(knots_node.element(failure.index),
                       "knot value " + format_number(source.knots[failure.index]) + " is repeated more than " +
                           std::to_string(p) + " times inside the domain (or " + std::to_string(p + 1) + " at an end)",
                       failure.code);
        case Error::NonPositiveWeight: reader_.fail(segment.member("weights").element(failure.index), std::string(describe(failure.code)), failure.code);
        default: fail_core(segment, failure);
      }
    };
    auto add_piece = [&](const Result<PathSegment>& made, double start, double end) {
      if (!made) {
        reader_.fail(points_node,
                     "the piece on knot span [" + format_number(start) + ", " + format_number(end) + "]: " +
                         (made.error() == Error::DegenerateCurve ? std::string("does not move (its control points coincide)")
                                                                 : std::string(describe(made.error()))),
                     made.error());
      }
      pieces.push_back(made.value());
      if (source.breaks.empty()) source.breaks.push_back(start);
      source.breaks.push_back(end);
    };
    auto grid = [&](std::span<const MachinePoint> control) {
      std::vector<MachinePoint> result(control.begin(), control.end());
      for (auto& p_i : result) {
        for (std::size_t axis = 0; axis < motion_axes; ++axis) {
          const auto q = quantise(p_i[axis]);
          if (!q) reader_.fail(points_node, "a Bezier piece leaves the Q16.16 range", Error::FixedOverflow);
          p_i[axis] = *q;
        }
      }
      return result;
    };
    if (!rational) {
      const auto spline = Spline::create(source.points, source.knots, p);
      if (!spline) fail_spline(spline.failure());
      const auto extracted = for_each_bezier(spline.value(), [&](const auto& piece) {
        add_piece(PathSegment::make_bezier(grid(piece.curve.control_points())), piece.start, piece.end);
      });
      if (!extracted) fail_core(segment, extracted.failure());
    } else {
      const auto nurbs = RationalSpline::create(source.points, source.weights, source.knots, p);
      if (!nurbs) fail_spline(nurbs.failure());
      const auto extracted = for_each_bezier(nurbs.value(), [&](const auto& piece) {
        // The pieces' weights travel as Q16.16 too: round them as the control points are.
        std::vector<double> piece_weights;
        for (std::size_t i = 0; i <= piece.curve.degree(); ++i) {
          const auto w = quantise(piece.curve.weight(i));
          if (!w || !(*w > 0)) {
            reader_.fail(segment.member("weights"),
                         "the piece on knot span [" + format_number(piece.start) + ", " + format_number(piece.end) + "] has weight " +
                             format_number(piece.curve.weight(i)) + ", which Q16.16 cannot carry",
                         Error::FixedOverflow);
          }
          piece_weights.push_back(*w);
        }
        add_piece(PathSegment::make_rational_bezier(grid(piece.curve.control_points()), piece_weights), piece.start, piece.end);
      });
      if (!extracted) fail_core(segment, extracted.failure());
    }
  }

  detail::JsonDocument document_;
  Reader reader_;
  Job job_;
  double scale_ = 1;
  std::optional<MachinePoint> previous_end_;
  std::size_t previous_index_ = 0;
};

}  // namespace

std::string_view segment_type_name(SegmentType type) noexcept {
  switch (type) {
    case SegmentType::Line: return "line";
    case SegmentType::Arc: return "arc";
    case SegmentType::Bezier: return "bezier";
    case SegmentType::RationalBezier: return "rational_bezier";
    case SegmentType::BSpline: return "bspline";
    case SegmentType::Nurbs: return "nurbs";
    case SegmentType::Rapid: return "rapid";
  }
  return "unknown";
}

std::string read_text_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw std::runtime_error(path.string() + ": cannot read the file");
  return text.str();
}

SourceLocation source_location(const Job& job, std::size_t source) {
  SourceLocation location;
  location.file = job.name;
  location.segment = source;
  if (source < job.sources.size()) {
    location.line = job.sources[source].line;
  } else if (source >= job.source_lines_from && source - job.source_lines_from < job.source_lines.size()) {
    location.line = job.source_lines[source - job.source_lines_from].line;
  }
  if (const auto type = source_type(job, source)) location.segment_type = std::string(segment_type_name(*type));
  return location;
}

std::size_t source_count(const Job& job) noexcept {
  return job.sources.empty() ? job.source_lines_from + job.source_lines.size() : job.sources.size();
}

std::optional<SegmentType> source_type(const Job& job, std::size_t source) noexcept {
  if (source < job.sources.size()) return job.sources[source].type;
  if (source >= job.source_lines_from && source - job.source_lines_from < job.source_lines.size()) {
    return job.source_lines[source - job.source_lines_from].type;
  }
  return std::nullopt;
}

SourceLocation piece_location(const Job& job, std::size_t piece) {
  if (piece < job.source_index.size()) return source_location(job, job.source_index[piece]);
  SourceLocation location;
  location.file = job.name;
  return location;
}

Job parse_job(std::string_view text, std::string name) { return JobParser(text, std::move(name)).parse(); }

Job load_job(const std::filesystem::path& path) { return parse_job(read_text_file(path), path.string()); }

MachinePoint evaluate_segment(const Job& job, std::size_t index, double u) {
  if (index >= job.sources.size()) {
    throw std::out_of_range("segment " + std::to_string(index) + " does not exist (the job has " +
                            std::to_string(job.sources.size()) + " segments, numbered from 0)");
  }
  const SourceSegment& source = job.sources[index];
  const auto [low, high] = source.domain();
  if (!(u >= low && u <= high)) {
    throw std::out_of_range("u = " + format_number(u) + " is outside the domain [" + format_number(low) + ", " +
                            format_number(high) + "] of segment " + std::to_string(index) + " (" +
                            std::string(segment_type_name(source.type)) + ")");
  }
  if (source.piece_count() == 0 || job.segments.size() <= source.first_piece) return source.points.front();
  std::size_t piece = 0;
  while (piece + 1 < source.piece_count() && source.breaks[piece + 1] <= u) ++piece;
  const double width = source.breaks[piece + 1] - source.breaks[piece];
  double t = (u - source.breaks[piece]) / width;
  if (u == source.breaks[piece + 1]) t = 1;
  t = std::clamp(t, 0.0, 1.0);
  return job.segments[source.first_piece + piece].point(t);
}

}  // namespace curvestep::host
