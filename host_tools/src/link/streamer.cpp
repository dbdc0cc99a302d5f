// SPDX-License-Identifier: MIT
#include <curvestep/host/link/streamer.hpp>

#include <curvestep/host/link/setpoint_capture.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <deque>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <curvestep/host/csv.hpp>
#include <curvestep/host/link/host_link.hpp>
#include <curvestep/host/link/tick_timing_text.hpp>
#include <curvestep/host/link/wire.hpp>
#include <curvestep/host/joint_stops.hpp>
#include <curvestep/host/piece_planner.hpp>
#include <curvestep/host/readable_job.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::host::link {
namespace {

/// Where the operator's feed hold stands (one phase; Abort leaves it as it is, an aborting stream
/// ignores it). Segment mode uses Running and Sent only; piece mode (a controller without a planner)
/// plans the hold here first.
///
/// | phase   | meaning                                        | next phase, on                                              |
/// |---------|------------------------------------------------|-------------------------------------------------------------|
/// | Running | no hold                                        | Sent: Hold key, FeedHold submitted (segment mode)           |
/// |         |                                                | Asked: Hold key (piece mode)                                |
/// | Asked   | the hold waits until the planner can brake     | Braking: planner_->hold() once started and can_hold()       |
/// |         | (not before the first piece, nor while it      | Running: Resume key (dropped, nothing on the wire), or the  |
/// |         | still brakes from a hold just resumed)         | planner is done (nothing left to brake, warns)              |
/// | Braking | the braking pieces go out, no FeedHold yet     | Sent: planner stands, its pieces all submitted, FeedHold    |
/// |         |                                                | Running: Resume key (planner_->resume(), no Resume sent)    |
/// | Sent    | FeedHold sent, no Resume yet                   | Running: Resume key, Resume submitted                       |
///
/// "Hold" in the progress line: every phase but Running. A hold in force (Resume ends it): Braking, Sent.
enum class HoldPhase : std::uint8_t { Running, Asked, Braking, Sent };

class Upload {
 public:
  Upload(Transport& transport, const ReadableJob& job, const MachineLimits& machine, const StreamOptions& options)
      : transport_(transport), job_(job), outline_(*job.outline), machine_(machine), options_(options), link_(transport, options.link),
        capture_(options.setpoint_sink) {}

  StreamResult run() {
    const auto handler = [this](const protocol::Message& m) { on_message(m); };
    try {
      link_.connect(handler);
      const std::size_t axes = link_.capabilities().axis_count;
      WireMachine wire_machine = to_wire(machine_, axes);
      for (std::size_t a = 0; a < axes && a < motion_axes; ++a) {
        if (!options_.travel[a]) continue;
        auto& axis = wire_machine.configuration.axes[a];
        axis.min_position_mm = Q16_16::from_double(options_.travel[a]->low_mm).value().raw();
        axis.max_position_mm = Q16_16::from_double(options_.travel[a]->high_mm).value().raw();
      }
      for (const auto& note : wire_machine.notes) warn("machine: " + note);
      rate_hz_ = wire_machine.configuration.control_rate_hz;
      capture_.set_rate_hz(rate_hz_);
      axes_ = axes;
      if (job_.segments == 0) throw StreamError(Error::NothingQueued, outline_.name + ": the job has no moves: nothing to stream");
      if (link_.capabilities().lookahead == 0) {
        plan_here();
        events_ = to_wire_events(outline_, machine_.rate_hz, job_.event_labels);  // pieces carry file labels
      } else {
        check_segments();
        const std::size_t total = job_.segments;  // the device numbers the segments as they arrive
        events_ = to_wire_events(outline_, machine_.rate_hz, [total](std::size_t k) { return std::min(k, total); });
      }
      count_pause_events();
      check_event_room(link_.capabilities().queue_capacity);
      link_.submit(protocol::Message(wire_machine.configuration));
      submitted_.push_back(configuration_marker);
      if (options_.seek_switch) submit_marked(protocol::Message(protocol::SeekSwitch{*options_.seek_switch}));
      if (!piece_mode_ && requested_override_ != FeedOverride{}) submit_override(requested_override_);
      while (!(aborting_ ? abort_settled() : finished())) {
        settle_acknowledged();
        take_operator_command();
        if (!aborting_) {
          submit_units();
          submit_host_hold();
          submit_start();
          serve_pause();
        }
        link_.pump(5, handler);
        watch_setpoint_stream();
        request_status();
        report_progress(false);
      }
    } catch (const LinkError& e) {
      throw StreamError(e.code(), std::string(e.what()) + progress_text() + last_state_text());
    }
    report_progress(true);
    if (pause_pending_) tell_end_pause();  // reported as the job ended
    return collect();
  }

 private:
  // --- the operator: hold, resume, abort (docs/host_board.md, "Operating a running job") -------

  /// Acts on the operator's request, or keeps it until the link can take it.
  void take_operator_command() {
    if (pending_command_ == OperatorCommand::None && options_.operator_command) pending_command_ = options_.operator_command();
    switch (pending_command_) {
      case OperatorCommand::Hold: return hold();
      case OperatorCommand::Resume: return resume();
      case OperatorCommand::Abort: return abort();
      default:
        if (changes_override(pending_command_)) return change_override();
        pending_command_ = OperatorCommand::None;
        return;
    }
  }

