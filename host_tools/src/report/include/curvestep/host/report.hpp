// SPDX-License-Identifier: MIT
// Seeing before moving: an SVG plot of a job's path and a self-contained HTML report of a simulation.
//
// The path plot is drawn in the XY plane (z is not shown), y up, scaled to fit. Feed moves are
// solid, rapids dashed grey, the start is a green circle and the end a red square, and a scale bar
// of 1, 2 or 5 × 10^k mm shows the size. With a simulation the feed moves are the setpoints
// themselves, coloured by the planned speed (a colour bar gives the range); without one they are
// the flattened segments, coloured by the job file's segment index.
//
// The report's acceleration and jerk curves are finite differences of the setpoint positions,
// like the simulator's summary: a = |p_i − 2p_{i−k} + p_{i−2k}| / (k·dt)², j = |third difference| /
// (k·dt)³. With exact (double) positions k = 1 and the curves' peaks are the summary's peaks.
// Q16.16 positions carry a rounding error e ≤ √3·2^-17 mm, which adds up to 4e/(k·dt)² to the
// acceleration and 8e/(k·dt)³ to the jerk; k is the smallest stride (at most 64) that keeps both
// below 1% of the machine's limits, and the report says which stride it used.
#pragma once

#include <cstddef>
#include <array>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/simulator.hpp>

namespace curvestep::host {

/// What the path plot shows and how big it is.
struct PathPlotOptions {
  std::string title;         ///< drawn at the top (escaped); empty: none
  double width_px = 800;     ///< width of the drawing in pixels
  double max_height_px = 0;  ///< height of the path area at most (0: 1.25 × width)
  bool standalone = true;    ///< an SVG document (with XML declaration) rather than an inline <svg> element
};

/// The path of `job` as SVG. With `setpoints` (a simulation of the job) feed moves are coloured by
/// their planned speed, else by segment. std::invalid_argument for a job without segments.
[[nodiscard]] std::string path_plot_svg(const Job& job, const std::vector<SetpointRecord>* setpoints, const PathPlotOptions& options);

/// Writes path_plot_svg to a stream or a file. std::runtime_error naming the file if it cannot be written.
void write_path_plot(std::ostream& out, const Job& job, const std::vector<SetpointRecord>* setpoints, const PathPlotOptions& options);
void write_path_plot(const std::string& file, const Job& job, const std::vector<SetpointRecord>* setpoints,
                     const PathPlotOptions& options);

/// Hands every setpoint of a simulation to the sink, in order, each time it is called (e.g. by
/// running simulate_stream again).
using SetpointReplay = std::function<void(const SetpointSink&)>;

/// The plot of a simulation whose setpoints `replay` hands over, written as they come and kept
/// nowhere: memory independent of the job's length. The replay runs twice (the extent and the peak
/// speed first, then the strokes); the text is path_plot_svg's with the same setpoints in a vector
/// (without setpoints, the plot by segment).
void write_path_plot_streamed(std::ostream& out, const Job& job, const SetpointReplay& replay, const PathPlotOptions& options);
void write_path_plot_streamed(const std::string& file, const Job& job, const SetpointReplay& replay, const PathPlotOptions& options);

/// What the plot of a simulation needs of its job besides the setpoints, for a job not held (a
/// streamed job, streamed_job.hpp): its name and which of its file segments are rapids.
struct PlottedJob {
  std::string name;
  std::function<bool(std::size_t source)> rapid_source;  ///< drawn grey and dashed, left out of the peak speed
};
/// A job held whole as a PlottedJob (its sources say which are rapids); `job` must outlive it.
[[nodiscard]] PlottedJob plotted(const Job& job);
/// write_path_plot_streamed of a job not held; std::invalid_argument if the replay has no setpoints.
void write_path_plot_streamed(std::ostream& out, const PlottedJob& job, const SetpointReplay& replay, const PathPlotOptions& options);
void write_path_plot_streamed(const std::string& file, const PlottedJob& job, const SetpointReplay& replay, const PathPlotOptions& options);

/// Speed, acceleration and jerk over time, from a simulation's setpoints.
struct MotionProfile {
  std::vector<double> time_s;         ///< one entry per setpoint
  std::vector<double> speed_mm_per_s;  ///< the planned path speed of each setpoint
  std::vector<double> acceleration_mm_per_s2;  ///< |second difference| / (stride·dt)², 0 before 2·stride
  std::vector<double> jerk_mm_per_s3;          ///< |third difference| / (stride·dt)³, 0 before 3·stride
  std::size_t stride = 1;             ///< setpoints between the differenced positions
};

/// The profile of `setpoints` taken at `machine.rate_hz`; `quantised` says the positions are Q16.16
/// (then the stride grows as the file comment explains).
[[nodiscard]] MotionProfile motion_profile(const std::vector<SetpointRecord>& setpoints, const MachineLimits& machine, bool quantised);

/// What the HTML report is about.
struct ReportInput {
  const Job* job = nullptr;                   ///< the job that was simulated
  const MachineLimits* machine = nullptr;     ///< the machine it ran on
  const SimulationResult* result = nullptr;   ///< the simulation
  bool fixed_point = true;                    ///< setpoint positions are Q16.16
  std::string title;                          ///< e.g. the job file's name
  /// Further summary rows (name, value, limit), e.g. path smoothing's figures.
  std::vector<std::array<std::string, 3>> extra_rows;
  /// For a job that holds no PathSegments (a streamed job, streamed_job.hpp): their count, and
  /// which file segments are rapids. Empty rapid_source: the job is held whole.
  std::size_t path_segments = 0;
  std::function<bool(std::size_t source)> rapid_source;
};

/// One self-contained HTML page (no external resources): summary figures, warnings, the path plot
/// and speed, acceleration and jerk over time with the limits drawn. std::invalid_argument if a
/// pointer of `input` is null or the simulation has no setpoints.
[[nodiscard]] std::string html_report(const ReportInput& input);

/// Writes html_report to a file. std::runtime_error naming the file if it cannot be written.
void write_html_report(const std::string& file, const ReportInput& input);

/// The same report from a replay that hands over the setpoints (called four times: the charts'
/// range and peaks, their pixel columns, then the path plot's two passes), written as it is made:
/// memory independent of the job's length. input.result gives the summary; its setpoints are
/// not read.
void write_html_report_streamed(const std::string& file, const ReportInput& input, const SetpointReplay& replay);

/// A progress callback that draws `[#####     ] 42%  ETA 3 s` on stderr when stderr is a
/// terminal, and an empty function (quiet) when it is not. finish_terminal_progress clears the line.
[[nodiscard]] std::function<void(double fraction)> make_terminal_progress();

/// Clears the progress line if stderr is a terminal.
void finish_terminal_progress();

/// The text of the progress line for a fraction done after `elapsed_s` seconds (no ETA below 1%).
[[nodiscard]] std::string format_progress_line(double fraction, double elapsed_s);

}  // namespace curvestep::host
