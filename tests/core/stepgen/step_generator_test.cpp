// SPDX-License-Identifier: MIT
// Tests of StepGenerator, StepConfig and the step-rate checks, measured on recorded edges.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <span>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/motion/step_generator.hpp>

#include "step_test_support.hpp"
#include "support/numeric.hpp"

using namespace curvestep;
using curvestep::testing::AxisWaveform;
using curvestep::testing::VectorStepRecorder;

namespace {

/// A 1 kHz control tick on a 1 MHz step timer, A4988-like timing, 100 kHz driver limit.
/// By the essay's formulas: H = 2, L = 2, S = 1, Hd = 1, M = max(4, 10) = 10,
/// G = max(1, 1, 10 - 1 - 2) = 7, R = 1000 - 1 - 2 - 7 = 990.
MachineLimits test_limits(double x_steps = 80, double y_steps = 80, double z_steps = 400) {
  MachineLimits limits;
  limits.rate_hz = 1000;
  limits.max_step_rate_hz = 100000;
  limits.axes[0].steps_per_mm = x_steps;
  limits.axes[1].steps_per_mm = y_steps;
  limits.axes[2].steps_per_mm = z_steps;
  return limits;
}

StepTiming test_timing() {
  StepTiming timing;
  timing.timer_hz = 1000000;
  timing.min_pulse_ns = 2000;
  timing.min_low_ns = 2000;
  timing.direction_setup_ns = 1000;
  timing.direction_hold_ns = 1000;
  return timing;
}

StepConfig make_config(const MachineLimits& limits, const StepTiming& timing) {
  const auto config = StepConfig::create(limits, timing);
  REQUIRE(config.has_value());
  return config.value();
}

template <Scalar S>
Setpoint<S> setpoint_at(std::uint64_t tick, S x, S y = S{}, S z = S{}) {
  Setpoint<S> s;
  s.tick = tick;
  s.position = {x, y, z};
  return s;
}

constexpr std::size_t batch_capacity = 4096;

/// Runs setpoints (the first is the start) through a generator and records every edge.
template <Scalar S>
std::vector<RecordedEdge> run_job(const StepConfig& config, const std::vector<Setpoint<S>>& job) {
  StepGenerator generator(config);
  REQUIRE(generator.reset(job.front()).has_value());
  VectorStepRecorder recorder;
  StepBatch<batch_capacity> batch;
  REQUIRE(config.max_events_per_tick() <= batch_capacity);
  for (std::size_t i = 1; i < job.size(); ++i) {
    INFO("setpoint " << i);
    const auto advanced = generator.advance(job[i], batch);
    REQUIRE(advanced.has_value());
    // Every edge of a tick lies inside the tick.
    for (const StepEvent& e : batch) {
      if (e.offset_ticks >= config.period_ticks()) FAIL("edge outside its tick at offset " << e.offset_ticks);
    }
    play(batch, recorder);
  }
  return recorder.edges;
}

std::vector<std::uint64_t> rises_between(const AxisWaveform& w, std::uint64_t from, std::uint64_t to) {
  std::vector<std::uint64_t> out;
  for (std::uint64_t t : w.rises) {
    if (t >= from && t < to) out.push_back(t);
  }
  return out;
}

/// A random walk of positions on a 1/1024 mm grid (exact in float and double); the expected
/// counts are computed from the grid integers alone: g/1024 mm is g * 64 raw Q16.16 units.
template <Scalar S>
void grid_walk(const StepConfig& config, const StepTiming& timing, std::mt19937& random, int ticks) {
  std::uniform_int_distribution<std::int32_t> velocity(-1024, 1024);
  std::array<std::int64_t, 3> grid{5000, -777, 12};
  const std::array<std::int64_t, 3> start_grid = grid;
  auto millimetres = [](std::int64_t g) { return static_cast<S>(static_cast<double>(g) / 1024.0); };
  std::vector<Setpoint<S>> job{setpoint_at(0, millimetres(grid[0]), millimetres(grid[1]), millimetres(grid[2]))};
  std::array<std::int32_t, 3> speed{};
  for (int tick = 1; tick <= ticks; ++tick) {
    for (std::size_t axis = 0; axis < 3; ++axis) {
      if (random() % 16 == 0) speed[axis] = velocity(random) / (axis == 2 ? 8 : 1);
      grid[axis] += speed[axis];
    }
    job.push_back(setpoint_at(static_cast<std::uint64_t>(tick), millimetres(grid[0]), millimetres(grid[1]), millimetres(grid[2])));
  }
  REQUIRE(check_step_rate(std::span<const Setpoint<S>>(job), config).has_value());
  const auto axes = curvestep::testing::measure(run_job(config, job));
  const std::array<std::int64_t, 3> steps_per_mm{80, 80, 400};
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const std::int64_t start = curvestep::testing::expected_q16_steps(start_grid[axis] * 64, steps_per_mm[axis], 1);
    const std::int64_t end = curvestep::testing::expected_q16_steps(grid[axis] * 64, steps_per_mm[axis], 1);
    INFO("axis " << axis);
    CHECK(axes[axis].count == end - start);
  }
  curvestep::testing::require_driver_timing(axes, timing, 100000);
}

}  // namespace

