// SPDX-License-Identifier: MIT
// The state table of docs/protocol.md, cell by cell: every phase, every host message, through
// the real App on the fake board (raw frames, so every answer is seen as sent). The expected
// answers are copied from the document's table, not from the code.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <curvestep/firmware/app.hpp>
#include <curvestep/protocol/frame_decoder.hpp>

#include "fake_board.hpp"

using namespace curvestep;
using namespace curvestep::firmware;
using namespace curvestep::protocol;
using namespace curvestep::firmware::testing;

namespace {

using TestApp = App<FakeBoard>;

/// The host messages of the table's columns.
enum class Col { Hello, HelloAgain, Configuration, Segment, Piece, Start, FeedHold, Resume, Abort, Status, Unknown };

/// One cell: the answer and the next phase.
struct Cell {
  Col message;
  std::string answer;  // "Capabilities", "Nak NotConnected", "Ack", "Ack + Error <code> <index>", "Ack + Status <state>"
  Phase next;
};

/// Everything the App wrote, as text: "Ack", "Nak 109", "Error 173 65535", "Status 0", "Capabilities".
std::vector<std::string> answers(FakeBoard& board) {
  std::vector<std::string> out;
  FrameDecoder<> decoder;
  for (const std::byte b : board.outgoing) {
    const auto pushed = decoder.push(b);
    if (!pushed || !pushed.value()) continue;
    const auto m = decode_message(decoder.frame());
    if (!m) continue;
    switch (m.value().type()) {
      case MessageType::Ack:  // one Ack per command; a further one only announces grown credit
        if (std::find(out.begin(), out.end(), "Ack") == out.end()) out.emplace_back("Ack");
        break;
      case MessageType::Nak: out.push_back("Nak " + std::to_string(static_cast<int>(m.value().get<Nak>().reason))); break;
      case MessageType::Capabilities: out.emplace_back("Capabilities"); break;
      case MessageType::ErrorReport: {
        const auto& e = m.value().get<ErrorReport>();
        out.push_back("Error " + std::to_string(static_cast<int>(e.code)) + " " + std::to_string(e.index));
        break;
      }
      case MessageType::StatusReport:
        out.push_back("Status " + std::to_string(static_cast<int>(m.value().get<StatusReport>().state)));
        break;
      default: break;  // setpoint batches are not answers
    }
  }
  board.outgoing.clear();
  return out;
}

/// A fake board, an App and a raw host that numbers its commands itself and never acknowledges
/// setpoints.
struct TableRig {
  explicit TableRig(AppSettings settings) : app(board, settings) {}

  void hello(std::uint16_t session) {
    send_raw(board, Hello{protocol_version, session}, 0);
    app.poll();
  }
  template <class M>
  void command(const M& m) {
    send_raw(board, m, sequence++);
    app.poll();
  }
  void unknown() {
    send_raw(board, 0x30, sequence++, std::span<const std::byte>());
    app.poll();
  }

