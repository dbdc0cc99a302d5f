// SPDX-License-Identifier: MIT
// stream_job: connect, send the machine configuration, upload a job under the controller's flow
// control, start it, and collect the controller's setpoint stream until the job ends.
//
// Sequence: Hello/Capabilities (the controller's limits are read, never assumed), then
// MachineConfiguration and Start, then QueueSegments while the credit allows, the last one
// flagged end_of_job. The controller arms on Start and begins moving by itself once its
// look-ahead window is full or the job's end has arrived (firmware/app.hpp, "the start rule"),
// so its plan equals `curvestep sim`'s. A controller without a planner (Capabilities::lookahead 0)
// gets the job planned here instead (PiecePlanner with StreamOptions::lookahead: once through before
// anything is sent, to refuse what cannot be planned or sent and to count the pieces, then piece by
// piece as they are sent, at most StreamOptions::piece_lead_s of motion ahead of the controller) as
// QueuePieces, one credit each like a segment, the last one flagged end_of_job: its setpoints are
// those of `curvestep sim --lookahead N`. The job is over when a StatusReport says Idle after the controller
// reported Running, every segment was sent and acknowledged, and every setpoint up to the
// reported index has arrived (the controller's setpoint stream is reliable since protocol
// version 2, so none may be missing); a Fault state or an ErrorReport ends it with the
// controller's cause (naming the job segment, and the piece number when pieces were sent). A controller that restarted mid-job (it answers NotConnected) ends it with
// DeviceRestarted, naming the last acknowledged segment and the last setpoint received.
//
// The operator (StreamOptions::operator_command, polled every loop): Hold sends FeedHold and at
// once a StatusRequest, whose answer (the controller takes both between the same two ticks) names
// the last setpoint before the hold: the hold acts before setpoint index + 1 (StreamHold::tick).
// Resume sends Resume; Abort sends Abort (nothing more is queued), then a StatusRequest, and the
// upload ends with StreamResult::aborted once the controller reports it stopped. `curvestep sim
// --hold-at T:R` with T = tick / rate and R = the ticks it stood / rate gives the held job's
// setpoints bit for bit (hold_at_option()). A controller without a planner: Hold holds the host's
// planner before the setpoint it has planned up to (StreamHold::tick, known here exactly), sends
// the braking pieces and then FeedHold (the controller stands at their end); Resume sends Resume
// and resumes the planner. The controller does not tick while it stands: R = 0.
// Feed and rapid override: StreamOptions::feed_override is sent (FeedOverride) before the first
// segment; the override commands send FeedOverride as the operator asks. The controller answers
// each with a StatusReport naming the setpoint it was set before (override_index): a new
// (values, index) there is a StreamOverride, and `curvestep sim --override-at T:F:R` with
// T = index / rate replays them bit for bit (override_at_option()). A controller without a
// planner gets the job planned here with the start override, and each later one is set on the
// host's planner before the setpoint it has planned up to (no FeedOverride is sent): the same
// replay. Once the job's last piece is sent, a hold or override cannot act any more (warn).
#pragma once

#include <cstddef>
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <curvestep/core/error.hpp>
#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/link/operator_command.hpp>
#include <curvestep/host/link/transport.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/readable_job.hpp>
#include <curvestep/host/simulator.hpp>
#include <curvestep/protocol/link_sender.hpp>

