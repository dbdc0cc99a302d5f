// SPDX-License-Identifier: MIT
// App<Board>: the board-independent controller (link, queue, planner, interpolator, steps, safety).
//
// Public API (stable; boards and the host board build on it):
//
//   template <Board B, Scalar S = Q16_16, std::size_t Queue = 32, std::size_t Lookahead = 16>
//   class App {
//     explicit App(B& board, AppSettings settings = {});
//     void poll();        // main loop: serial in -> frames -> link -> commands; reports; serial out
//     void on_tick();     // once per control period (control_rate_hz()): one setpoint, its steps
//     protocol::MachineState state();      // Idle, Running, Holding, Fault (as in StatusReport)
//     bool configured();  std::uint32_t control_rate_hz();   // 0 until a MachineConfiguration
//     bool moving();      // on_tick() produces setpoints
//     const Controller& controller();   // the MotionController, for reports and tests
//     const AppStatistics& statistics(); // dropped frames, stalled ticks, setpoint retransmissions
//     const TickWatch& tick_watch();     // tick overruns and the worst tick (boards with a cycle clock)
//     bool ready_to_tick();  // on_tick() would advance (false: the setpoint stream is backed up)
//     bool job_end_known();  // the job's last segment (flag end of job) has arrived
//     std::uint8_t last_error();  const protocol::WirePoint& position();  // as in StatusReport
//     std::uint16_t free_segments();     // the credit offered to the host, in whole segments
//   };
//
// poll() and on_tick() must not run concurrently: call both from one context (the main loop,
// with on_tick() paced by a timer flag, as the host board does), or mask the tick interrupt
// while poll() runs. The edge interrupt that replays the board's step edges may run at any time.
//
// What happens, in the order of a job:
//   Hello                -> LinkReceiver answers Capabilities (protocol version, queue slots, the
//                           wire's Q16.16 format, axis count, highest degree, step-timer rate);
//                           a new session stops and clears any job.
//   MachineConfiguration -> to_machine_limits, MotionController::configure, StepConfig from the
//                           board's StepTiming (InvalidRate if the timer is no multiple of the rate).
//   QueueSegment         -> continuity with the previous segment (SegmentsNotConnected),
//                           to_path_segment, travel range (OutsideTravel, index = axis), try_push.
//                           The credit granted to the host counts whole wire segments of the worst
//                           case: a Bézier may be split at up to 6 cusps into 7 queue slots, so the
//                           credit is free slots / 7 and an accepted segment always fits.
//                           Flag "end of job" marks the last one. Flags "stop before" / "rest"
//                           pass on as the segment's JointStop (an exact stop, a dwell).
//   QueueEvent           -> EventTimeline (a ring of Queue events, each credit a segment or an
//                           event): when the setpoints reach the event's segment (and ticks into
//                           its rest), the board's optional hooks (board_hooks.hpp) are called
//                           with the setpoint index; the job's end calls the rest.
//   Start                -> arms the job; motion begins when the queue holds Lookahead + 1
//                           segments or the job's last segment (the start rule, below).
//                           ConfigurationMissing / NothingQueued before a configuration / segment.
// Which command is taken in which phase (Phase, phase.hpp) is the state table of docs/protocol.md;
// a new session drops the configuration; a failed setpoint stream (Phase::StreamFailed) refuses
// new jobs until the next Hello.
//   FeedHold / Resume    -> MotionController::hold / resume (braking along the path); a StatusReport
//                           at once (Holding, the setpoint index the hold acted after) and another
//                           once the machine stands; Resume while still braking continues
//                           from the stop. Without a planner the host brakes in the pieces it
//                           sends before FeedHold: the App holds, runs them, and stands where the
//                           queue runs dry (no stall, no underrun) until Resume (host_hold).
//   Abort                -> stop at once: controller aborted and flushed, board.fault_stop(); the
//                           next job must start where the machine stopped (StatusReport position).
//   FeedOverride         -> MotionController::set_override (feed_override_command.hpp); a StatusReport
//                           at once naming the setpoint it was set before. NotSupported without a planner.
//   StatusRequest        -> StatusReport (state, last error, queue depth, setpoint index, limit switches,
//                           tick timing, overrides, position).
//   SeekSwitch           -> homing: the next job ends at once where that limit switch closes
//                           (SwitchReport; limit_switches.hpp); SetPosition -> new coordinates at rest.
// Every failed command is answered with ErrorReport(code, index, the frame's sequence number); a
// fault met while running carries the sequence number of the last frame received. The segments of
// the next job are accepted once the previous job has finished (state Idle again).
//
// The start rule (bit-identical streams). The planner's exit speed for a segment comes from a
// window of the next Lookahead segments that always ends at rest, so a segment's plan equals the
// simulator's exactly when at least Lookahead segments follow it in the queue, or the job ends
// inside the window. The firmware therefore does not begin until the queue holds Lookahead + 1
// segments or the job's end is known; a host that keeps the queue topped up then gets
// `curvestep sim`'s setpoints bit for bit.
//
// Safety:
//   * queue underrun: the window ends at rest, so an empty queue is a controlled stop on the path
//     (the controller's Starved state); the App reports QueueUnderrun in a StatusReport and goes on
//     by itself once the start rule holds again;
//   * loss of the link: no valid frame for settings.link_timeout_ms -> feed hold (plus an
//     ErrorReport(LinkTimeout) in case the host still listens); Resume continues;
//   * abort: immediate stop and flush, no braking, board.fault_stop();
//   * hard limits: after each tick's edges, a closed limit switch whose axis moved toward it is a
//     fault (HardLimit, index = the switch; limit_switches.hpp);
//   * a fault (a setpoint outside Q16.16, a step rate the drivers cannot follow, ...): the
//     controller stops, board.fault_stop(), state Fault, ErrorReport(code, index); only Abort or
//     a new session leaves Fault.
//
// Setpoints are also streamed to the host (settings.stream_setpoints) in the controller's own
// reliable stream (setpoint_stream.hpp). Nothing is ever dropped: when the stream's buffer is
// full, on_tick() does not advance the controller at all; it counts a stalled tick and returns.
// The host board's fast mode simply waits (ready_to_tick()); in real time a stall longer than
// settings.stall_timeout_ms is a Fault, because a machine cannot keep a paused interpolator
// waiting for ever. Setpoints while held or starved are not sent; a stalled App sends what it
// has (a short batch).
//
// Tick timing: on a board with a cycle clock (cycle_count(), cycles_per_second()) every tick is
// timed (TickWatch, tick_watch.hpp): overruns are counted, and a tick that starts more than
// settings.tick_deadline_periods periods late is a Fault (TickDeadlineMissed, index = periods late).
// Time budget of on_tick(): one MotionController::next_setpoint (a profile evaluation, a table
// search, one de Casteljau evaluation in double) plus StepGenerator::advance (see its header:
// ~800 to ~3500 Cortex-M3 instructions) plus one copy into the setpoint ring; it never waits.
// The tick that crosses into a new segment also plans it (arc-length table and speed profile,
// MotionController::begin_segment): that is the worst-case tick. Segment analysis (try_push:
// cusps, caps, junction speed) runs in poll().
// Code size: the App links only the codecs of what a controller receives and sends
// (protocol::HostToController, protocol::ControllerToHost): dispatch() decodes each command with
// its own decode<T>, the host's Ack / Nak of the setpoint stream go through
// decode_message<MessageSet<Ack, Nak>>, and the setpoint stream encodes SetpointBatch only. A
// command type it does not take (a report, or one a newer host defines) is answered, as ever,
// with ErrorReport(UnknownMessage, index = type).
// Nothing allocates; all buffers are members sized at compile time (see docs/firmware.md).
//
// The App composes parts that own their state (docs/firmware.md): Outbox (outbox.hpp, outgoing
// frames), SetpointStream, LinkWatch (link_watch.hpp, link loss and stalls), MachineEvents
// (machine_events.hpp), SwitchSeek (switch_seek.hpp, homing), NextStart (next_start.hpp,
// continuity), TickWatch; board_facts.hpp holds what it derives from the board type. It keeps
// the phase, the commands and the tick.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>

