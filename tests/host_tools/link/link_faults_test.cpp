// SPDX-License-Identifier: MIT
// The link after the handshake under faults (issue 19 items 4, 5, 6), against a firmware App in
// this process (in_process_device.hpp) behind Transport wrappers that damage or interrupt it:
//   * 20 % duplicated bytes both ways: the upload ends with a clear error instead of running for
//     ever, no stretch without progress longer than the link timeout, and the device stops;
//   * a host that vanishes mid-job leaves a held device with a LinkTimeout report in the line;
//     the next session's first job runs;
//   * a device frozen for 1.5 s (its clock jumps, as after SIGSTOP/SIGCONT) with a 30 s link
//     timeout on both ends: the job goes on;
//   * a host away from the line for longer than its link timeout (planning, or not scheduled on a
//     loaded machine) keeps its session: the controller's heartbeats and answers waiting in the
//     line are read before silence is judged.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstddef>
#include <random>
#include <regex>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/firmware/app.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/link/host_link.hpp>
#include <curvestep/host/link/streamer.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/protocol/frame_decoder.hpp>
#include <curvestep/protocol/messages.hpp>

#include "in_process_device.hpp"

using namespace curvestep;
namespace hl = curvestep::host::link;
using Clock = std::chrono::steady_clock;

namespace {

using PlanningApp = firmware::App<firmware::testing::FakeBoard, Q16_16, 17, 9>;
const std::filesystem::path examples = CURVESTEP_EXAMPLE_JOBS;

/// The match of `pattern` in `text` (empty if none).
std::smatch match(const std::string& text, const std::regex& pattern) {
  std::smatch found;
  std::regex_search(text, found, pattern);
  return found;
}

/// Ends a test that would run for ever: the transport throws after `limit`.
class Deadline {
 public:
  explicit Deadline(std::chrono::seconds limit) : end_(Clock::now() + limit), limit_(limit) {}
  void check() const {
    if (Clock::now() > end_) throw std::runtime_error("no result after " + std::to_string(limit_.count()) + " s");
  }

 private:
  Clock::time_point end_;
  std::chrono::seconds limit_;
};

/// Watches the host's progress from the frames it writes and receives, independently of its own
/// bookkeeping (docs/protocol.md, "Sequence numbers, acknowledgements, retransmission"): a stretch
/// without progress runs while commands are outstanding (sent, not yet acknowledged) and no Ack or
/// Nak from the controller acknowledges more of them. Keeps the longest stretch.
class ProgressWatch {
 public:
  /// Takes bytes as the host writes them (before the line damages them).
  void sent(std::span<const std::byte> bytes) {
    for (const std::byte b : bytes) {
      const auto pushed = sent_decoder_.push(b);
      if (pushed && pushed.value()) on_sent(sent_decoder_.frame());
    }
  }
  /// Takes bytes as the host receives them.
  void received(std::span<const std::byte> bytes) {
    for (const std::byte b : bytes) {
      const auto pushed = received_decoder_.push(b);
      if (pushed && pushed.value()) on_received(received_decoder_.frame());
    }
  }
  /// The longest stretch without progress, the one still open at `end` included.
  [[nodiscard]] std::chrono::milliseconds longest_stretch(Clock::time_point end) const {
    return std::max(std::chrono::duration_cast<std::chrono::milliseconds>(longest_), open_stretch(end));
  }
  /// The stretch still open at `end` (0 if nothing is outstanding).
  [[nodiscard]] std::chrono::milliseconds open_stretch(Clock::time_point end) const {
    return open_ ? std::chrono::duration_cast<std::chrono::milliseconds>(end - since_) : std::chrono::milliseconds(0);
  }
  /// Acknowledgements that moved the window.
  [[nodiscard]] std::size_t events() const { return events_; }

