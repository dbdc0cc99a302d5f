// SPDX-License-Identifier: MIT
// Rules of docs/protocol.md that a document-only client found broken or unsaid (issues 21, 24):
// configuration per session, NothingQueued, the failed setpoint stream, RetransmitLimit, control
// rates, Hello edge cases, axis counts of segments, a refused configuration.
#include <catch2/catch.hpp>

#include <cstdint>
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

struct Rig {
  explicit Rig(AppSettings settings = {}) : app(board, settings), host(board, app) {}
  void configure(const MachineConfiguration& c = machine(50)) {
    REQUIRE(host.send(Message(c)));
    host.pump(5);
  }
  FakeBoard board;
  TestApp app;
  Host<TestApp> host;
};

QueueSegment ending(QueueSegment s) {
  s.end_of_job = true;
  return s;
}

/// The App's answers to raw frames (the host link bypassed): each frame's type and, for a Nak, its reason.
struct Answer {
  MessageType type;
  Error reason;
};
std::vector<Answer> raw_answers(FakeBoard& board) {
  std::vector<Answer> out;
  FrameDecoder<> decoder;
  for (const std::byte b : board.outgoing) {
    const auto pushed = decoder.push(b);
    if (!pushed || !pushed.value()) continue;
    const auto m = decode_message(decoder.frame());
    if (!m) continue;
    out.push_back(Answer{m.value().type(), m.value().holds<Nak>() ? m.value().get<Nak>().reason : Error{}});
  }
  board.outgoing.clear();
  return out;
}

}  // namespace

TEST_CASE("protocol rules: a new session starts without a configuration (Start and segments: ConfigurationMissing)",
          "[firmware][app][rules]") {
  Rig rig;
  REQUIRE(rig.host.connect());
  rig.configure();
  REQUIRE(rig.app.configured());
  Host<TestApp> second(rig.board, rig.app);
  REQUIRE(second.connect(0x4321));
  CHECK(second.received.last_capabilities.credit_end == 0);  // no credit until configured
  CHECK_FALSE(rig.app.configured());
  REQUIRE(second.send(Message(Start{})));
  second.pump(3);
  REQUIRE(second.received.errors.size() == 1);
  CHECK(second.received.errors[0].code == Error::ConfigurationMissing);
  CHECK(rig.app.state() == MachineState::Idle);
  // A segment without credit (a broken host) is still answered by the rule, not by the credit.
  send_raw(rig.board, line(p(0, 0), p(1, 0)), 1);
  second.pump(3);
  REQUIRE(second.received.errors.size() == 2);
  CHECK(second.received.errors[1].code == Error::ConfigurationMissing);
  CHECK(rig.app.controller().queued() == 0);
}

TEST_CASE("protocol rules: Start on an empty queue is NothingQueued and nothing is armed", "[firmware][app][rules]") {
  Rig rig;
  REQUIRE(rig.host.connect());
  rig.configure();
  REQUIRE(rig.host.send(Message(Start{})));
  rig.host.pump(3);
  REQUIRE(rig.host.received.errors.size() == 1);
  CHECK(rig.host.received.errors[0].code == Error::NothingQueued);
  CHECK(rig.app.state() == MachineState::Idle);
  // A later job starts normally.
  REQUIRE(rig.host.send(Message(ending(line(p(0, 0), p(1, 0))))));
  REQUIRE(rig.host.send(Message(Start{})));
  rig.host.run_ticks(2000);
  CHECK(rig.app.position() == p(1, 0));
  CHECK(rig.host.received.errors.size() == 1);
}

