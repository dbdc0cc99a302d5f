// SPDX-License-Identifier: MIT
// EdgeClock (boards/host/include/curvestep/boards/host/edge_clock.hpp): step-timer times to
// CLOCK_MONOTONIC deadlines, re-based when an edge comes late. Expected deadlines are worked out
// by hand in integer nanoseconds.
#include <cstdint>

#include <catch2/catch.hpp>

#include <curvestep/boards/host/edge_clock.hpp>

using curvestep::boards::host::EdgeClock;

TEST_CASE("edge clock: an edge on time is due at epoch + time, and the epoch stays", "[host_tools][gpio]") {
  EdgeClock clock(1'000'000);  // 1 us ticks, 0.5 ms late limit
  clock.set_epoch(5'000'000'000);
  CHECK(clock.deadline_ns(0, 4'000'000'000) == 5'000'000'000);               // early: wait 1 s
  CHECK(clock.deadline_ns(3'000, 5'003'000'000) == 5'003'000'000);           // exactly due
  CHECK(clock.deadline_ns(3'000, 5'003'500'000) == 5'003'000'000);           // 0.5 ms late: still on time
  CHECK(clock.rebases() == 0);
  CHECK(clock.epoch_ns() == 5'000'000'000);
}

TEST_CASE("edge clock: an edge more than the late limit behind moves the epoch so that it is due now",
          "[host_tools][gpio]") {
  EdgeClock clock(1'000'000, 1'000'000);  // 1 ms late limit
  clock.set_epoch(1'000'000'000);
  // The job's step time 3 ms comes 10 s after the device started (an upload): re-based to now.
  CHECK(clock.deadline_ns(3'000, 11'000'000'000) == 11'000'000'000);
  CHECK(clock.rebases() == 1);
  CHECK(clock.epoch_ns() == 11'000'000'000 - 3'000'000);
  // The edges after it keep their spacing: 2 us and 500 us later.
  CHECK(clock.deadline_ns(3'002, 11'000'000'100) == 11'000'002'000);
  CHECK(clock.deadline_ns(3'500, 11'000'000'200) == 11'000'500'000);
  CHECK(clock.rebases() == 1);
  // A hold of 2 s: the next edge (time 4 ms) is re-based again.
  CHECK(clock.deadline_ns(4'000, 13'000'000'000) == 13'000'000'000);
  CHECK(clock.rebases() == 2);
}

TEST_CASE("edge clock: times are exact to the nanosecond for other timer rates and long runs", "[host_tools][gpio]") {
  EdgeClock clock(3'000'000);  // 1/3 us ticks
  clock.set_epoch(0);
  CHECK(clock.deadline_ns(1, 0) == 333);                   // floor(1e9 / 3e6)
  CHECK(clock.deadline_ns(3'000'000, 0) == 1'000'000'000);
  // 100 days of 3 MHz ticks: 2.592e13 ticks, beyond what ticks * 1e9 could hold in 64 bits.
  const std::uint64_t ticks = 100ull * 86'400 * 3'000'000 + 2;
  CHECK(clock.deadline_ns(ticks, 0) == 100ll * 86'400 * 1'000'000'000 + 666);
}

TEST_CASE("edge clock: one stalled control tick at 1 kHz (edges 1 ms late) re-bases with the default limit",
          "[host_tools][gpio]") {
  EdgeClock clock(1'000'000);
  clock.set_epoch(0);
  CHECK(clock.deadline_ns(10'000, 10'000'100) == 10'000'000);  // tick 10 on time (0.1 ms wake-up latency)
  // Tick 11 stood still (the stream stalled): its edges come one period, 1 ms, late.
  CHECK(clock.deadline_ns(11'000, 12'000'000) == 12'000'000);
  CHECK(clock.deadline_ns(11'002, 12'000'050) == 12'002'000);  // the pulse keeps its 2 us
  CHECK(clock.rebases() == 1);
}