#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/core/motion/motion_controller.hpp>
#include <curvestep/core/motion/piece_executor.hpp>
#include <curvestep/core/motion/step_generator.hpp>
#include <curvestep/core/motion/step_output.hpp>
#include <curvestep/core/scalar.hpp>
#include <curvestep/firmware/app_settings.hpp>
#include <curvestep/firmware/board.hpp>
#include <curvestep/firmware/board_facts.hpp>
#include <curvestep/firmware/conversions.hpp>
#include <curvestep/firmware/limit_switches.hpp>
#include <curvestep/firmware/link_watch.hpp>
#include <curvestep/firmware/machine_events.hpp>
#include <curvestep/firmware/next_start.hpp>
#include <curvestep/firmware/outbox.hpp>
#include <curvestep/firmware/feed_override_command.hpp>
#include <curvestep/firmware/phase.hpp>
#include <curvestep/firmware/setpoint_stream.hpp>
#include <curvestep/firmware/switch_seek.hpp>
#include <curvestep/firmware/tick_watch.hpp>
#include <curvestep/protocol/frame.hpp>
#include <curvestep/protocol/frame_decoder.hpp>
#include <curvestep/protocol/link_receiver.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::firmware {

/// The controller application for board B; S is the setpoint scalar (Q16.16 for bit-identity).
/// Lookahead == 0: no planner on board; the App replays pieces the host planned (PieceExecutor).
/// Events: machine events (QueueEvent) it can hold, 0 for none (QueueEvent is then NotSupported).
template <Board B, Scalar S = Q16_16, std::size_t Queue = 32, std::size_t Lookahead = 16, std::size_t Events = Queue>
class App {
  /// True if the board plans (QueueSegment); false: it replays host-planned pieces (QueuePiece).
  static constexpr bool plans_on_board = Lookahead > 0;
  /// Queue slots one command may need: a segment split at every cusp, or one piece.
  static constexpr std::size_t slots_per_command = plans_on_board ? slots_per_segment : 1;
  // Credit is granted in whole worst-case segments (slots_per_segment slots each), so at most
  // Queue - slots_per_segment + 1 segments are queued, and a segment is planned just after its
  // predecessor left the queue. The full window of Lookahead segments behind it (what the
  // simulator's --lookahead assumes) is therefore there only if Queue >= Lookahead + slots + 1.
  static_assert(!plans_on_board || Queue >= Lookahead + slots_per_segment + 1,
                "the queue must keep Lookahead segments behind the one being planned (bit-identity with the simulator)");
  static_assert(Lookahead <= 0xFFFF, "Capabilities carries the look-ahead as a u16");

 public:
  /// The motion controller type: the planner, or the replay of host-planned pieces.
  using Controller = std::conditional_t<plans_on_board, MotionController<S, Queue, plans_on_board ? Lookahead : 1>, PieceExecutor<S, Queue>>;

  /// Frames of setpoint batches that may be unacknowledged at once.
  static constexpr std::size_t setpoint_window = SetpointStream<B>::window;
  /// The sender of the setpoint stream (SetpointBatch only, no handshake of its own).
  using SetpointSender = typename SetpointStream<B>::Sender;

  /// An App driving `board` (which must outlive it), not connected and unconfigured.
  explicit App(B& board, AppSettings settings = {}) noexcept
      : board_(board),
        settings_(settings),
        receiver_(board_capabilities<B>(Queue, Lookahead), make_receiver_settings(settings)),
        stream_(settings.retransmit_timeout_ms) {
    edges_dropped_seen_ = edges_dropped_by(board);  // edges lost before this App existed are not its to report
  }

  /// Main-loop work: reads serial bytes, runs the link and the commands, reports, writes bytes.
  void poll() noexcept {
    const std::uint32_t now = board_.now_ms();
    service_tick_events();  // first, so commands see the state the ticks left (a finished job is Idle)
    receive(now);
    service_tick_events();
    apply_start_rule();
    watch_link(now);
    watch_stall(now);
    send_setpoints();
    if (auto sent = stream_.transmit(now, outbox_.buffer()); !sent) raise_fault(sent.failure());
    outbox_.flush(board_);
  }