TEST_CASE("protocol rules: a host that talks but never acknowledges setpoints gets RetransmitLimit, and the session "
          "refuses new jobs until a new Hello (issue 24.1, 24.2)",
          "[firmware][app][rules]") {
  AppSettings settings;
  settings.stall_timeout_ms = 0;  // as `curvestep device --fast`: only the sender gives up
  settings.link_timeout_ms = 0;
  Rig rig(settings);
  REQUIRE(rig.host.connect());
  rig.configure();
  REQUIRE(rig.host.send(Message(ending(line(p(0, 0), p(30, 0))))));
  REQUIRE(rig.host.send(Message(Start{})));
  rig.host.pump(3);
  rig.host.acknowledge_setpoints = false;
  for (int i = 0; i < 400 && rig.app.state() != MachineState::Fault; ++i) {
    rig.app.on_tick();
    rig.board.clock_ms += 100;
    REQUIRE(rig.host.send(Message(StatusRequest{})));
    rig.host.pump();
  }
  rig.host.pump(2);
  REQUIRE(rig.app.state() == MachineState::Fault);
  REQUIRE_FALSE(rig.host.received.errors.empty());
  CHECK(rig.host.received.errors.back().code == Error::RetransmitLimit);
  CHECK(rig.app.last_error() == static_cast<std::uint8_t>(Error::RetransmitLimit));

  // Abort stops, but the stream stays failed: a new job is refused with the reason.
  rig.host.acknowledge_setpoints = true;
  const std::size_t errors = rig.host.received.errors.size();
  REQUIRE(rig.host.send(Message(Abort{})));
  REQUIRE(rig.host.send(Message(StatusRequest{})));
  rig.host.pump(3);
  CHECK(rig.app.state() == MachineState::Fault);
  REQUIRE(rig.host.send(Message(ending(line(rig.app.position(), p(31, 0))))));
  REQUIRE(rig.host.send(Message(Start{})));
  rig.host.pump(3);
  REQUIRE(rig.host.received.errors.size() == errors + 2);
  CHECK(rig.host.received.errors[errors].code == Error::RetransmitLimit);
  CHECK(rig.host.received.errors[errors + 1].code == Error::RetransmitLimit);

  // A new session restores the stream: the next job moves and streams its setpoints.
  Host<TestApp> second(rig.board, rig.app);
  REQUIRE(second.connect(0x4321));
  REQUIRE(second.send(Message(machine(50))));
  REQUIRE(second.send(Message(ending(line(p(0, 0), p(1, 0))))));
  REQUIRE(second.send(Message(Start{})));
  second.run_ticks(2000);
  CHECK(second.received.errors.empty());
  CHECK_FALSE(second.setpoints().empty());
  CHECK(rig.app.state() == MachineState::Idle);
}

TEST_CASE("protocol rules: in real time a stalled stream of a host that still talks is RetransmitLimit",
          "[firmware][app][rules]") {
  AppSettings settings;
  settings.stall_timeout_ms = 300;
  settings.link_timeout_ms = 0;
  Rig rig(settings);
  REQUIRE(rig.host.connect());
  rig.configure();
  REQUIRE(rig.host.send(Message(ending(line(p(0, 0), p(30, 0))))));
  REQUIRE(rig.host.send(Message(Start{})));
  rig.host.pump(3);
  rig.host.acknowledge_setpoints = false;
  for (int t = 0; t < 1000 && rig.app.state() != MachineState::Fault; ++t) {
    if (t % 50 == 0) REQUIRE(rig.host.send(Message(StatusRequest{})));
    rig.host.run_ticks(1);
  }
  rig.host.pump(2);
  REQUIRE(rig.app.state() == MachineState::Fault);
  REQUIRE_FALSE(rig.host.received.errors.empty());
  CHECK(rig.host.received.errors.back().code == Error::RetransmitLimit);
}