namespace curvestep::host::link {

/// Where an upload is.
struct StreamProgress {
  std::size_t sent = 0;                ///< queue messages submitted (segments or pieces, see unit)
  std::size_t total = 0;               ///< queue messages of the job; pieces after a hold or override changed the plan: 0 until its last one is planned
  const char* unit = "segments";       ///< what sent and total count: "segments", or "pieces" for a controller without a planner
  std::size_t setpoints_received = 0;  ///< setpoints captured so far
  double elapsed_s = 0;                ///< since connect
  double eta_s = -1;                   ///< estimated seconds left (-1: not known yet)
  const char* state = "Running";       ///< the operator's view: "Running", "Hold" or "Aborting"
  bool have_status = false;            ///< a StatusReport arrived: the fields below hold
  std::uint32_t setpoint_index = 0;    ///< the controller's last StatusReport: its setpoint index
  const char* machine_state = "";      ///< ... its state (Idle, Running, Holding, Fault)
  std::array<double, 3> position_mm{}; ///< ... its commanded position
  std::uint32_t tick_overruns = 0;     ///< ... its late or long control ticks this session (StatusReport::tick_overruns)
  FeedOverride override_percent{};     ///< the feed and rapid override last set (as the controller reports it)
};

/// Options of one upload.
struct StreamOptions {
  /// Retransmission and link timeout. Only timeouts in a row without any progress, each with
  /// the controller heard since the last, count toward max_retransmits (Nak-triggered go-backs
  /// on a noisy line do not), so the default 10 gives up after about a second of no progress
  /// while the controller talks; a silent controller, and any lack of progress however many
  /// Naks arrive, are bounded by the link timeout (docs/protocol.md, "Sequence numbers, acknowledgements, retransmission").
  protocol::SenderSettings link{100, 10, 3000};
  std::function<void(const StreamProgress&)> progress;  ///< called about 10 times a second (may be empty)
  std::function<void(const std::string&)> warn;         ///< called for each value the wire cannot carry exactly
  double status_interval_s = 0.2;                       ///< StatusRequest period while running
  /// The look-ahead window the job is planned with here (plan_pieces) for a controller without a
  /// planner (Capabilities::lookahead 0); unused for one that plans. 1..max_lookahead.
  std::size_t lookahead = SimulationOptions::max_lookahead;
  /// A controller without a planner: the pieces sent cover at most this much motion (seconds of
  /// setpoints) past its last known setpoint once it runs, plus the piece being sent (at most 256
  /// ticks, or one rest). That bounds how late an operator's hold or override acts: they change the
  /// plan after what was sent. Before it starts, the credit alone decides (its start rule wants a
  /// full queue).
  double piece_lead_s = 0.5;
  /// With it: the window extended by distance (SimulationOptions::lookahead_distance_mm; 0 = off).
  /// `curvestep stream` without --lookahead uses lookahead_distance_for(machine), as `curvestep sim` does.
  double lookahead_distance_mm = 0;
  /// Soft limits sent in MachineConfiguration, per axis [low, high] mm (the machine file's
  /// "travel"); an axis without them travels unlimited (the whole Q16.16 range).
  MachineTravel travel{};
  /// Receives each of the controller's setpoints as it arrives, in index order; then none is kept
  /// (StreamResult::setpoints stays empty): memory independent of the job's length. Empty: the
  /// setpoints are collected in StreamResult::setpoints.
  SetpointSink setpoint_sink;
  /// The operator's requests (keys, signals: OperatorConsole), polled about every 5 ms (may be empty).
  std::function<OperatorCommand()> operator_command;
  /// The controller paused the job for the operator (M0/M1, a tool change, a pen change):
  /// told once per pause what it is for (may be empty).
  std::function<void(const std::string&)> paused;
  /// Polled while paused: true once the job may go on (Resume is sent). Empty: at once.
  std::function<bool()> resume_now;
  /// Homing: the job ends at once where this limit switch closes (SeekSwitch; bit 2 x axis, + 1
  /// for max); StreamResult::switch_closed says where. None: an ordinary job.
  std::optional<std::uint8_t> seek_switch;
  /// The feed and rapid override the job starts with (`--feed-override`, `--rapid-override`).
  FeedOverride feed_override{};
};

/// One feed or rapid override of a streamed job, as the controller took it.
struct StreamOverride {
  std::uint64_t tick = 0;  ///< set before this setpoint index (sim --override-at T = tick / rate)
  FeedOverride value{};    ///< feed and rapid percent
};

/// One feed hold of a streamed job.
struct StreamHold {
  /// The hold acted before this setpoint index (sim --hold-at T = tick / rate); 0: before the job
  /// began moving (the controller reported index 0: armed, or at most one setpoint made).
  std::uint64_t tick = 0;
  std::optional<std::uint64_t> standing_ticks;  ///< ticks stood still before the resume (sim R × rate); none: not resumed
};

/// The controller stopped the job or the link died: a one-line cause naming what failed.
class StreamError : public std::runtime_error {
 public:
  /// An error with its code.
  StreamError(Error code, const std::string& message) : std::runtime_error(message), code_(code) {}
  /// The controller's or the link's error code.
  [[nodiscard]] Error code() const noexcept { return code_; }