  FakeBoard board;
  TestApp app;
  std::uint8_t sequence = 0;
};

AppSettings table_settings() {
  AppSettings s;
  s.link_timeout_ms = 0;     // the clock moves only where a row needs it
  s.stall_timeout_ms = 100;  // the Fault row: a stalled setpoint stream
  return s;
}

/// `s` marked as the job's last segment.
QueueSegment ending(QueueSegment s) {
  s.end_of_job = true;
  return s;
}

/// The job's segment: a line from where the test machine stands, not ending the job.
QueueSegment first_segment() { return line(p(0, 0), p(30, 0)); }

/// Brings `rig` into `phase` through the wire.
void reach(TableRig& rig, Phase phase) {
  if (phase == Phase::NotConnected) return;
  rig.hello(0x1234);
  if (phase == Phase::Connected) return;
  rig.command(machine(50));
  if (phase == Phase::Configured) return;
  if (phase == Phase::StreamFailed) {
    // A job that moves; the host never acknowledges a setpoint but keeps asking for its status:
    // after 255 retransmission timeouts the stream gives up with RetransmitLimit.
    rig.command(ending(first_segment()));
    rig.command(Start{});
    for (int i = 0; i < 400 && rig.app.phase() != Phase::StreamFailed; ++i) {
      rig.app.on_tick();
      rig.board.clock_ms += 100;
      rig.command(StatusRequest{});
    }
    rig.app.poll();  // the fault's report
    return;
  }
  rig.command(first_segment());
  if (phase == Phase::Queued) return;
  if (phase == Phase::Fault) {
    rig.command(ending(line(p(30, 0), p(31, 0))));
    rig.command(Start{});
    // The never-acknowledged setpoints back the stream up; a stall of 100 ms is a Fault.
    for (int i = 0; i < 400 && rig.app.phase() != Phase::Fault; ++i) {
      rig.app.on_tick();
      ++rig.board.clock_ms;
      rig.app.poll();
    }
    rig.app.poll();  // the fault's report
    return;
  }
  rig.command(Start{});  // armed: one segment, the job's end not known yet
  if (phase == Phase::Running) return;
  rig.command(FeedHold{});  // Holding
}

/// Sends the column's message and returns the answers as one string.
std::string send_column(TableRig& rig, Col c) {
  switch (c) {
    case Col::Hello: rig.hello(0x5678); break;
    case Col::HelloAgain: rig.hello(0x1234); break;
    case Col::Configuration: rig.command(machine(50)); break;
    case Col::Segment: rig.command(first_segment()); break;
    case Col::Piece: {
      QueuePiece piece;
      piece.axis_count = 3;
      piece.ticks = 1;
      rig.command(piece);
      break;
    }
    case Col::Start: rig.command(Start{}); break;
    case Col::FeedHold: rig.command(FeedHold{}); break;
    case Col::Resume: rig.command(Resume{}); break;
    case Col::Abort: rig.command(Abort{}); break;
    case Col::Status: rig.command(StatusRequest{}); break;
    case Col::Unknown: rig.unknown(); break;
  }
  std::string text;
  for (const auto& a : answers(rig.board)) text += (text.empty() ? "" : " + ") + a;
  return text;
}

// Codes (docs/errors.md): 52 QueueFull, 78 NothingQueued, 77 PlannerBusy, 104 UnknownMessage,
// 109 NotConnected, 110 RetransmitLimit, 170 InvalidState, 173 ConfigurationMissing.
// States in a StatusReport: 0 Idle, 1 Running, 2 Holding, 3 Fault. 65535: no index.
const std::string refused_piece = "Ack + Error 104 23";  // QueuePiece (0x17) on a planner: UnknownMessage, index = type
const std::string unknown = "Ack + Error 104 48";        // type 0x30: UnknownMessage, index = type

// clang-format off
const std::vector<std::pair<Phase, std::vector<Cell>>> table = {
  {Phase::NotConnected, {
    {Col::Hello, "Capabilities", Phase::Connected},
    {Col::Configuration, "Nak 109", Phase::NotConnected},
    {Col::Segment, "Nak 109", Phase::NotConnected},
    {Col::Piece, "Nak 109", Phase::NotConnected},
    {Col::Start, "Nak 109", Phase::NotConnected},
    {Col::FeedHold, "Nak 109", Phase::NotConnected},
    {Col::Resume, "Nak 109", Phase::NotConnected},
    {Col::Abort, "Nak 109", Phase::NotConnected},
    {Col::Status, "Nak 109", Phase::NotConnected},
    {Col::Unknown, "Nak 109", Phase::NotConnected}}},
  {Phase::Connected, {
    {Col::Hello, "Capabilities", Phase::Connected},
    {Col::HelloAgain, "Capabilities", Phase::Connected},
    {Col::Configuration, "Ack", Phase::Configured},
    {Col::Segment, "Ack + Error 173 65535", Phase::Connected},
    {Col::Piece, refused_piece, Phase::Connected},
    {Col::Start, "Ack + Error 173 65535", Phase::Connected},
    {Col::FeedHold, "Ack", Phase::Connected},
    {Col::Resume, "Ack + Error 170 65535", Phase::Connected},
    {Col::Abort, "Ack", Phase::Connected},
    {Col::Status, "Ack + Status 0", Phase::Connected},
    {Col::Unknown, unknown, Phase::Connected}}},
  {Phase::Configured, {
    {Col::Hello, "Capabilities", Phase::Connected},
    {Col::HelloAgain, "Capabilities", Phase::Configured},
    {Col::Configuration, "Ack", Phase::Configured},
    {Col::Segment, "Ack", Phase::Queued},
    {Col::Piece, refused_piece, Phase::Configured},
    {Col::Start, "Ack + Error 78 65535", Phase::Configured},
    {Col::FeedHold, "Ack", Phase::Configured},
    {Col::Resume, "Ack + Error 170 65535", Phase::Configured},
    {Col::Abort, "Ack", Phase::Configured},
    {Col::Status, "Ack + Status 0", Phase::Configured},
    {Col::Unknown, unknown, Phase::Configured}}},
  {Phase::Queued, {
    {Col::Hello, "Capabilities", Phase::Connected},
    {Col::HelloAgain, "Capabilities", Phase::Queued},
    {Col::Configuration, "Ack + Error 77 65535", Phase::Queued},
    {Col::Piece, refused_piece, Phase::Queued},
    {Col::Start, "Ack", Phase::Running},
    {Col::FeedHold, "Ack", Phase::Queued},
    {Col::Resume, "Ack + Error 170 65535", Phase::Queued},
    {Col::Abort, "Ack", Phase::Configured},
    {Col::Status, "Ack + Status 0", Phase::Queued},
    {Col::Unknown, unknown, Phase::Queued}}},
  {Phase::Running, {
    {Col::Hello, "Capabilities", Phase::Connected},
    {Col::HelloAgain, "Capabilities", Phase::Running},
    {Col::Configuration, "Ack + Error 77 65535", Phase::Running},
    {Col::Piece, refused_piece, Phase::Running},
    {Col::Start, "Ack + Error 170 65535", Phase::Running},
    {Col::FeedHold, "Ack", Phase::Holding},
    {Col::Resume, "Ack + Error 170 65535", Phase::Running},
    {Col::Abort, "Ack", Phase::Configured},
    {Col::Status, "Ack + Status 1", Phase::Running},
    {Col::Unknown, unknown, Phase::Running}}},
  {Phase::Holding, {
    {Col::Hello, "Capabilities", Phase::Connected},
    {Col::HelloAgain, "Capabilities", Phase::Holding},
    {Col::Configuration, "Ack + Error 77 65535", Phase::Holding},
    {Col::Piece, refused_piece, Phase::Holding},
    {Col::Start, "Ack + Error 170 65535", Phase::Holding},
    {Col::FeedHold, "Ack", Phase::Holding},
    {Col::Resume, "Ack", Phase::Running},
    {Col::Abort, "Ack", Phase::Configured},
    {Col::Status, "Ack + Status 2", Phase::Holding},
    {Col::Unknown, unknown, Phase::Holding}}},
  {Phase::Fault, {
    {Col::Hello, "Capabilities", Phase::Connected},
    {Col::HelloAgain, "Capabilities", Phase::Fault},
    {Col::Configuration, "Ack + Error 170 65535", Phase::Fault},
    {Col::Segment, "Ack + Error 170 65535", Phase::Fault},
    {Col::Piece, refused_piece, Phase::Fault},
    {Col::Start, "Ack + Error 170 65535", Phase::Fault},
    {Col::FeedHold, "Ack", Phase::Fault},
    {Col::Resume, "Ack + Error 170 65535", Phase::Fault},
    {Col::Abort, "Ack", Phase::Configured},
    {Col::Status, "Ack + Status 3", Phase::Fault},
    {Col::Unknown, unknown, Phase::Fault}}},
  {Phase::StreamFailed, {
    {Col::Hello, "Capabilities", Phase::Connected},
    {Col::HelloAgain, "Capabilities", Phase::StreamFailed},
    {Col::Configuration, "Ack + Error 110 65535", Phase::StreamFailed},
    {Col::Segment, "Ack + Error 110 65535", Phase::StreamFailed},
    {Col::Piece, refused_piece, Phase::StreamFailed},
    {Col::Start, "Ack + Error 110 65535", Phase::StreamFailed},
    {Col::FeedHold, "Ack", Phase::StreamFailed},
    {Col::Resume, "Ack + Error 110 65535", Phase::StreamFailed},
    {Col::Abort, "Ack", Phase::StreamFailed},
    {Col::Status, "Ack + Status 3", Phase::StreamFailed},
    {Col::Unknown, unknown, Phase::StreamFailed}}},
};
// clang-format on

}  // namespace

