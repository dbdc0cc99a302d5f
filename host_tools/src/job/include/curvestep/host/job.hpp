// SPDX-License-Identifier: MIT
// Job files (JSON, docs/job_format.md): loading into PathSegments, and exact evaluation of a
// segment of the file at its own parameter.
//
// Loading checks everything a planner relies on: types, counts, knots, weights, connectivity,
// and that every coordinate fits Q16.16. Coordinates are converted to mm, quantised to Q16.16
// and converted back to double, so the simulator and a Q16.16 firmware see the same numbers.
// B-spline and NURBS segments are split into (rational) Bézier pieces at their knots (Bézier
// extraction by blossoming); the pieces' control points are quantised again, so a piece is
// within one Q16.16 rounding (2^-17 mm per coordinate) of the exact spline.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <curvestep/core/motion/path_segment.hpp>
#include <curvestep/host/load_error.hpp>

namespace curvestep::host {

/// The segment types of the job format.
enum class SegmentType : std::uint8_t { Line, Arc, Bezier, RationalBezier, BSpline, Nurbs, Rapid };

/// The "type" text of a segment type ("rational_bezier").
[[nodiscard]] std::string_view segment_type_name(SegmentType type) noexcept;

/// One segment as the file gives it (after unit conversion and quantisation), and the
/// PathSegments it became.
struct SourceSegment {
  SegmentType type = SegmentType::Line;
  std::size_t line = 0;                ///< line of the segment in the file (0 if unknown)
  std::vector<MachinePoint> points;    ///< control points / start and end, mm, quantised
  std::vector<double> weights;         ///< rational_bezier and nurbs
  std::vector<double> knots;           ///< bspline and nurbs
  std::size_t degree = 0;              ///< curve degree (1 for lines and rapids, 0 for arcs)
  double feed_mm_per_s = 0;            ///< the segment's feed, 0 for the machine default
  std::size_t first_piece = 0;         ///< index in Job::segments of the first piece of the domain
  std::vector<double> breaks;          ///< parameter values where the pieces meet, front..back = domain
  [[nodiscard]] std::size_t piece_count() const noexcept { return breaks.empty() ? 0 : breaks.size() - 1; }
  /// The parameter domain: [0,1], or [u_p, u_{n+1}] for bspline and nurbs.
  [[nodiscard]] std::pair<double, double> domain() const noexcept {
    return breaks.empty() ? std::pair<double, double>{0.0, 1.0} : std::pair<double, double>{breaks.front(), breaks.back()};
  }
};

/// What a job event does (G-code machine words that are not motion, docs/gcode.md).
enum class JobEventKind : std::uint8_t {
  Dwell,          ///< G4: stay at rest for `value` seconds
  ProgramPause,   ///< M0 / M1: stop until resumed
  ProgramEnd,     ///< M2 / M30
  SpindleOn,      ///< M3 (value = S, rev/min, clockwise) / M4 (counter-clockwise: `flag` set)
  SpindleOff,     ///< M5
  SpindleSpeed,   ///< S alone while the spindle runs (value = rev/min)
  CoolantMist,    ///< M7
  CoolantFlood,   ///< M8
  CoolantOff,     ///< M9
  ToolChange,     ///< M6 (value = tool number)
  DigitalOutput,  ///< M62-M65 (value = output number, `flag` = on)
  PenUp,          ///< plotter pen lifted (machine file's pen model)
  PenDown,        ///< plotter pen lowered
  LayerChange,    ///< a plotter layer ends and the next begins (pen change pause); text = layer name
  Message,        ///< an operator message: G-code (MSG,...), (DEBUG,...) or (PRINT,...); text = the message
};

/// What a streamed G-code load keeps of a file segment once its pieces are handed on: the line and
/// type its messages name (8 bytes instead of a SourceSegment's 136; docs/robustness.md).
struct SourceLine {
  std::uint32_t line = 0;  ///< line of the segment in the file (0 if unknown)
  SegmentType type = SegmentType::Line;
};

/// A non-motion event of a job, in program order between segments.
struct JobEvent {
  JobEventKind kind = JobEventKind::Dwell;
  std::size_t before_segment = 0;  ///< happens after Job::segments[before_segment - 1] ends, before segments[before_segment]
  double value = 0;                ///< seconds (Dwell), rev/min, tool or output number
  bool flag = false;               ///< M4 counter-clockwise / output on
  std::size_t line = 0;            ///< source line (0 if none)
  std::string text;                ///< what the program said (e.g. "M6 T3"), for reports
};

/// A loaded job: the path as PathSegments, and where each one came from.
struct Job {
  int version = 1;                        ///< format version of the file
  std::string name;                       ///< file name, used in messages
  std::vector<PathSegment> segments;      ///< the path, connected end to start
  std::vector<std::size_t> source_index;  ///< for each PathSegment, the file's segment index
  std::vector<SourceSegment> sources;     ///< the file's segments, in file order
  /// Instead of `sources` after a streamed G-code load: each file segment's line and type only
  /// (sources then stays empty). source_location, source_count and source_type read either.
  std::vector<SourceLine> source_lines;
  /// The file segment index of source_lines.front(): a load that forgets them as it goes
  /// (GcodeOptions::keep_source_lines false) keeps none once a line's segments are handed on.
  std::size_t source_lines_from = 0;
  std::vector<JobEvent> events;           ///< non-motion events, ordered by before_segment then program order
  /// Path-control tolerance per junction (G64 P), mm: blend_tolerance_mm[k] applies to the corner
  /// between segments[k-1] and segments[k]; empty = the machine file's tolerance everywhere,
  /// a negative entry = exact stop (G61 / G61.1) at that corner.
  std::vector<double> blend_tolerance_mm;
};

/// Receives a job's path in program order as it is read (a streamed load, job_pipeline.hpp): every
/// event before the segment it precedes (JobEvent::before_segment is the index that segment has in
/// the file's job), then the segment, with the index of the file segment it comes from and the
/// path-control tolerance of the joint into it (Job::blend_tolerance_mm) if the job has them.
class JobSink {
 public:
  virtual ~JobSink() = default;
  virtual void event(JobEvent event) = 0;
  virtual void segment(const PathSegment& segment, std::size_t source, std::optional<double> blend_tolerance_mm) = 0;
};

/// Hands `job`'s events (all of them first, in their order) and then its segments to `sink`, and
/// returns the rest of the job (name, version, sources). What a streamed load does with a file
/// read whole.
[[nodiscard]] Job feed_job(Job job, JobSink& sink);

/// Loads a job file. Throws LoadError (naming file, line, segment, field) or std::runtime_error
/// if the file cannot be read.
[[nodiscard]] Job load_job(const std::filesystem::path& path);

/// Parses job text; `name` is used in error messages as the file name.
[[nodiscard]] Job parse_job(std::string_view text, std::string name);

/// The position of the file's segment `index` at its own parameter `u` (lines, arcs, Béziers and
/// rapids: [0,1]; bspline and nurbs: the knot domain), from the PathSegments the machine runs.
/// std::out_of_range (one-line message) for a bad index or a u outside the domain.
[[nodiscard]] MachinePoint evaluate_segment(const Job& job, std::size_t index, double u);

/// Where Job::segments[piece] comes from, for a message: the job's file, the line and index of
/// the file's segment it belongs to, and that segment's type.
[[nodiscard]] SourceLocation piece_location(const Job& job, std::size_t piece);
/// The same for the file's segment `source` of `job`.
[[nodiscard]] SourceLocation source_location(const Job& job, std::size_t source);

/// The number of file segments of `job` (sources or source_lines).
[[nodiscard]] std::size_t source_count(const Job& job) noexcept;
/// The type of the file's segment `source`, nullopt past the end.
[[nodiscard]] std::optional<SegmentType> source_type(const Job& job, std::size_t source) noexcept;

/// Reads a whole text file; std::runtime_error naming the file if it cannot be read.
[[nodiscard]] std::string read_text_file(const std::filesystem::path& path);

}  // namespace curvestep::host
