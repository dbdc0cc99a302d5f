// SPDX-License-Identifier: MIT
// Host side of the wire: jobs and machines as messages, checked against the firmware's own
// conversions back (firmware/conversions.hpp), which are independent code.
#include <catch2/catch.hpp>

#include <filesystem>

#include <curvestep/firmware/conversions.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/link/transport.hpp>
#include <curvestep/host/link/wire.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/protocol/frame.hpp>

#include "hil_support.hpp"

namespace ct = curvestep::test;
namespace hl = curvestep::host::link;

TEST_CASE("host link: every segment of the example jobs survives the wire exactly", "[host_tools][wire]") {
  for (const char* name : {"every_type.json", "inch_square.json", "seed_cubic.json", "helix.json"}) {
    INFO(name);
    const auto job = curvestep::host::load_job(ct::wire_exact_job(std::filesystem::path(CURVESTEP_EXAMPLE_JOBS) / name));
    const auto wire = hl::to_wire(job, 3, 1000);
    CHECK(wire.notes.empty());
    REQUIRE(wire.segments.size() == job.segments.size());
    for (std::size_t i = 0; i < job.segments.size(); ++i) {
      // Through the bytes on the wire and back with the firmware's decoder and conversion.
      std::array<std::byte, curvestep::protocol::max_payload_size> payload{};
      const auto size = curvestep::protocol::encode(wire.segments[i], payload);
      REQUIRE(size);
      const auto decoded = curvestep::protocol::decode<curvestep::protocol::QueueSegment>(
          std::span<const std::byte>(payload.data(), size.value()));
      REQUIRE(decoded);
      const auto back = curvestep::firmware::to_path_segment(decoded.value());
      REQUIRE(back);
      const auto& original = job.segments[i];
      CHECK(back.value().kind() == original.kind());
      CHECK(back.value().rapid() == original.rapid());
      CHECK(back.value().feed_mm_per_s() == original.feed_mm_per_s());
      if (original.kind() == curvestep::SegmentKind::Arc) CHECK(back.value().arc_sweep_rad() == original.arc_sweep_rad());
      for (double u : {0.0, 0.125, 0.5, 0.875, 1.0}) {
        const auto a = original.point(u);
        const auto b = back.value().point(u);
        for (std::size_t axis = 0; axis < 3; ++axis) CHECK(a[axis] == b[axis]);
      }
    }
  }
}

TEST_CASE("host link: the example machine travels exactly, rapid speed, profile and step rate included",
          "[host_tools][wire]") {
  const auto example = curvestep::host::load_machine(std::filesystem::path(CURVESTEP_EXAMPLE_JOBS) / "machine.json");
  const auto wire = hl::to_wire(example, 3);
  CHECK(wire.notes.empty());
  // Through the bytes on the wire and back with the firmware's decoder and conversion.
  std::array<std::byte, curvestep::protocol::max_payload_size> payload{};
  const auto size = curvestep::protocol::encode(wire.configuration, payload);
  REQUIRE(size);
  const auto decoded = curvestep::protocol::decode<curvestep::protocol::MachineConfiguration>(
      std::span<const std::byte>(payload.data(), size.value()));
  REQUIRE(decoded);
  const auto back = curvestep::firmware::to_machine_limits(decoded.value());
  REQUIRE(back);
  const auto& m = back.value();
  CHECK(m.tolerance_mm == 0.01);
  CHECK(m.junction_deviation_mm == 0.02);
  CHECK(m.rapid_mm_per_s == 150.0);
  CHECK(m.max_step_rate_hz == 40000.0);
  CHECK(m.jerk_limited);
  CHECK(m.v_max_mm_per_s == example.v_max_mm_per_s);
  CHECK(m.a_max_mm_per_s2 == example.a_max_mm_per_s2);
  CHECK(m.j_max_mm_per_s3 == example.j_max_mm_per_s3);
  CHECK(m.feed_mm_per_s == example.feed_mm_per_s);
  CHECK(m.rate_hz == example.rate_hz);
  for (std::size_t a = 0; a < 3; ++a) {
    CHECK(m.axes[a].steps_per_mm == example.axes[a].steps_per_mm);
    CHECK(m.axes[a].v_max_mm_per_s == example.axes[a].v_max_mm_per_s);
    CHECK(m.axes[a].a_max_mm_per_s2 == example.axes[a].a_max_mm_per_s2);
  }
  auto trapezoid = example;
  trapezoid.jerk_limited = false;
  CHECK_FALSE(curvestep::firmware::to_machine_limits(hl::to_wire(trapezoid, 3).configuration).value().jerk_limited);
}

TEST_CASE("host link: machine feeds the wire cannot carry exactly are named in notes", "[host_tools][wire]") {
  auto odd = curvestep::host::load_machine(std::filesystem::path(CURVESTEP_EXAMPLE_JOBS) / "machine.json");
  odd.feed_mm_per_s = 0.01;  // feeds are Q16.16 like segment feeds: 655/65536
  odd.rapid_mm_per_s = 0.01;
  const auto wire = hl::to_wire(odd, 3);
  bool feed = false;
  bool rapid = false;
  for (const auto& note : wire.notes) {
    feed = feed || note.find("feed 0.01 travels as") != std::string::npos;
    rapid = rapid || note.find("rapid 0.01 travels as") != std::string::npos;
  }
  CHECK(feed);
  CHECK(rapid);
  const auto exact = curvestep::host::load_machine(ct::wire_exact_machine());
  const auto exact_wire = hl::to_wire(exact, 3);
  CHECK(exact_wire.notes.empty());
  const auto limits = curvestep::firmware::to_machine_limits(exact_wire.configuration);
  REQUIRE(limits);
  CHECK(limits.value().tolerance_mm == exact.tolerance_mm);
  CHECK(limits.value().junction_deviation_mm == exact.junction_deviation_mm);
  CHECK(limits.value().v_max_mm_per_s == exact.v_max_mm_per_s);
  CHECK(limits.value().j_max_mm_per_s3 == exact.j_max_mm_per_s3);
  CHECK(limits.value().axes[2].steps_per_mm == exact.axes[2].steps_per_mm);
}

TEST_CASE("host link: a pseudo-terminal carries bytes both ways through the termios transport", "[host_tools][transport]") {
  hl::PseudoTerminal pty;
  CHECK(hl::is_pseudo_terminal(pty.slave_path()));
  auto host = hl::open_port(pty.slave_path(), 115200);
  auto device = pty.master_transport();
  const std::array<std::byte, 4> hello{std::byte{1}, std::byte{0}, std::byte{0x0a}, std::byte{0xff}};
  host->write(hello);
  std::array<std::byte, 16> got{};
  std::size_t n = 0;
  for (int i = 0; i < 50 && n < hello.size(); ++i) n += device->read(std::span<std::byte>(got).subspan(n), 20);
  REQUIRE(n == hello.size());
  CHECK(std::equal(hello.begin(), hello.end(), got.begin()));  // raw: no echo, no CR/LF mapping
  CHECK(host->read(got, 20) == 0);
}