  /// FeedHold and, right behind it, a StatusRequest. The first Holding report after it names the last
  /// setpoint before the hold: the controller reports at once when a hold stops a moving machine
  /// (docs/protocol.md), and the StatusRequest's answer covers a hold before the job moved.
  void hold() {
    if (piece_mode_) return hold_here();
    if (aborting_ || holding()) {
      pending_command_ = OperatorCommand::None;
      return;
    }
    if (!started_ || link_.in_flight() + 2 > HostLink::window) return;  // later
    submit_operator_message(protocol::Message(protocol::FeedHold{}));
    submit_status_request();
    hold_phase_ = HoldPhase::Sent;
    hold_index_pending_ = true;
    holds_.push_back(StreamHold{});
    resumed_.push_back(false);
    pending_command_ = OperatorCommand::None;
  }

  /// A hold the planner or the controller has taken: Resume ends it (HoldPhase Braking or Sent).
  [[nodiscard]] bool holding() const { return hold_phase_ == HoldPhase::Braking || hold_phase_ == HoldPhase::Sent; }

  void resume() {
    if (pause_pending_ && !holding() && !aborting_) {  // the operator's answer to a program pause
      pause_resume_asked_ = true;
      pending_command_ = OperatorCommand::None;
      return;
    }
    if (hold_phase_ == HoldPhase::Asked) hold_phase_ = HoldPhase::Running;  // a hold not yet applied is simply dropped
    if (!holding() || aborting_) {
      pending_command_ = OperatorCommand::None;
      return;
    }
    const bool tell_controller = hold_phase_ == HoldPhase::Sent;  // a hold planned here waits there only after FeedHold
    if (tell_controller && !link_.can_submit(protocol::MessageType::Resume)) return;  // later
    if (tell_controller) submit_operator_message(protocol::Message(protocol::Resume{}));
    if (piece_mode_) planner_->resume();  // the pieces after the hold follow the Resume
    hold_phase_ = HoldPhase::Running;
    resumed_.back() = true;
    pending_command_ = OperatorCommand::None;
  }

  /// The operator's override key: FeedOverride with the new values (no credit), once the link has room.
  void change_override() {
    const OperatorCommand command = pending_command_;
    if (aborting_) {
      pending_command_ = OperatorCommand::None;
      return;
    }
    const FeedOverride next = adjusted_override(requested_override_, command);
    if (next == requested_override_) {
      pending_command_ = OperatorCommand::None;
      return;
    }
    if (piece_mode_) return override_here(next);
    if (!link_.can_submit(protocol::MessageType::FeedOverride)) return;  // later
    submit_override(next);
    pending_command_ = OperatorCommand::None;
  }

  void submit_override(FeedOverride value) {
    submit_operator_message(protocol::Message(protocol::FeedOverride{value.feed_percent, value.rapid_percent}));
    requested_override_ = value;
  }

  /// A StatusReport's override fields: a new value or index is an override the controller took.
  void note_override(const protocol::StatusReport& status) {
    const StreamOverride seen{status.override_index, FeedOverride{status.feed_override_percent, status.rapid_override_percent}};
    if (seen.tick == last_override_.tick && seen.value == last_override_.value) return;
    record_override(seen);
    last_override_ = seen;
  }

  void record_override(const StreamOverride& taken) {
    if (!overrides_.empty() && overrides_.back().tick == taken.tick) {
      overrides_.back() = taken;  // set again before the same setpoint: the last one counts
    } else {
      overrides_.push_back(taken);
    }
  }

  // --- the operator on a controller without a planner: the host's plan holds and overrides --------

  /// A feed hold planned here: the planner brakes before the setpoint it has planned up to (what
  /// was sent runs as planned); its braking pieces go out as credit allows, then FeedHold
  /// (submit_host_hold) so the controller waits at their end. Before the plan has begun it waits;
  /// once the job's last piece is sent nothing can brake any more (warn).
  void hold_here() {
    pending_command_ = OperatorCommand::None;
    if (!aborting_ && hold_phase_ == HoldPhase::Running) hold_phase_ = HoldPhase::Asked;  // the other keys stay free meanwhile (Abort)
    apply_asked_hold();
  }

  /// The operator's hold, as soon as the planner can brake: not before the first piece, nor while
  /// it still brakes from a hold just resumed.
  void apply_asked_hold() {
    if (hold_phase_ != HoldPhase::Asked || aborting_) return;
    if (planner_->done()) {
      warn("the whole rest of the job is already sent to this controller (it has no planner): it cannot be held now; abort with Ctrl-X or Esc");
      hold_phase_ = HoldPhase::Running;
      return;
    }
    if (!started_ || !planner_->can_hold()) return;  // later
    holds_.push_back(StreamHold{planner_->hold(), std::nullopt});
    plan_changed_ = true;
    resumed_.push_back(false);
    hold_phase_ = HoldPhase::Braking;
  }

  /// FeedHold once the planner stands and its braking pieces are all submitted: the controller
  /// then stands at their end without faulting until Resume (docs/protocol.md, "FeedHold").
  void submit_host_hold() {
    if (!piece_mode_) return;
    apply_asked_hold();
    if (hold_phase_ != HoldPhase::Braking || next_piece_ || !planner_->held()) return;
    if (!link_.can_submit(protocol::MessageType::FeedHold)) return;
    submit_operator_message(protocol::Message(protocol::FeedHold{}));
    hold_phase_ = HoldPhase::Sent;
  }

  /// An override planned here, before the setpoint the planner has planned up to.
  void override_here(FeedOverride next) {
    pending_command_ = OperatorCommand::None;
    if (planner_->done()) {
      warn("the whole rest of the job is already sent to this controller (it has no planner): the override cannot change it now");
      return;
    }
    record_override(StreamOverride{planner_->set_override(next), next});
    plan_changed_ = true;
    requested_override_ = next;
  }

