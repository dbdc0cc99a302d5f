// SPDX-License-Identifier: MIT
// FakeBoard and a scripted host for App tests: serial bytes in memory, a settable clock, edge counts.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <span>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/motion/step_generator.hpp>
#include <curvestep/firmware/conversions.hpp>
#include <curvestep/firmware/app.hpp>
#include <curvestep/firmware/board.hpp>
#include <curvestep/protocol/frame_decoder.hpp>
#include <curvestep/protocol/link_receiver.hpp>
#include <curvestep/protocol/link_sender.hpp>

namespace curvestep::firmware::testing {

/// A board in memory: the host writes into `incoming`, the App's bytes land in `outgoing`.
class FakeBoard {
 public:
  static constexpr std::uint8_t axis_count = 3;
  static constexpr std::size_t step_events_per_tick = 64;
  static constexpr StepTiming step_timing() { return StepTiming{1000000, 2000, 2000, 1000, 1000}; }

  std::uint32_t now_ms() { return clock_ms; }
  std::size_t read(std::span<std::byte> into) {
    std::size_t n = 0;
    while (n < into.size() && !incoming.empty()) {
      into[n++] = incoming.front();
      incoming.pop_front();
    }
    return n;
  }
  std::size_t write(std::span<const std::byte> bytes) {
    const std::size_t n = bytes.size() < write_limit ? bytes.size() : write_limit;
    outgoing.insert(outgoing.end(), bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(n));
    return n;
  }
  void set_direction(std::uint64_t time_ticks, std::uint8_t axis, bool positive) {
    last_edge_time = time_ticks;
    direction[axis] = positive;
  }
  void set_step(std::uint64_t time_ticks, std::uint8_t axis, bool high) {
    last_edge_time = time_ticks;
    if (high) steps[axis] += direction[axis] ? 1 : -1;
  }
  void fault_stop() { ++fault_stops; }
  /// Puts `bytes` on the line toward the App (what the host's serial port would send).
  void put_incoming(std::span<const std::byte> bytes) { incoming.insert(incoming.end(), bytes.begin(), bytes.end()); }

  std::uint32_t clock_ms = 0;
  std::size_t write_limit = 1u << 20;
  std::deque<std::byte> incoming;
  std::vector<std::byte> outgoing;
  std::array<bool, 3> direction{};
  std::array<std::int64_t, 3> steps{};
  std::uint64_t last_edge_time = 0;
  int fault_stops = 0;
};

static_assert(Board<FakeBoard>);

/// Puts the frame of `type`, `sequence` and `message` on the line toward the App, bypassing the
/// host's link (any type, any sequence number).
inline void send_raw(FakeBoard& board, std::uint8_t type, std::uint8_t sequence, std::span<const std::byte> message) {
  std::array<std::byte, protocol::max_encoded_frame_size> frame{};
  const auto size = protocol::encode_frame(type, sequence, message, frame);
  REQUIRE(size.has_value());
  board.put_incoming(std::span<const std::byte>(frame.data(), size.value()));
}

/// Puts the frame of message struct `m` with `sequence` on the line toward the App, bypassing
/// the host's link.
template <class M>
void send_raw(FakeBoard& board, const M& m, std::uint8_t sequence) {
  std::array<std::byte, protocol::max_encoded_frame_size> frame{};
  const auto size = protocol::encode_frame(m, sequence, frame);
  REQUIRE(size.has_value());
  board.put_incoming(std::span<const std::byte>(frame.data(), size.value()));
}

/// What the host received, decoded.
struct Received {
  std::vector<protocol::StatusReport> status;
  std::vector<protocol::SetpointBatch> batches;
  std::vector<protocol::ErrorReport> errors;
  std::vector<protocol::Nak> naks;
  std::vector<protocol::Ack> acks;
  std::vector<protocol::PauseReport> pauses;
  std::vector<protocol::SwitchReport> switches;
  int capabilities = 0;
  protocol::Capabilities last_capabilities{};
};

/// The host end: a LinkSender for commands and a LinkReceiver for the App's setpoint stream
/// over the FakeBoard's byte queues, with the App in the loop.
template <class AppType>
class Host {
 public:
  Host(FakeBoard& board, AppType& app)
      : board_(board),
        app_(app),
        sender_(protocol::SenderSettings{100, 10, 0}),
        receiver_(protocol::Capabilities{}, protocol::ReceiverSettings{}, protocol::Endpoint::Host) {}

