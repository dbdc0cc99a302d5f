// SPDX-License-Identifier: MIT
// Path smoothing before planning (docs/motion.md, "Path smoothing"): the host turns a job into one
// the planner can follow at feed, within a path tolerance of what was programmed.
//
//   1. runs of short lines that approximate a smooth curve → C2 cubic B-splines (line_run_fit.hpp);
//   2. every remaining corner (and every tangent joint whose curvature jumps) → a G2 quintic blend
//      (corner_blend.hpp), using at most a share of each neighbour.
//
// It runs on the host, before `sim` plans and before `stream`/`gpio`/`demo` send: the device
// receives the smoothed segments themselves, so simulator and device plan the same segments and
// stay bit-identical; the firmware needs no blending code and no extra look-ahead.
//
// A blend is kept only when passing it is faster than stopping at the corner: under a jerk limit a
// sharp corner's tolerance-sized blend is crawled through for longer than a stop and restart take.
// Rapids are never fitted; a corner between two rapids is blended, one between a rapid and a feed move
// kept as programmed, as are reversals (deflection above 179°),
// joints with a job event (a dwell or a spindle change needs the stop), exact-stop joints (G61),
// arcs of more than one turn. With a fit next to it, a blend gets half the tolerance (the fit took
// the other half), so the deviation from the programmed path never exceeds the tolerance.
#pragma once

#include <cstddef>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/host/job.hpp>

namespace curvestep::host::smoothing {

/// How to smooth.
struct SmoothingOptions {
  double tolerance_mm = 0;              ///< largest deviation from the programmed path; 0 = off
  bool fit_line_runs = true;            ///< replace runs of short lines by splines
  bool blend_corners = true;            ///< replace corners by G2 blends
  double fit_max_line_mm = 5;           ///< longer lines are features, never fitted
  double fit_max_deflection_deg = 30;   ///< a sharper corner ends a run
  std::size_t fit_max_run_lines = 100'000;  ///< a longer run is fitted in runs of this many lines (bounds a streamed load's memory)
  double blend_max_share = 0.49;        ///< a blend takes at most this share of a neighbour (each end)
  MachineLimits machine{};              ///< the machine the job is smoothed for: its limits shape the blends
                                        ///< for speed, and a blend is kept only where its planner passes it
                                        ///< faster than the corner
};

/// The jerk limit smoothing shapes and times speed changes with: the machine's, or 1e12 mm/s³
/// (none: its speed changes are trapezoids) on a machine without one.
[[nodiscard]] inline double smoothing_jerk_mm_per_s3(const MachineLimits& machine) noexcept {
  return machine.jerk_limited ? machine.j_max_mm_per_s3 : 1e12;
}

/// What smoothing did.
struct SmoothingReport {
  double tolerance_mm = 0;          ///< the tolerance in force (machine file or command line)
  std::size_t corners = 0;          ///< joints that were corners or curvature jumps
  std::size_t corners_blended = 0;  ///< of those, replaced by blends
  std::size_t corners_stopped = 0;  ///< of those, kept because the planner passes them faster than their blend (a stop at a sharp one)
  std::size_t corners_reversed = 0;     ///< of those, reversals (deflection above 179°): kept, the planner stops there
  std::size_t corners_unblendable = 0;  ///< of those, kept because no blend fits (a neighbour too short, an arc of over one turn)
  std::size_t runs_fitted = 0;      ///< runs of lines replaced by splines
  std::size_t lines_fitted = 0;     ///< lines in those runs
  std::size_t fitted_pieces = 0;    ///< Bézier pieces the runs became
  std::size_t segments_before = 0;  ///< segments of the programmed job
  std::size_t segments_after = 0;   ///< segments of the smoothed job
  double max_deviation_mm = 0;      ///< largest deviation from the programmed path (both ways)
  double largest_tolerance_mm = 0;  ///< the largest tolerance smoothing used (G64 P may set more than tolerance_mm)
  /// The largest deviation from the programmed path as a share of the tolerance in force where it
  /// occurs (at most 1): with G64 P per move, max_deviation_mm alone does not say whether it held.
  double max_deviation_share = 0;
  /// With smoothing off: the largest G64 P the program set (it is not applied: the machine file's
  /// "blend_tolerance" or --blend-tolerance turns smoothing on); 0 if none.
  double unapplied_tolerance_mm = 0;
};

/// Options for a machine: its limits and `tolerance_mm`.
[[nodiscard]] SmoothingOptions options_for(const MachineLimits& machine, double tolerance_mm);

/// The smoothed job (the same job when the tolerance is 0). Job::blend_tolerance_mm gives the
/// tolerance per joint when set (> 0 that value, 0 the options' tolerance, < 0 exact stop); events
/// keep their place. `report` (optional) receives the figures. The job is taken by value: a caller
/// that moves it in lets the smoothed job take over its source records and frees its segments
/// early (a large program's peak memory).
[[nodiscard]] Job smooth_job(Job job, const SmoothingOptions& options, SmoothingReport* report = nullptr);

/// smooth_job() with options_for(machine, tolerance_mm): what every command that moves a machine
/// (sim, stream, gpio, demo) runs, so what was simulated is what runs.
[[nodiscard]] inline Job smooth_for_machine(Job job, const MachineLimits& machine, double tolerance_mm,
                                            SmoothingReport* report = nullptr) {
  return smooth_job(std::move(job), options_for(machine, tolerance_mm), report);
}

/// The report as summary lines ("  smoothing: ..."), for sim and stream.
[[nodiscard]] std::string format_smoothing(const SmoothingReport& report);

/// The report as (name, value, limit) rows for the HTML report.
[[nodiscard]] std::vector<std::array<std::string, 3>> smoothing_rows(const SmoothingReport& report);

/// The tolerance in force: `command_line_mm` when given (>= 0), else the machine file's.
[[nodiscard]] inline double tolerance_in_force(double machine_file_mm, double command_line_mm) noexcept {
  return command_line_mm >= 0 ? command_line_mm : machine_file_mm;
}

}  // namespace curvestep::host::smoothing