  /// Abort, then a StatusRequest for where the machine stopped; nothing more is queued.
  void abort() {
    if (aborting_) {
      pending_command_ = OperatorCommand::None;
      return;
    }
    if (link_.in_flight() + 2 > HostLink::window) return;  // later
    submit_operator_message(protocol::Message(protocol::Abort{}));
    submit_status_request();
    aborting_ = true;
    abort_reported_ = false;
    pending_command_ = OperatorCommand::None;
  }

  /// The aborted job is over once Abort and the StatusRequest behind it were acknowledged and a
  /// report says the controller stands (every earlier report came before the Abort).
  [[nodiscard]] bool abort_settled() const { return link_.idle() && abort_reported_; }

  /// FeedHold, Resume or Abort (no credit; errors about it name no segment).
  void submit_operator_message(const protocol::Message& message) {
    link_.submit(message);
    submitted_.push_back(operator_marker);
    sequence_to_unit_[sequence_++] = operator_marker;
  }

  void submit_status_request() {
    link_.submit(protocol::Message(protocol::StatusRequest{}));
    submitted_.push_back(status_marker);
    sequence_to_unit_.erase(sequence_);
    ++sequence_;
    last_status_ms_ = link_.now_ms();
  }

  void warn(const std::string& text) const {
    if (options_.warn) options_.warn(text);
  }

  /// During the host's long passes between the handshake and the job (the check-through read or
  /// planning of a job read from its file can take seconds): a StatusRequest every
  /// keep_alive_ms and its answer taken in, so that neither side's link timeout ends the session.
  void keep_link_alive() {
    const std::uint32_t now = link_.now_ms();
    const std::uint32_t timeout = options_.link.link_timeout_ms;
    if (now - last_keep_alive_ms_ < (timeout == 0 ? keep_alive_ms : std::min(keep_alive_ms, timeout / 4))) return;
    last_keep_alive_ms_ = now;
    settle_acknowledged();
    if (link_.can_submit(protocol::MessageType::StatusRequest)) submit_status_request();
    link_.pump(0, [this](const protocol::Message& m) { on_message(m); });
  }

  /// A controller without a planner: the job is planned here (PiecePlanner, the simulator's Q16.16
  /// controller with options_.lookahead), piece by piece as they are sent. It is first planned
  /// through once, keeping nothing but the count: what the planner refuses or the wire cannot
  /// carry is refused before the machine moves (the executor cannot brake on a broken stream).
  void plan_here() {
    SimulationOptions planning;
    planning.lookahead = options_.lookahead;
    planning.lookahead_distance_mm = options_.lookahead_distance_mm;
    if (requested_override_ != FeedOverride{}) {
      planning.overrides.push_back({0, requested_override_});
      overrides_.push_back({0, requested_override_});
    }
    PiecePlanner check(job_, machine_, planning);
    while (const std::optional<PlannedPiece> piece = check.next_piece()) {
      (void)wire_piece(*piece, planned_total_++);
      keep_link_alive();
    }
    planner_ = std::make_unique<PiecePlanner>(job_, machine_, planning);
    piece_mode_ = true;
  }

  /// Segment mode: reads the job once through, converting each segment for the wire and keeping
  /// none: what the wire cannot carry is refused, and what it rounds is told, before the machine
  /// moves. Then opens the read the upload takes its segments from.
  void check_segments() {
    entries_ = joint_stops(outline_.events, job_.segments, outline_.name, machine_.rate_hz);
    std::vector<std::string> notes;
    std::unique_ptr<SegmentSource> all = job_.read();
    std::size_t source = 0;
    for (std::size_t k = 0; const PathSegment* segment = all->next(source); ++k) {
      (void)to_wire(*segment, entries_[k], axes_, wire_segment_where(outline_.name, source), notes);
      keep_link_alive();
    }
    for (const auto& note : notes) warn(note);
    segments_ = job_.read();
  }

  /// Segment mode: converts the next segment into next_segment_ unless one waits there; false once
  /// all went out.
  bool prepare_segment() {
    if (next_segment_) return true;
    if (next_ == job_.segments) return false;
    std::size_t source = 0;
    const PathSegment* segment = segments_->next(source);
    if (segment == nullptr) {
      throw std::runtime_error(outline_.name + ": the job ended after " + std::to_string(next_) + " of its " +
                               std::to_string(job_.segments) + " segments");
    }
    std::vector<std::string> notes;  // told by check_segments
    next_segment_ = to_wire(*segment, entries_[next_], axes_, wire_segment_where(outline_.name, source), notes);
    next_segment_label_ = static_cast<std::uint32_t>(source);
    if (next_ + 1 == job_.segments) {
      next_segment_->end_of_job = true;
      next_segment_->end_rest_ticks = entries_.at_end().rest_ticks;  // the dwells after the last move
    }
    return true;
  }

  /// Piece mode: plans the next piece into next_piece_ unless one waits there, the planner has none
  /// now (held, done) or the pieces sent reach options_.piece_lead_s ahead of the controller.
  /// Segment mode: true while segments are left. True if a unit is ready to go.
  bool prepare_unit() {
    if (!piece_mode_) return prepare_segment();
    if (next_piece_) return true;
    if (planner_->done() || !within_piece_lead()) return false;
    const std::optional<PlannedPiece> planned = planner_->next_piece();
    if (!planned) return false;
    next_piece_ = wire_piece(*planned, next_);
    return true;
  }