  /// One control period: the next setpoint, its step edges to the board, the setpoint to the stream.
  /// If the setpoint stream is backed up, nothing advances (a stalled tick, see the header).
  void on_tick() noexcept {
    if (motion_ != JobMotion::Moving) return;  // a program pause: nothing advances until Resume
    if constexpr (has_cycle_clock<B>) {
      if (!settings_.watch_ticks) return run_tick();
      const std::uint32_t late_periods = tick_watch_.on_start(board_.cycle_count());
      if (late_periods != 0) return raise_fault(fail(Error::TickDeadlineMissed, late_periods));
      run_tick();
      tick_watch_.on_end(board_.cycle_count());
    } else {
      run_tick();
    }
  }

  /// The state reported to the host.
  [[nodiscard]] protocol::MachineState state() const noexcept { return reported_state(phase_); }
  /// The session and job phase (the row of the state table in docs/protocol.md).
  [[nodiscard]] Phase phase() const noexcept { return phase_; }
  /// Tick overruns and the worst tick in board cycles (TickWatch; nothing on a board without
  /// cycle_count()); StatusReport carries them (docs/firmware.md, "Tick timing").
  [[nodiscard]] const TickWatch& tick_watch() const noexcept { return tick_watch_; }

 private:
  /// The work of on_tick(), untimed.
  void run_tick() noexcept {
    if (!ready_to_tick()) {
      if (stands_in_host_hold()) {
        link_watch_.stall_ended();  // waiting for Resume, not for the host's pieces
        return;
      }
      link_watch_.stalled_tick(board_);
      ++statistics_.stalled_ticks;
      return;
    }
    link_watch_.stall_ended();
    if constexpr (Events > 0 && plans_on_board) {
      if (wait_at_joint()) return;
    }
    const ControllerState before = controller_.state();
    auto next = controller_.next_setpoint();
    if (!next) {
      motion_ = JobMotion::Idle;
      if (controller_.state() == ControllerState::Fault) raise_fault(controller_.fault());
      return;
    }
    Setpoint<S> setpoint = next.value();
    const std::uint64_t job_tick = setpoint.tick;
    protocol::WirePoint wire{};
    for (std::size_t axis = 0; axis < protocol::max_axes; ++axis) {
      auto raw = to_raw(setpoint.position[axis]);
      if (!raw) return raise_fault(fail(raw.error(), setpoint.segment));
      wire[axis] = raw.value();
    }
    if (!positioned_) {
      // The first setpoint after power-up, a new session or a new configuration declares where
      // the machine is; every later one moves the steps from there.
      setpoint.tick = steps_.tick();
      if (auto reset = steps_.reset(setpoint); !reset) return raise_fault(reset.failure());
      declare_position(board_, {steps_.count(0), steps_.count(1), steps_.count(2)});
      positioned_ = true;
    } else {
      if (auto advanced = steps_.advance(setpoint, batch_); !advanced) return raise_fault(advanced.failure());
      play(batch_, board_);
      if (edges_lost()) {
        position_ = wire;  // the step generator and the board have moved to this setpoint
        return raise_fault(fail(Error::StepsLost, setpoint.segment));
      }
      const std::uint8_t closed = read_limit_switches(board_);
      const std::uint8_t hit = hard_limit_hit(closed, position_, wire, axis_count_);
      const bool sought_switch_closed = switch_seek_.met(closed);
      if (sought_switch_closed || hit != no_limit_switch) {
        position_ = wire;  // the board has this setpoint's edges: the machine stops there
        setpoint_index_ = static_cast<std::uint32_t>(job_tick);
        if (sought_switch_closed) return stop_at_switch();
        return raise_fault(fail(Error::HardLimit, hit));
      }
    }
    position_ = wire;
    setpoint_index_ = static_cast<std::uint32_t>(job_tick);
    if constexpr (Events > 0) machine_events_.reached(setpoint.segment, [this](const protocol::QueueEvent& e) { act_on(e); });
    const bool in_motion = before == ControllerState::Running || before == ControllerState::Holding;
    if (settings_.stream_setpoints && in_motion) stream_.push(setpoint_index_, wire);  // room checked above
    const ControllerState after = controller_.state();
    if (after == ControllerState::Finished) {
      if constexpr (Events > 0) machine_events_.finish([this](const protocol::QueueEvent& e) { act_on(e); });  // after the last move
      motion_ = JobMotion::Idle;  // a pause due at the end ends with the job (its PauseReport still goes out)
      events_.finished = true;
    } else if (after == ControllerState::Starved && before == ControllerState::Running) {
      events_.underrun = true;
    } else if (after == ControllerState::Held && before == ControllerState::Holding) {
      events_.held = true;
    }
  }


 public:
  /// True while a MachineConfiguration is in force.
  [[nodiscard]] bool configured() const noexcept { return control_rate_hz_ != 0; }
  /// The configured setpoint rate in Hz (0 without a configuration): call on_tick() this often.
  [[nodiscard]] std::uint32_t control_rate_hz() const noexcept { return control_rate_hz_; }
  /// True while a started job is in motion: on_tick() produces setpoints, or a pause holds it.
  [[nodiscard]] bool moving() const noexcept { return motion_ != JobMotion::Idle; }
  /// The motion controller (queue, planner, interpolator).
  [[nodiscard]] const Controller& controller() const noexcept { return controller_; }
  /// Counts of dropped frames and setpoints.
  [[nodiscard]] const AppStatistics& statistics() const noexcept { return statistics_; }
  /// The last error reported (Error code), 0 if none.
  [[nodiscard]] std::uint8_t last_error() const noexcept { return last_error_; }
  /// The commanded position (Q16.16 raw) of the last setpoint.
  [[nodiscard]] const protocol::WirePoint& position() const noexcept { return position_; }
  /// True if on_tick() may advance: no setpoint stream, or room for one more setpoint in it.
  /// Without a planner also false while the next setpoint needs a piece that has not arrived.
  [[nodiscard]] bool ready_to_tick() const noexcept {
    if (settings_.stream_setpoints && stream_.full()) return false;
    if constexpr (!plans_on_board) return !moving() || controller_.state() != ControllerState::Running || controller_.can_step();
    return true;
  }
  /// True once the job's last segment (flag end of job) has been queued.
  [[nodiscard]] bool job_end_known() const noexcept { return job_end_known_; }
  /// The setpoint stream's sender (window, go-backs), for diagnostics and tests.
  [[nodiscard]] const SetpointSender& setpoint_sender() const noexcept { return stream_.sender(); }
  /// Whole wire segments the queue can take now (the credit offered to the host).
  /// Each credit may be a segment or a machine event (QueueEvent), so it is the smaller room.
  [[nodiscard]] std::uint16_t free_segments() const noexcept {
    if (!takes_segments(phase_)) return 0;
    const std::size_t segments = (Queue - controller_.queued()) / slots_per_command;
    return static_cast<std::uint16_t>(segments < machine_events_.free() ? segments : machine_events_.free());
  }
  /// True while a program pause (M0/M1, M6, a layer change) holds the job until Resume.
  [[nodiscard]] bool paused() const noexcept { return motion_ == JobMotion::Paused; }
  /// Machine events queued and not yet reached by the motion.
  [[nodiscard]] std::size_t queued_events() const noexcept { return machine_events_.size(); }