TEST_CASE("stepgen: the configuration follows the documented tick layout", "[core][stepgen]") {
  const StepConfig config = make_config(test_limits(), test_timing());
  CHECK(config.period_ticks() == 1000);
  CHECK(config.pulse_ticks() == 2);
  CHECK(config.low_ticks() == 2);
  CHECK(config.setup_ticks() == 1);
  CHECK(config.hold_ticks() == 1);
  CHECK(config.spacing_ticks() == 10);
  CHECK(config.guard_ticks() == 7);
  CHECK(config.window_ticks() == 990);
  CHECK(config.max_fine_delta() == 99u * 65536u);
  CHECK(config.max_steps_per_tick() == 100);
  CHECK(config.max_events_per_tick() == 3 * (1 + 2 * 100));
  CHECK(config.usable_step_rate_hz() == 99000.0);  // R / P of the 100 kHz driver limit
}

TEST_CASE("stepgen: nanosecond timings round up to whole timer ticks", "[core][stepgen]") {
  StepTiming timing = test_timing();
  timing.timer_hz = 72000000;   // 13.9 ns per tick
  timing.min_pulse_ns = 1900;   // 136.8 ticks -> 137
  timing.min_low_ns = 0;        // at least one tick
  timing.direction_setup_ns = 650;  // 46.8 -> 47
  timing.direction_hold_ns = 0;
  const StepConfig config = make_config(test_limits(), timing);
  CHECK(config.pulse_ticks() == 137);
  CHECK(config.low_ticks() == 1);
  CHECK(config.setup_ticks() == 47);
  CHECK(config.hold_ticks() == 0);
  CHECK(config.spacing_ticks() == 720);  // 72 MHz / 100 kHz
}

TEST_CASE("stepgen: an unusable configuration is rejected with the field at fault", "[core][stepgen]") {
  SECTION("a zero timer frequency") {
    StepTiming timing = test_timing();
    timing.timer_hz = 0;
    const auto config = StepConfig::create(test_limits(), timing);
    CHECK(config.error() == Error::InvalidArgument);
    CHECK(config.where() == static_cast<std::uint16_t>(StepTimingField::TimerHz));
  }
  SECTION("a timer that is not a whole multiple of the control rate") {
    StepTiming timing = test_timing();
    timing.timer_hz = 1000500;
    const auto config = StepConfig::create(test_limits(), timing);
    CHECK(config.error() == Error::InvalidRate);
    CHECK(config.where() == static_cast<std::uint16_t>(LimitField::RateHz));
  }
  SECTION("a pulse longer than a control tick") {
    StepTiming timing = test_timing();
    timing.min_pulse_ns = 999000;
    const auto config = StepConfig::create(test_limits(), timing);
    CHECK(config.error() == Error::InvalidArgument);
    CHECK(config.where() == static_cast<std::uint16_t>(StepTimingField::Period));
  }
  SECTION("steps per mm beyond 2^20 on the y axis") {
    const auto config = StepConfig::create(test_limits(80, 2.0e6, 80), test_timing());
    CHECK(config.error() == Error::InvalidLimit);
    CHECK(config.where() == static_cast<std::uint16_t>(LimitField::AxisStepsPerMm) + 1);
  }
  SECTION("a negative steps per mm on the z axis") {
    const auto config = StepConfig::create(test_limits(80, 80, -1), test_timing());
    CHECK(config.error() == Error::InvalidLimit);
    CHECK(config.where() == static_cast<std::uint16_t>(LimitField::AxisStepsPerMm) + 2);
  }
}