  /// Piece `k` (0-based) for the wire; std::runtime_error naming the job and the piece if it cannot go.
  [[nodiscard]] protocol::QueuePiece wire_piece(const PlannedPiece& piece, std::size_t k) const {
    try {
      return to_wire(piece, axes_);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(outline_.name + ": piece " + std::to_string(k + 1) + ", " + e.what());
    }
  }

  /// True while the pieces sent cover less than options_.piece_lead_s of motion past the
  /// controller's last known setpoint. Before it moves the credit alone decides: it starts with a
  /// full queue (firmware/app.hpp, the start rule).
  [[nodiscard]] bool within_piece_lead() const {
    if (!seen_running_ && capture_.empty()) return true;  // not moving yet
    const std::uint64_t known = std::max<std::uint64_t>(have_status_ ? last_status_.setpoint_index : 0, capture_.last_index());
    const auto lead = static_cast<std::uint64_t>(std::ceil(options_.piece_lead_s * rate_hz_));
    return planned_ticks_ <= known + lead;
  }

  /// The machine events at one joint that this controller cannot take before the segment after
  /// it (its event ring holds `capacity`, docs/protocol.md "Credit"): a controller with a planner
  /// waits at the joint and takes any number of them, except before the first move (nothing moves
  /// yet), after a dwell there (the rest comes with the segment) and after the last move (they
  /// travel before it); one without a planner takes at
  /// most `capacity` per joint. StreamError (CapacityExceeded) naming the line of the first event
  /// too many, before anything is queued.
  void check_event_room(std::size_t capacity) const {
    std::size_t joint = ~std::size_t{0};
    std::size_t count = 0;
    bool after_dwell = false;
    for (const JobEvent& event : outline_.events) {
      if (event.before_segment != joint) {
        joint = event.before_segment;
        count = 0;
        after_dwell = false;
      }
      if (event.kind == JobEventKind::Dwell) {
        after_dwell = true;
        continue;
      }
      if (event.kind == JobEventKind::Message) continue;
      ++count;
      const bool last = joint >= job_.segments;
      const bool limited = piece_mode_ || joint == 0 || after_dwell || last;
      if (!limited || count <= capacity) continue;
      const char* where = piece_mode_ ? "at one joint (a controller without a planner cannot wait there for more)"
                          : joint == 0 ? "before the first move"
                          : last       ? "after the last move"
                                       : "after a dwell at one joint";
      throw StreamError(Error::CapacityExceeded, outline_.name + (event.line > 0 ? ":" + std::to_string(event.line) : "") + ": " +
                                                     event.text + ": more than " + std::to_string(capacity) +
                                                     " machine events " + where + "; this controller's event ring holds " +
                                                     std::to_string(capacity) + " (docs/gcode.md, \"Machine events\")");
    }
  }

  /// True once every unit of the job was submitted.
  [[nodiscard]] bool all_units_sent() const {
    return piece_mode_ ? planner_->done() && !next_piece_ : next_ == job_.segments;
  }
  /// The job's units (segments, or pieces for a controller without a planner); pieces after a hold
  /// or override changed the plan: 0 until its last one is planned.
  [[nodiscard]] std::size_t known_units() const {
    if (!piece_mode_) return job_.segments;
    if (!plan_changed_) return planned_total_;
    return planner_->done() ? next_ + (next_piece_ ? 1 : 0) : 0;
  }
  /// The job file's segment index of unit k (unacknowledged or among the last 256 acknowledged).
  [[nodiscard]] std::size_t file_segment(std::size_t k) const {
    const bool kept = k >= unit_labels_base_ && k - unit_labels_base_ < unit_labels_.size();
    return kept ? unit_labels_[k - unit_labels_base_] : 0;
  }
  /// The job file's segments (the last one's index + 1).
  [[nodiscard]] std::size_t file_segment_count() const { return job_.file_segments; }
  /// "piece 12" (1-based; "piece 12 of 340" once the last is planned) in piece mode, "" otherwise.
  [[nodiscard]] std::string piece_text(std::size_t k) const {
    if (!piece_mode_) return "";
    const std::size_t total = known_units();
    return "piece " + std::to_string(k + 1) + (total > 0 ? " of " + std::to_string(total) : "");
  }

  /// Where the job stopped: the last segment the controller acknowledged, the last setpoint received.
  std::string progress_text() {
    settle_acknowledged();
    std::string text = "; the job stopped after ";
    if (acknowledged_units_ == 0) {
      text += piece_mode_ ? "no acknowledged piece" : "no acknowledged segment";
    } else {
      const std::size_t last = acknowledged_units_ - 1;
      text += "segment " + std::to_string(file_segment(last)) + " of " + outline_.name + " (" +
              (piece_mode_ ? piece_text(last) : std::to_string(acknowledged_units_) + " of " + std::to_string(known_units())) +
              " acknowledged)";
    }
    if (capture_.empty()) return text + ", no setpoint received";
    return text + ", setpoints received up to index " + std::to_string(capture_.first_run_end());
  }

  /// Drops the oldest submissions the controller has acknowledged (they leave the window in order).
  void settle_acknowledged() {
    while (submitted_.size() > link_.in_flight()) {
      if (submitted_.front() < event_marker) acknowledged_units_ = submitted_.front() + 1;  // a unit, not a marker
      // Keep the pieces a report may still name: up to 256 frames back (the sequence numbers' range).
      while (!unit_labels_.empty() && unit_labels_base_ + 256 < acknowledged_units_) {
        unit_labels_.pop_front();
        ++unit_labels_base_;
      }
      if (submitted_.front() == start_marker) {
        start_acknowledged_ = true;
        mark_stream_progress();
      }
      submitted_.pop_front();
    }
  }