 private:
  void on_sent(const protocol::Frame& frame) {
    if (!protocol::is_sequenced(static_cast<protocol::MessageType>(frame.type))) return;
    const auto next = static_cast<std::uint8_t>(frame.sequence + 1);
    if (static_cast<std::int8_t>(next - next_sent_) > 0) next_sent_ = next;  // a retransmission changes nothing
    if (!open_) {
      open_ = true;
      since_ = Clock::now();
    }
  }
  void on_received(const protocol::Frame& frame) {
    const auto type = static_cast<protocol::MessageType>(frame.type);
    if (type == protocol::MessageType::Ack) {
      if (const auto ack = protocol::decode<protocol::Ack>(frame.payload)) acknowledged(ack.value().next_expected);
    } else if (type == protocol::MessageType::Nak) {
      if (const auto nak = protocol::decode<protocol::Nak>(frame.payload)) acknowledged(nak.value().expected);
    }
  }
  void acknowledged(std::uint8_t next_expected) {
    if (static_cast<std::int8_t>(next_expected - acknowledged_) <= 0) return;  // a repeat (heartbeat) or a stale one
    acknowledged_ = next_expected;
    const Clock::time_point now = Clock::now();
    if (open_) longest_ = std::max(longest_, now - since_);
    ++events_;
    open_ = static_cast<std::int8_t>(next_sent_ - acknowledged_) > 0;  // more outstanding: a new stretch
    since_ = now;
  }

  protocol::FrameDecoder<> sent_decoder_;
  protocol::FrameDecoder<> received_decoder_;
  std::uint8_t next_sent_ = 0;     // the host's commands are numbered from 0 in each session (Hello is not sequenced)
  std::uint8_t acknowledged_ = 0;  // every command before this one is acknowledged
  bool open_ = false;              // commands outstanding since `since_`
  Clock::time_point since_{};
  Clock::duration longest_{};
  std::size_t events_ = 0;
};

/// Duplicates each byte with probability `rate` in both directions, once the host has sent its
/// first frame after Hello (a clean handshake); watches the host's progress.
class DuplicatingLine final : public hl::Transport {
 public:
  DuplicatingLine(hl::Transport& device, double rate) : device_(device), rate_(rate) {}

  std::size_t read(std::span<std::byte> out, int timeout_ms) override {
    deadline_.check();
    if (writes_ < 2) {
      const std::size_t n = device_.read(out, timeout_ms);
      watch_.received(out.first(n));
      return n;
    }
    std::array<std::byte, 256> raw{};
    const std::size_t n = device_.read(std::span<std::byte>(raw.data(), out.size() / 2 < raw.size() ? out.size() / 2 : raw.size()), timeout_ms);
    std::size_t k = 0;
    for (std::size_t i = 0; i < n; ++i) {
      out[k++] = raw[i];
      if (chance_(random_) < rate_) out[k++] = raw[i];
    }
    watch_.received(out.first(k));
    return k;
  }
  void write(std::span<const std::byte> bytes) override {
    watch_.sent(bytes);
    if (++writes_ <= 2) return device_.write(bytes);
    std::vector<std::byte> copy;
    for (const std::byte b : bytes) {
      copy.push_back(b);
      if (chance_(random_) < rate_) copy.push_back(b);
    }
    device_.write(copy);
  }
  [[nodiscard]] const std::string& name() const override { return name_; }
  /// The host's progress through the damaged line.
  [[nodiscard]] const ProgressWatch& progress() const { return watch_; }

 private:
  hl::Transport& device_;
  double rate_;
  std::size_t writes_ = 0;
  std::mt19937 random_{19};
  std::uniform_real_distribution<double> chance_{0.0, 1.0};
  Deadline deadline_{std::chrono::seconds(40)};  // a livelock ends here, failing the test
  ProgressWatch watch_;
  std::string name_ = "duplicating line";
};

/// Passes everything until the device has sent `cut_after` bytes, then the host's line closes.
class CutLine final : public hl::Transport {
 public:
  CutLine(hl::Transport& device, std::size_t cut_after) : device_(device), cut_after_(cut_after) {}
  std::size_t read(std::span<std::byte> out, int timeout_ms) override {
    if (received_ >= cut_after_) throw hl::TransportError("cut line: closed");
    const std::size_t n = device_.read(out, timeout_ms);
    received_ += n;
    return n;
  }
  void write(std::span<const std::byte> bytes) override { device_.write(bytes); }
  [[nodiscard]] const std::string& name() const override { return name_; }