TEST_CASE("stepgen: the steps of one tick are spread evenly inside the tick", "[core][stepgen]") {
  // 64 steps/mm: one step is 1/64 mm = 1024 raw in Q16.16, so whole steps are exact.
  const StepConfig config = make_config(test_limits(64, 80, 400), test_timing());
  for (const int steps : {2, 3, 7, 10, 33, 64, 99}) {
    INFO(steps << " steps in one tick");
    const std::vector<Setpoint<Q16_16>> job{setpoint_at<Q16_16>(0, Q16_16{}),
                                            setpoint_at<Q16_16>(1, Q16_16::from_raw(steps * 1024))};
    const auto axes = curvestep::testing::measure(run_job(config, job));
    const auto rises = rises_between(axes[0], 0, config.period_ticks());
    REQUIRE(rises.size() == static_cast<std::size_t>(steps));
    std::uint64_t smallest = UINT64_MAX, largest = 0;
    for (std::size_t i = 1; i < rises.size(); ++i) {
      smallest = std::min(smallest, rises[i] - rises[i - 1]);
      largest = std::max(largest, rises[i] - rises[i - 1]);
    }
    CHECK(largest - smallest <= 1);
    // Step j is due where the straight line crosses j + 1/2 steps, at (j + 1/2) / steps of the
    // tick; the documented bound puts each rise within [-(P - R) - 1, S] timer ticks of that.
    for (std::size_t j = 0; j < rises.size(); ++j) {
      const double ideal = (static_cast<double>(j) + 0.5) / steps * config.period_ticks();
      const double error = static_cast<double>(rises[j]) - ideal;
      CHECK(error >= -static_cast<double>(config.period_ticks() - config.window_ticks() + 1));
      CHECK(error <= static_cast<double>(config.setup_ticks()));
    }
    CHECK(rises.front() >= config.setup_ticks());
    CHECK(axes[0].falls.back() < config.period_ticks());
    CHECK(axes[0].count == steps);
  }
}

TEST_CASE("stepgen: a constant speed gives a uniform pulse train across ticks", "[core][stepgen]") {
  // 64 steps/mm, Q16.16: 2.5 steps per tick is 2.5/64 mm = 2560 raw; 0.4 steps per tick is 409.6
  // raw, so use 0.375 steps (384 raw) for an exact slow speed.
  const StepConfig config = make_config(test_limits(64, 80, 400), test_timing());
  for (const std::int32_t raw_per_tick : {2560, 384}) {
    const double steps_per_tick = raw_per_tick / 1024.0;
    INFO(steps_per_tick << " steps per tick");
    std::vector<Setpoint<Q16_16>> job;
    for (std::int32_t tick = 0; tick <= 200; ++tick) job.push_back(setpoint_at<Q16_16>(static_cast<std::uint64_t>(tick), Q16_16::from_raw(tick * raw_per_tick)));
    const auto axes = curvestep::testing::measure(run_job(config, job));
    const auto& rises = axes[0].rises;
    REQUIRE(rises.size() == static_cast<std::size_t>(std::llround(200 * steps_per_tick)));
    // Step j is due when the position crosses j + 1/2 steps: at (j + 1/2) / v ticks. The
    // documented bound: within [-(P - R) - 1, S] timer ticks of that instant.
    const double allowed_early = static_cast<double>(config.period_ticks() - config.window_ticks() + 1);
    const double allowed_late = config.setup_ticks();
    for (std::size_t j = 0; j < rises.size(); ++j) {
      const double ideal = (static_cast<double>(j) + 0.5) / steps_per_tick * config.period_ticks();
      const double error = static_cast<double>(rises[j]) - ideal;
      INFO("step " << j);
      REQUIRE(error >= -allowed_early);
      REQUIRE(error <= allowed_late);
    }
  }
}