  void mark_stream_progress() {
    stream_progress_ms_ = link_.now_ms();
    rejected_at_progress_ = link_.statistics().frames_rejected;
    delivered_seen_ = link_.statistics().batches_delivered;
  }

  /// The setpoint stream's progress watch (issue 19.4): once Start was acknowledged, damaged frames
  /// arriving for the link timeout with no setpoint batch delivered (and no report of a state that
  /// streams nothing) end the upload: the host's commands may still trickle through, one short
  /// frame now and then, while no batch, a longer frame, ever arrives whole. A quiet controller
  /// (armed, held) is not streaming and is left alone.
  void watch_setpoint_stream() {
    const std::uint32_t limit = options_.link.link_timeout_ms;
    if (!start_acknowledged_ || limit == 0) return;
    const LinkStatistics& statistics = link_.statistics();
    if (statistics.batches_delivered != delivered_seen_) return mark_stream_progress();
    const std::uint32_t waited = link_.now_ms() - stream_progress_ms_;
    if (waited < limit) return;
    const std::size_t damaged = statistics.frames_rejected - rejected_at_progress_;
    if (damaged == 0) return mark_stream_progress();
    throw StreamError(Error::RetransmitLimit,
                      transport_.name() + ": link failed: " + describe_error(Error::RetransmitLimit) +
                          ": no setpoint batch arrived whole for " + std::to_string(waited) + " ms although " +
                          std::to_string(damaged) + " damaged frame(s) did (a line too noisy to carry a whole frame?)" +
                          progress_text() + last_state_text());
  }

  std::string last_state_text() const {
    if (!have_status_) return "";
    return "; last controller state: " + std::string(protocol::machine_state_name(last_status_.state)) + " at setpoint " +
           std::to_string(last_status_.setpoint_index) + tick_overrun_text(last_status_.tick_overruns, last_status_.worst_tick_us);
  }

  std::string segment_text(std::uint8_t sequence) const {
    const auto found = sequence_to_unit_.find(sequence);
    if (found == sequence_to_unit_.end()) return "";
    if (found->second == configuration_marker) return " in the machine configuration";
    if (found->second == start_marker) return " in the Start command";
    if (found->second == operator_marker) return " in the operator's FeedHold, Resume, Abort or FeedOverride";
    const std::size_t k = found->second;
    const std::string text = " in " + outline_.name + " segment " + std::to_string(file_segment(k));
    return piece_mode_ ? text + " (" + piece_text(k) + ")" : text;
  }

  void submit_units() {
    const auto type = piece_mode_ ? protocol::MessageType::QueuePiece : protocol::MessageType::QueueSegment;
    while (prepare_unit() && submit_events_before_next() && link_.can_submit(type)) {
      if (piece_mode_) {
        link_.submit(protocol::Message(*next_piece_));
        planned_ticks_ += next_piece_->ticks;
        unit_labels_.push_back(next_piece_->segment);
        last_piece_segment_ = next_piece_->segment;
        next_piece_.reset();
      } else {
        link_.submit(protocol::Message(*next_segment_));
        unit_labels_.push_back(next_segment_label_);
        next_segment_.reset();
      }
      submitted_.push_back(next_);
      sequence_to_unit_[sequence_] = next_;
      ++sequence_;
      ++next_;
    }
  }

  /// Submits the machine events due before the next unit (those keyed to its segment number or an
  /// earlier one; all that are left before the last unit); false while one waits for credit.
  bool submit_events_before_next() {
    const std::size_t label = piece_mode_ ? next_piece_->segment : next_;
    const bool last = piece_mode_ ? next_piece_->end_of_job : next_ + 1 == job_.segments;
    while (next_event_ < events_.size() && (events_[next_event_].segment <= label || last)) {
      if (!link_.can_submit(protocol::MessageType::QueueEvent)) return false;
      link_.submit(protocol::Message(events_[next_event_]));
      submitted_.push_back(event_marker);
      sequence_to_unit_.erase(sequence_);
      ++sequence_;
      ++next_event_;
    }
    return true;
  }

  /// Submits a command that is no unit of the job (a pause's Resume, SeekSwitch).
  void submit_marked(const protocol::Message& m) {
    link_.submit(m);
    submitted_.push_back(event_marker);
    sequence_to_unit_.erase(sequence_);
    ++sequence_;
  }

  /// The events that pause the controller (M0/M1, M6, a pen change), and whether the last one comes
  /// after the job's last move (its label is the end's: the job's segments, or its file segments
  /// for pieces).
  void count_pause_events() {
    const std::size_t end_label = piece_mode_ ? job_.file_segments : job_.segments;
    for (const protocol::QueueEvent& e : events_) {
      if (e.kind != protocol::MachineEventKind::ProgramPause && e.kind != protocol::MachineEventKind::ToolChange &&
          e.kind != protocol::MachineEventKind::LayerChange) {
        continue;
      }
      ++pause_events_;
      last_pause_ends_job_ = e.segment >= end_label;
    }
  }

  /// A pause after the job's last move: the controller ends the job with it (firmware/app.hpp), so
  /// there is nothing to resume (a Resume would be refused); the operator is told once.
  void tell_end_pause() {
    if (!pause_told_) warn(pause_text_ + ", after the job's last move: the job ended there, nothing is left to resume");
    pause_told_ = true;
    pause_pending_ = false;
  }