 private:
  /// What on_tick() met, for poll() to act on and report (the tick itself never sends).
  struct TickEvents {
    bool finished = false;  ///< the job's last setpoint was produced
    bool underrun = false;  ///< the queue ran dry while moving (stopped on the path)
    bool held = false;      ///< a feed hold came to a stop
    bool paused = false;    ///< a pause event stopped the job: report it (PauseReport)
    bool fault = false;     ///< raise_fault() stopped the machine: report fault_
    bool switch_closed = false;  ///< a SeekSwitch job met its switch: report it (SwitchSeek)
  };

  [[nodiscard]] static constexpr protocol::ReceiverSettings make_receiver_settings(const AppSettings& s) noexcept {
    return protocol::ReceiverSettings{s.ack_interval_ms, s.link_timeout_ms};
  }

  [[nodiscard]] static Result<std::int32_t> to_raw(const S& value) noexcept {
    if constexpr (std::is_same_v<S, Q16_16>) {
      return value.raw();
    } else {
      CURVESTEP_TRY(const Q16_16 q, from_double<Q16_16>(to_double(value)));
      return q.raw();
    }
  }

  /// The phase of a session whose job is not started: by its configuration and queue.
  [[nodiscard]] Phase settled_phase() const noexcept {
    if (!configured()) return Phase::Connected;
    return controller_.queued() > 0 ? Phase::Queued : Phase::Configured;
  }
  /// Started and waiting for the start rule (Running) or held before it began (Holding).
  [[nodiscard]] bool armed() const noexcept { return job_started(phase_) && !moving(); }

  // --- receiving ---------------------------------------------------------------------------

  void receive(std::uint32_t now) noexcept {
    std::array<std::byte, 64> chunk{};
    for (int round = 0; round < 8; ++round) {
      const std::size_t count = board_.read(chunk);
      if (count == 0) return;
      for (std::size_t i = 0; i < count && i < chunk.size(); ++i) {
        const auto pushed = decoder_.push(chunk[i]);
        if (!pushed) {
          send_reply(receiver_.on_bad_frame(pushed.error(), now));
        } else if (pushed.value()) {
          on_frame(decoder_.frame(), now);
        }
      }
    }
  }

  void on_frame(const protocol::Frame& frame, std::uint32_t now) noexcept {
    link_watch_.heard(now);
    stream_.heard(now);  // the host talks: a stream it never acknowledges is RetransmitLimit, not LinkTimeout
    // A new session starts without a configuration: its Capabilities grant no credit. Credit
    // commands are refused by phase where no segment is taken (ConfigurationMissing, ...), not
    // by the credit (docs/protocol.md, "State table").
    const bool hello = frame.type == static_cast<std::uint8_t>(protocol::MessageType::Hello);
    const protocol::Reception r = receiver_.on_frame(frame, hello ? 0 : free_segments(), now, takes_segments(phase_));
    send_reply(r);
    if (r.disposition == protocol::Disposition::Connect) {
      stop_job(moving());
      control_rate_hz_ = 0;  // a new session declares its machine afresh
      axis_count_ = static_cast<std::uint8_t>(B::axis_count);
      phase_ = Phase::Connected;
      last_error_ = 0;
      next_start_.forget();
      positioned_ = false;
      stream_.open(now);
      statistics_.max_queue_depth = 0;
      tick_watch_.clear();
      if constexpr (plans_on_board) override_.reset(controller_);  // a new session starts at 100 %
    } else if (frame.type == static_cast<std::uint8_t>(protocol::MessageType::Ack) ||
               frame.type == static_cast<std::uint8_t>(protocol::MessageType::Nak)) {
      if (!receiver_.connected()) return;
      if (auto handled = stream_.on_reply(frame, now); !handled) raise_fault(handled.failure());
    } else if (r.disposition == protocol::Disposition::Deliver) {
      outbox_.answering(frame.sequence);
      dispatch(frame);
    }
  }