TEST_CASE("stepgen: pulse width, low time and direction timing meet the driver's datasheet",
          "[core][stepgen]") {
  // A slow timer and a fast one, with different datasheets.
  struct Case {
    std::uint32_t timer_hz, pulse_ns, low_ns, setup_ns, hold_ns;
    double max_rate;
  };
  for (const Case c : {Case{1000000, 2000, 2000, 1000, 1000, 100000}, Case{72000000, 1900, 1900, 650, 650, 250000},
                       Case{72000000, 100, 100, 20, 0, 500000}, Case{2000000, 5000, 1000, 20000, 5000, 50000}}) {
    INFO("timer " << c.timer_hz << " pulse " << c.pulse_ns << " setup " << c.setup_ns);
    MachineLimits limits = test_limits();
    limits.max_step_rate_hz = c.max_rate;
    const StepTiming timing{c.timer_hz, c.pulse_ns, c.low_ns, c.setup_ns, c.hold_ns};
    const StepConfig config = make_config(limits, timing);
    // A zig-zag job with reversals every few ticks and speeds up to the per-tick limit.
    const double max_steps = static_cast<double>(config.max_fine_delta()) / 65536.0;
    std::vector<Setpoint<double>> job{setpoint_at<double>(0, 0.0)};
    double x = 0, y = 0, z = 0;
    for (std::uint64_t tick = 1; tick <= 60; ++tick) {
      const double sign = (tick / 5) % 2 == 0 ? 1.0 : -1.0;
      x += sign * (max_steps * 0.999) / 80.0;
      y -= sign * 1.3 / 80.0;
      z += sign * (static_cast<double>(tick % 7) * 0.37) / 400.0;
      job.push_back(setpoint_at<double>(tick, x, y, z));
    }
    const auto axes = curvestep::testing::measure(run_job(config, job));
    curvestep::testing::require_driver_timing(axes, timing, c.max_rate);
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      const double steps = std::array<double, 3>{80, 80, 400}[axis];
      const double end = std::array<double, 3>{x, y, z}[axis];
      CHECK(axes[axis].count == std::llround(end * steps));
      CHECK(axes[axis].directions.size() >= 2);
    }
  }
}

TEST_CASE("stepgen: a direction reversal writes the direction before the first step of the tick",
          "[core][stepgen]") {
  const StepTiming timing = test_timing();
  const StepConfig config = make_config(test_limits(64, 80, 400), timing);
  // x: 0 -> +3 steps (tick 1) -> +3 (tick 2, no steps) -> -2 (tick 3) -> 0 (tick 4).
  const double step = 1.0 / 64.0;
  const std::vector<Setpoint<double>> job{setpoint_at(0, 0.0), setpoint_at(1, 3 * step), setpoint_at(2, 3 * step),
                                          setpoint_at(3, -2 * step), setpoint_at(4, 0.0)};
  const auto edges = run_job(config, job);
  const auto axes = curvestep::testing::measure(edges);
  const AxisWaveform& x = axes[0];
  CHECK(x.count == 0);
  CHECK(x.rises.size() == 10);
  REQUIRE(x.directions.size() == 3);
  // Direction edges at the starts of ticks 1, 3 and 4: never in the tick without steps.
  CHECK(x.directions[0] == 0);
  CHECK(x.directions[1] == 2000);
  CHECK(x.directions[2] == 3000);
  CHECK(rises_between(x, 0, 1000).size() == 3);
  CHECK(rises_between(x, 1000, 2000).empty());
  CHECK(rises_between(x, 2000, 3000).size() == 5);
  CHECK(rises_between(x, 3000, 4000).size() == 2);
  std::vector<StepEdge> levels;
  for (const RecordedEdge& e : edges) {
    if (e.axis == 0 && (e.edge == StepEdge::DirectionPositive || e.edge == StepEdge::DirectionNegative)) levels.push_back(e.edge);
  }
  CHECK(levels == std::vector<StepEdge>{StepEdge::DirectionPositive, StepEdge::DirectionNegative, StepEdge::DirectionPositive});
  curvestep::testing::require_driver_timing(axes, timing, 100000);
  CHECK(axes[1].rises.empty());
  CHECK(axes[2].rises.empty());
}

TEST_CASE("stepgen: a tiny oscillation around a half step still meets the driver timing", "[core][stepgen]") {
  // The position dithers across the 0.5-step threshold every tick: one step up, one step down.
  const StepTiming timing = test_timing();
  const StepConfig config = make_config(test_limits(64, 80, 400), timing);
  std::vector<Setpoint<Q16_16>> job{setpoint_at<Q16_16>(0, Q16_16::from_raw(511))};
  for (std::uint64_t tick = 1; tick <= 40; ++tick) job.push_back(setpoint_at<Q16_16>(tick, Q16_16::from_raw(tick % 2 == 1 ? 513 : 511)));
  const auto axes = curvestep::testing::measure(run_job(config, job));
  CHECK(axes[0].rises.size() == 40);
  CHECK(axes[0].count == 0);
  curvestep::testing::require_driver_timing(axes, timing, 100000);
}

