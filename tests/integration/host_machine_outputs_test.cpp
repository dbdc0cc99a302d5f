// SPDX-License-Identifier: MIT
// The host board's machine outputs (boards/host machine_outputs.hpp, servo_pulse_train.hpp,
// gpiod_lines.hpp): the hooks' line writes and the servo's pulse train through a recording
// stand-in with the libgpiod line set's interface (set(line, level)) and a fake clock; the events
// of a streamed job reaching the lines through the real firmware on the host board; the libgpiod
// error path (this machine has no GPIO chips, so only the chip can be missing here).
#include <catch2/catch.hpp>

#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <utility>
#include <vector>

#include <curvestep/boards/host/device.hpp>
#include <curvestep/boards/host/gpiod_lines.hpp>
#include <curvestep/boards/host/gpiod_machine_outputs.hpp>
#include <curvestep/boards/host/machine_outputs.hpp>
#include <curvestep/boards/host/servo_pulse_train.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/machine_file.hpp>

#include "hil_support.hpp"
#include "host_board_stream.hpp"
#include "process.hpp"

namespace ct = curvestep::test;
namespace hb = curvestep::boards::host;

namespace {

/// Time of a fake clock, and what happens at its sleeps.
struct FakeTime {
  std::int64_t now = 0;
  std::vector<std::int64_t> sleeps;
  std::function<void(std::size_t)> on_sleep;  // called with the sleep's index, before it returns
};

/// A Clock for ServoPulseTrain: sleeping sets the time to the deadline (or leaves a later time).
struct FakeClock {
  FakeTime* time = nullptr;
  [[nodiscard]] std::int64_t now_ns() const noexcept { return time->now; }
  void sleep_until_ns(std::int64_t deadline) const {
    time->sleeps.push_back(deadline);
    if (deadline > time->now) time->now = deadline;
    if (time->on_sleep) time->on_sleep(time->sleeps.size() - 1);
  }
};

/// The stand-in for GpiodLineSet: records every write (line, level, time of the fake clock if any).
struct RecordingLines {
  struct Write {
    std::size_t line;
    bool high;
    std::int64_t time;
    bool operator==(const Write&) const = default;
  };
  FakeTime* time = nullptr;
  std::mutex mutex;
  std::vector<Write> writes;
  void set(std::size_t line, bool high) {
    const std::lock_guard lock(mutex);
    writes.push_back({line, high, time != nullptr ? time->now : 0});
  }
};

constexpr std::int64_t ms = 1'000'000;  // ns
constexpr std::int64_t us = 1'000;

}  // namespace

TEST_CASE("host board: the servo pulse train sends 50 Hz pulses of the width in force from absolute deadlines",
          "[host_tools][gpio][servo]") {
  FakeTime time;
  time.now = 1000 * ms;
  RecordingLines lines;
  lines.time = &time;
  std::atomic<bool> stop{false};
  hb::ServoPulseTrain<RecordingLines, FakeClock> train(lines, 7, FakeClock{&time});
  train.set_pulse_us(1250);
  time.on_sleep = [&](std::size_t index) {
    if (index == 2) train.set_pulse_us(1800);  // during period 1's pulse: from period 2 on
    if (index == 7) stop = true;               // after period 3
  };
  train.run(stop);
  const std::int64_t t0 = 1000 * ms;
  // Rising at t0 + k x 20 ms; falling 1250 us later in periods 0 and 1, 1800 us in 2 and 3; low at the end.
  const std::vector<RecordingLines::Write> expected{
      {7, true, t0},           {7, false, t0 + 1250 * us},           {7, true, t0 + 20 * ms}, {7, false, t0 + 20 * ms + 1250 * us},
      {7, true, t0 + 40 * ms}, {7, false, t0 + 40 * ms + 1800 * us}, {7, true, t0 + 60 * ms}, {7, false, t0 + 60 * ms + 1800 * us},
      {7, false, t0 + 80 * ms}};
  CHECK(lines.writes == expected);
  // Every sleep was to an absolute deadline on that grid.
  CHECK(time.sleeps == std::vector<std::int64_t>{t0 + 1250 * us, t0 + 20 * ms, t0 + 20 * ms + 1250 * us, t0 + 40 * ms,
                                                 t0 + 40 * ms + 1800 * us, t0 + 60 * ms, t0 + 60 * ms + 1800 * us, t0 + 80 * ms});
}

