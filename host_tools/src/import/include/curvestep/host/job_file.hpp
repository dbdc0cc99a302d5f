// SPDX-License-Identifier: MIT
// load_job_file: a job from JSON (.json), G-code (.ngc, .nc, .gcode, .tap, .gc, .gco, .g, .cnc) or SVG (.svg), by extension.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <curvestep/host/gcode_import.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/page_layout.hpp>

namespace curvestep::host {

/// How to read a job file.
struct JobFileOptions {
  bool optimize = false;    ///< SVG: order subpaths to shorten pen-up travel (greedy nearest neighbour)
  bool strict_svg = false;  ///< SVG: refuse malformed path data or points (else drawn up to the error, with a note)
  std::vector<std::string> layers;  ///< SVG: Inkscape layers to draw, by label (empty: all)
  PageLayout page;          ///< SVG: page size, centring, fit, rotation and the page check (page_layout.hpp)
  GcodeOptions gcode;       ///< G-code: the machine file's tool table and G28/G30 positions
};

/// "Job file: .json, G-code (.ngc .nc ...) or .svg": what the commands' help says of their job argument.
[[nodiscard]] std::string job_file_help();

/// Loads the job in `path`, choosing the format by its extension (case-insensitive). Lines worth
/// telling the user (SVG warnings, travel saved by --optimize, the page layout) are appended to
/// `notes`. A page layout applies to SVG only (std::invalid_argument for other formats). Throws
/// LoadError for a malformed file (naming file, line and what is wrong) and std::runtime_error for
/// an unreadable file or an unknown extension (naming the extensions understood).
[[nodiscard]] Job load_job_file(const std::filesystem::path& path, const JobFileOptions& options = {},
                                std::vector<std::string>* notes = nullptr);

/// load_job_file handing the job's segments and events to `sink` (job.hpp) instead of keeping them;
/// returns the rest of the job (name, version, sources). A G-code program is streamed line by
/// line, so its memory does not grow with its segments (its sources keep only lines and types:
/// gcode_import.hpp); JSON and SVG jobs are read whole, checked, then handed over (feed_job).
[[nodiscard]] Job load_job_file(const std::filesystem::path& path, const JobFileOptions& options, std::vector<std::string>* notes,
                                JobSink& sink);

}  // namespace curvestep::host