TEST_CASE("state table: every phase answers every host message as docs/protocol.md says", "[firmware][app][state]") {
  for (const auto& [phase, cells] : table) {
    for (const Cell& cell : cells) {
      INFO("phase " << static_cast<int>(phase) << ", message column " << static_cast<int>(cell.message));
      TableRig rig(table_settings());
      reach(rig, phase);
      REQUIRE(rig.app.phase() == phase);
      answers(rig.board);  // what reaching the phase produced
      CHECK(send_column(rig, cell.message) == cell.answer);
      CHECK(rig.app.phase() == cell.next);
    }
  }
}

TEST_CASE("state table: a segment while a job is queued, running or holding takes credit and is queued",
          "[firmware][app][state]") {
  // The Queued, Running and Holding rows' QueueSegment cell: a segment that continues the job.
  for (const Phase phase : {Phase::Queued, Phase::Running, Phase::Holding}) {
    INFO("phase " << static_cast<int>(phase));
    TableRig rig(table_settings());
    reach(rig, phase);
    answers(rig.board);
    rig.command(line(p(30, 0), p(31, 0)));
    CHECK(answers(rig.board) == std::vector<std::string>{"Ack"});
    CHECK(rig.app.phase() == phase);
    CHECK(rig.app.controller().queued() == 2);
  }
}