TEST_CASE("host board: the servo pulse train skips a period it woke too late for and sends nothing at width 0",
          "[host_tools][gpio][servo]") {
  FakeTime time;
  RecordingLines lines;
  lines.time = &time;
  std::atomic<bool> stop{false};
  hb::ServoPulseTrain<RecordingLines, FakeClock> train(lines, 0, FakeClock{&time});
  train.set_pulse_us(1000);
  time.on_sleep = [&](std::size_t index) {
    if (index == 1) time.now = 65 * ms;  // the wait for period 1 (20 ms) ended 45 ms late
    if (index == 3) train.set_pulse_us(0);
    if (index == 5) stop = true;
  };
  train.run(stop);
  // Period 0 at 0; periods 1..3 (20, 40, 60 ms) are skipped: the next pulse starts at 80 ms on the
  // same grid, then no pulses at width 0 (periods at 100 and 120 ms), the line low at the end.
  const std::vector<RecordingLines::Write> expected{
      {0, true, 0}, {0, false, 1 * ms}, {0, true, 80 * ms}, {0, false, 81 * ms}, {0, false, 120 * ms}};
  CHECK(lines.writes == expected);
  CHECK(time.sleeps == std::vector<std::int64_t>{1 * ms, 20 * ms, 80 * ms, 81 * ms, 100 * ms, 120 * ms});
  train.set_pulse_us(9000);
  CHECK(train.pulse_us() == 2500);  // wider than a servo takes: clamped
}

TEST_CASE("host board: machine output hooks drive their lines, and an unwired digital output is counted, not written",
          "[host_tools][gpio]") {
  RecordingLines lines;
  hb::MachineOutputs<RecordingLines> outputs(lines, 2, false);
  hb::MachineOutputHooks& hooks = outputs;
  hooks.spindle(true, false, 12000);  // M3
  hooks.coolant(false, true);         // M8
  hooks.digital_output(1, true);      // M62 P1
  hooks.digital_output(2, true);      // M62 P2: only outputs 0 and 1 are wired
  hooks.spindle(true, true, 8000);    // M4
  hooks.coolant(true, true);          // M7
  hooks.spindle(false, true, 8000);   // M5
  hooks.coolant(false, false);        // M9
  hooks.pen(true, 1800);
  using W = RecordingLines::Write;
  // Lines: 0 spindle enable, 1 direction, 2 mist, 3 flood, 4 servo, 5.. outputs (output_line_roles).
  const std::vector<W> expected{{1, false, 0}, {0, true, 0},  {2, false, 0}, {3, true, 0}, {6, true, 0},
                                {1, true, 0},  {0, true, 0},  {2, true, 0},  {3, true, 0}, {1, true, 0},
                                {0, false, 0}, {2, false, 0}, {3, false, 0}};
  CHECK(lines.writes == expected);
  CHECK(outputs.unwired_outputs() == 1);
  CHECK(outputs.servo_pulse_us() == 1800);
  hb::MachineOutputLines names;
  names.spindle_enable = "EN";
  names.outputs = {"OUT0", "OUT1"};
  const auto roles = hb::output_line_roles(names);
  REQUIRE(roles.size() == 7);
  CHECK(roles[hb::spindle_enable_line] == std::pair<std::string, std::string>{"EN", "spindle enable"});
  CHECK(roles[hb::servo_line].second == "servo pen");
  CHECK(roles[hb::first_digital_output_line + 1] == std::pair<std::string, std::string>{"OUT1", "digital output 1"});
}