  // dispatch and the two decoding handlers are separate frames (noinline): with LTO, a decoded
  // MachineConfiguration and a decoded QueueSegment would otherwise share one frame on the
  // deepest call chain (receive -> dispatch -> queue_segment -> planning), docs/boards.md.
  [[gnu::noinline]] void dispatch(const protocol::Frame& frame) noexcept {
    using protocol::MessageType;
    const auto type = static_cast<MessageType>(frame.type);
    if (phase_ == Phase::StreamFailed && moves(type)) {
      // The setpoint stream gave up: nothing more can be streamed in this session (Hello).
      return report(fail(stream_.sender().last_error()));
    }
    switch (type) {
      case MessageType::MachineConfiguration: return on_machine_configuration(frame.payload);
      case MessageType::QueueSegment:
        if constexpr (plans_on_board) {
          return on_queue_segment(frame.payload);
        } else {
          return report(fail(Error::UnknownMessage, frame.type));
        }
      case MessageType::QueuePiece:
        if constexpr (plans_on_board) {
          return report(fail(Error::UnknownMessage, frame.type));
        } else {
          return on_queue_piece(frame.payload);
        }
      case MessageType::QueueEvent:
        if constexpr (Events > 0) {
          return on_queue_event(frame.payload);
        } else {
          return report(fail(Error::NotSupported));  // no room for machine events on this controller
        }
      case MessageType::Start:
        if (!frame.payload.empty()) return report(fail(Error::BadPayload, 0));
        return report_if_failed(start());
      case MessageType::FeedHold:
        if (!frame.payload.empty()) return report(fail(Error::BadPayload, 0));
        if constexpr (plans_on_board) {
          return feed_hold();
        } else {
          return host_hold();  // the host braked in its pieces
        }
      case MessageType::Resume:
        if (!frame.payload.empty()) return report(fail(Error::BadPayload, 0));
        return report_if_failed(resume());
      case MessageType::Abort:
        if (!frame.payload.empty()) return report(fail(Error::BadPayload, 0));
        return abort();
      case MessageType::StatusRequest:
        if (!frame.payload.empty()) return report(fail(Error::BadPayload, 0));
        return send_status();
      case MessageType::SeekSwitch: return on_seek_switch(frame.payload);
      case MessageType::SetPosition: return on_set_position(frame.payload);
      case MessageType::FeedOverride:
        if constexpr (plans_on_board) {
          if (auto taken = override_.take(frame.payload, controller_); !taken) return report(taken.failure());
          return send_status();  // names the setpoint it was set before: the host replays it (sim --override-at)
        } else {
          return report(fail(Error::NotSupported));  // the host's planner applies it
        }
      default: return report(fail(Error::UnknownMessage, frame.type));
    }
  }

  /// Commands that configure, queue or move (refused once the setpoint stream has failed).
  [[nodiscard]] static constexpr bool moves(protocol::MessageType type) noexcept {
    using protocol::MessageType;
    const MessageType queues = plans_on_board ? MessageType::QueueSegment : MessageType::QueuePiece;
    return type == MessageType::MachineConfiguration || type == queues || type == MessageType::QueueEvent ||
           type == MessageType::Start || type == MessageType::Resume || type == MessageType::SeekSwitch ||
           type == MessageType::SetPosition;
  }

  [[gnu::noinline]] void on_machine_configuration(std::span<const std::byte> payload) noexcept {
    const auto m = decode_configuration(payload);
    if (!m) return report(m.failure());
    report_if_failed(configure(m.value()));
  }

  /// Not inlined: the decoder's working copy must not sit under queue_piece() on the stack.
  [[nodiscard, gnu::noinline]] static Result<protocol::QueuePiece> decode_piece(std::span<const std::byte> payload) noexcept {
    return protocol::decode<protocol::QueuePiece>(payload);
  }

  /// Not inlined: the decoder's working copy must not sit under configure() on the stack.
  [[nodiscard, gnu::noinline]] static Result<protocol::MachineConfiguration> decode_configuration(std::span<const std::byte> payload) noexcept {
    return protocol::decode<protocol::MachineConfiguration>(payload);
  }

  /// A due machine event at setpoint `at` (by default the last one): the board's hooks, and a
  /// pause if it is one.
  void act_on(const protocol::QueueEvent& e) noexcept { act_on(e, setpoint_index_); }
  void act_on(const protocol::QueueEvent& e, std::uint32_t at) noexcept {
    if (machine_events_.act_on(board_, e, at) && !paused()) pause_for(e, at);
  }

  /// The motion waits at a joint whose segment has not arrived (MachineEvents::wait_at_joint,
  /// while the job runs); the events due there act at the setpoint they precede. True while
  /// waiting (no setpoint this tick).
  [[nodiscard]] bool wait_at_joint() noexcept {
    if (phase_ != Phase::Running || controller_.state() != ControllerState::Running) {
      machine_events_.stop_waiting();
      return false;
    }
    return machine_events_.wait_at_joint(
        controller_.next_tick_ends_queue(), job_segments_, [this] { return window_ready(1); },
        [this](const protocol::QueueEvent& e) { act_on(e, setpoint_index_ + 1); });
  }

  /// Stops producing setpoints after this one until Resume; poll() reports the pause.
  void pause_for(const protocol::QueueEvent& e, std::uint32_t at) noexcept {
    motion_ = JobMotion::Paused;
    machine_events_.hold_for(e, at);
    phase_ = Phase::Holding;
    events_.paused = true;
  }

  /// A machine event for the board at a joint of the job (event_timeline.hpp): taken while
  /// segments are (before the job's last one), like a segment.
  /// Not inlined: the decoded event must not sit in dispatch()'s frame (docs/boards.md, stack).
  [[gnu::noinline]] void on_queue_event(std::span<const std::byte> payload) noexcept {
    const auto m = protocol::decode<protocol::QueueEvent>(payload);
    if (!m) return report(m.failure());
    if (!configured()) return report(fail(Error::ConfigurationMissing));
    if (phase_ == Phase::Fault || job_end_known_) return report(fail(Error::InvalidState));
    report_if_failed(machine_events_.push(m.value()));
  }

  // --- homing (limit_switches.hpp, docs/firmware.md "Homing") ---------------------------------

  /// SeekSwitch: the next job ends where `limit_switch` closes. Before Start only.
  [[gnu::noinline]] void on_seek_switch(std::span<const std::byte> payload) noexcept {
    const auto m = protocol::decode<protocol::SeekSwitch>(payload);
    if (!m) return report(m.failure());
    if (!configured()) return report(fail(Error::ConfigurationMissing));
    if (phase_ == Phase::Fault || job_started(phase_)) return report(fail(Error::InvalidState));
    if (!switch_seek_.arm(m.value().limit_switch, axis_count_)) return report(fail(Error::InvalidArgument, 0));
  }

  /// SetPosition: new coordinates for the standing machine; the next job starts there (its first
  /// setpoint declares the position again, no step is taken).
  [[gnu::noinline]] void on_set_position(std::span<const std::byte> payload) noexcept {
    const auto m = protocol::decode<protocol::SetPosition>(payload);
    if (!m) return report(m.failure());
    if (phase_ == Phase::Fault) return report(fail(Error::InvalidState));
    if (moving() || job_started(phase_) || controller_.queued() > 0) return report(fail(Error::PlannerBusy));
    if (m.value().axes >= (1u << axis_count_)) return report(fail(Error::InvalidArgument, 0));
    const protocol::WirePoint at{m.value().x, m.value().y, m.value().z};
    for (std::size_t axis = 0; axis < axis_count_; ++axis) {
      if ((m.value().axes & (1u << axis)) != 0) position_[axis] = at[axis];
    }
    next_start_.set(position_);
    positioned_ = false;
  }