 private:
  hl::Transport& device_;
  std::size_t cut_after_;
  std::size_t received_ = 0;
  std::string name_ = "cut line";
};

/// Freezes the device for `pause` once it has sent `after` bytes: it neither runs nor answers
/// (the host's bytes wait in its input), and its clock jumps when it thaws, as after SIGSTOP and
/// SIGCONT.
class FreezingLine final : public hl::Transport {
 public:
  FreezingLine(hl::Transport& device, std::size_t after, std::chrono::milliseconds pause)
      : device_(device), after_(after), pause_(pause) {}
  std::size_t read(std::span<std::byte> out, int timeout_ms) override {
    deadline_.check();
    if (received_ >= after_ && !frozen_once_) {
      frozen_once_ = true;
      thaw_ = Clock::now() + pause_;
    }
    if (frozen_once_ && Clock::now() < thaw_) return 0;
    const std::size_t n = device_.read(out, timeout_ms);
    received_ += n;
    return n;
  }
  void write(std::span<const std::byte> bytes) override { device_.write(bytes); }
  [[nodiscard]] const std::string& name() const override { return name_; }
  [[nodiscard]] bool froze() const { return frozen_once_; }

 private:
  hl::Transport& device_;
  std::size_t after_;
  std::chrono::milliseconds pause_;
  std::size_t received_ = 0;
  bool frozen_once_ = false;
  Clock::time_point thaw_{};
  Deadline deadline_{std::chrono::seconds(60)};
  std::string name_ = "freezing line";
};

}  // namespace

TEST_CASE("link faults: 20 % duplicated bytes both ways after a clean handshake end in a clear error within the link timeout",
          "[host_tools][link][robustness]") {
  const auto machine = host::load_machine(examples / "machine.json");
  const auto job = host::load_job(examples / "helix.json");
  hl::testing::InProcessDevice<PlanningApp> device;
  DuplicatingLine line(device, 0.2);
  const hl::StreamOptions options;  // the default link timeout
  // docs/robustness.md ("No livelock") and docs/protocol.md: each stretch without progress is at
  // most the link timeout, 3000 ms by default. The whole run is not bounded by it (a frame gets
  // through now and then, and a loaded machine runs the in-process device slower); a livelock
  // never ends and meets the line's 40 s deadline, which fails the test.
  const std::chrono::milliseconds documented_link_timeout{3000};
  // The host notices the timeout on its next pass through its loop (milliseconds apart unloaded):
  // 1 s of slack covers that on a loaded machine, and is far less than a second timeout.
  const std::chrono::milliseconds slack{1000};
  const auto start = Clock::now();
  try {
    (void)hl::stream_job(line, job, machine, options);
    FAIL("a job streamed through 20 % duplicated bytes");
  } catch (const hl::StreamError& e) {
    const auto end = Clock::now();
    const auto took = std::chrono::duration_cast<std::chrono::milliseconds>(end - start);
    const auto longest = line.progress().longest_stretch(end);
    const auto last = line.progress().open_stretch(end);
    const std::string text = e.what();
    INFO(text << " after " << took.count() << " ms; stretches without progress: longest " << longest.count() << " ms, last "
              << last.count() << " ms, after " << line.progress().events() << " acknowledgement(s) that moved the window");
    CHECK((e.code() == Error::RetransmitLimit || e.code() == Error::LinkTimeout));
    CHECK(longest <= documented_link_timeout + slack);
    // The watch sees the progress the host counts: the host's own last stretch ("no progress for T
    // ms"; it may end before the link timeout, after max_retransmits timeouts with the controller
    // heard) is the one still open here, which began no later (less the host's whole-millisecond clock).
    const std::smatch host_stretch = match(text, std::regex("no progress for ([0-9]+) ms"));
    REQUIRE(host_stretch.size() == 2);
    CHECK(last >= std::chrono::milliseconds(std::stol(host_stretch[1].str())) - std::chrono::milliseconds(2));
  }
  // The host is gone: the device stops (held by its own link timeout, 1 s) and moves no more.
  device.run_unattended(std::chrono::milliseconds(1500));
  CHECK(device.app().state() != protocol::MachineState::Running);
}