TEST_CASE("host board: a streamed job's spindle, coolant and output events reach the output lines in program order",
          "[host_tools][gpio][events]") {
  // The zig-zag job with events between its lines, as a G-code program's M-words become them.
  auto job = curvestep::host::load_job(ct::zigzag_job(4));
  REQUIRE(job.segments.size() >= 4);
  using K = curvestep::host::JobEventKind;
  const auto event = [](K kind, std::size_t before, double value = 0, bool flag = false) {
    curvestep::host::JobEvent e;
    e.kind = kind;
    e.before_segment = before;
    e.value = value;
    e.flag = flag;
    return e;
  };
  job.events = {event(K::SpindleOn, 0, 10000), event(K::CoolantFlood, 0), event(K::DigitalOutput, 1, 0, true),
                event(K::SpindleOn, 2, 5000, true), event(K::CoolantMist, 2), event(K::DigitalOutput, 3, 0, false),
                event(K::SpindleOff, 4), event(K::CoolantOff, 4)};
  const auto machine = curvestep::host::load_machine(ct::wire_exact_machine());
  RecordingLines lines;
  hb::MachineOutputs<RecordingLines> outputs(lines, 1, false);
  hb::CountingStepOutput steps;
  hb::DeviceOptions options;
  options.machine_outputs = &outputs;
  const auto result = ct::stream_to_host_board(job, machine, steps, options);
  REQUIRE(result.standing_ticks == 0);
  using W = RecordingLines::Write;
  // Lines 0 enable, 1 direction, 2 mist, 3 flood, 5 output 0; each hook writes its whole state.
  const std::vector<W> expected{
      {1, false, 0}, {0, true, 0},                 // M3 S10000
      {2, false, 0}, {3, true, 0},                 // M8
      {5, true, 0},                                // M62 P0
      {1, true, 0},  {0, true, 0},                 // M4 S5000
      {2, true, 0},  {3, true, 0},                 // M7
      {5, false, 0},                               // M65 P0
      {1, true, 0},  {0, false, 0},                // M5 (the direction keeps M4's level)
      {2, false, 0}, {3, false, 0}};               // M9
  CHECK(lines.writes == expected);
  CHECK(outputs.unwired_outputs() == 0);
}

TEST_CASE("host board: machine output lines on a GPIO chip that does not exist are an error naming the chip",
          "[host_tools][gpio]") {
  hb::MachineOutputLines names;
  names.chip = "curvestep-no-such-chip";
  names.spindle_enable = "SPINDLE_EN";
  names.servo = "PEN_SERVO";
  try {
    hb::GpiodMachineOutputs outputs(names);
    FAIL("opened a chip that does not exist");
  } catch (const hb::GpioError& e) {
    CHECK_THAT(e.what(), Catch::Contains("curvestep-no-such-chip") && Catch::Contains("not found"));
  }
}

TEST_CASE("host board: curvestep device --gpio refuses a machine file whose output lines are malformed, naming the key",
          "[host_tools][gpio]") {
  const auto machine = ct::scratch_dir() / "gpio_outputs_machine.json";
  std::ofstream(machine) << R"({"gpio": {"chip": "gpiochip-curvestep-test", "x": {"step": "X_STEP", "dir": "X_DIR"},
  "spindle": {"enable": "X_DIR"}}})";
  std::string errors;
  const int status = ct::run_program({"device", "--gpio", "--machine", machine.string()}, errors, "device_gpio_outputs",
                                     std::chrono::seconds(20));
  CHECK(status != 0);
  CHECK_THAT(errors, Catch::Contains("gpio_outputs_machine.json:2") && Catch::Contains("\"gpio\".\"spindle\".\"enable\"") &&
                         Catch::Contains("\"X_DIR\" is already used by \"gpio\".\"x\".\"dir\""));
}

TEST_CASE("host board: curvestep gpio refuses a job that switches a digital output the machine file does not wire",
          "[host_tools][gpio]") {
  const auto machine = ct::scratch_dir() / "gpio_outputs_limits.json";
  std::ofstream(machine) << R"({"version": 1, "v_max": 200, "a_max": 2000, "j_max": 50000, "feed": 50, "tolerance": 0.01,
  "rate_hz": 1000, "axes": {"x": {"steps_per_mm": 80}, "y": {"steps_per_mm": 80}, "z": {"steps_per_mm": 400}},
  "gpio": {"chip": "gpiochip-curvestep-test", "x": {"step": "X_STEP", "dir": "X_DIR"}, "outputs": ["OUT0", "OUT1"]}})";
  const auto job = ct::scratch_dir() / "outputs_job.ngc";
  std::ofstream(job) << "G21 G90\nG1 X5 F600\nM62 P1\nG1 X10\nM64 P2\nG1 X15\n";
  std::string errors;
  const int status = ct::run_program({"gpio", job.string(), "--machine", machine.string(), "--dry-run"}, errors, "gpio_outputs",
                                     std::chrono::seconds(20));
  CHECK(status != 0);
  CHECK_THAT(errors, Catch::Contains("outputs_job.ngc:5: M64: digital output 2 has no line in the machine file (wired: 0 .. 1)"));
}