  /// Handshake; true once Capabilities arrived.
  bool connect(std::uint16_t session = 0x1234) {
    receiver_.close();
    sender_.connect(session, board_.clock_ms);
    for (int i = 0; i < 20 && sender_.state() != protocol::LinkState::Connected; ++i) pump();
    if (sender_.state() == protocol::LinkState::Connected) receiver_.open(board_.clock_ms);
    return sender_.state() == protocol::LinkState::Connected;
  }

  /// False: the host stops acknowledging setpoint batches (it ignores them).
  bool acknowledge_setpoints = true;
  /// False: the host does not read what the App sent (a slow host: the bytes wait).
  bool reading = true;
  /// Setpoint batches the App sent again after the host had them (retransmissions seen).
  int repeated_batches = 0;

  /// Submits a message (waiting for window and credit by pumping); false if it never fits.
  bool send(const protocol::Message& m) {
    for (int i = 0; i < 200; ++i) {
      if (sender_.can_submit(m.type())) return sender_.submit(m).has_value();
      pump();
    }
    return false;
  }

  /// One exchange: host frames out, App poll, App frames back into the host.
  void pump() {
    std::array<std::byte, protocol::max_encoded_frame_size> frame{};
    for (;;) {
      const auto r = sender_.poll(board_.clock_ms, frame);
      if (!r || r.value() == 0) break;
      board_.put_incoming(std::span<const std::byte>(frame.data(), r.value()));
    }
    app_.poll();
    take_output();
  }

  /// `times` exchanges.
  void pump(int times) {
    for (int i = 0; i < times; ++i) pump();
  }

  /// Runs `ticks` control ticks, pumping the link every tick.
  void run_ticks(int ticks, int ms_per_tick_divisor = 1) {
    for (int t = 0; t < ticks; ++t) {
      app_.on_tick();
      if (t % ms_per_tick_divisor == 0) ++board_.clock_ms;
      pump();
    }
  }

  /// Decodes what the App wrote so far; setpoint batches go through the host's receiver
  /// (acknowledged, delivered once each and in order).
  void take_output() {
    if (!reading) return;  // the bytes wait in the line
    for (const std::byte b : board_.outgoing) {
      const auto pushed = decoder_.push(b);
      if (!pushed) {
        if (acknowledge_setpoints) reply(receiver_.on_bad_frame(pushed.error(), board_.clock_ms));
        continue;
      }
      if (!pushed.value()) continue;
      const auto m = protocol::decode_message(decoder_.frame());
      if (!m) continue;
      const protocol::Message& msg = m.value();
      if (msg.holds<protocol::SetpointBatch>()) {
        if (!acknowledge_setpoints) continue;
        const protocol::Reception r = receiver_.on_frame(decoder_.frame(), 0, board_.clock_ms);
        reply(r);
        if (r.disposition != protocol::Disposition::Deliver) {
          ++repeated_batches;
          continue;
        }
      }
      [[maybe_unused]] const auto handled = sender_.on_message(msg, board_.clock_ms);
      switch (msg.type()) {
        case protocol::MessageType::Capabilities:
          ++received.capabilities;
          received.last_capabilities = msg.get<protocol::Capabilities>();
          break;
        case protocol::MessageType::Ack: received.acks.push_back(msg.get<protocol::Ack>()); break;
        case protocol::MessageType::Nak: received.naks.push_back(msg.get<protocol::Nak>()); break;
        case protocol::MessageType::StatusReport: received.status.push_back(msg.get<protocol::StatusReport>()); break;
        case protocol::MessageType::SetpointBatch: received.batches.push_back(msg.get<protocol::SetpointBatch>()); break;
        case protocol::MessageType::ErrorReport: received.errors.push_back(msg.get<protocol::ErrorReport>()); break;
        case protocol::MessageType::PauseReport: received.pauses.push_back(msg.get<protocol::PauseReport>()); break;
        case protocol::MessageType::SwitchReport: received.switches.push_back(msg.get<protocol::SwitchReport>()); break;
        default: break;
      }
    }
    board_.outgoing.clear();
  }

