// SPDX-License-Identifier: MIT
// Tick timing of App<Board> on a board with a cycle clock: overruns counted, a missed deadline a Fault.
// Expected counts come from the scripted clock (hand-made schedules), not from the App.
#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

#include <curvestep/firmware/app.hpp>
#include <curvestep/firmware/tick_watch.hpp>

#include "fake_board.hpp"
#include "line_job_rig.hpp"

using namespace curvestep;
using namespace curvestep::firmware;
using namespace curvestep::protocol;
using namespace curvestep::firmware::testing;

namespace {

/// A FakeBoard with a 1 MHz cycle clock the test sets: each read returns `cycles`, then adds
/// `tick_cost` (so a tick, read at its start and end, lasts tick_cost cycles).
struct TimedBoard : FakeBoard {
  std::uint32_t cycles = 0;
  std::uint32_t tick_cost = 0;
  std::uint32_t cycle_count() {
    const std::uint32_t now = cycles;
    cycles += tick_cost;
    return now;
  }
  static std::uint32_t cycles_per_second() { return 1'000'000; }
};
static_assert(Board<TimedBoard>);

constexpr std::uint32_t period = 1000;  // 1 MHz clock, 1 kHz control rate (machine())

/// The App on a TimedBoard with `settings`, moving along a 40 mm line along +x (about 800 ticks).
struct TimedRig : LineJobRig<TimedBoard> {
  explicit TimedRig(AppSettings settings) : LineJobRig(settings) {}
  /// One tick starting at cycle `start` and lasting `cost` cycles, then a link exchange.
  void tick_at(std::uint32_t start, std::uint32_t cost) {
    board.cycles = start;
    board.tick_cost = cost;
    tick();
  }
};

}  // namespace

TEST_CASE("firmware: ticks on time count no overrun, a tick longer than its period counts one", "[firmware][app][tick]") {
  TimedRig rig(AppSettings{});
  const std::uint32_t origin = 5'000'000;  // anywhere: the first tick anchors the schedule
  for (std::uint32_t k = 0; k < 100; ++k) rig.tick_at(origin + k * period, 300);
  CHECK(rig.app.tick_watch().overruns() == 0);
  CHECK(rig.app.tick_watch().worst_cycles() == 300);
  CHECK(rig.app.tick_watch().period_cycles() == period);
  // Tick 100 runs 1500 cycles (half a period too long): one overrun. Tick 101 starts when it
  // ends, 500 cycles late (less than a period: on time enough), and the schedule goes on.
  rig.tick_at(origin + 100 * period, 1500);
  CHECK(rig.app.tick_watch().overruns() == 1);
  CHECK(rig.app.tick_watch().worst_cycles() == 1500);
  rig.tick_at(origin + 100 * period + 1500, 300);
  for (std::uint32_t k = 102; k < 200; ++k) rig.tick_at(origin + k * period, 300);
  CHECK(rig.app.tick_watch().overruns() == 1);
  CHECK(rig.app.state() == MachineState::Running);
  CHECK(rig.host.received.errors.empty());
}

TEST_CASE("firmware: a tick more than a period late is a TickDeadlineMissed fault naming how many periods",
          "[firmware][app][tick]") {
  TimedRig rig(AppSettings{});  // tick_deadline_periods 1: the edges of a tick are played a period after it
  for (std::uint32_t k = 0; k < 50; ++k) rig.tick_at(k * period, 200);
  // Tick 50 is due at 50 000 and starts 2 500 cycles late (two whole periods and a half).
  rig.tick_at(50 * period + 2500, 200);
  CHECK(rig.app.state() == MachineState::Fault);
  CHECK_FALSE(rig.app.moving());
  CHECK(rig.board.fault_stops == 1);
  REQUIRE(rig.host.received.errors.size() == 1);
  CHECK(rig.host.received.errors[0].code == Error::TickDeadlineMissed);
  CHECK(rig.host.received.errors[0].index == 2);
}

TEST_CASE("firmware: a tick within the tolerated lateness is an overrun, not a fault, and 0 tolerates any lateness",
          "[firmware][app][tick]") {
  AppSettings settings;
  SECTION("two periods tolerated") {
    settings.tick_deadline_periods = 2;
    TimedRig rig(settings);
    for (std::uint32_t k = 0; k < 50; ++k) rig.tick_at(k * period, 200);
    rig.tick_at(50 * period + 1800, 200);  // 1.8 periods late: an overrun, tolerated
    CHECK(rig.app.tick_watch().overruns() == 1);
    CHECK(rig.app.state() == MachineState::Running);
    rig.tick_at(51 * period + 2100, 200);  // 2.1 periods late: beyond the tolerance
    CHECK(rig.app.state() == MachineState::Fault);
    REQUIRE(rig.host.received.errors.size() == 1);
    CHECK(rig.host.received.errors[0].code == Error::TickDeadlineMissed);
    CHECK(rig.host.received.errors[0].index == 2);
  }
  SECTION("count only") {
    settings.tick_deadline_periods = 0;
    TimedRig rig(settings);
    for (std::uint32_t k = 0; k < 50; ++k) rig.tick_at(k * period, 200);
    rig.tick_at(50 * period + 9000, 200);   // nine periods late
    rig.tick_at(51 * period + 9000, 200);   // still nine periods behind the schedule
    rig.tick_at(52 * period + 9000, 2000);  // and two periods long
    CHECK(rig.app.tick_watch().overruns() == 3);
    CHECK(rig.app.state() == MachineState::Running);
    CHECK(rig.host.received.errors.empty());
  }
}

