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
  for (const char* name : {"every_type.json", "inch_square.json", "seed_cubic.json"}) {
    INFO(name);
    const auto job = curvestep::host::load_job(ct::wire_exact_job(std::filesystem::path(CURVESTEP_EXAMPLE_JOBS) / name));
    const auto wire = hl::to_wire(job, 3);
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
      for (double u : {0.0, 0.125, 0.5, 0.875, 1.0}) {
        const auto a = original.point(u);
        const auto b = back.value().point(u);
        for (std::size_t axis = 0; axis < 3; ++axis) CHECK(a[axis] == b[axis]);
      }
    }
  }
}

TEST_CASE("host link: machine values the wire cannot carry exactly are named in notes", "[host_tools][wire]") {
  const auto example = curvestep::host::load_machine(std::filesystem::path(CURVESTEP_EXAMPLE_JOBS) / "machine.json");
  const auto wire = hl::to_wire(example, 3);
  bool tolerance = false;
  bool rapid = false;
  for (const auto& note : wire.notes) {
    tolerance = tolerance || note.find("tolerance 0.01 travels as") != std::string::npos;
    rapid = rapid || note.find("rapid 150") != std::string::npos;
  }
  CHECK(tolerance);
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