TEST_CASE("protocol rules: control rates the step timer cannot hold are InvalidRate naming the rate (issue 24.3)",
          "[firmware][app][rules]") {
  struct Case {
    std::uint32_t rate;
    double max_step_rate;
    bool accepted;
  };
  // FakeBoard: 1 MHz step timer, 2 us pulses, 1 us direction setup.
  for (const Case c : {Case{100000, 100000, true}, Case{50000, 100000, true}, Case{100, 100000, true},
                       Case{50000, 20000, false}, Case{3000, 100000, false}}) {
    INFO("rate " << c.rate << " max step rate " << c.max_step_rate);
    Rig rig;
    REQUIRE(rig.host.connect());
    MachineConfiguration config = machine(50);
    config.control_rate_hz = c.rate;
    config.max_step_rate_hz = c.max_step_rate;
    rig.configure(config);
    if (c.accepted) {
      CHECK(rig.host.received.errors.empty());
      CHECK(rig.app.control_rate_hz() == c.rate);
    } else {
      REQUIRE(rig.host.received.errors.size() == 1);
      CHECK(rig.host.received.errors[0].code == Error::InvalidRate);
      CHECK(rig.host.received.errors[0].index == static_cast<std::uint16_t>(LimitField::RateHz));
    }
  }
}

TEST_CASE("protocol rules: a Hello of the wrong length is VersionMismatch, its sequence byte is not looked at",
          "[firmware][app][rules]") {
  FakeBoard board;
  TestApp app(board);
  const std::array<std::byte, 6> longer{std::byte{4}, std::byte{0}, std::byte{0x34}, std::byte{0x12}, std::byte{0}, std::byte{0}};
  send_raw(board, 0x01, 0, longer);
  app.poll();
  auto answers = raw_answers(board);
  REQUIRE(answers.size() == 1);
  CHECK(answers[0].type == MessageType::Nak);
  CHECK(answers[0].reason == Error::VersionMismatch);
  CHECK(app.phase() == Phase::NotConnected);

  send_raw(board, Hello{protocol_version, 0x1234}, 7);
  app.poll();
  answers = raw_answers(board);
  REQUIRE(answers.size() == 1);
  CHECK(answers[0].type == MessageType::Capabilities);
  CHECK(app.phase() == Phase::Connected);
}

TEST_CASE("protocol rules: a 2-axis segment has z = 0, and a 3-axis segment under a 2-axis configuration is refused",
          "[firmware][app][rules]") {
  Rig rig;
  REQUIRE(rig.host.connect());
  rig.configure();
  REQUIRE(rig.host.send(Message(line(p(0, 0, 0), p(1, 0, 2)))));
  REQUIRE(rig.host.send(Message(line(p(1, 0), p(2, 0), 2))));  // its z is 0, the machine's is 2
  rig.host.pump(3);
  REQUIRE(rig.host.received.errors.size() == 1);
  CHECK(rig.host.received.errors[0].code == Error::SegmentsNotConnected);
  CHECK(rig.host.received.errors[0].index == 1);

  Rig two;
  REQUIRE(two.host.connect());
  MachineConfiguration config = machine(50);
  config.axis_count = 2;
  two.configure(config);
  REQUIRE(two.host.received.errors.empty());
  REQUIRE(two.host.send(Message(line(p(0, 0, 0), p(1, 0, 0)))));  // three axes
  two.host.pump(3);
  REQUIRE(two.host.received.errors.size() == 1);
  CHECK(two.host.received.errors[0].code == Error::InvalidArgument);
  CHECK(two.host.received.errors[0].index == 1);  // the flags byte, which carries the axis count
}

TEST_CASE("protocol rules: a refused configuration leaves the one in force", "[firmware][app][rules]") {
  Rig rig;
  REQUIRE(rig.host.connect());
  rig.configure();
  MachineConfiguration bad = machine(50);
  bad.control_rate_hz = 2000;
  bad.max_velocity_mm_per_s = 5e-324;
  rig.configure(bad);
  REQUIRE(rig.host.received.errors.size() == 1);
  CHECK(rig.host.received.errors[0].code == Error::InvalidLimit);
  CHECK(rig.host.received.errors[0].index == static_cast<std::uint16_t>(LimitField::VMax));
  CHECK(rig.app.configured());
  CHECK(rig.app.control_rate_hz() == 1000);
  REQUIRE(rig.host.send(Message(ending(line(p(0, 0), p(1, 0))))));
  REQUIRE(rig.host.send(Message(Start{})));
  rig.host.run_ticks(2000);
  CHECK(rig.host.received.errors.size() == 1);
  CHECK(rig.app.position() == p(1, 0));
}