  /// A SeekSwitch job met its switch: it ends where it stands, without braking (the edges already
  /// handed to the board play out, so the position stays exact); poll() sends the SwitchReport.
  void stop_at_switch() noexcept {
    switch_seek_.record_stop(setpoint_index_, position_);
    stop_job(false);
    events_.switch_closed = true;
  }

  [[gnu::noinline]] void on_queue_segment(std::span<const std::byte> payload) noexcept {
    const auto m = protocol::decode<protocol::QueueSegment>(payload);
    if (!m) return report(m.failure());
    report_if_failed(queue_segment(m.value()));
  }

  [[gnu::noinline]] void on_queue_piece(std::span<const std::byte> payload) noexcept {
    const auto m = decode_piece(payload);
    if (!m) return report(m.failure());
    report_if_failed(queue_piece(m.value()));
  }

  // --- commands --------------------------------------------------------------------------

  [[nodiscard, gnu::noinline]] Result<void> configure(const protocol::MachineConfiguration& m) noexcept {
    // Queued segments were planned with the old limits: a new configuration needs an empty queue.
    if (phase_ == Phase::Fault) return fail(Error::InvalidState);  // Abort first
    if (moving() || job_started(phase_) || controller_.queued() > 0) return fail(Error::PlannerBusy);
    if (m.axis_count > B::axis_count) return fail(Error::InvalidArgument, 0);
    // The Results are used in place (no CURVESTEP_TRY copies): this frame is on the deepest
    // call chain of a small board's stack (docs/boards.md, "Footprint").
    auto limits = to_machine_limits(m);
    if (!limits) return limits.failure();
    const auto travel = to_travel_limits(m);
    if (!travel) return travel.failure();
    const auto step_config = fit_step_config<B>(limits.value());
    if (!step_config) {
      // A control period too short for one step (StepConfig's Period) is the rate's fault.
      const Failure f = step_config.failure();
      if (f.code == Error::InvalidArgument && f.index == static_cast<std::size_t>(StepTimingField::Period)) {
        return fail(Error::InvalidRate, static_cast<std::size_t>(LimitField::RateHz));
      }
      return f;
    }
    if (controller_.state() != ControllerState::Idle) controller_.reset();
    CURVESTEP_CHECK(controller_.configure(limits.value()));
    steps_ = StepGenerator(step_config.value());
    travel_ = travel.value();
    positioned_ = false;
    next_start_.forget();
    axis_count_ = m.axis_count;
    control_rate_hz_ = m.control_rate_hz;
    configure_tick_watch();
    phase_ = Phase::Configured;
    return ok();
  }

  /// The tick watch for the configured rate. Not inlined: configure() is on a small board's
  /// deepest call chain (docs/boards.md, "Footprint").
  [[gnu::noinline]] void configure_tick_watch() noexcept {
    if constexpr (has_cycle_clock<B>) tick_watch_.configure(board_.cycles_per_second() / control_rate_hz_, settings_.tick_deadline_periods);
  }

  /// Counts one more accepted segment or piece: the deepest queue, and Configured becomes Queued.
  void note_queued() noexcept {
    const auto depth = static_cast<std::uint16_t>(controller_.queued());
    if (depth > statistics_.max_queue_depth) statistics_.max_queue_depth = depth;
    ++job_segments_;
    if (phase_ == Phase::Configured) phase_ = Phase::Queued;
  }

  [[nodiscard, gnu::noinline]] Result<void> queue_segment(const protocol::QueueSegment& s) noexcept {
    if (!configured()) return fail(Error::ConfigurationMissing);
    if (phase_ == Phase::Fault || job_end_known_) return fail(Error::InvalidState);
    if (s.axis_count > axis_count_) return fail(Error::InvalidArgument, 1);
    const protocol::WirePoint start = segment_start(s);
    if (!next_start_.connects(start)) return fail(Error::SegmentsNotConnected, job_segments_);
    const auto made = to_path_segment(s);  // used in place: a PathSegment is large for small stacks
    if (!made) return made.failure();
    const PathSegment& segment = made.value();
    CURVESTEP_CHECK(check_travel(segment, travel_));
    CURVESTEP_CHECK(controller_.try_push(segment, job_segments_, JointStop{s.stop_before, s.rest_ticks}));
    next_start_.set(segment_end(s));
    note_queued();
    if (s.end_of_job) {
      controller_.end_of_job(s.end_rest_ticks);
      job_end_known_ = true;
    }
    return ok();
  }

  /// A host-planned piece (no planner on board). The job's first piece must be where the machine
  /// stands (SegmentsNotConnected, as a segment's start); every piece's end and every point of an
  /// exact run must be inside the travel range (OutsideTravel, index = axis). The stepped setpoints of a chunk stay within
  /// chunk_error_bound of the host's exact path, which ends on the checked end points.
  [[nodiscard, gnu::noinline]] Result<void> queue_piece(const protocol::QueuePiece& m) noexcept {
    if (!configured()) return fail(Error::ConfigurationMissing);
    if (phase_ == Phase::Fault || job_end_known_) return fail(Error::InvalidState);
    if (m.axis_count > axis_count_) return fail(Error::InvalidArgument, 1);
    const PlannedPiece piece = to_planned_piece(m);
    CURVESTEP_CHECK(check_travel(piece.end, travel_));
    if (piece.exact_run) {
      for (std::uint32_t k = 0; k + 1 < piece.ticks; ++k) CURVESTEP_CHECK(check_travel(piece.controls[k], travel_));
    }
    if (job_segments_ == 0 && next_start_.known()) {
      // The job's first setpoint: an exact run's first point, else the piece's end.
      CURVESTEP_TRY(const protocol::WirePoint start, to_wire_point(piece.exact_run ? piece.controls[0] : piece.end));
      if (!next_start_.connects(start)) return fail(Error::SegmentsNotConnected, 0);
    }
    CURVESTEP_TRY(const protocol::WirePoint end, to_wire_point(piece.end));  // checked before anything is queued
    CURVESTEP_CHECK(controller_.push(piece));
    note_queued();
    if (m.end_of_job) {
      job_end_known_ = true;
      next_start_.set(end);  // where the next job must start
    }
    return ok();
  }