 private:
  Error code_;
};

/// What a finished upload produced.
struct StreamResult {
  std::vector<SetpointRecord> setpoints;  ///< the controller's setpoints, index order (time = index / rate); empty with a setpoint_sink
  std::size_t setpoints_received = 0;     ///< setpoints received (once each)
  std::size_t standing_ticks = 0;         ///< tick indices not reported: ticks the controller stood held or starved (the reliable stream loses none)
  std::size_t duplicate_setpoints = 0;    ///< setpoints received twice or out of order, dropped (0 unless the link is broken)
  std::size_t batches_repeated = 0;       ///< setpoint batches the controller resent and the host had already
  std::size_t max_queue_depth = 0;        ///< deepest the controller's segment queue was (its last StatusReport)
  std::size_t queue_capacity = 0;         ///< the controller's segment queue slots (Capabilities)
  std::size_t lookahead = 0;              ///< the controller's planning window (Capabilities): sim --lookahead; 0: no planner
  std::size_t pieces_sent = 0;            ///< planned pieces sent (a controller without a planner; 0 when it planned)
  std::size_t planned_lookahead = 0;      ///< the window the pieces were planned with here (sim --lookahead); 0 when the controller planned
  std::size_t frames_rejected = 0;        ///< damaged frames from the controller
  std::size_t bytes_sent = 0;             ///< bytes written, retransmissions included
  std::vector<StreamHold> holds;          ///< the operator's feed holds, in order
  std::vector<StreamOverride> overrides;  ///< the overrides the controller took (and the start one), in order
  bool aborted = false;                   ///< the operator aborted the job (the controller stopped at once)
  std::uint32_t final_setpoint_index = 0; ///< the controller's last StatusReport: setpoint index
  std::array<std::int32_t, 3> final_position_q16{};  ///< ... and commanded position (Q16.16 raw)
  std::optional<protocol::SwitchReport> switch_closed;  ///< a seek job (StreamOptions::seek_switch) met its switch here
  std::uint32_t tick_overruns = 0;        ///< ... ticks that started a period late or ran longer than one (0: kept real time)
  std::uint32_t worst_tick_us = 0;        ///< ... the longest tick, microseconds (0: the controller does not time its ticks)
};

/// The `curvestep sim` option that replays `holds` ("--hold-at 1.234:0 --hold-at ..."), "" for none.
/// Holds never resumed (the job was aborted there) and holds before the start are left out.
[[nodiscard]] std::string hold_at_option(const std::vector<StreamHold>& holds, double rate_hz);

/// The `curvestep sim` option that replays `overrides` ("--override-at 0:150:100,1.234:50:100"), "" for none.
[[nodiscard]] std::string override_at_option(const std::vector<StreamOverride>& overrides, double rate_hz);

/// Runs `job` on the controller behind `transport`. Throws StreamError (controller error, link
/// failure), TransportError (line closed) or std::runtime_error (job cannot be sent or planned,
/// StreamOptions::lookahead outside 1..max_lookahead for a controller without a planner).
[[nodiscard]] StreamResult stream_job(Transport& transport, const Job& job, const MachineLimits& machine,
                                      const StreamOptions& options = {});
/// The same for a job read rather than held (readable_job.hpp): the segments are read once through
/// before anything moves (the wire's checks; for a controller without a planner, the planning's),
/// then again as they go out. Memory then does not grow with the job.
[[nodiscard]] StreamResult stream_job(Transport& transport, const ReadableJob& job, const MachineLimits& machine,
                                      const StreamOptions& options);

}  // namespace curvestep::host::link
