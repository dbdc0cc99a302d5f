// SPDX-License-Identifier: MIT
// PieceExecutor replays the pieces a PieceRecorder took from a MotionController: the same setpoints
// bit for bit (the controller's own stream is the reference), fed through a small queue as a
// firmware would be; a hand-computed chunk; and every refusal and fault with its cause.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/motion/piece_executor.hpp>
#include <curvestep/core/motion/piece_recorder.hpp>

#include "chunk_test_support.hpp"

#ifdef CURVESTEP_MOTION_EXAMPLE_JOBS
#include <curvestep/host/job.hpp>
#include <curvestep/host/machine_file.hpp>
#endif

using namespace curvestep;
using namespace curvestep::testing;

namespace {

template <class S>
struct RecordedRun {
  std::vector<Setpoint<S>> setpoints;
  std::vector<PlannedPiece> pieces;
};

/// The controller's setpoints and the pieces recorded from them.
template <class S>
RecordedRun<S> record(const std::vector<PathSegment>& job, const MachineLimits& machine, const std::vector<JointStop>& entries = {}) {
  RecordedRun<S> run;
  PieceRecorder recorder;
  const auto sink = [&](const PlannedPiece& p) { run.pieces.push_back(p); };
  run.setpoints = run_chunked<S>(job, machine, HermiteChunk::max_ticks, [&](const MotionController<S>& c, const Setpoint<S>& sp) {
                    recorder.record(c, sp, sink);
                  }, entries).setpoints;
  recorder.finish(sink);
  return run;
}

/// The executor's setpoints for `pieces`, pushed whenever its 16-piece queue has room.
template <class S>
std::vector<Setpoint<S>> replay(const std::vector<PlannedPiece>& pieces, const MachineLimits& machine) {
  PieceExecutor<S, 16> executor;
  REQUIRE(executor.configure(machine).has_value());
  std::size_t next = 0;
  auto fill = [&] {
    while (next < pieces.size() && !executor.queue_full()) {
      REQUIRE(executor.push(pieces[next]).has_value());
      ++next;
    }
  };
  fill();
  REQUIRE(executor.start().has_value());
  std::vector<Setpoint<S>> out;
  while (!executor.finished() && out.size() < 3000000) {
    fill();
    const auto sp = executor.next_setpoint();
    REQUIRE(sp.has_value());
    out.push_back(sp.value());
  }
  CHECK(next == pieces.size());
  return out;
}

/// Same ticks, positions (bit for bit) and segments; the executor's speed is 0 by design.
template <class S>
void require_same_stream(const std::vector<Setpoint<S>>& replayed, const std::vector<Setpoint<S>>& reference) {
  REQUIRE(replayed.size() == reference.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    const bool same = replayed[i].tick == reference[i].tick && replayed[i].position == reference[i].position &&
                      replayed[i].segment == reference[i].segment;
    if (!same && differing++ == 0) {
      INFO("first difference at setpoint " << i);
      CHECK(same);
    }
  }
  CHECK(differing == 0);
}

template <class S>
void check_job(const std::vector<PathSegment>& job, const MachineLimits& machine) {
  const auto run = record<S>(job, machine);
  std::uint64_t ticks = 0;
  std::size_t chunks = 0;
  for (const PlannedPiece& p : run.pieces) {
    ticks += p.ticks;
    if (is_chunk(p)) ++chunks;
    CHECK(valid_piece_ticks(p.ticks, p.exact_run));
  }
  CHECK(ticks == run.setpoints.size());  // every setpoint in exactly one piece
  CHECK(chunks > 0);                     // the replay steps chunks, not only exact ticks
  CHECK(run.pieces.front().ticks == 1);
  CHECK(run.pieces.back().end_of_job);
  CHECK(std::count_if(run.pieces.begin(), run.pieces.end(), [](const PlannedPiece& p) { return p.end_of_job; }) == 1);
  require_same_stream(replay<S>(run.pieces, machine), run.setpoints);
}

}  // namespace

