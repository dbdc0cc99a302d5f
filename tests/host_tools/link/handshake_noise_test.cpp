// SPDX-License-Identifier: MIT
// The handshake under noise (issue 19.10): the host keeps trying for its documented time, with a
// pause that grows between rounds of Hellos, and when it gives up it says what arrived. The device
// is a firmware App in this process whose replies are damaged (one byte of every frame flipped)
// for a while, or for ever.
#include <chrono>
#include <cstddef>
#include <span>
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/firmware/app.hpp>
#include <curvestep/host/link/host_link.hpp>

#include "in_process_device.hpp"

using namespace curvestep;
namespace hl = curvestep::host::link;

namespace {

using PlanningApp = firmware::App<firmware::testing::FakeBoard, Q16_16, 17, 9>;

/// The device's bytes with the first byte of every frame (its COBS code byte) changed while
/// `damaging()` says so: the frame is damaged, the delimiters kept. Frame starts are tracked across
/// reads, so a frame split between two reads is damaged too.
class DamagingLine final : public hl::Transport {
 public:
  explicit DamagingLine(std::chrono::milliseconds damage_for) : until_(std::chrono::steady_clock::now() + damage_for) {}

  std::size_t read(std::span<std::byte> out, int timeout_ms) override {
    const std::size_t n = device_.read(out, timeout_ms);
    const bool damage = damaging();
    for (std::size_t i = 0; i < n; ++i) {
      if (out[i] == std::byte{0}) {
        at_frame_start_ = true;
        continue;
      }
      if (at_frame_start_ && damage) {
        out[i] ^= std::byte{0x55};
        if (out[i] == std::byte{0}) out[i] = std::byte{0x55};  // never make a delimiter
      }
      at_frame_start_ = false;
    }
    return n;
  }
  void write(std::span<const std::byte> bytes) override { device_.write(bytes); }
  [[nodiscard]] const std::string& name() const override { return name_; }

 private:
  [[nodiscard]] bool damaging() const { return std::chrono::steady_clock::now() < until_; }

  hl::testing::InProcessDevice<PlanningApp> device_;
  std::chrono::steady_clock::time_point until_;
  bool at_frame_start_ = true;
  std::string name_ = "noisy line";
};

}  // namespace

TEST_CASE("handshake under noise: damaged answers for 2 s, longer than one round of Hellos, still connect", "[host_tools][link][robustness]") {
  // One round is max_retransmits + 1 Hellos 100 ms apart (about 1.1 s): the old host gave up there.
  DamagingLine line(std::chrono::milliseconds(2000));
  hl::HostLink link(line, protocol::SenderSettings{});
  const auto start = std::chrono::steady_clock::now();
  link.connect({});
  const auto took = std::chrono::steady_clock::now() - start;
  CHECK(took >= std::chrono::milliseconds(2000));
  CHECK(link.statistics().frames_rejected > 0);
  CHECK(link.capabilities().queue_capacity > 0);
}

TEST_CASE("handshake under noise: a line that damages everything fails after the handshake time, saying what arrived", "[host_tools][link][robustness]") {
  DamagingLine line(std::chrono::hours(1));
  hl::HostLink link(line, protocol::SenderSettings{});
  link.set_handshake_timeout_ms(2500);
  const auto start = std::chrono::steady_clock::now();
  try {
    link.connect({});
    FAIL("connected over a line that damages every frame");
  } catch (const hl::LinkError& e) {
    const auto took = std::chrono::steady_clock::now() - start;
    CHECK(e.code() == Error::LinkTimeout);
    CHECK(took >= std::chrono::milliseconds(1100));
    CHECK(took <= std::chrono::milliseconds(2500 + 1500));
    const std::string text = e.what();
    INFO(text);
    CHECK(text.find("damaged frame(s)") != std::string::npos);
    CHECK(text.find("noisy line") != std::string::npos);
  }
}

TEST_CASE("handshake under noise: a silent line fails saying nothing arrived", "[host_tools][link][robustness]") {
  class Silent final : public hl::Transport {
   public:
    std::size_t read(std::span<std::byte>, int) override { return 0; }
    void write(std::span<const std::byte>) override {}
    [[nodiscard]] const std::string& name() const override { return name_; }

   private:
    std::string name_ = "silent line";
  } silent;
  hl::HostLink link(silent, protocol::SenderSettings{10, 3, 0});
  link.set_handshake_timeout_ms(300);
  try {
    link.connect({});
    FAIL("connected to nothing");
  } catch (const hl::LinkError& e) {
    CHECK(std::string(e.what()).find("nothing arrived") != std::string::npos);
  }
}