  [[nodiscard]] Result<void> start() noexcept {
    if (!configured()) return fail(Error::ConfigurationMissing);
    if (phase_ == Phase::Configured) return fail(Error::NothingQueued);
    if (phase_ != Phase::Queued) return fail(Error::InvalidState);
    phase_ = Phase::Running;  // armed: Moving once the start rule holds
    apply_start_rule();
    return ok();
  }

  void feed_hold() noexcept {
    resume_when_held_ = false;
    if (phase_ == Phase::Running && armed()) {
      phase_ = Phase::Holding;  // held before the start
      return;
    }
    if (!moving()) return;
    if (controller_.state() == ControllerState::Starved) {
      phase_ = Phase::Holding;  // already stopped on the path: stay there
      return;
    }
    if (controller_.state() != ControllerState::Running) return;
    controller_.hold();
    phase_ = Phase::Holding;
    send_status();  // names the tick the hold acted at: the host replays it (sim --hold-at)
  }

  /// FeedHold without a planner: the host planned the braking into the pieces it sent before
  /// (docs/protocol.md, "FeedHold"). The App holds (Holding) and runs what is queued; once the queue
  /// runs dry at their end it stands, neither a stall nor an underrun (stands_in_host_hold), until
  /// Resume. Held before the start as with a planner.
  void host_hold() noexcept {
    if (phase_ != Phase::Running) return;
    phase_ = Phase::Holding;
    if (moving()) send_status();
  }

  /// Without a planner: held by the host (host_hold) with the queue run dry, at the end of the
  /// braking pieces. The machine stands there; ticks make no setpoint and count no stall.
  [[nodiscard]] bool stands_in_host_hold() const noexcept {
    if constexpr (plans_on_board) {
      return false;
    } else {
      return phase_ == Phase::Holding && motion_ == JobMotion::Moving && !controller_.can_step();
    }
  }

  [[nodiscard]] Result<void> resume() noexcept {
    if (paused()) {  // the operator is done: on from the pause
      motion_ = JobMotion::Moving;
      phase_ = Phase::Running;
      return ok();
    }
    if (phase_ == Phase::Holding && armed()) {
      phase_ = Phase::Running;  // armed again
      apply_start_rule();
      return ok();
    }
    if (phase_ != Phase::Holding) return fail(Error::InvalidState);
    if constexpr (!plans_on_board) {
      phase_ = Phase::Running;  // the host's pieces after the hold follow
      return ok();
    }
    if (controller_.state() == ControllerState::Starved) {
      phase_ = Phase::Running;  // continues under the start rule
      apply_start_rule();
      return ok();
    }
    if (controller_.state() == ControllerState::Holding) {
      resume_when_held_ = true;  // still braking: continue from the stop
      return ok();
    }
    CURVESTEP_CHECK(controller_.resume());
    phase_ = Phase::Running;
    return ok();
  }

  /// Abort: ends the job at once and stops the board's edges. A failed setpoint stream stays
  /// failed (StreamFailed until the next Hello).
  void abort() noexcept {
    const bool stream_failed = phase_ == Phase::StreamFailed;
    stop_job(true);
    if (stream_failed) phase_ = Phase::StreamFailed;
  }

  /// Ends the job at once; `outputs` also stops the board's scheduled edges (Abort).
  void stop_job(bool outputs) noexcept {
    if (outputs) board_.fault_stop();
    machine_events_.switch_off_spindle_and_coolant(board_, setpoint_index_);
    controller_.abort();
    controller_.reset();
    machine_events_.clear();  // and any wait at a joint
    switch_seek_.disarm();
    motion_ = JobMotion::Idle;
    job_end_known_ = false;
    events_ = TickEvents{};
    resume_when_held_ = false;
    link_watch_.stall_ended();  // a stall of the stopped job is not the next job's
    job_segments_ = 0;
    // The next job starts where the machine stands.
    next_start_.stand_at(position_, positioned_);
    phase_ = settled_phase();
  }

  // --- tick events, start rule, link watch ----------------------------------------------------

  /// True when the board lost edges since the last check: a lost edge is a lost step, so the
  /// position is no longer known.
  [[nodiscard]] bool edges_lost() noexcept {
    const std::uint32_t dropped = edges_dropped_by(board_);
    if (dropped == edges_dropped_seen_) return false;
    edges_dropped_seen_ = dropped;
    return true;
  }

  /// Stops the machine at once (phase Fault); poll() reports `failure`.
  void raise_fault(Failure failure) noexcept {
    board_.fault_stop();
    machine_events_.switch_off_spindle_and_coolant(board_, setpoint_index_);
    controller_.abort();
    motion_ = JobMotion::Idle;  // a fault also ends a pause (Resume does not leave Fault)
    fault_ = failure;
    events_.fault = true;
    phase_ = stream_.failed() ? Phase::StreamFailed : Phase::Fault;
  }

  void service_tick_events() noexcept {
    if (events_.fault) {
      events_.fault = false;
      report(fault_);
      send_status();
    }
    if (events_.switch_closed) {
      events_.switch_closed = false;
      send_message(switch_seek_.report());
      send_status();
    }
    if (events_.finished) {
      events_.finished = false;
      switch_seek_.disarm();  // the job ended without meeting its switch
      controller_.reset();
      job_end_known_ = false;
      job_segments_ = 0;
      phase_ = settled_phase();
      send_status();
    }
    if constexpr (Events > 0) {
      if (events_.paused) {
        events_.paused = false;
        send_message(machine_events_.pause());
        send_status();
      }
    }
    if (events_.held) {
      events_.held = false;
      if (resume_when_held_) {
        resume_when_held_ = false;
        if (auto resumed = controller_.resume(); resumed) {
          phase_ = Phase::Running;
        } else {
          report(resumed.failure());
        }
      }
      send_status();
    }
    if (events_.underrun) {
      events_.underrun = false;
      last_error_ = static_cast<std::uint8_t>(Error::QueueUnderrun);
      send_status();
    }
  }

