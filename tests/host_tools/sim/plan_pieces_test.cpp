// SPDX-License-Identifier: MIT
// plan_pieces: the pieces a host plans for a controller without a planner. The reference is the
// simulator (simulate(), the stream `curvestep sim` writes): the pieces cover every one of its
// setpoints, and a PieceExecutor<Q16_16, 16> (the executor firmware's replay) fed with them gives
// its raw Q16.16 setpoints and segment indices bit for bit, for every example job and for two
// look-ahead windows. Invalid requests fail with simulate()'s messages.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/motion/piece_executor.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/simulator.hpp>

using namespace curvestep;

namespace {

const std::filesystem::path examples = std::filesystem::path(CURVESTEP_SOURCE_DIR) / "examples" / "jobs";

/// The executor's setpoints for `pieces`, pushed whenever its 16-piece queue has room.
std::vector<Setpoint<Q16_16>> replay(const std::vector<PlannedPiece>& pieces, const MachineLimits& machine) {
  PieceExecutor<Q16_16, 16> executor;
  REQUIRE(executor.configure(machine).has_value());
  std::size_t next = 0;
  const auto fill = [&] {
    while (next < pieces.size() && !executor.queue_full()) {
      REQUIRE(executor.push(pieces[next]).has_value());
      ++next;
    }
  };
  fill();
  REQUIRE(executor.start().has_value());
  std::vector<Setpoint<Q16_16>> out;
  while (!executor.finished() && out.size() < 10000000) {
    fill();
    const auto setpoint = executor.next_setpoint();
    REQUIRE(setpoint.has_value());
    out.push_back(setpoint.value());
  }
  CHECK(next == pieces.size());
  return out;
}

void check_against_simulator(const host::Job& job, const MachineLimits& machine, std::size_t lookahead) {
  host::SimulationOptions options;
  options.lookahead = lookahead;
  const auto simulated = host::simulate(job, machine, options);
  const auto pieces = host::plan_pieces(job, machine, options);
  REQUIRE_FALSE(pieces.empty());

  std::uint64_t ticks = 0;
  std::size_t chunks = 0;
  for (const PlannedPiece& piece : pieces) {
    CHECK(valid_piece_ticks(piece.ticks, piece.exact_run));
    ticks += piece.ticks;
    if (piece.ticks > 1) ++chunks;
  }
  CHECK(ticks == simulated.setpoints.size());  // every setpoint of the sim stream, once
  CHECK(chunks > 0);                           // chunks, not only exact ticks
  CHECK(pieces.front().ticks == 1);
  CHECK(pieces.back().end_of_job);
  CHECK(std::count_if(pieces.begin(), pieces.end(), [](const PlannedPiece& p) { return p.end_of_job; }) == 1);

  const auto replayed = replay(pieces, machine);
  REQUIRE(replayed.size() == simulated.setpoints.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < replayed.size(); ++i) {
    const auto& expected = simulated.setpoints[i];
    bool same = replayed[i].tick == i && replayed[i].segment == expected.segment;
    for (std::size_t axis = 0; axis < 3; ++axis) same = same && replayed[i].position[axis].raw() == expected.raw_q16[axis];
    if (!same && differing++ == 0) {
      INFO("first difference at setpoint " << i);
      CHECK(same);
    }
  }
  CHECK(differing == 0);
}

}  // namespace

TEST_CASE("plan pieces: replaying them gives curvestep sim's Q16.16 setpoints bit for bit for every example job",
          "[host_tools][sim][pieces]") {
  const MachineLimits machine = host::load_machine(examples / "machine.json");
  std::size_t jobs = 0;
  for (const auto& entry : std::filesystem::directory_iterator(examples)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "machine.json") continue;
    const host::Job job = host::load_job(entry.path());
    for (const std::size_t lookahead : {host::SimulationOptions::max_lookahead, std::size_t{3}}) {
      INFO(entry.path().filename().string() << ", look-ahead " << lookahead);
      check_against_simulator(job, machine, lookahead);
    }
    ++jobs;
  }
  CHECK(jobs >= 4);
}

TEST_CASE("plan pieces: the window changes the plan as it changes the simulation", "[host_tools][sim][pieces]") {
  // 40 collinear lines of 0.25 mm at the example machine's feed of 50 mm/s: braking takes about
  // 1.6 mm (v²/2a + va/2j), more than one segment, so a window of 1 slows the cruise.
  const MachineLimits machine = host::load_machine(examples / "machine.json");
  host::Job job;
  job.name = "short lines";
  for (int k = 0; k < 40; ++k) {
    const auto line = PathSegment::make_line(MachinePoint{0.25 * k, 0, 0}, MachinePoint{0.25 * (k + 1), 0, 0});
    REQUIRE(line.has_value());
    job.segments.push_back(line.value());
  }
  host::SimulationOptions narrow;
  narrow.lookahead = 1;
  std::vector<std::array<std::int32_t, 3>> wide_stream;
  std::vector<std::array<std::int32_t, 3>> narrow_stream;
  for (const auto& r : host::simulate(job, machine).setpoints) wide_stream.push_back(r.raw_q16);
  for (const auto& r : host::simulate(job, machine, narrow).setpoints) narrow_stream.push_back(r.raw_q16);
  CHECK(wide_stream != narrow_stream);  // the window matters for this job
  const bool pieces_differ = host::plan_pieces(job, machine) != host::plan_pieces(job, machine, narrow);
  CHECK(pieces_differ);
  check_against_simulator(job, machine, 1);
  // The default options plan with simulate()'s default window, the largest.
  host::SimulationOptions widest;
  widest.lookahead = host::SimulationOptions::max_lookahead;
  const bool default_is_max = host::plan_pieces(job, machine) == host::plan_pieces(job, machine, widest);
  CHECK(default_is_max);
}

TEST_CASE("plan pieces: refuses what simulate refuses, with the same one-line message", "[host_tools][sim][pieces]") {
  const MachineLimits machine = host::load_machine(examples / "machine.json");
  const host::Job job = host::load_job(examples / "seed_cubic.json");
  const auto message_of = [](auto&& call) -> std::string {
    try {
      call();
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  };
  for (const std::size_t bad : {std::size_t{0}, std::size_t{17}}) {
    host::SimulationOptions options;
    options.lookahead = bad;
    const std::string planned = message_of([&] { (void)host::plan_pieces(job, machine, options); });
    CHECK(planned.find("between 1 and 16") != std::string::npos);
    CHECK(planned == message_of([&] { (void)host::simulate(job, machine, options); }));
  }
  host::Job empty = job;
  empty.segments.clear();
  // A job without moves (LinuxCNC runs a program of modes and M words only) runs in both and
  // makes nothing.
  CHECK(host::plan_pieces(empty, machine).empty());
  CHECK(host::simulate(empty, machine).setpoints.empty());
  MachineLimits broken = machine;
  broken.rate_hz = 0;
  const std::string machine_message = message_of([&] { (void)host::plan_pieces(job, broken); });
  CHECK(machine_message.rfind("machine: ", 0) == 0);
  CHECK(machine_message == message_of([&] { (void)host::simulate(job, broken); }));
}