  /// A pause the controller reported: tell the operator once, Resume when resume_now() says so.
  void serve_pause() {
    if (!pause_pending_) return;
    if (last_pause_ends_job_ && pauses_reported_ == pause_events_) return tell_end_pause();
    if (!pause_told_) {
      if (options_.paused) options_.paused(pause_text_);
      pause_told_ = true;
    }
    const bool go = !options_.resume_now || pause_resume_asked_ || options_.resume_now();
    if (!go || !link_.can_submit(protocol::MessageType::Resume)) return;
    submit_marked(protocol::Message(protocol::Resume{}));
    pause_pending_ = false;
    pause_resume_asked_ = false;
  }

  /// Start right after the first unit (Start on an empty queue is NothingQueued): the controller
  /// arms the job and begins by itself when its look-ahead window is full or the job's last
  /// segment (flag end_of_job) has arrived.
  void submit_start() {
    if (started_ || next_ == 0 || !link_.can_submit(protocol::MessageType::Start)) return;
    link_.submit(protocol::Message(protocol::Start{}));
    submitted_.push_back(start_marker);
    sequence_to_unit_[sequence_] = start_marker;
    ++sequence_;
    started_ = true;
    start_ms_ = link_.now_ms();
    last_status_ms_ = start_ms_;
  }

  void request_status() {
    if (!started_) return;
    const std::uint32_t now = link_.now_ms();
    const auto interval = static_cast<std::uint32_t>(options_.status_interval_s * 1000);
    if (now - last_status_ms_ < interval || !link_.can_submit(protocol::MessageType::StatusRequest)) return;
    submit_status_request();
  }

  void on_message(const protocol::Message& m) {
    switch (m.type()) {
      case protocol::MessageType::SetpointBatch: {
        const auto& batch = m.get<protocol::SetpointBatch>();
        for (std::uint32_t k = 0; k < batch.count; ++k) capture_.receive(batch.first_index + k, batch.setpoints[k]);
        break;
      }
      case protocol::MessageType::StatusReport: {
        last_status_ = m.get<protocol::StatusReport>();
        have_status_ = true;
        if (!piece_mode_) note_override(last_status_);
        if (hold_index_pending_ && last_status_.state == protocol::MachineState::Holding) {
          hold_index_pending_ = false;  // the answer to the StatusRequest sent with FeedHold
          // Index 0: held before the job began moving (armed), or right after its first setpoint;
          // the two look alike, so such a hold counts as one before the start (tick 0).
          holds_.back().tick = last_status_.setpoint_index == 0 ? 0 : std::uint64_t{last_status_.setpoint_index} + 1;
        }
        if (aborting_ && link_.idle() && last_status_.state != protocol::MachineState::Running &&
            last_status_.state != protocol::MachineState::Holding) {
          abort_reported_ = true;
        }
        if (last_status_.state != protocol::MachineState::Running) mark_stream_progress();  // nothing to stream
        if (last_status_.state == protocol::MachineState::Running || last_status_.setpoint_index > 0) seen_running_ = true;
        if (last_status_.state == protocol::MachineState::Fault && !aborting_) {
          const auto code = static_cast<Error>(last_status_.error);
          if (hard_limit_switch_ && code == Error::HardLimit) {
            throw StreamError(code, transport_.name() + ": hard limit: " + limit_switch_name(*hard_limit_switch_) + " at setpoint " +
                                        std::to_string(last_status_.setpoint_index) + " (the controller stopped at once; Abort or a new session clears it)");
          }
          throw StreamError(code, transport_.name() + ": the controller stopped with a fault: " + describe_error(code) +
                                      " at setpoint " + std::to_string(last_status_.setpoint_index));
        }
        break;
      }
      case protocol::MessageType::PauseReport: {
        const auto& pause = m.get<protocol::PauseReport>();
        pause_text_ = "paused at setpoint " + std::to_string(pause.setpoint_index) + ": " +
                      (pause.kind == protocol::MachineEventKind::ToolChange ? "tool change to tool " + std::to_string(pause.value)
                       : pause.kind == protocol::MachineEventKind::LayerChange ? std::string("pen change (next layer)")
                                                                                : std::string("program pause (M0/M1)"));
        pause_pending_ = true;
        pause_told_ = false;
        ++pauses_reported_;
        break;
      }
      case protocol::MessageType::SwitchReport: switch_closed_ = m.get<protocol::SwitchReport>(); break;
      case protocol::MessageType::ErrorReport: {
        const auto& report = m.get<protocol::ErrorReport>();
        if (report.code == Error::HardLimit) {
          hard_limit_switch_ = report.index;  // told with its setpoint by the StatusReport that follows
          break;
        }
        std::string text = transport_.name() + ": the controller reported " + describe_error(report.code) + segment_text(report.sequence);
        if (report.index != no_index) text += " (index " + std::to_string(report.index) + ")";
        throw StreamError(report.code, text);
      }
      default: break;
    }
  }

