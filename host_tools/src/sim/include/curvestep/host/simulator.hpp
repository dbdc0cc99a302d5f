// SPDX-License-Identifier: MIT
// The host simulator: replays a job through the firmware's MotionController and measures the result,
// or plans it into pieces for a controller that only replays them (plan_pieces).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include <curvestep/core/motion/feed_override.hpp>
#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/core/motion/planned_piece.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/readable_job.hpp>
#include <curvestep/host/segment_source.hpp>

namespace curvestep::host {

/// One setpoint as written to CSV: time, position, speed, and the raw Q16.16 position.
struct SetpointRecord {
  double time_s = 0;
  std::array<double, 3> position_mm{};
  double speed_mm_per_s = 0;
  std::array<std::int32_t, 3> raw_q16{};  ///< the bits a Q16.16 firmware sends (fixed-point runs)
  std::uint32_t segment = 0;               ///< the job file's segment index
  std::uint64_t index = 0;                 ///< the setpoint's index (tick) from the job's start: time_s = index / rate
};

/// What `curvestep sim` reports.
struct SimulationSummary {
  std::size_t setpoints = 0;
  double duration_s = 0;
  double distance_mm = 0;
  double peak_speed_mm_per_s = 0;          ///< numerical, from the exact (double) positions
  double peak_acceleration_mm_per_s2 = 0;  ///< |second difference| / dt²
  double peak_jerk_mm_per_s3 = 0;          ///< |third difference| / dt³
  double max_quantisation_mm = 0;          ///< largest |Q16.16 setpoint − exact point on the path|
  double max_chord_deviation_mm = 0;       ///< largest sagitta between consecutive setpoints (|Δ²p|/8)
  std::array<double, 3> peak_step_rate_hz{};  ///< per axis: peak |velocity| × steps/mm
  std::vector<std::string> violations;    ///< limits exceeded (by more than 1%), one line each
};

/// A feed hold during a simulation (`curvestep sim --hold-at T[:R]`): the controller's hold()
/// before the setpoint of index `tick` (T × rate) is made, as the firmware's FeedHold between two
/// ticks; once it stands, `standing_ticks` (R × rate) setpoints stand still, then resume() before
/// the next one. A device in fast mode never ticks while held: standing_ticks 0 gives its stream.
struct FeedHoldEvent {
  std::uint64_t tick = 0;
  std::uint64_t standing_ticks = 0;
};

/// A feed or rapid override during a simulation (`curvestep sim --override-at T:F[:R]`): the
/// controller's set_override() before the setpoint of index `tick` (T × rate) is made, as the
/// firmware takes FeedOverride between two ticks. The controller lets it take effect at its next
/// point of zero acceleration (docs/motion.md, "Feed override").
struct FeedOverrideEvent {
  std::uint64_t tick = 0;
  FeedOverride value{};
};

/// Why a FeedOverride is not valid(): "the feed override must be 10..200 % and the rapid override
/// 10..100 %", from FeedOverride's range constants; the one text every host check of an override ends with.
[[nodiscard]] std::string override_range_text();

/// Options of one simulation.
struct SimulationOptions {
  /// The largest look-ahead window the simulator's controllers have (their template Lookahead).
  static constexpr std::size_t max_lookahead = 16;
  bool fixed_point = true;  ///< Q16.16 setpoints (the firmware's); false: double
  /// Look-ahead window in segments (MotionController::set_lookahead), 1..max_lookahead. The
  /// setpoints depend on it: replay a device with its own window to get its stream bit for bit
  /// (an App<Board, S, Queue, Lookahead> with Queue >= Lookahead + 8 plans with Lookahead).
  std::size_t lookahead = max_lookahead;
  /// Extends the window by distance (MotionController::set_lookahead_distance): up to
  /// max_distance_window segments until their lengths cover this many mm. 0 (the default): the count
  /// window alone, as a device with an on-board planner runs it. `curvestep sim` without --lookahead
  /// and executor streaming use lookahead_distance_for(machine).
  double lookahead_distance_mm = 0;
  /// The most segments a distance window may take.
  static constexpr std::size_t max_distance_window = 256;
  std::function<void(double fraction)> progress;  ///< called now and then with 0..1 (may be empty)
  /// Feed holds in tick order (simulate and simulate_stream; plan_pieces ignores them). A hold at a
  /// tick where the job is not moving (it ended) is refused with std::runtime_error.
  std::vector<FeedHoldEvent> holds;
  /// Overrides in tick order (simulate, simulate_stream and plan_pieces); one past the job's end is
  /// refused with std::runtime_error.
  std::vector<FeedOverrideEvent> overrides;
};

/// The look-ahead distance that lets a planner reach any speed the machine allows and stop again:
/// twice the S-curve (or trapezoid) distance from v_max to rest.
[[nodiscard]] double lookahead_distance_for(const MachineLimits& machine);

/// The setpoints and the summary of a run.
struct SimulationResult {
  std::vector<SetpointRecord> setpoints;
  SimulationSummary summary;
};

/// Receives each setpoint of a run as it is made.
using SetpointSink = std::function<void(const SetpointRecord&)>;

/// Runs the job on the machine, handing each setpoint to `sink` (may be empty) as it is made and
/// keeping none: memory independent of the job's length. The summary is simulate()'s, bit for bit.
/// Throws what simulate() throws.
[[nodiscard]] SimulationSummary simulate_stream(const Job& job, const MachineLimits& machine, const SimulationOptions& options,
                                                const SetpointSink& sink);

/// A smoothed job whose segments are pulled from `source` as the run needs them instead of held
/// (streamed_job.hpp: a G-code program read once more while it runs).
struct StreamedJob {
  const Job* outline = nullptr;        ///< its name, events and source_index; no segments
  std::size_t segments = 0;            ///< how many `source` gives
  double approximate_length_mm = 0;    ///< the sum of approximate_length(segment), for progress
  std::unique_ptr<SegmentSource> source;
};

/// simulate_stream of a streamed job: the setpoints and summary of the same job held whole, bit
/// for bit, in memory independent of its length. Also throws what `source` throws.
[[nodiscard]] SimulationSummary simulate_stream(StreamedJob job, const MachineLimits& machine, const SimulationOptions& options,
                                                const SetpointSink& sink);

/// simulate_stream of a new read of `job` (job.read(), a StreamedJob of its outline, count and
/// approximate length): the one way a ReadableJob is simulated (`sim`'s streamed job, gpio's check).
[[nodiscard]] SimulationSummary simulate_stream(const ReadableJob& job, const MachineLimits& machine, const SimulationOptions& options,
                                                const SetpointSink& sink);

/// A segment's path length for progress: arcs exactly (helix: √((r·sweep)² + Δz²)), curves by the
/// chords of 16 samples (a slight underestimate).
[[nodiscard]] double approximate_length(const PathSegment& segment);

/// Runs the job on the machine and keeps every setpoint (simulate_stream into a vector). Throws std::runtime_error with a one-line cause if the controller
/// rejects a segment (naming the job file and segment) or faults, or if options.lookahead is
/// outside 1..max_lookahead.
[[nodiscard]] SimulationResult simulate(const Job& job, const MachineLimits& machine, const SimulationOptions& options = {});

/// The job planned here for a controller without a planner (Capabilities::lookahead 0): the
/// PlannedPieces (planned_piece.hpp) of the Q16.16 MotionController that simulate() runs, with
/// options.lookahead as its window (the other options are not used). Replaying them
/// (PieceExecutor<Q16_16>) gives simulate()'s raw_q16 setpoints bit for bit: their ticks add up
/// to its setpoint count, the last piece has end_of_job, and each piece's segment is the job
/// file's segment index (SetpointRecord::segment). Throws what simulate() throws. It is
/// PiecePlanner::next_piece() until none is left (piece_planner.hpp: the same pieces on demand).
[[nodiscard]] std::vector<PlannedPiece> plan_pieces(const Job& job, const MachineLimits& machine,
                                                    const SimulationOptions& options = {});

/// Writes `t,x,y,z,v,index` and one line per setpoint (shortest round-trip decimals; `index` is the
/// setpoint's index from the job's start, the same in `curvestep sim -o` and `stream --capture`).
void write_setpoints_csv(std::ostream& out, const std::vector<SetpointRecord>& setpoints);
/// The CSV's header line and one setpoint's line, for writing as the setpoints come.
void write_setpoints_csv_header(std::ostream& out);
void write_setpoint_csv_line(std::ostream& out, const SetpointRecord& r);

/// The summary as the human-readable block `curvestep sim` prints.
[[nodiscard]] std::string format_summary(const SimulationSummary& summary, const MachineLimits& machine);

}  // namespace curvestep::host
