// SPDX-License-Identifier: MIT
// FakeBoard and a scripted host for App tests: serial bytes in memory, a settable clock, edge counts.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <span>
#include <vector>

#include <curvestep/core/motion/step_generator.hpp>
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

/// What the host received, decoded.
struct Received {
  std::vector<protocol::StatusReport> status;
  std::vector<protocol::SetpointBatch> batches;
  std::vector<protocol::ErrorReport> errors;
  std::vector<protocol::Nak> naks;
  std::vector<protocol::Ack> acks;
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
      for (std::size_t i = 0; i < r.value(); ++i) board_.incoming.push_back(frame[i]);
    }
    app_.poll();
    take_output();
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
    for (std::size_t i = 0; i < size.value(); ++i) board_.incoming.push_back(frame[i]);
  }

  FakeBoard& board_;
  AppType& app_;
  protocol::LinkSender<8> sender_;
  protocol::LinkReceiver receiver_;
  protocol::FrameDecoder<> decoder_;
};

/// The host's side of streaming a job while the App runs, one step per control tick: every segment
/// the window and the credit allow, Start once it fits, and a StatusRequest every 100 ticks (a host
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
    if (!started_ && sender.can_submit(protocol::MessageType::Start)) {
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

}  // namespace curvestep::firmware::testing