TEST_CASE("stepgen: a zero steps per mm axis emits nothing", "[core][stepgen]") {
  const StepConfig config = make_config(test_limits(80, 80, 0), test_timing());
  std::vector<Setpoint<float>> job;
  for (std::uint64_t tick = 0; tick <= 20; ++tick) job.push_back(setpoint_at<float>(tick, 0.0f, 0.0f, static_cast<float>(tick) * 37.5f));
  const auto edges = run_job(config, job);
  CHECK(edges.empty());
  StepGenerator generator(config);
  StepBatch<16> batch;
  CHECK(generator.advance(setpoint_at<float>(1, 0.0f, 0.0f, 1.0e9f), batch).has_value());
  CHECK(batch.empty());
  CHECK(generator.count(2) == 0);
}

TEST_CASE("stepgen: the step count on every axis equals the end position in steps after random walks",
          "[core][stepgen]") {
  const StepTiming timing = test_timing();
  const StepConfig config = make_config(test_limits(80, 80, 400), timing);
  std::mt19937 random(curvestep::testing::test_seed());
  const int ticks = curvestep::testing::test_count(3000);

  SECTION("Q16.16 positions, counts from exact integer arithmetic") {
    std::uniform_int_distribution<std::int32_t> velocity(-65536, 65536);  // +-1 mm per tick: +-80 / 400 steps... clamp z
    std::array<std::int32_t, 3> raw{-123457, 99999, 4242};
    std::vector<Setpoint<Q16_16>> job{setpoint_at(0, Q16_16::from_raw(raw[0]), Q16_16::from_raw(raw[1]), Q16_16::from_raw(raw[2]))};
    std::array<std::int32_t, 3> speed{};
    for (int tick = 1; tick <= ticks; ++tick) {
      for (std::size_t axis = 0; axis < 3; ++axis) {
        if (random() % 16 == 0) speed[axis] = velocity(random) / (axis == 2 ? 8 : 1);  // z: 400 steps/mm
        raw[axis] += speed[axis];
      }
      job.push_back(setpoint_at(static_cast<std::uint64_t>(tick), Q16_16::from_raw(raw[0]), Q16_16::from_raw(raw[1]),
                                Q16_16::from_raw(raw[2])));
    }
    REQUIRE(check_step_rate(std::span<const Setpoint<Q16_16>>(job), config).has_value());
    const auto axes = curvestep::testing::measure(run_job(config, job));
    const std::array<std::int64_t, 3> steps_per_mm{80, 80, 400};
    for (std::size_t axis = 0; axis < 3; ++axis) {
      const std::int64_t start = curvestep::testing::expected_q16_steps(job.front().position[axis].raw(), steps_per_mm[axis], 1);
      const std::int64_t end = curvestep::testing::expected_q16_steps(raw[axis], steps_per_mm[axis], 1);
      INFO("axis " << axis);
      CHECK(axes[axis].count == end - start);
    }
    curvestep::testing::require_driver_timing(axes, timing, 100000);
  }

  SECTION("double positions on a 1/1024 mm grid, counts from exact integers") {
    grid_walk<double>(config, timing, random, ticks);
  }
  SECTION("float positions on a 1/1024 mm grid, counts from exact integers") {
    grid_walk<float>(config, timing, random, ticks);
  }
}

TEST_CASE("stepgen: the generator's count matches the recorded steps after every tick", "[core][stepgen]") {
  const StepConfig config = make_config(test_limits(80, 80, 400), test_timing());
  StepGenerator generator(config);
  CountingStepOutput counter;
  StepBatch<batch_capacity> batch;
  std::mt19937 random(curvestep::testing::test_seed() + 7);
  std::uniform_int_distribution<std::int32_t> delta(-20000, 20000);
  std::int32_t raw = 0;
  for (std::uint64_t tick = 1; tick <= 500; ++tick) {
    raw += delta(random);
    REQUIRE(generator.advance(setpoint_at(tick, Q16_16::from_raw(raw)), batch).has_value());
    play(batch, counter);
    INFO("tick " << tick);
    REQUIRE(counter.count(0) == curvestep::testing::expected_q16_steps(raw, 80, 1));
    REQUIRE(generator.count(0) == counter.count(0));
  }
  CHECK(counter.steps_without_direction() == 0);
  CHECK(generator.tick() == 500);
}

