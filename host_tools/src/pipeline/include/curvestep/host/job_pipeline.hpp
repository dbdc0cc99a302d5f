// SPDX-License-Identifier: MIT
// One job pipeline for every command that moves a machine (sim, plot, stream, gpio, demo), so that
// what was simulated is what runs:
//
//   file ─► load_job_file (by extension; --optimize orders SVG subpaths, --layers selects layers)
//        ─► pen moves (SVG with a machine-file "pen": z up for rapids, down to draw; pen_moves.hpp)
//        ─► step-rate-aware limits (each axis's v_max lowered to what its drivers can step)
//        ─► path smoothing (blend_tolerance / --blend-tolerance)  ─► Job + MachineLimits to plan/send
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/host/gcode_import.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/job_file.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/smoothing/path_smoothing.hpp>
#include <curvestep/host/smoothing/smoothing_stream.hpp>

namespace curvestep::host {

/// The options every machine-moving command accepts (add_job_pipeline_options in the program).
struct JobPipelineOptions {
  bool optimize = false;            ///< --optimize: order SVG subpaths to shorten pen-up travel
  double blend_tolerance_mm = -1;   ///< --blend-tolerance; < 0: the machine file's
  bool strict_step_rate = false;    ///< --strict-step-rate: refuse instead of planning slower
  bool strict_svg = false;          ///< --strict: refuse SVG path data or points errors (SVG's rule draws up to them)
  std::string page;                 ///< --page: a4, letter, WxH... (empty: none)
  bool landscape = false;           ///< --landscape
  bool center = false;              ///< --center
  bool fit = false;                 ///< --fit
  std::string margin;               ///< --margin (mm, or with a unit mm/cm/in; empty: 0)
  int rotate_deg = 0;               ///< --rotate: 0, 90, 180, 270 clockwise
  std::vector<std::string> layers;  ///< --layers: Inkscape layers to draw, by label (empty: all)
  std::vector<std::string> subroutine_path;  ///< --subroutine-path: G-code subroutine file folders, searched in order
};

/// `options` without what applies to SVG drawings only (--optimize, --strict, --layers and the page
/// options): what a command that runs a drawing and a program alike (demo) gives the program.
[[nodiscard]] JobPipelineOptions without_drawing_options(const JobPipelineOptions& options);

/// The job-file options (import, page layout) of the pipeline options. std::invalid_argument for a
/// malformed --page or --margin.
[[nodiscard]] JobFileOptions job_file_options(const JobPipelineOptions& options);

/// A job ready to plan or send, with the limits to plan it with.
struct PreparedJob {
  Job job;                                 ///< smoothed
  MachineLimits machine;                   ///< the machine file's limits, step-rate aware unless strict
  smoothing::SmoothingReport smoothing;    ///< what smoothing did
  std::vector<std::string> notes;          ///< lines worth telling the user (import notes, lowered axis speeds)
  /// The event timeline's labels (SmoothingStream::event_labels), for a job whose source_index is
  /// not held (prepare_job_streamed); a pen drawing's stay empty.
  std::map<std::size_t, std::size_t> event_labels;
};

/// Share of max_step_rate an axis may use when its speed is lowered to fit it (the setpoints'
/// measured speed may exceed the planned cap by rounding).
inline constexpr double step_rate_share = 0.99;

/// `machine` with each stepped axis's v_max lowered so that v_max × steps_per_mm stays within
/// step_rate_share × max_step_rate (the planner then keeps every axis within it: per-axis speed caps,
/// docs/motion.md). A note per lowered axis is appended to `notes`.
[[nodiscard]] MachineLimits step_rate_aware(const MachineLimits& machine, std::vector<std::string>* notes = nullptr);

/// Loads `job_file` and prepares it for `machine` (the machine file's limits, possibly with a rate
/// override), the machine file's `blend_tolerance_mm` and its `pen` (applied to SVG drawings only,
/// before smoothing). Throws what load_job_file throws.
[[nodiscard]] PreparedJob prepare_job(const std::filesystem::path& job_file, const MachineLimits& machine,
                                      double machine_blend_tolerance_mm, const JobPipelineOptions& options,
                                      const std::optional<PenModel>& pen = std::nullopt);

/// prepare_job with the whole machine file: a G-code job reads its tool table and G28/G30
/// positions (gcode_options), and the prepared job is checked against its travel (soft limits,
/// check_travel: OutsideTravel naming file:line) before anything moves. `machine` is the file's
/// limits, possibly with a rate override.
[[nodiscard]] PreparedJob prepare_job(const std::filesystem::path& job_file, const MachineFile& machine_file,
                                      const MachineLimits& machine, const JobPipelineOptions& options);

/// True if prepare_job reads `job_file` into smoothing as a stream: anything but an SVG drawing on
/// a machine with a pen (whose pen moves are added to the whole drawing).
[[nodiscard]] bool is_streamed(const std::filesystem::path& job_file, const MachineFile& machine_file);

/// prepare_job with the whole machine file for a streamed job (is_streamed, else std::logic_error),
/// whose smoothed segments go to `downstream` as they are decided instead of into the job (its
/// segments and source_index stay empty) and are not checked against the travel (the caller's
/// part: streamed_job.hpp). The same load and smoothing, so the same segments and errors. A
/// G-code load keeps no line per file segment (GcodeOptions::keep_source_lines false): a message
/// naming the line of a smoothed segment needs the job loaded again (prepare_job).
[[nodiscard]] PreparedJob prepare_job_streamed(const std::filesystem::path& job_file, const MachineFile& machine_file,
                                               const MachineLimits& machine, const JobPipelineOptions& options,
                                               smoothing::SmoothingStream::SegmentHandler downstream);

/// What a machine file tells the G-code importer: tool lengths and diameters, G28/G30 positions.
[[nodiscard]] GcodeOptions gcode_options(const MachineFile& machine_file);

}  // namespace curvestep::host