  /// The setpoints of every batch received, in order, with their indices.
  std::vector<std::pair<std::uint32_t, protocol::WirePoint>> setpoints() const {
    std::vector<std::pair<std::uint32_t, protocol::WirePoint>> out;
    for (const auto& b : received.batches) {
      for (std::size_t k = 0; k < b.count; ++k) out.emplace_back(b.first_index + static_cast<std::uint32_t>(k), b.setpoints[k]);
    }
    return out;
  }

  protocol::LinkSender<8>& sender() { return sender_; }
  Received received;

 private:
  void reply(const protocol::Reception& r) {
    std::array<std::byte, protocol::max_encoded_frame_size> frame{};
    const auto size = receiver_.encode_reply(r, frame);
    if (!size) return;
    board_.put_incoming(std::span<const std::byte>(frame.data(), size.value()));
  }

  FakeBoard& board_;
  AppType& app_;
  protocol::LinkSender<8> sender_;
  protocol::LinkReceiver receiver_;
  protocol::FrameDecoder<> decoder_;
};

/// The host's side of streaming a job while the App runs, one step per control tick: every segment
/// the window and the credit allow, Start once it fits after the first segment, and a StatusRequest every 100 ticks (a host
/// polls the status now and then; that traffic also keeps the link watchdog quiet).
class JobUpload {
 public:
  explicit JobUpload(const std::vector<protocol::QueueSegment>& job) : job_(job) {}

  /// This tick's submissions; false if the sender refused one it said it had room for.
  template <class Sender>
  [[nodiscard]] bool step(Sender& sender, int tick) {
    while (next_ < job_.size() && sender.can_submit(protocol::MessageType::QueueSegment)) {
      if (!sender.submit(protocol::Message(job_[next_])).has_value()) return false;
      ++next_;
    }
    // Start once a segment is on its way (Start on an empty queue is NothingQueued).
    if (!started_ && next_ > 0 && sender.can_submit(protocol::MessageType::Start)) {
      if (!sender.submit(protocol::Message(protocol::Start{})).has_value()) return false;
      started_ = true;
    }
    if (tick % 100 == 99 && sender.can_submit(protocol::MessageType::StatusRequest)) {
      if (!sender.submit(protocol::Message(protocol::StatusRequest{})).has_value()) return false;
    }
    return true;
  }

  /// Segments submitted so far.
  [[nodiscard]] std::size_t segments_sent() const { return next_; }
  /// Every segment and the Start were submitted.
  [[nodiscard]] bool all_sent() const { return started_ && next_ == job_.size(); }

