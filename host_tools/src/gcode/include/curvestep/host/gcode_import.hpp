// SPDX-License-Identifier: MIT
// G-code import: a LinuxCNC-dialect program (docs/gcode.md) -> a Job, as job files load.
//
// Each motion becomes one SourceSegment (G0 rapid, G1 line, G2/G3 arc with points start, end,
// centre, G5 cubic and G5.1 quadratic bezier, G5.2…G5.3 nurbs with a clamped uniform knot
// vector) whose `line` is the program line; coordinates are in mm, quantised to Q16.16 like job
// files. Feeds are converted from units per minute to mm/s.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <curvestep/host/job.hpp>
#include <curvestep/host/load_error.hpp>

namespace curvestep::host {

/// What the machine file tells the importer (its tool table and the G28/G30 positions) and where
/// subroutine files are.
struct GcodeOptions {
  /// Tool number -> cutter diameter, mm, for G41/G42 D<tool>. A tool not listed has no diameter:
  /// G41/G42 with it is refused (tool 0 means no offset).
  std::map<int, double> tool_diameter_mm;
  /// Tool number -> length, mm, for G43 H<tool> (a tool not listed has length 0).
  std::map<int, double> tool_length_mm;
  /// Where G28 and G30 go, machine coordinates, mm (machine 0 by default, as G28.1/G30.1 set them).
  MachinePoint g28_position{};
  MachinePoint g30_position{};
  /// A streamed load (with a JobSink) keeps each file segment's line and type for messages
  /// (Job::source_lines, 8 bytes each). false: it forgets them once the line's segments are handed
  /// on, so its memory does not grow with the program (`curvestep sim`, which gets the whole job's
  /// message for a later error by loading it again, streamed_job.hpp).
  bool keep_source_lines = true;
  /// Folders searched in this order for a subroutine file (`o<name> call` -> name.ngc) after the
  /// program's own folder, as LinuxCNC's SUBROUTINE_PATH after PROGRAM_PREFIX (--subroutine-path).
  std::vector<std::filesystem::path> subroutine_path;
};

/// Loads a G-code program. Throws LoadError (file:line:column, the word at fault as field, an
/// Error code 140-150 or FixedOverflow) or std::runtime_error if the file cannot be read.
[[nodiscard]] Job import_gcode(const std::filesystem::path& path);
[[nodiscard]] Job import_gcode(const std::filesystem::path& path, const GcodeOptions& options);

/// Parses G-code text; `name` is used in error messages as the file name.
[[nodiscard]] Job parse_gcode_job(std::string_view text, std::string name);
[[nodiscard]] Job parse_gcode_job(std::string_view text, std::string name, const GcodeOptions& options);

/// A streamed load: each line's segments and events go to `sink` once the line ran (after the
/// checks load_job_file makes of every segment: swept extent, parameter speed), and are not kept.
/// The job returned holds the name and the sources, each without its points, weights, knots and
/// breaks (the file's lines and segment types, what messages name). Throws what import_gcode throws.
[[nodiscard]] Job import_gcode(const std::filesystem::path& path, const GcodeOptions& options, JobSink& sink);
[[nodiscard]] Job parse_gcode_job(std::string_view text, std::string name, const GcodeOptions& options, JobSink& sink);

}  // namespace curvestep::host