  [[nodiscard]] bool window_ready(std::size_t ahead_of_front) const noexcept {
    const std::size_t queued = controller_.queued();
    if (job_end_known_) return queued >= 1 + ahead_of_front;
    if constexpr (!plans_on_board) return queued == Queue;  // the host keeps it full from here on
    return queued >= Lookahead + 1 + ahead_of_front || (free_segments() == 0 && queued > ahead_of_front);
  }

  void apply_start_rule() noexcept {
    if (phase_ == Phase::Running && armed() && window_ready(0)) {
      if (auto started = controller_.start(); !started) {
        phase_ = settled_phase();
        return report(started.failure());
      }
      motion_ = JobMotion::Moving;
      tick_watch_.restart();  // the ticks of this motion keep its schedule
    }
    // After an underrun the finished segment is still at the front: resume() drops it.
    if (moving() && controller_.state() == ControllerState::Starved && phase_ == Phase::Running && window_ready(1)) {
      if (auto resumed = controller_.resume(); !resumed) report(resumed.failure());
    }
  }

  /// A setpoint stream backed up for longer than stall_timeout_ms while moving is a fault.
  void watch_stall(std::uint32_t now) noexcept {
    if (!moving() || !link_watch_.stall_expired(now, settings_.stall_timeout_ms)) return;
    // Without a planner a stall is usually a queue the host did not refill in time.
    bool starved = false;
    if constexpr (!plans_on_board) starved = !controller_.can_step();
    raise_fault(link_watch_.stall_fault(now, starved));
  }

  void watch_link(std::uint32_t now) noexcept {
    send_reply(receiver_.poll(free_segments(), now));
    if (!link_watch_.newly_lost([&] { return static_cast<bool>(receiver_.check_link(now)); })) return;
    const bool running = moving() && controller_.state() == ControllerState::Running;
    if (!running && !(phase_ == Phase::Running && armed())) return;
    // Without a planner there is no braking: the queued pieces run out (QueueUnderrun).
    if constexpr (plans_on_board) feed_hold();
    report(fail(Error::LinkTimeout));
  }

  // --- sending -------------------------------------------------------------------------------

  // Frames that find the transmit buffer full are counted, not queued (outbox.hpp).
  void send_reply(const protocol::Reception& r) noexcept { outbox_.reply(receiver_, r, statistics_.dropped_frames); }

  template <class M>
  void send_message(const M& m) noexcept {
    outbox_.send(receiver_, m, statistics_.dropped_frames);
  }

  void report(Failure failure) noexcept {
    last_error_ = static_cast<std::uint8_t>(failure.code);
    send_message(outbox_.error_report(failure));
  }
  void report_if_failed(const Result<void>& r) noexcept {
    if (!r) report(r.failure());
  }

  void send_status() noexcept {
    protocol::StatusReport s;
    s.state = state();
    s.error = last_error_;
    s.axis_count = axis_count_;
    s.queue_depth = static_cast<std::uint16_t>(controller_.queued());
    s.max_queue_depth = statistics_.max_queue_depth;
    s.setpoint_index = setpoint_index_;
    s.limit_switches = read_limit_switches(board_);
    s.tick_overruns = tick_watch_.overruns();
    if constexpr (has_cycle_clock<B>) s.worst_tick_us = tick_watch_.worst_microseconds(board_.cycles_per_second());
    override_.describe(s);
    s.position = position_;
    send_message(s);
  }

  /// Moves buffered setpoints into the setpoint stream's window as batches (never drops any).
  void send_setpoints() noexcept {
    // Stopped, stalled or paused (a paused interpolator must not hold back what it already produced).
    const bool stopped = motion_ != JobMotion::Moving || link_watch_.stalled() || controller_.state() == ControllerState::Held ||
                         controller_.state() == ControllerState::Starved || stands_in_host_hold();
    stream_.submit(stopped, axis_count_, statistics_.setpoint_go_backs);
  }

  B& board_;
  AppSettings settings_;
  protocol::FrameDecoder<> decoder_{};
  protocol::LinkReceiver receiver_;
  SetpointStream<B> stream_;
  Controller controller_{};
  /// The override last set (FeedOverride; nothing without a planner).
  [[no_unique_address]] std::conditional_t<plans_on_board, FeedOverrideCommand, NoFeedOverride> override_{};
  // The App's parts are [[no_unique_address]] so that the one-byte members after each fill its
  // tail padding (RAM of the small boards, docs/boards.md "Footprint").
  [[no_unique_address]] MachineEvents<Events> machine_events_{};  ///< QueueEvents, the spindle and coolant they set, the pause
  JobMotion motion_ = JobMotion::Idle;  ///< idle, moving or paused (phase.hpp)
  [[no_unique_address]] SwitchSeek switch_seek_{};  ///< the homing seek (SeekSwitch) and its SwitchReport
  bool positioned_ = false;            ///< the step generator knows where the machine is
  bool job_end_known_ = false;         ///< the job's last segment has been queued
  bool resume_when_held_ = false;      ///< a Resume arrived while still braking
  StepGenerator steps_{StepConfig{}};
  StepBatch<B::step_events_per_tick> batch_{};
  AppStatistics statistics_{};
  TickWatch tick_watch_{};
  [[no_unique_address]] LinkWatch link_watch_{};  ///< link loss and setpoint-stream stalls
  Phase phase_ = Phase::NotConnected;
  std::uint8_t last_error_ = 0;
  protocol::WirePoint position_{};
  [[no_unique_address]] NextStart next_start_{};  ///< where the next segment must start
  std::uint8_t axis_count_ = static_cast<std::uint8_t>(B::axis_count);
  TravelLimits travel_{};
  Failure fault_{Error::InvalidState, no_index};
  std::uint32_t control_rate_hz_ = 0;
  std::uint32_t setpoint_index_ = 0;
  std::uint32_t job_segments_ = 0;
  std::uint32_t edges_dropped_seen_ = 0;  ///< the board's edges_dropped() at the last check
  TickEvents events_{};
  [[no_unique_address]] Outbox outbox_{};  ///< outgoing frames (transmit buffer) and the sequence ErrorReports answer
};

}  // namespace curvestep::firmware