  [[nodiscard]] bool finished() {
    if (!started_ || !all_units_sent() || !link_.idle() || !have_status_ || !seen_running_) return false;
    if (last_status_.state != protocol::MachineState::Idle || last_status_.queue_depth != 0) {
      idle_seen_ = false;
      return false;
    }
    if (switch_closed_) return true;  // a seek ends at its switch: the setpoint that closed it is not streamed
    // Idle: done once every setpoint up to the last one arrived (the reliable stream delivers
    // them in order, maybe after the report). Indices may skip: a held or starved controller
    // ticks without reporting (docs/firmware.md). A stream that does not reach the last index
    // within the link timeout means the controller stopped sending: an error, never a silent loss.
    const std::uint32_t now = link_.now_ms();
    if (!idle_seen_) {
      idle_seen_ = true;
      idle_since_ms_ = now;
    }
    if (!capture_.empty() && capture_.last_index() >= last_status_.setpoint_index) {
      return true;
    }
    const std::uint32_t patience = options_.link.link_timeout_ms != 0 ? options_.link.link_timeout_ms : 3000;
    if (now - idle_since_ms_ > patience) {
      throw StreamError(Error::LinkTimeout, transport_.name() + ": the controller finished the job but its setpoint stream stopped" +
                                                progress_text());
    }
    return false;
  }

  void report_progress(bool final_call) {
    if (!options_.progress) return;
    const std::uint32_t now = link_.now_ms();
    if (!final_call && now - last_progress_ms_ < 100) return;
    last_progress_ms_ = now;
    StreamProgress p;
    p.sent = next_;
    p.total = known_units();
    p.unit = piece_mode_ ? "pieces" : "segments";
    p.setpoints_received = capture_.received();
    p.elapsed_s = now / 1000.0;
    if (started_ && next_ > 0 && have_status_) {
      const double running_s = (now - start_ms_) / 1000.0;
      if (p.total > 0) {
        // Units done = sent - still queued; the rest take as long, per unit, as those did.
        const double done = static_cast<double>(next_) - last_status_.queue_depth;
        if (done > 0) p.eta_s = running_s / done * (static_cast<double>(p.total) - done);
      } else {
        // Pieces still being planned: by the job segments planned so far (at most the piece lead ahead).
        const double done = static_cast<double>(last_piece_segment_ + 1) / static_cast<double>(file_segment_count());
        if (done > 0 && done < 1) p.eta_s = running_s / done * (1 - done);
      }
    }
    if (final_call) p.eta_s = 0;
    p.state = aborting_ ? "Aborting" : hold_phase_ != HoldPhase::Running ? "Hold" : "Running";
    p.have_status = have_status_;
    if (have_status_) {
      p.setpoint_index = last_status_.setpoint_index;
      p.machine_state = protocol::machine_state_name(last_status_.state);
      p.tick_overruns = last_status_.tick_overruns;
      for (std::size_t a = 0; a < 3; ++a) p.position_mm[a] = static_cast<double>(last_status_.position[a]) / 65536.0;
    }
    p.override_percent = piece_mode_ || !have_status_ ? requested_override_ : last_override_.value;
    options_.progress(p);
  }

  StreamResult collect() {
    StreamResult result;
    result.setpoints = std::move(capture_.records());
    result.setpoints_received = capture_.received();
    result.standing_ticks = capture_.standing_ticks(last_status_.setpoint_index);
    result.duplicate_setpoints = capture_.duplicates();
    result.max_queue_depth = last_status_.max_queue_depth;
    result.queue_capacity = link_.capabilities().queue_capacity;
    result.lookahead = link_.capabilities().lookahead;
    if (piece_mode_) {
      result.pieces_sent = next_;
      result.planned_lookahead = options_.lookahead;
    }
    result.batches_repeated = link_.statistics().batches_repeated;
    result.frames_rejected = link_.statistics().frames_rejected;
    result.bytes_sent = link_.statistics().bytes_sent;
    result.holds = holds_;
    result.overrides = overrides_;
    for (std::size_t k = 0; k < result.holds.size(); ++k) {
      const std::uint64_t until = k + 1 < holds_.size() ? holds_[k + 1].tick : std::uint64_t{0xffffffff};
      // A hold planned here stands between its pieces: the executor does not tick while it waits.
      if (resumed_[k]) result.holds[k].standing_ticks = piece_mode_ ? 0 : standing_between(holds_[k].tick, until);
    }
    result.aborted = aborting_;
    result.switch_closed = switch_closed_;
    result.final_setpoint_index = last_status_.setpoint_index;
    for (std::size_t a = 0; a < 3; ++a) result.final_position_q16[a] = last_status_.position[a];
    result.tick_overruns = last_status_.tick_overruns;
    result.worst_tick_us = last_status_.worst_tick_us;
    return result;
  }

  /// The ticks the controller stood in a resumed hold at `tick`: the first gap in the setpoint
  /// indices from there to `until` (a held controller ticks in real time without streaming; a fast
  /// one does not tick while held, so there is no gap: 0).
  [[nodiscard]] std::uint64_t standing_between(std::uint64_t tick, std::uint64_t until) const {
    return capture_.first_gap_between(tick > 0 ? tick - 1 : 0, until);
  }

  static constexpr std::size_t configuration_marker = static_cast<std::size_t>(-1);
  static constexpr std::size_t start_marker = static_cast<std::size_t>(-2);
  static constexpr std::size_t status_marker = static_cast<std::size_t>(-3);
  static constexpr std::size_t operator_marker = static_cast<std::size_t>(-4);  // FeedHold, Resume, Abort
  static constexpr std::size_t event_marker = static_cast<std::size_t>(-5);     // QueueEvent, a pause's Resume; the smallest marker