TEST_CASE("firmware: ticks not paced by a clock are not watched (watch_ticks off)", "[firmware][app][tick]") {
  AppSettings settings;
  settings.watch_ticks = false;
  TimedRig rig(settings);
  for (std::uint32_t k = 0; k < 20; ++k) rig.tick_at(k * 10 * period, 5000);  // ten periods apart, five long
  CHECK(rig.app.tick_watch().overruns() == 0);
  CHECK(rig.app.state() == MachineState::Running);
}

TEST_CASE("firmware: TickWatch anchors on the first tick and re-anchors on an early one", "[firmware][tick]") {
  TickWatch watch;
  watch.configure(1000, 1);
  CHECK(watch.on_start(0xFFFFFF00u) == 0);  // near the counter's wrap
  watch.on_end(0xFFFFFF00u + 100);
  CHECK(watch.on_start(0xFFFFFF00u + 1000 + 900) == 0);  // 900 late, across the wrap: no overrun
  watch.on_end(0xFFFFFF00u + 1000 + 1000);
  CHECK(watch.overruns() == 0);
  // The next is due at +2000; it starts at +2500 (500 late): the next due stays +3000.
  CHECK(watch.on_start(0xFFFFFF00u + 2500) == 0);
  watch.on_end(0xFFFFFF00u + 2600);
  // Early (+2900, before +3000): re-anchored there, so +3900 is on time, +4900 is next due, and
  // +6001 is 1101 late.
  CHECK(watch.on_start(0xFFFFFF00u + 2900) == 0);
  watch.on_end(0xFFFFFF00u + 2950);
  CHECK(watch.on_start(0xFFFFFF00u + 3900) == 0);
  watch.on_end(0xFFFFFF00u + 3950);
  CHECK(watch.overruns() == 0);
  CHECK(watch.on_start(0xFFFFFF00u + 6001) == 1);  // 1101 cycles: more than the one tolerated period
  CHECK(watch.overruns() == 1);
}

TEST_CASE("firmware: the StatusReport on the wire carries the tick overruns and the worst tick in microseconds",
          "[firmware][app][tick]") {
  AppSettings settings;
  settings.tick_deadline_periods = 0;  // count only: a late tick is an overrun, not a fault
  TimedRig rig(settings);
  const auto status = [&rig] {
    rig.host.received.status.clear();
    REQUIRE(rig.host.send(Message(StatusRequest{})));
    rig.host.pump(5);
    REQUIRE_FALSE(rig.host.received.status.empty());
    return rig.host.received.status.back();  // encoded by the App, decoded by the host's receiver
  };
  for (std::uint32_t k = 0; k < 20; ++k) rig.tick_at(k * period, 250);
  StatusReport s = status();
  CHECK(s.tick_overruns == 0);
  CHECK(s.worst_tick_us == 250);  // 250 cycles of the 1 MHz clock
  // Tick 20 runs 1700 cycles (longer than its 1000-cycle period): one overrun, the worst tick.
  rig.tick_at(20 * period, 1700);
  s = status();
  CHECK(s.tick_overruns == 1);
  CHECK(s.worst_tick_us == 1700);
  // Tick 21, due at 21 000, starts at 24 000 (three periods late, behind a long poll): a second.
  rig.tick_at(21 * period + 3000, 250);
  s = status();
  CHECK(s.tick_overruns == 2);
  CHECK(s.worst_tick_us == 1700);
  CHECK(s.state == MachineState::Running);
  // A new session starts counting afresh.
  REQUIRE(rig.host.connect(0x4321));
  s = status();
  CHECK(s.tick_overruns == 0);
  CHECK(s.worst_tick_us == 0);
}

TEST_CASE("firmware: TickWatch gives the worst tick in microseconds of the board's clock", "[firmware][tick]") {
  TickWatch watch;
  watch.configure(72'000, 1);  // 72 MHz, 1 kHz
  CHECK(watch.on_start(0) == 0);
  watch.on_end(36'000);  // 36 000 cycles / 72 per microsecond
  CHECK(watch.worst_microseconds(72'000'000) == 500);
  CHECK(watch.worst_microseconds(168'000'000) == 214);  // 36 000 / 168 = 214.3
  CHECK(watch.worst_microseconds(1'000'000) == 36'000);  // the host board counts microseconds
  CHECK(watch.worst_microseconds(999'999) == 0);         // below 1 MHz: not given
}
