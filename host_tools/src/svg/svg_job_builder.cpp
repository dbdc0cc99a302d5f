// SPDX-License-Identifier: MIT
// Drawn subpaths -> the SvgImport (svg_job_builder.hpp).
#include "svg_job_builder.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <optional>

#include <curvestep/core/error_text.hpp>
#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/host/csv.hpp>
#include <curvestep/host/wire_value.hpp>

namespace curvestep::host::svg {
namespace {

double distance(const MachinePoint& a, const MachinePoint& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

double travel(const MachinePoint& from, const std::vector<DrawnSubpath>& order) {
  double total = 0;
  MachinePoint at = from;
  for (const auto& subpath : order) {
    total += distance(at, subpath.start());
    at = subpath.end();
  }
  return total;
}

/// Greedy nearest neighbour: always draw next the subpath whose start (or, for an open one,
/// end) is nearest; ties keep document order. Returns how many subpaths were reversed.
std::size_t optimise(const MachinePoint& from, std::vector<DrawnSubpath>& drawn) {
  std::vector<DrawnSubpath> ordered;
  std::vector<bool> used(drawn.size(), false);
  MachinePoint at = from;
  std::size_t reversed = 0;
  for (std::size_t n = 0; n < drawn.size(); ++n) {
    std::size_t best = 0;
    bool best_reversed = false;
    double best_distance = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < drawn.size(); ++i) {
      if (used[i]) continue;
      const double forward = distance(at, drawn[i].start());
      if (forward < best_distance) {
        best = i;
        best_distance = forward;
        best_reversed = false;
      }
      if (!drawn[i].closed()) {
        const double backward = distance(at, drawn[i].end());
        if (backward < best_distance) {
          best = i;
          best_distance = backward;
          best_reversed = true;
        }
      }
    }
    used[best] = true;
    ordered.push_back(drawn[best]);
    if (best_reversed) {
      ordered.back().reverse();
      ++reversed;
    }
    at = ordered.back().end();
  }
  drawn = std::move(ordered);
  return reversed;
}

void push(Job& job, SourceSegment source, PathSegment segment) {
  source.first_piece = job.segments.size();
  source.breaks = {0.0, 1.0};
  job.source_index.push_back(job.sources.size());
  job.segments.push_back(segment);
  job.sources.push_back(std::move(source));
}

/// The feed option on the Q16.16 grid (0: the machine default), with the job loader's errors.
double wire_feed(const std::string& file, double feed) {
  if (feed == 0) return 0;
  const SourceLocation location{file, 0, 0, std::nullopt, "", "feed"};
  if (!(feed > 0) || !std::isfinite(feed)) {
    throw LoadError(location, "feed " + format_number(feed) + " must be a finite number > 0 (or 0 for the machine default)",
                    Error::InvalidArgument);
  }
  const auto rounded = round_for_wire(feed, WireQuantity::Feed);
  if (!rounded) throw LoadError(location, rounded.problem, rounded.code);
  return rounded.value;
}

}  // namespace

SvgImport build_import(const Diagnostics& diagnostics, std::vector<DrawnSubpath> drawn, const SvgOptions& options,
                       std::vector<std::string> warnings, const std::vector<Layer>& layers) {
  SvgImport result;
  MachinePoint start{};
  for (std::size_t axis = 0; axis < motion_axes; ++axis) {
    const auto q = Q16_16::from_double(options.start[axis]);
    if (!q) {
      throw LoadError(SourceLocation{diagnostics.file(), 0, 0, std::nullopt, "", "start"}, "the start point is outside the Q16.16 range",
                      Error::FixedOverflow);
    }
    start[axis] = q.value().to_double();
  }
  const double feed = wire_feed(diagnostics.file(), options.feed_mm_per_s);
  result.travel_document_mm = travel(start, drawn);
  if (options.optimize) {
    // Layer by layer (drawn is grouped by layer): a pen is never taken back to an earlier layer.
    MachinePoint from = start;
    for (auto first = drawn.begin(); first != drawn.end();) {
      const auto last = std::find_if(first, drawn.end(), [&](const DrawnSubpath& s) { return s.layer != first->layer; });
      std::vector<DrawnSubpath> group(std::make_move_iterator(first), std::make_move_iterator(last));
      result.reversed_count += optimise(from, group);
      std::move(group.begin(), group.end(), first);
      from = std::prev(last)->end();
      first = last;
    }
  }
  result.travel_mm = travel(start, drawn);
  result.subpath_count = drawn.size();
  result.warnings = std::move(warnings);

  Job& job = result.job;
  job.version = 1;
  job.name = diagnostics.file();
  MachinePoint at = start;
  for (std::size_t n = 0; n < drawn.size(); ++n) {
    const DrawnSubpath& subpath = drawn[n];
    if (subpath.layer < layers.size() && (n == 0 || drawn[n - 1].layer != subpath.layer)) {
      result.layers.push_back(layer_text(layers[subpath.layer]));
      if (n > 0) {  // the pen change: after the previous layer's last segment, before the travel to this one
        JobEvent change;
        change.kind = JobEventKind::LayerChange;
        change.before_segment = job.segments.size();
        change.line = subpath.line;
        change.text = result.layers.back();
        job.events.push_back(std::move(change));
      }
    }
    if (!(subpath.start() == at)) {
      auto move = PathSegment::make_line(at, subpath.start());
      move.value().set_rapid(true);
      SourceSegment source;
      source.type = SegmentType::Rapid;
      source.line = subpath.line;
      source.points = {at, subpath.start()};
      source.degree = 1;
      push(job, std::move(source), move.value());
    }
    for (const auto& piece : subpath.pieces) {
      Result<PathSegment> made = piece.type == SegmentType::Line     ? PathSegment::make_line(piece.points[0], piece.points[1])
                                 : piece.type == SegmentType::Bezier ? PathSegment::make_bezier(piece.points)
                                                                     : PathSegment::make_rational_bezier(piece.points, piece.weights);
      if (!made) {
        diagnostics.fail_at(subpath.line, "", "a piece of this element cannot be used: " + std::string(describe(made.error())),
                            made.error());
      }
      made.value().set_feed_mm_per_s(feed);
      SourceSegment source;
      source.type = piece.type;
      source.line = subpath.line;
      source.points = piece.points;
      source.weights = piece.weights;
      source.degree = piece.points.size() - 1;
      source.feed_mm_per_s = feed;
      push(job, std::move(source), made.value());
    }
    at = subpath.end();
  }
  return result;
}

}  // namespace curvestep::host::svg