  Transport& transport_;
  const ReadableJob& job_;
  const Job& outline_;  // the job's name and events
  const MachineLimits& machine_;
  const StreamOptions& options_;
  HostLink link_;
  std::unique_ptr<SegmentSource> segments_;         // segment mode: the job's segments, read as they go out
  JointStops entries_;                              // segment mode: the joint stops its events ask for
  std::optional<protocol::QueueSegment> next_segment_;  // segment mode: converted, waiting for credit
  std::uint32_t next_segment_label_ = 0;            // its job file segment
  std::vector<protocol::QueueEvent> events_;  // machine events, sent before the unit they precede
  std::size_t next_event_ = 0;
  bool pause_pending_ = false;  // the controller paused and waits for Resume
  bool pause_told_ = false;     // options_.paused was called for it
  bool pause_resume_asked_ = false;  // the operator's Resume came for it
  std::string pause_text_;
  std::size_t pause_events_ = 0;      // the job's events that pause the controller
  std::size_t pauses_reported_ = 0;   // PauseReports received
  bool last_pause_ends_job_ = false;  // the last of them comes after the job's last move
  bool piece_mode_ = false;                        // the controller has no planner (Capabilities::lookahead 0)
  std::unique_ptr<PiecePlanner> planner_;          // piece mode: plans the job as its pieces go out
  std::size_t axes_ = 3;                           // the controller's axes (QueuePiece and QueueSegment axis_count)
  std::optional<protocol::QueuePiece> next_piece_;  // piece mode: planned, waiting for credit
  std::deque<std::uint32_t> unit_labels_;          // job file segment of the last 256 acknowledged units and those after
  std::size_t unit_labels_base_ = 0;               // the unit index of unit_labels_.front()
  std::uint64_t planned_ticks_ = 0;                // piece mode: setpoints the pieces sent cover
  std::uint32_t last_piece_segment_ = 0;           // piece mode: the job segment of the last piece sent
  std::size_t planned_total_ = 0;                  // piece mode: the job's pieces as planned before it started
  bool plan_changed_ = false;                      // piece mode: a hold or override changed that plan
  SetpointCapture capture_;  // the setpoint stream, to options_.setpoint_sink or kept
  std::map<std::uint8_t, std::size_t> sequence_to_unit_{{0, configuration_marker}};
  protocol::StatusReport last_status_{};
  double rate_hz_ = 1000;
  std::size_t next_ = 0;
  std::deque<std::size_t> submitted_;  // what each unacknowledged frame carries, oldest first
  std::size_t acknowledged_units_ = 0;
  std::uint8_t sequence_ = 1;  // the configuration is sequence 0
  std::uint32_t idle_since_ms_ = 0;
  bool idle_seen_ = false;
  std::uint32_t last_status_ms_ = 0;
  static constexpr std::uint32_t keep_alive_ms = 200;  // a fifth of the default link timeout, at most a quarter of the one set
  std::uint32_t last_keep_alive_ms_ = 0;
  std::uint32_t last_progress_ms_ = 0;
  std::uint32_t start_ms_ = 0;
  std::uint32_t stream_progress_ms_ = 0;  // the last setpoint batch delivered (or Start acknowledged, or a non-running report)
  std::size_t rejected_at_progress_ = 0;  // damaged frames counted then
  std::size_t delivered_seen_ = 0;        // batches delivered then
  bool start_acknowledged_ = false;
  bool started_ = false;
  bool have_status_ = false;
  bool seen_running_ = false;
  OperatorCommand pending_command_ = OperatorCommand::None;  // waiting for room in the window
  HoldPhase hold_phase_ = HoldPhase::Running;  // the operator's hold, see HoldPhase
  bool hold_index_pending_ = false;  // waiting for the StatusReport that names the hold's setpoint
  bool aborting_ = false;            // Abort sent
  std::optional<std::uint16_t> hard_limit_switch_;  // the switch of a HardLimit fault, until its StatusReport
  std::optional<protocol::SwitchReport> switch_closed_;  // where a seek job met its switch
  bool abort_reported_ = false;      // a report after the Abort says the controller stands
  std::vector<StreamHold> holds_;
  std::vector<bool> resumed_;  // per hold: Resume sent
  FeedOverride requested_override_ = options_.feed_override;  // the override last sent (or planned with)
  StreamOverride last_override_{};         // the override fields of the last StatusReport
  std::vector<StreamOverride> overrides_;  // the overrides the controller took, in order
};

}  // namespace

std::string hold_at_option(const std::vector<StreamHold>& holds, double rate_hz) {
  std::string text;
  for (const StreamHold& hold : holds) {
    if (!hold.standing_ticks || hold.tick == 0) continue;
    if (!text.empty()) text += " ";
    text += "--hold-at " + format_number(static_cast<double>(hold.tick) / rate_hz) + ":" +
            format_number(static_cast<double>(*hold.standing_ticks) / rate_hz);
  }
  return text;
}

std::string override_at_option(const std::vector<StreamOverride>& overrides, double rate_hz) {
  std::string text;
  for (const StreamOverride& o : overrides) {
    text += (text.empty() ? "--override-at " : ",") + format_number(static_cast<double>(o.tick) / rate_hz) + ":" +
            std::to_string(o.value.feed_percent) + ":" + std::to_string(o.value.rapid_percent);
  }
  return text;
}

StreamResult stream_job(Transport& transport, const ReadableJob& job, const MachineLimits& machine, const StreamOptions& options) {
  Upload upload(transport, job, machine, options);
  return upload.run();
}

StreamResult stream_job(Transport& transport, const Job& job, const MachineLimits& machine, const StreamOptions& options) {
  return stream_job(transport, readable(job), machine, options);
}

}  // namespace curvestep::host::link