 private:
  const std::vector<protocol::QueueSegment>& job_;
  std::size_t next_ = 0;
  bool started_ = false;
};

/// Millimetres as Q16.16 (exact for the binary fractions the tests use).
constexpr std::int32_t q(double mm) { return static_cast<std::int32_t>(mm * 65536.0); }

inline protocol::WirePoint p(double x, double y, double z = 0) { return protocol::WirePoint{q(x), q(y), q(z)}; }

/// The test machine: 3 axes, 100 mm/s, 1000 mm/s², 10000 mm/s³, 80 steps/mm, travel ±100 mm,
/// 1 kHz control rate and the given default feed.
inline protocol::MachineConfiguration machine(double default_feed_mm_per_s) {
  protocol::MachineConfiguration c;
  c.axis_count = 3;
  c.max_velocity_mm_per_s = 100;  // protocol version 2: limits travel as binary64
  c.max_acceleration_mm_per_s2 = 1000;
  c.max_jerk_mm_per_s3 = 10000;
  c.default_feed_mm_per_s = q(default_feed_mm_per_s);
  c.tolerance_mm = 0.01;
  c.junction_deviation_mm = 0.05;
  c.max_step_rate_hz = 100000;
  c.control_rate_hz = 1000;
  for (auto& axis : c.axes) {
    axis.steps_per_mm = 80;
    axis.min_position_mm = q(-100);
    axis.max_position_mm = q(100);
  }
  return c;
}

inline protocol::QueueSegment line(protocol::WirePoint a, protocol::WirePoint b, std::uint8_t axes = 3) {
  protocol::QueueSegment s;
  s.kind = protocol::SegmentKind::Line;
  s.axis_count = axes;
  s.points[0] = a;
  s.points[1] = b;
  return s;
}

inline protocol::QueueSegment cubic(protocol::WirePoint a, protocol::WirePoint b, protocol::WirePoint c, protocol::WirePoint d,
                                    std::uint8_t axes = 3) {
  protocol::QueueSegment s;
  s.kind = protocol::SegmentKind::Bezier;
  s.axis_count = axes;
  s.degree = 3;
  s.points[0] = a;
  s.points[1] = b;
  s.points[2] = c;
  s.points[3] = d;
  return s;
}

/// An arc about `center` from `start` to `end`.
inline protocol::QueueSegment arc(protocol::WirePoint start, protocol::WirePoint end, protocol::WirePoint center,
                                  ArcDirection direction, std::uint8_t axes = 3) {
  protocol::QueueSegment s;
  s.kind = protocol::SegmentKind::Arc;
  s.axis_count = axes;
  s.degree = 2;  // fixed by the kind (the decoder sets it too)
  s.points[0] = start;
  s.points[1] = end;
  s.points[2] = center;
  s.direction = direction;
  return s;
}

using Setpoints = std::vector<std::pair<std::uint32_t, protocol::WirePoint>>;

/// The reference: a MotionController (Q16.16) run directly on the same wire segments, as curvestep
/// sim does, fed whenever there is room.
template <class Controller>
Setpoints controller_reference(const protocol::MachineConfiguration& config, const std::vector<protocol::QueueSegment>& job) {
  Controller controller;
  REQUIRE(controller.configure(to_machine_limits(config).value()).has_value());
  std::size_t next = 0;
  const auto fill = [&] {
    while (next < job.size() && !controller.queue_full()) {
      const auto segment = to_path_segment(job[next]);
      REQUIRE(segment.has_value());
      const auto pushed = controller.try_push(segment.value(), static_cast<std::uint32_t>(next),
                                              JointStop{job[next].stop_before, job[next].rest_ticks});
      if (!pushed && pushed.error() == Error::QueueFull) return;
      REQUIRE(pushed.has_value());
      ++next;
    }
    if (next == job.size()) controller.end_of_job();
  };
  fill();
  REQUIRE(controller.start().has_value());
  Setpoints out;
  while (!controller.finished()) {
    const auto sp = controller.next_setpoint();
    REQUIRE(sp.has_value());
    protocol::WirePoint w{};
    for (std::size_t a = 0; a < 3; ++a) w[a] = sp.value().position[a].raw();
    out.emplace_back(static_cast<std::uint32_t>(sp.value().tick), w);
    fill();
  }
  return out;
}

/// The App's stream is the reference's: as long, and no setpoint (index and position) differs.
inline void check_same_stream(const Setpoints& got, const Setpoints& expected) {
  REQUIRE(got.size() == expected.size());
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    if (got[i] != expected[i]) ++mismatches;
  }
  CHECK(mismatches == 0);
}

/// Sends nothing between ticks (stream_job's default).
struct NothingBetweenTicks {
  template <class AppType, class HostType>
  void operator()(AppType& /*app*/, HostType& /*host*/) const {}
};

/// Streams `job` to the App while it runs, one submission attempt per tick, until the App is idle
/// again (the test fails, with the App's state, if it is not within `max_ticks`). Before each tick
/// `between_ticks(app, host)` may send commands (the App takes them before that tick).
template <class AppType, class BetweenTicks = NothingBetweenTicks>
void stream_job(Host<AppType>& host, AppType& app, FakeBoard& board, const std::vector<protocol::QueueSegment>& job,
                int max_ticks = 200000, BetweenTicks between_ticks = {}) {
  JobUpload upload(job);
  for (int t = 0; t < max_ticks; ++t) {
    between_ticks(app, host);
    REQUIRE(upload.step(host.sender(), t));
    app.on_tick();
    ++board.clock_ms;
    host.pump();
    if (upload.all_sent() && !app.moving() && app.state() == protocol::MachineState::Idle && host.sender().idle()) {
      return;
    }
  }
  INFO("state " << static_cast<int>(app.state()) << " moving " << app.moving() << " queued "
                 << app.controller().queued() << " controller " << static_cast<int>(app.controller().state())
                 << " sent " << upload.segments_sent() << " errors " << host.received.errors.size() << " credit "
                 << host.sender().credit() << " in flight " << host.sender().in_flight());
  INFO("first error " << (host.received.errors.empty() ? 0 : static_cast<int>(host.received.errors[0].code)) << " at "
                       << (host.received.errors.empty() ? 0 : host.received.errors[0].index) << " clock " << board.clock_ms);
  FAIL("the job did not finish");
}

}  // namespace curvestep::firmware::testing