TEST_CASE("stepgen: the peak speed check rejects a too-fast axis and accepts one just below the limit",
          "[core][stepgen]") {
  const MachineLimits limits = test_limits(80, 80, 400);  // 100 kHz: 1250 mm/s on x, y; 250 on z
  CHECK(check_step_rate({1250.0, 1250.0, 250.0}, limits).has_value());
  CHECK(check_step_rate({-1249.99, 1000.0, -249.99}, limits).has_value());
  const auto y = check_step_rate({100.0, 1250.001, 10.0}, limits);
  CHECK(y.error() == Error::StepRateTooHigh);
  CHECK(y.where() == 1);
  const auto z = check_step_rate({100.0, 100.0, -250.001}, limits);
  CHECK(z.error() == Error::StepRateTooHigh);
  CHECK(z.where() == 2);
  CHECK(check_step_rate({std::nan(""), 0.0, 0.0}, limits).error() == Error::NotFinite);
  MachineLimits broken = limits;
  broken.axes[1].steps_per_mm = -80;  // would make every speed pass if it were not rejected
  const auto invalid = check_step_rate({1.0e6, 1.0e6, 1.0e6}, broken);
  CHECK(invalid.error() == Error::InvalidLimit);
  CHECK(invalid.where() == static_cast<std::uint16_t>(LimitField::AxisStepsPerMm) + 1);
}

TEST_CASE("stepgen: the machine check uses each axis's own speed limit", "[core][stepgen]") {
  MachineLimits limits = test_limits(80, 80, 400);
  limits.v_max_mm_per_s = 2000;
  limits.axes[0].v_max_mm_per_s = 1200;
  limits.axes[1].v_max_mm_per_s = 1200;
  limits.axes[2].v_max_mm_per_s = 200;
  CHECK(check_machine_step_rate(limits).has_value());
  limits.axes[1].v_max_mm_per_s = 0;  // y only limited by the path speed: 2000 * 80 = 160 kHz
  const auto result = check_machine_step_rate(limits);
  CHECK(result.error() == Error::StepRateTooHigh);
  CHECK(result.where() == 1);
}

TEST_CASE("stepgen: the per-tick check accepts a tick at capacity and rejects one a hair above",
          "[core][stepgen]") {
  const StepTiming timing = test_timing();
  // R = 990, M = 10: at most 99 steps' worth of travel in a tick with two or more steps.
  const StepConfig config = make_config(test_limits(80, 80, 64), timing);
  const Q16_16 at_capacity = Q16_16::from_raw(99 * 1024);  // 99/64 mm on z (64 steps/mm)
  const Q16_16 above = Q16_16::from_raw(99 * 1024 + 1);

  const std::vector<Setpoint<Q16_16>> good{setpoint_at(0, Q16_16{}, Q16_16{}, Q16_16{}),
                                           setpoint_at(1, Q16_16{}, Q16_16{}, at_capacity),
                                           setpoint_at(2, Q16_16{}, Q16_16{}, at_capacity + at_capacity)};
  const std::vector<Setpoint<Q16_16>> bad{setpoint_at(0, Q16_16{}, Q16_16{}, Q16_16{}),
                                          setpoint_at(1, Q16_16{}, Q16_16{}, at_capacity),
                                          setpoint_at(2, Q16_16{}, Q16_16{}, at_capacity + above)};
  CHECK(check_step_rate(std::span<const Setpoint<Q16_16>>(good), config).has_value());
  const auto rejected = check_step_rate(std::span<const Setpoint<Q16_16>>(bad), config);
  CHECK(rejected.error() == Error::StepRateTooHigh);
  CHECK(rejected.where() == 2);

  const auto report = measure_step_rate(std::span<const Setpoint<Q16_16>>(bad), config);
  REQUIRE(report.has_value());
  CHECK(report.value().violations == 1);
  CHECK(report.value().first_violation_setpoint == 2);
  CHECK(report.value().first_violation_axis == 2);
  CHECK(report.value().peak_steps_per_tick[2] == 99);
  CHECK(report.value().peak_steps_per_s[2] == Approx(99000.0 + 1000.0 / 1024.0));

  // The accepted job, measured: rising edges 10 us apart at the closest, i.e. 100 kHz at most.
  const auto axes = curvestep::testing::measure(run_job(config, good));
  CHECK(axes[2].count == 198);
  CHECK(axes[2].min_rise_spacing >= 10);
  curvestep::testing::require_driver_timing(axes, timing, 100000);
}