TEMPLATE_TEST_CASE("piece executor: rests at joints become rest pieces and replay bit for bit", "[core][motion][pieces]", Q16_16,
                   double) {
  // A rest before the first segment, a short one at a corner, and one longer than a piece holds.
  const std::vector<PathSegment> job{line(mp(0, 0), mp(10, 0)), line(mp(10, 0), mp(10, 10)), line(mp(10, 10), mp(0, 10))};
  const std::vector<JointStop> entries{JointStop{true, 3}, JointStop{true, 500}, JointStop{true, max_rest_ticks + 10}};
  const auto run = record<TestType>(job, test_machine(), entries);
  std::vector<std::uint32_t> rests;
  std::uint64_t ticks = 0;
  for (const PlannedPiece& p : run.pieces) {
    ticks += p.ticks;
    CHECK(valid_piece_ticks(p.ticks, p.exact_run, p.rest));
    if (p.rest) rests.push_back(p.ticks);
  }
  CHECK(ticks == run.setpoints.size());
  CHECK(rests == std::vector<std::uint32_t>{3, 500, max_rest_ticks, 10});
  require_same_stream(replay<TestType>(run.pieces, test_machine()), run.setpoints);
}

namespace {

PlannedPiece exact_piece(double x, double y, std::uint32_t segment = 0) {
  PlannedPiece p;
  p.end = mp(x, y);
  p.segment = segment;
  return p;
}

}  // namespace

TEMPLATE_TEST_CASE("piece executor: replays the acceptance jobs bit for bit", "[core][motion][pieces]", Q16_16, double) {
  const auto jobs = acceptance_jobs();
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    INFO("acceptance job " << j);
    check_job<TestType>(jobs[j], test_machine());
  }
}

#ifdef CURVESTEP_MOTION_EXAMPLE_JOBS
TEST_CASE("piece executor: replays every example job bit for bit in Q16.16", "[core][motion][pieces]") {
  const std::filesystem::path folder = CURVESTEP_MOTION_EXAMPLE_JOBS;
  const MachineLimits machine = host::load_machine(folder / "machine.json");
  std::size_t jobs = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "machine.json") continue;
    INFO(entry.path().filename().string());
    check_job<Q16_16>(host::load_job(entry.path()).segments, machine);
    ++jobs;
  }
  CHECK(jobs >= 4);
}
#endif

TEST_CASE("piece executor: a chunk of a straight line steps to the exact quarters", "[core][motion][pieces]") {
  // A line from the origin to d = (1, 2) as a quintic: control points i/5 d. Over 4 ticks the
  // setpoints are d/4, d/2, 3d/4 (exact in binary), then the piece's end.
  PieceExecutor<double, 4> executor;
  REQUIRE(executor.configure(test_machine()).has_value());
  REQUIRE(executor.push(exact_piece(0, 0)).has_value());
  PlannedPiece chunk;
  chunk.ticks = 4;
  for (std::size_t i = 0; i < 5; ++i) {
    const double f = static_cast<double>(i + 1) / 5.0;
    chunk.controls[i] = mp(f, 2 * f);
  }
  chunk.end = mp(1, 2);
  chunk.segment = 3;
  chunk.end_of_job = true;
  REQUIRE(executor.push(chunk).has_value());
  REQUIRE(executor.start().has_value());
  const double expected[5][2] = {{0, 0}, {0.25, 0.5}, {0.5, 1}, {0.75, 1.5}, {1, 2}};
  for (std::size_t k = 0; k < 5; ++k) {
    const auto sp = executor.next_setpoint();
    REQUIRE(sp.has_value());
    CHECK(sp.value().tick == k);
    CHECK(sp.value().position[0] == Approx(expected[k][0]).margin(1e-15));
    CHECK(sp.value().position[1] == Approx(expected[k][1]).margin(1e-15));
    CHECK(sp.value().position[2] == 0);
    CHECK(sp.value().segment == (k == 0 ? 0u : 3u));
  }
  CHECK(executor.finished());
  CHECK(executor.next_setpoint().error() == Error::InvalidState);
}

TEST_CASE("piece executor: an exact run gives its setpoints in order then its end", "[core][motion][pieces]") {
  PieceExecutor<Q16_16, 4> executor;
  REQUIRE(executor.configure(test_machine()).has_value());
  PlannedPiece run = exact_piece(3, -3, 9);
  run.exact_run = true;
  run.ticks = 3;
  run.controls[0] = mp(1, -1);
  run.controls[1] = mp(2, -2);
  run.controls[2] = mp(100, 100);  // beyond the run's ticks: never a setpoint
  run.end_of_job = true;
  REQUIRE(executor.push(run).has_value());  // a run may open a job: it needs no setpoint before it
  REQUIRE(executor.start().has_value());
  for (int k = 1; k <= 3; ++k) {
    const auto sp = executor.next_setpoint();
    REQUIRE(sp.has_value());
    CHECK(sp.value().tick == static_cast<std::uint64_t>(k - 1));
    CHECK(sp.value().position[0] == Q16_16(k));
    CHECK(sp.value().position[1] == Q16_16(-k));
    CHECK(sp.value().segment == 9u);
  }
  CHECK(executor.finished());
  PlannedPiece long_run = exact_piece(0, 0);
  long_run.exact_run = true;
  long_run.ticks = max_exact_run + 1;
  executor.reset();
  CHECK(executor.push(long_run).error() == Error::InvalidArgument);
  long_run.ticks = 1;  // a run of one tick is an exact piece without the flag
  CHECK(executor.push(long_run).error() == Error::InvalidArgument);
}