TEST_CASE("link faults: after a link-timeout hold the first job of a new session runs", "[host_tools][link][robustness]") {
  const auto machine = host::load_machine(examples / "machine.json");
  hl::testing::InProcessDevice<PlanningApp> device;
  {
    CutLine line(device, 4000);
    CHECK_THROWS(hl::stream_job(line, host::load_job(examples / "helix.json"), machine, {}));
  }
  device.run_unattended(std::chrono::milliseconds(1500));  // link timeout 1000 ms: held, ErrorReport(LinkTimeout) queued
  REQUIRE(device.app().phase() == firmware::Phase::Holding);
  REQUIRE(device.app().last_error() == static_cast<std::uint8_t>(Error::LinkTimeout));
  const hl::StreamResult result = hl::stream_job(device, host::load_job(examples / "seed_cubic.json"), machine, {});
  CHECK(!result.setpoints.empty());
  CHECK(device.app().last_error() == 0);
}

TEST_CASE("link faults: a device frozen for 1.5 s with a 30 s link timeout on both ends finishes its job",
          "[host_tools][link][robustness]") {
  const auto machine = host::load_machine(examples / "machine.json");
  const auto job = host::load_job(examples / "helix.json");
  firmware::AppSettings settings;
  settings.link_timeout_ms = 30000;  // as `curvestep device --link-timeout-ms 30000` (stall timeout stays 1000)
  hl::testing::InProcessDevice<PlanningApp> device(settings);
  FreezingLine line(device, 6000, std::chrono::milliseconds(1500));
  hl::StreamOptions options;
  options.link.link_timeout_ms = 30000;
  const hl::StreamResult result = hl::stream_job(line, job, machine, options);
  CHECK(line.froze());
  CHECK(result.standing_ticks == 0);
  CHECK(!result.setpoints.empty());
}

TEST_CASE("link faults: a host that does not read the line for twice its link timeout keeps the session: the heartbeats waiting count",
          "[host_tools][link][robustness]") {
  // The device heartbeats every 250 ms (AppSettings::ack_interval_ms); the host's link timeout is
  // 300 ms and it is away for 700 ms. Before the host read what waited, its sender judged 700 ms
  // of silence first: "the controller stopped answering" (the HIL check-through test's failure on
  // a loaded machine, where planning kept the host away from the line).
  hl::testing::InProcessDevice<PlanningApp> device;
  protocol::SenderSettings settings;
  settings.link_timeout_ms = 300;
  hl::HostLink host(device, settings);
  host.connect({});
  host.pump(0, {});
  const std::size_t heard = host.statistics().frames_received;
  device.run_unattended(std::chrono::milliseconds(700));
  CHECK_NOTHROW(host.pump(0, {}));
  CHECK(host.statistics().frames_received >= heard + 2);  // the heartbeats of the 700 ms
  int reports = 0;  // and the session still answers
  host.submit(protocol::Message(protocol::StatusRequest{}));
  for (int i = 0; i < 50 && reports == 0; ++i) {
    host.pump(1, [&reports](const protocol::Message& m) { reports += m.type() == protocol::MessageType::StatusReport; });
  }
  CHECK(reports == 1);
}
