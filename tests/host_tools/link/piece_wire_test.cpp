// SPDX-License-Identifier: MIT
// Planned pieces as QueuePiece messages (host::link::to_wire): every piece of a planned example
// job goes through the protocol's encoder and decoder (independent code) and comes back with the
// same ticks, segment, end_of_job and binary64 coordinates (the firmware's conversion back to a
// PlannedPiece equals the original), for 3 and for 2 axes; what the wire
// cannot express (z on a 2-axis controller, a bad length) is refused naming the job segment.
#include <algorithm>
#include <array>
#include <cstddef>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>

#include <catch2/catch.hpp>

#include <curvestep/firmware/conversions.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/link/wire.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/simulator.hpp>
#include <curvestep/protocol/messages.hpp>

using namespace curvestep;
namespace hl = curvestep::host::link;

namespace {

const std::filesystem::path examples = CURVESTEP_EXAMPLE_JOBS;

/// The message through the encoder, the decoder and the firmware's conversion back
/// (firmware/conversions.hpp, the executor's own code).
PlannedPiece through_the_wire(const protocol::QueuePiece& message) {
  std::array<std::byte, protocol::max_payload_size> payload{};
  const auto size = protocol::encode(message, payload);
  REQUIRE(size.has_value());
  const auto decoded = protocol::decode<protocol::QueuePiece>(std::span<const std::byte>(payload.data(), size.value()));
  REQUIRE(decoded.has_value());
  CHECK(decoded.value().axis_count == message.axis_count);
  return firmware::to_planned_piece(decoded.value());
}

/// Every piece of the planned job survives the wire with `axes` axes, coordinates bit for bit.
std::size_t check_job(const char* name, std::size_t axes) {
  INFO(name << ", " << axes << " axes");
  const auto machine = host::load_machine(examples / "machine.json");
  const auto pieces = host::plan_pieces(host::load_job(examples / name), machine);
  std::size_t chunks = 0;
  std::size_t differing = 0;
  for (const PlannedPiece& piece : pieces) {
    const protocol::QueuePiece sent = hl::to_wire(piece, axes);
    CHECK(sent.axis_count == axes);
    if (!(through_the_wire(sent) == piece)) ++differing;
    if (piece.ticks > 1) ++chunks;
  }
  CHECK(differing == 0);
  CHECK(pieces.back().end_of_job);
  return chunks;
}

std::string refusal(const PlannedPiece& piece, std::size_t axes) {
  try {
    (void)hl::to_wire(piece, axes);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("host link: every planned piece of a 3-axis job survives the wire bit for bit", "[host_tools][wire][pieces]") {
  CHECK(check_job("helix.json", 3) > 0);  // chunks included
  const auto pieces = host::plan_pieces(host::load_job(examples / "helix.json"), host::load_machine(examples / "machine.json"));
  CHECK(std::any_of(pieces.begin(), pieces.end(), [](const PlannedPiece& p) { return p.end[2] != 0; }));  // z moves
}

TEST_CASE("host link: every planned piece of a flat job survives the wire with 2 axes", "[host_tools][wire][pieces]") {
  CHECK(check_job("seed_cubic.json", 2) > 0);
  CHECK(check_job("every_type.json", 2) > 0);
}

TEST_CASE("host link: a planned piece that moves Z is refused for 2 axes naming its segment", "[host_tools][wire][pieces]") {
  PlannedPiece exact;
  exact.segment = 7;
  exact.end = MachinePoint{1, 2, 0.5};
  const std::string end_message = refusal(exact, 2);
  CHECK(end_message.find("segment 7") != std::string::npos);
  CHECK(end_message.find("z = 0.5") != std::string::npos);
  CHECK(end_message.find("2 axes") != std::string::npos);
  CHECK(refusal(exact, 3).empty());

  PlannedPiece chunk;
  chunk.segment = 12;
  chunk.ticks = 8;
  chunk.end = MachinePoint{1, 2, 0};
  chunk.controls[3] = MachinePoint{0.5, 1, -0.25};
  const std::string control_message = refusal(chunk, 2);
  CHECK(control_message.find("segment 12") != std::string::npos);
  CHECK(control_message.find("control point") != std::string::npos);
  CHECK(control_message.find("2 axes") != std::string::npos);
  const auto sent = hl::to_wire(chunk, 3);
  CHECK(sent.controls[3] == std::array<double, 3>{0.5, 1, -0.25});
}

TEST_CASE("host link: a planned piece of a length the wire cannot carry is refused naming its segment",
          "[host_tools][wire][pieces]") {
  for (const std::uint32_t ticks : {0u, 3u, 512u}) {
    PlannedPiece piece;
    piece.segment = 4;
    piece.ticks = ticks;
    const std::string message = refusal(piece, 3);
    CHECK(message.find("segment 4") != std::string::npos);
    CHECK(message.find(std::to_string(ticks) + " ticks") != std::string::npos);
  }
}