TEST_CASE("piece executor: refuses bad pieces and leaves the queue unchanged", "[core][motion][pieces]") {
  PieceExecutor<Q16_16, 2> executor;
  CHECK(executor.push(exact_piece(0, 0)).error() == Error::ConfigurationMissing);
  REQUIRE(executor.configure(test_machine()).has_value());
  CHECK(executor.start().error() == Error::NothingQueued);

  PlannedPiece first_chunk;
  first_chunk.ticks = 2;
  const auto refused_chunk = executor.push(first_chunk);
  CHECK(refused_chunk.error() == Error::InvalidArgument);
  CHECK(refused_chunk.failure().index == 2);  // a chunk cannot open a job: QueuePiece's ticks field

  for (std::uint32_t ticks : {0u, 3u, 6u, 512u}) {
    PlannedPiece p = exact_piece(0, 0);
    p.ticks = ticks;
    const auto r = executor.push(p);
    CHECK(r.error() == Error::InvalidArgument);
    CHECK(r.failure().index == 2);
  }
  PlannedPiece nan = exact_piece(std::numeric_limits<double>::quiet_NaN(), 0, 7);
  CHECK(executor.push(nan).error() == Error::NotFinite);
  CHECK(executor.push(nan).failure().index == 7);
  PlannedPiece inf = exact_piece(0, 0);
  inf.controls[2][1] = std::numeric_limits<double>::infinity();
  CHECK(executor.push(inf).error() == Error::NotFinite);
  CHECK(executor.queued() == 0);

  REQUIRE(executor.push(exact_piece(0, 0)).has_value());
  REQUIRE(executor.push(exact_piece(1, 0)).has_value());
  CHECK(executor.push(exact_piece(2, 0)).error() == Error::QueueFull);
  CHECK(executor.queued() == 2);
  CHECK(executor.hold().error() == Error::NotSupported);
  CHECK(executor.state() == ControllerState::Idle);
}

TEST_CASE("piece executor: an empty queue before the job's end is a QueueUnderrun fault", "[core][motion][pieces]") {
  PieceExecutor<Q16_16, 4> executor;
  REQUIRE(executor.configure(test_machine()).has_value());
  REQUIRE(executor.push(exact_piece(0, 0, 5)).has_value());
  REQUIRE(executor.start().has_value());
  REQUIRE(executor.next_setpoint().has_value());
  const auto starved = executor.next_setpoint();
  CHECK(starved.error() == Error::QueueUnderrun);
  CHECK(starved.failure().index == 5);
  CHECK(executor.state() == ControllerState::Fault);
  CHECK(executor.fault().code == Error::QueueUnderrun);
  CHECK(executor.push(exact_piece(1, 0)).error() == Error::InvalidState);
  executor.reset();
  CHECK(executor.state() == ControllerState::Idle);
  CHECK(executor.push(exact_piece(1, 0)).has_value());
}

TEST_CASE("piece executor: a position outside Q16.16 faults with the piece's segment", "[core][motion][pieces]") {
  PieceExecutor<Q16_16, 4> executor;
  REQUIRE(executor.configure(test_machine()).has_value());
  REQUIRE(executor.push(exact_piece(0, 0, 1)).has_value());
  PlannedPiece far = exact_piece(40000, 0, 2);  // Q16.16 holds up to 32768 mm
  far.end_of_job = true;
  REQUIRE(executor.push(far).has_value());
  CHECK(executor.push(exact_piece(0, 0)).error() == Error::InvalidState);  // after the job's last piece
  REQUIRE(executor.start().has_value());
  REQUIRE(executor.next_setpoint().has_value());
  const auto out = executor.next_setpoint();
  REQUIRE_FALSE(out.has_value());
  CHECK(out.failure().index == 2);
  CHECK(executor.state() == ControllerState::Fault);
  CHECK(executor.fault().code == out.error());
}