TEST_CASE("stepgen: a tick the timing cannot hold fails before any edge and changes nothing",
          "[core][stepgen]") {
  const StepConfig config = make_config(test_limits(80, 80, 400), test_timing());
  StepGenerator generator(config);
  StepBatch<batch_capacity> batch;
  REQUIRE(generator.advance(setpoint_at(1, 0.5, 0.0, 0.0), batch).has_value());  // 40 steps on x
  REQUIRE(batch.size() == 81);
  // 200 steps on y in one tick: more than the 100 the tick can hold.
  const auto result = generator.advance(setpoint_at(2, 0.5, 2.5, 0.0), batch);
  CHECK(result.error() == Error::StepRateTooHigh);
  CHECK(result.where() == 1);
  CHECK(batch.size() == 81);  // untouched
  CHECK(generator.count(0) == 40);
  CHECK(generator.count(1) == 0);
  CHECK(generator.tick() == 1);
  // The generator carries on from where it was.
  REQUIRE(generator.advance(setpoint_at(2, 0.5, 0.5, 0.0), batch).has_value());
  CHECK(generator.count(1) == 40);
  CHECK(batch.start_ticks() == 1000);
}

TEST_CASE("stepgen: a batch too small for a tick is BufferTooSmall and changes nothing", "[core][stepgen]") {
  const StepConfig config = make_config(test_limits(80, 80, 400), test_timing());
  StepGenerator generator(config);
  StepBatch<6> small;
  const auto result = generator.advance(setpoint_at(1, 3.0 / 80.0), small);  // 3 steps: 7 edges
  CHECK(result.error() == Error::BufferTooSmall);
  CHECK(generator.count(0) == 0);
  CHECK(generator.advance(setpoint_at(1, 2.0 / 80.0), small).has_value());  // 2 steps: 5 edges
  CHECK(small.size() == 5);
}

TEST_CASE("stepgen: positions beyond 32-bit step counts are StepCountOverflow with the axis", "[core][stepgen]") {
  const StepConfig config = make_config(test_limits(80, 100000, 80), test_timing());
  StepGenerator generator(config);
  StepBatch<batch_capacity> batch;
  const auto result = generator.advance(setpoint_at(1, Q16_16{}, Q16_16{30000}, Q16_16{}), batch);
  CHECK(result.error() == Error::StepCountOverflow);
  CHECK(result.where() == 1);
  const auto reset = generator.reset(setpoint_at(0, 0.0, 0.0, 3.0e7));
  CHECK(reset.error() == Error::StepCountOverflow);
  CHECK(reset.where() == 2);
  const std::vector<Setpoint<double>> job{setpoint_at(0, 0.0), setpoint_at(1, std::nan(""))};
  const auto checked = check_step_rate(std::span<const Setpoint<double>>(job), config);
  CHECK(checked.error() == Error::NotFinite);
  CHECK(checked.where() == 0);
}

TEST_CASE("stepgen: a batch played into the recording output keeps its order and times", "[core][stepgen]") {
  const StepConfig config = make_config(test_limits(80, 80, 400), test_timing());
  StepGenerator generator(config);
  REQUIRE(generator.reset(setpoint_at(41, 0.0, 0.0, 0.0)).has_value());
  StepBatch<batch_capacity> batch;
  REQUIRE(generator.advance(setpoint_at(42, 0.05, -0.025, 0.01), batch).has_value());  // 4, -2, 4 steps
  CHECK(batch.start_ticks() == 41000);
  RecordingStepOutput<64> recorder;
  play(batch, recorder);
  REQUIRE(recorder.size() == batch.size());
  CHECK(recorder.dropped() == 0);
  CHECK(batch.size() == 3 + 2 * (4 + 2 + 4));
  for (std::size_t i = 0; i < batch.size(); ++i) {
    CHECK(recorder[i].time_ticks == 41000 + batch[i].offset_ticks);
    CHECK(recorder[i].axis == batch[i].axis);
    CHECK(recorder[i].edge == batch[i].edge);
    if (i > 0) {
      const bool ordered = batch[i - 1].offset_ticks < batch[i].offset_ticks ||
                           (batch[i - 1].offset_ticks == batch[i].offset_ticks && batch[i - 1].axis <= batch[i].axis);
      CHECK(ordered);
    }
  }
  RecordingStepOutput<4> tiny;
  play(batch, tiny);
  CHECK(tiny.size() == 4);
  CHECK(tiny.dropped() == batch.size() - 4);
}
