// SPDX-License-Identifier: MIT
// The host board's outputs: the libgpiod output's error path (this machine has no GPIO chips),
// and the step/dir waveform of a streamed job through a recording output of the same interface.
#include <catch2/catch.hpp>

#include <memory>

#include <curvestep/boards/host/device.hpp>
#include <curvestep/boards/host/gpio_output.hpp>
#include <curvestep/core/motion/step_output.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/machine_file.hpp>

#include "hil_support.hpp"
#include "host_board_stream.hpp"
#include "process.hpp"

namespace ct = curvestep::test;
namespace hb = curvestep::boards::host;

TEST_CASE("host board: a GPIO chip that does not exist is an error naming the chip", "[host_tools][gpio]") {
  hb::GpioLines lines;
  lines.chip = "curvestep-no-such-chip";
  lines.step[0] = "X_STEP";
  lines.direction[0] = "X_DIR";
  try {
    hb::GpiodStepOutput output(lines, hb::SystemClock::step_timer_hz);
    FAIL("opening a missing chip succeeded");
  } catch (const hb::GpioError& e) {
    CHECK_THAT(e.what(), Catch::Contains("GPIO chip \"curvestep-no-such-chip\" not found"));
  }
}

TEST_CASE("host board: curvestep device --gpio with a missing chip exits with a message naming the chip",
          "[host_tools][gpio]") {
  const auto machine = ct::scratch_dir() / "gpio_machine.json";
  std::ofstream(machine) << R"({"gpio": {"chip": "gpiochip-curvestep-test", "x": {"step": "X_STEP", "dir": "X_DIR"}}})";
  std::string errors;
  const int status = ct::run_program({"device", "--gpio", "--machine", machine.string()}, errors, "device_gpio", std::chrono::seconds(20));
  CHECK(status == 1);
  CHECK_THAT(errors, Catch::Contains("gpiochip-curvestep-test") && Catch::Contains("not found"));
}

TEST_CASE("host board: the step/dir waveform of a streamed job has the driver timing and the expected step counts",
          "[host_tools][waveform]") {
  // A zig-zag of 6 lines: X 0 -> 24 mm always forward, Y up and down 10 mm six times.
  const auto job = curvestep::host::load_job(ct::zigzag_job(6));
  const auto machine = curvestep::host::load_machine(ct::wire_exact_machine());
  using Recorder = curvestep::RecordingStepOutput<65536>;
  auto recorder = std::make_unique<Recorder>();
  const auto result = ct::stream_to_host_board(job, machine, *recorder);
  REQUIRE(result.standing_ticks == 0);
  REQUIRE(recorder->dropped() == 0);

  // Expected from the geometry: X 24 mm * 80 steps/mm forward; Y 6 * 10 mm * 80 steps/mm, half each way.
  constexpr std::uint64_t pulse = 2;  // 2 us at the 1 MHz step timer
  constexpr std::uint64_t low = 2;
  constexpr std::uint64_t setup = 1;
  std::array<long, 3> up{}, down{};
  std::array<bool, 3> positive{true, true, true};
  std::array<bool, 3> high{};
  std::array<std::uint64_t, 3> last_rise{}, last_fall{}, last_direction{};
  std::array<bool, 3> any_fall{};
  std::array<bool, 3> any_direction{};
  std::uint64_t previous_time = 0;
  for (const auto& edge : *recorder) {
    const std::size_t a = edge.axis;
    REQUIRE(a < 3);
    REQUIRE(edge.time_ticks >= previous_time);  // edges in time order
    previous_time = edge.time_ticks;
    switch (edge.edge) {
      case curvestep::StepEdge::DirectionPositive:
      case curvestep::StepEdge::DirectionNegative:
        REQUIRE_FALSE(high[a]);  // never change direction during a pulse
        if (any_fall[a]) REQUIRE(edge.time_ticks >= last_fall[a] + 1);  // direction hold after the pulse
        positive[a] = edge.edge == curvestep::StepEdge::DirectionPositive;
        last_direction[a] = edge.time_ticks;
        any_direction[a] = true;
        break;
      case curvestep::StepEdge::StepHigh:
        REQUIRE_FALSE(high[a]);
        if (any_fall[a]) REQUIRE(edge.time_ticks >= last_fall[a] + low);
        if (any_direction[a]) REQUIRE(edge.time_ticks >= last_direction[a] + setup);
        high[a] = true;
        last_rise[a] = edge.time_ticks;
        (positive[a] ? up[a] : down[a]) += 1;
        break;
      case curvestep::StepEdge::StepLow:
        REQUIRE(high[a]);
        REQUIRE(edge.time_ticks >= last_rise[a] + pulse);
        high[a] = false;
        last_fall[a] = edge.time_ticks;
        any_fall[a] = true;
        break;
    }
  }
  CHECK(up[0] == 24 * 80);
  CHECK(down[0] == 0);
  CHECK(up[1] == 3 * 10 * 80);
  CHECK(down[1] == 3 * 10 * 80);
  CHECK(up[2] + down[2] == 0);
  CHECK_FALSE(high[0]);
  CHECK_FALSE(high[1]);
}
