// SPDX-License-Identifier: MIT
// StepGenerator: setpoints to timed step/dir edges per axis, with exact counts, driver timing and
// a step-rate check that rejects a job the machine cannot follow before it runs.
//
// The maths
// ---------
// Every control tick the interpolator hands over the next Setpoint. Between two setpoints each axis
// moves along a straight line in "fine" step units u (1/65536 step, step_position.hpp). The step
// count is c = round(u). In the tick an axis takes n = |c1 - c0| steps, in the direction of
// c1 - c0, so after any job the count is c_end - c_start, the end position in steps, exactly: the
// counts telescope and nothing is lost to rounding (grbl's Bresenham gives the same guarantee per
// block; here it holds per tick and so for the whole job).
//
// Where in the tick do the steps go? Step j is taken where the straight line crosses the j-th
// half-step threshold, i.e. at the fraction x_j = d_j / D of the tick, with D = |u1 - u0| and
// d_j = d_0 + j * 65536 the distance from u0 to the threshold. That is a DDA on the step timer:
// after one or two divisions per axis and tick, each further step costs two additions and a compare
// (quotient and remainder of d_j * R / D advance by fixed amounts). At a constant speed the pulse
// train is uniform across tick boundaries too, including speeds below one step per tick; this
// removes the aliasing that grbl's AMASS fights by over-driving its ISR at low step rates.
//
// One tick, in step-timer ticks (P = timer_hz / rate_hz):
//
//     0          S                                  S+R          P-G        P
//     |--dir-----|===== rising edges live here =====|--pulse H--|--guard G--|
//
//   H  pulse high time  = max(1, ceil(min_pulse_ns * timer_hz / 1e9))
//   L  pulse low time   = max(1, ceil(min_low_ns ...))
//   S  direction set-up = ceil(direction_setup_ns ...)
//   Hd direction hold   = ceil(direction_hold_ns ...)
//   M  rise spacing     = max(H + L, ceil(timer_hz / max_step_rate_hz))
//   G  guard            = max(1, Hd, M - S - H)
//   R  rise window      = P - S - H - G            (must be >= 0)
//
// Step j rises at S + floor(x_j * R) and falls H later. A direction change is written at offset 0
// of the first tick that steps the other way (never in a tick without steps).
//
// Guarantees (each follows from the layout; the tests measure them on recorded edges):
//   * every edge of a tick lies in [0, P - G], inside the tick: batches never overlap;
//   * direction set-up >= S ticks >= direction_setup_ns (first rise of a tick is at >= S);
//   * direction hold >= Hd ticks >= direction_hold_ns (every fall is at <= P - G <= P - Hd, the
//     next direction edge at >= P);
//   * pulse high time = H ticks >= min_pulse_ns;
//   * two rising edges of one axis are >= M ticks apart, hence low time >= L ticks >= min_low_ns
//     and no instantaneous rate above max_step_rate_hz. Across ticks: (P + S) - (S + R) = S + H + G
//     >= M. Inside a tick: successive rises differ by >= floor(65536 * R / D), which is >= M when
//     D <= max_fine_delta = floor(65536 * R / M). That is the per-tick step-rate check: a tick with
//     two or more steps and D > max_fine_delta is StepRateTooHigh, before any edge is written;
//   * timing error: a rise sits within [-(P - R) - 1, S] ticks of the exact crossing time x_j * P;
//   * the window costs rate: the usable steady rate is R / P of timer_hz / M
//     (usable_step_rate_hz(); 99 % for a 1 kHz tick on a 1 MHz timer).
//
// Before a job runs, check_step_rate() over its setpoints applies the same per-tick rule on the
// host (the failure Klipper reports only at run time as "Rescheduled timer in the past", and of
// which its maintainer says "there's no way to check for this type of error in the host
// software"), and check_step_rate(peak speeds) / check_machine_step_rate(limits) compare
// |v_axis| * steps_per_mm with max_step_rate_hz.
//
// ISR time budget. advance() runs once per control tick (in the tick interrupt or right after
// it); the board's edge interrupt then replays the batch. Instruction counts measured in QEMU
// (lm3s6965evb, Cortex-M3, -O2, one instruction per translation block, traced and counted):
//   * Q16.16, one axis taking one step:                      ~800 instructions per tick;
//   * Q16.16, three axes stepping: ~1 100 fixed + ~55 per edge (two edges per step), e.g.
//     10 + 10 + 2.5 steps per tick: ~3 500 instructions;
//   * float positions: ~450 more per tick (three software double multiplications);
//   * the divisions are one hardware UDIV each in the usual case (fewer than 65536 steps per
//     tick); only larger values fall back to the 64-bit library division.
// A Cortex-M3 takes about 1.2 to 1.5 cycles per instruction here, so at 72 MHz a 1 kHz tick with
// 22 steps spends ~70 us in advance(): 7 % of the CPU; the per-tick worst case (three axes at
// max_steps_per_tick() = 100 steps, i.e. 100 kHz on every axis) is ~34 000 instructions, about
// 0.6 ms of each 1 ms: on a 72 MHz Cortex-M3 plan for at most ~50 kHz per axis with three axes
// moving. The board's edge interrupt (one pin write and one compare-register write per edge) is
// estimated at 20..40 cycles per edge, not measured here.
// Nothing here loops over anything but the edges it emits; no allocation, no exceptions.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/core/motion/setpoint.hpp>
#include <curvestep/core/motion/step_output.hpp>
#include <curvestep/core/motion/step_position.hpp>
#include <curvestep/core/result.hpp>
#include <curvestep/core/scalar.hpp>

namespace curvestep {

/// Electrical timing of the step and direction lines, from the driver's datasheet.
struct StepTiming {
  std::uint32_t timer_hz = 1000000;        ///< resolution of the step timer (edges land on its ticks)
  std::uint32_t min_pulse_ns = 2000;       ///< step line high time
  std::uint32_t min_low_ns = 2000;         ///< step line low time between two pulses
  std::uint32_t direction_setup_ns = 1000; ///< direction stable before a rising step edge
  std::uint32_t direction_hold_ns = 1000;  ///< direction stable after a falling step edge
};

/// Which StepTiming field an InvalidArgument from StepConfig::create names (the error's index).
enum class StepTimingField : std::uint8_t {
  TimerHz = 0,  ///< timer_hz is zero
  Period = 1,   ///< timer ticks per control tick above 2^23, or too few to hold one pulse
};

/// Largest number of step-timer ticks per control tick (keeps the DDA products below 2^63).
inline constexpr std::uint32_t max_period_ticks = std::uint32_t{1} << 23;

/// The step generator's configuration in step-timer ticks, derived once from MachineLimits and
/// StepTiming (see the layout in the essay above).
class StepConfig {
 public:
  /// An unusable configuration; use create().
  constexpr StepConfig() noexcept = default;

  /// Validates and converts. Failures: whatever limits.validate() reports; InvalidLimit
  /// (AxisStepsPerMm + axis) for steps_per_mm above max_steps_per_mm; InvalidRate (RateHz) if
  /// timer_hz is not a whole multiple of rate_hz; InvalidArgument (StepTimingField) otherwise.
  [[nodiscard]] static constexpr Result<StepConfig> create(const MachineLimits& limits,
                                                           const StepTiming& timing) noexcept {
    CURVESTEP_CHECK(limits.validate());
    if (timing.timer_hz == 0) return fail(Error::InvalidArgument, static_cast<std::size_t>(StepTimingField::TimerHz));
    StepConfig config;
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      const auto scale = StepScale::create(limits.axes[axis].steps_per_mm);
      if (!scale) return fail(Error::InvalidLimit, static_cast<std::size_t>(LimitField::AxisStepsPerMm) + axis);
      config.scales_[axis] = scale.value();
    }
    const double timer = static_cast<double>(timing.timer_hz);
    const double period = timer / limits.rate_hz;
    if (!(period >= 1.0) || !(period <= static_cast<double>(max_period_ticks))) {
      return fail(Error::InvalidArgument, static_cast<std::size_t>(StepTimingField::Period));
    }
    const auto period_ticks = static_cast<std::uint32_t>(period);
    if (static_cast<double>(period_ticks) * limits.rate_hz != timer) {
      return fail(Error::InvalidRate, static_cast<std::size_t>(LimitField::RateHz));
    }
    const double rate_spacing = timer / limits.max_step_rate_hz;  // clamped to 2^32 for tiny rates
    std::uint64_t spacing_rate = rate_spacing >= 4294967296.0 ? 4294967296u : static_cast<std::uint64_t>(rate_spacing);
    if (static_cast<double>(spacing_rate) < rate_spacing) ++spacing_rate;
    const std::uint64_t pulse = at_least_one(ns_to_ticks(timing.min_pulse_ns, timing.timer_hz));
    const std::uint64_t low = at_least_one(ns_to_ticks(timing.min_low_ns, timing.timer_hz));
    const std::uint64_t setup = ns_to_ticks(timing.direction_setup_ns, timing.timer_hz);
    const std::uint64_t hold = ns_to_ticks(timing.direction_hold_ns, timing.timer_hz);
    const std::uint64_t spacing = maximum(pulse + low, spacing_rate);
    std::uint64_t guard = maximum(1, hold);
    if (spacing > setup + pulse) guard = maximum(guard, spacing - setup - pulse);
    if (setup + pulse + guard > period_ticks) {
      return fail(Error::InvalidArgument, static_cast<std::size_t>(StepTimingField::Period));
    }
    config.timer_hz_ = timing.timer_hz;
    config.period_ticks_ = period_ticks;
    config.pulse_ticks_ = static_cast<std::uint32_t>(pulse);
    config.low_ticks_ = static_cast<std::uint32_t>(low);
    config.setup_ticks_ = static_cast<std::uint32_t>(setup);
    config.hold_ticks_ = static_cast<std::uint32_t>(hold);
    config.spacing_ticks_ = static_cast<std::uint32_t>(spacing);
    config.guard_ticks_ = static_cast<std::uint32_t>(guard);
    config.window_ticks_ = static_cast<std::uint32_t>(period_ticks - setup - pulse - guard);
    config.max_fine_delta_ = (std::uint64_t{config.window_ticks_} << fine_step_bits) / spacing;
    return config;
  }

  /// Quantised steps per millimetre of an axis.
  [[nodiscard]] constexpr StepScale scale(std::size_t axis) const {
    CURVESTEP_EXPECTS(axis < motion_axes);
    return scales_[axis];
  }
  /// Step-timer frequency in Hz.
  [[nodiscard]] constexpr std::uint32_t timer_hz() const noexcept { return timer_hz_; }
  /// P: step-timer ticks per control tick.
  [[nodiscard]] constexpr std::uint32_t period_ticks() const noexcept { return period_ticks_; }
  /// H: step pulse high time in timer ticks.
  [[nodiscard]] constexpr std::uint32_t pulse_ticks() const noexcept { return pulse_ticks_; }
  /// L: least step low time in timer ticks.
  [[nodiscard]] constexpr std::uint32_t low_ticks() const noexcept { return low_ticks_; }
  /// S: direction set-up time in timer ticks (rising edges start this late in a tick).
  [[nodiscard]] constexpr std::uint32_t setup_ticks() const noexcept { return setup_ticks_; }
  /// Hd: direction hold time in timer ticks.
  [[nodiscard]] constexpr std::uint32_t hold_ticks() const noexcept { return hold_ticks_; }
  /// M: least spacing of two rising edges on one axis, in timer ticks.
  [[nodiscard]] constexpr std::uint32_t spacing_ticks() const noexcept { return spacing_ticks_; }
  /// G: quiet time at the end of every tick, in timer ticks.
  [[nodiscard]] constexpr std::uint32_t guard_ticks() const noexcept { return guard_ticks_; }
  /// R: rising edges lie in [S, S + R] of a tick.
  [[nodiscard]] constexpr std::uint32_t window_ticks() const noexcept { return window_ticks_; }
  /// Largest fine-position change (1/65536 step) of a tick with two or more steps.
  [[nodiscard]] constexpr std::uint64_t max_fine_delta() const noexcept { return max_fine_delta_; }
  /// Most steps one axis can take in one tick.
  [[nodiscard]] constexpr std::uint32_t max_steps_per_tick() const noexcept {
    return static_cast<std::uint32_t>(max_fine_delta_ >> fine_step_bits) + 1;
  }
  /// Fastest steady step rate an axis can run at under the per-tick rule, in steps per second:
  /// max_fine_delta() / 65536 steps per tick times the control rate. Plan axis speeds below it.
  [[nodiscard]] constexpr double usable_step_rate_hz() const noexcept {
    if (period_ticks_ == 0) return 0;
    return static_cast<double>(max_fine_delta_) / 65536.0 * static_cast<double>(timer_hz_) /
           static_cast<double>(period_ticks_);
  }
  /// Most edges one tick can produce on all axes (size a StepBatch with at least this).
  [[nodiscard]] constexpr std::size_t max_events_per_tick() const noexcept {
    return motion_axes * (1 + 2 * std::size_t{max_steps_per_tick()});
  }

 private:
  static constexpr std::uint64_t ns_to_ticks(std::uint32_t ns, std::uint32_t timer_hz) noexcept {
    const std::uint64_t product = std::uint64_t{ns} * timer_hz;  // < 2^64
    return (product + 999999999u) / 1000000000u;                 // rounded up: never shorter
  }
  static constexpr std::uint64_t at_least_one(std::uint64_t ticks) noexcept { return ticks == 0 ? 1 : ticks; }
  static constexpr std::uint64_t maximum(std::uint64_t a, std::uint64_t b) noexcept { return a < b ? b : a; }

  std::array<StepScale, motion_axes> scales_{};
  std::uint32_t timer_hz_ = 0;
  std::uint32_t period_ticks_ = 0;
  std::uint32_t pulse_ticks_ = 0;
  std::uint32_t low_ticks_ = 0;
  std::uint32_t setup_ticks_ = 0;
  std::uint32_t hold_ticks_ = 0;
  std::uint32_t spacing_ticks_ = 0;
  std::uint32_t guard_ticks_ = 0;
  std::uint32_t window_ticks_ = 0;
  std::uint64_t max_fine_delta_ = 0;
};

/// Checks peak axis speeds against the driver limit: StepRateTooHigh (index = axis) if
/// |v_axis| * steps_per_mm > max_step_rate_hz, NotFinite (index = axis) for NaN/inf; first
/// whatever limits.validate() reports.
[[nodiscard]] constexpr Result<void> check_step_rate(const std::array<double, motion_axes>& peak_speed_mm_per_s,
                                                     const MachineLimits& limits) noexcept {
  CURVESTEP_CHECK(limits.validate());
  for (std::size_t axis = 0; axis < motion_axes; ++axis) {
    const double speed = peak_speed_mm_per_s[axis] < 0 ? -peak_speed_mm_per_s[axis] : peak_speed_mm_per_s[axis];
    if (!is_finite(speed)) return fail(Error::NotFinite, axis);
    if (speed * limits.axes[axis].steps_per_mm > limits.max_step_rate_hz) return fail(Error::StepRateTooHigh, axis);
  }
  return ok();
}

/// Checks the fastest speed the limits allow on each axis (its v_max, else the larger of the path
/// v_max and the rapid speed) against max_step_rate_hz: passing means no job planned within these
/// limits can ask an axis for too high a step rate. StepRateTooHigh (index = axis).
[[nodiscard]] constexpr Result<void> check_machine_step_rate(const MachineLimits& limits) noexcept {
  const double path_speed = limits.rapid_mm_per_s > limits.v_max_mm_per_s ? limits.rapid_mm_per_s : limits.v_max_mm_per_s;
  std::array<double, motion_axes> peak{};
  for (std::size_t axis = 0; axis < motion_axes; ++axis) {
    const double axis_limit = limits.axes[axis].v_max_mm_per_s;
    peak[axis] = axis_limit > 0 && axis_limit < path_speed ? axis_limit : path_speed;
  }
  return check_step_rate(peak, limits);
}

/// What a job asks of the step generator, from check over its setpoints.
struct StepRateReport {
  std::array<std::uint32_t, motion_axes> peak_steps_per_tick{};  ///< most steps one tick asks of each axis
  std::array<double, motion_axes> peak_steps_per_s{};  ///< fastest straight-line step rate of any tick
  std::size_t violations = 0;                ///< ticks (axis by axis) beyond the per-tick capacity
  std::size_t first_violation_setpoint = 0;  ///< index of the setpoint that ends the first such tick
  std::size_t first_violation_axis = 0;      ///< its axis
};

namespace detail {
/// One axis's move over one tick: counts and fine positions.
struct AxisMove {
  std::int64_t fine_from = 0;
  std::int64_t fine_to = 0;
  std::int32_t count_from = 0;
  std::int32_t count_to = 0;

  /// Steps taken in the tick.
  [[nodiscard]] constexpr std::uint32_t steps() const noexcept {
    const std::int64_t delta = std::int64_t{count_to} - count_from;
    return static_cast<std::uint32_t>(delta < 0 ? -delta : delta);
  }
  /// D: the distance moved in the tick, in 1/65536 step.
  [[nodiscard]] constexpr std::uint64_t fine_distance() const noexcept {
    const std::int64_t delta = fine_to - fine_from;
    return static_cast<std::uint64_t>(delta < 0 ? -delta : delta);
  }
  /// True if the tick fits the configuration's rise spacing.
  [[nodiscard]] constexpr bool fits(const StepConfig& config) const noexcept {
    return steps() < 2 || fine_distance() <= config.max_fine_delta();
  }
};

/// The fine positions of a setpoint, with the axis as the failure index.
template <Scalar S>
[[nodiscard]] constexpr Result<std::array<std::int64_t, motion_axes>> fine_positions(const Setpoint<S>& setpoint,
                                                                                      const StepConfig& config) noexcept {
  std::array<std::int64_t, motion_axes> fine{};
  for (std::size_t axis = 0; axis < motion_axes; ++axis) {
    const auto converted = fine_step_position(setpoint.position[axis], config.scale(axis));
    if (!converted) return fail(converted.error(), axis);
    fine[axis] = converted.value();
  }
  return fine;
}
}  // namespace detail

/// measure_step_rate fed one setpoint at a time, for setpoints that are not held (a simulation
/// streamed through, host_tools' gpio command): add() each in order, the first being where the
/// machine starts; report() is measure_step_rate's for the setpoints added so far.
template <Scalar S>
class StepRateMeter {
 public:
  explicit constexpr StepRateMeter(const StepConfig& config) noexcept
      : config_(config), ticks_per_s_(static_cast<double>(config.timer_hz()) / static_cast<double>(config.period_ticks())) {}

  /// The next setpoint. Fails only on StepCountOverflow / NotFinite (index = axis).
  [[nodiscard]] constexpr Result<void> add(const Setpoint<S>& setpoint) noexcept {
    CURVESTEP_TRY(const auto next, detail::fine_positions(setpoint, config_));
    if (added_++ > 0) {
      for (std::size_t axis = 0; axis < motion_axes; ++axis) {
        const detail::AxisMove move{previous_[axis], next[axis], steps_of_fine_position(previous_[axis]),
                                    steps_of_fine_position(next[axis])};
        if (move.steps() > report_.peak_steps_per_tick[axis]) report_.peak_steps_per_tick[axis] = move.steps();
        const double rate = static_cast<double>(move.fine_distance()) / 65536.0 * ticks_per_s_;
        if (rate > report_.peak_steps_per_s[axis]) report_.peak_steps_per_s[axis] = rate;
        if (!move.fits(config_)) {
          if (report_.violations == 0) {
            report_.first_violation_setpoint = added_ - 1;
            report_.first_violation_axis = axis;
          }
          ++report_.violations;
        }
      }
    }
    previous_ = next;
    return ok();
  }

  [[nodiscard]] constexpr const StepRateReport& report() const noexcept { return report_; }

 private:
  StepConfig config_;
  double ticks_per_s_;
  StepRateReport report_{};
  std::array<std::int64_t, motion_axes> previous_{};
  std::size_t added_ = 0;
};

/// Measures a job's setpoints (one per tick; setpoints[0] is where the machine starts) against
/// the per-tick rule of the generator. Fails only on StepCountOverflow / NotFinite (index = axis).
template <Scalar S>
[[nodiscard]] constexpr Result<StepRateReport> measure_step_rate(std::span<const Setpoint<S>> setpoints,
                                                                 const StepConfig& config) noexcept {
  StepRateMeter<S> meter(config);
  for (const Setpoint<S>& setpoint : setpoints) CURVESTEP_CHECK(meter.add(setpoint));
  return meter.report();
}

/// Rejects, before it runs, a job whose setpoints (one per tick; setpoints[0] is the start) ask
/// some tick for more steps than it can hold: StepRateTooHigh with index = the axis of the first
/// such tick (measure_step_rate() names the setpoint). StepCountOverflow / NotFinite as there.
template <Scalar S>
[[nodiscard]] constexpr Result<void> check_step_rate(std::span<const Setpoint<S>> setpoints,
                                                     const StepConfig& config) noexcept {
  CURVESTEP_TRY(const StepRateReport report, measure_step_rate(setpoints, config));
  if (report.violations != 0) return fail(Error::StepRateTooHigh, report.first_violation_axis);
  return ok();
}

/// Turns setpoints, one per control tick, into timed step/dir edges (see the essay above).
/// Holds the last setpoint's fine positions, the step counts and the direction levels.
class StepGenerator {
 public:
  /// A generator at position 0 on every axis, tick 0, direction levels not yet written.
  explicit constexpr StepGenerator(const StepConfig& config) noexcept : config_(config) {}

  /// Declares where the machine is (after homing or at the start of a job), without any edges:
  /// the counts become the setpoint's position in steps and the next batch starts at its tick.
  /// StepCountOverflow / NotFinite (index = axis); nothing changes on failure.
  template <Scalar S>
  [[nodiscard]] constexpr Result<void> reset(const Setpoint<S>& setpoint) noexcept {
    CURVESTEP_TRY(const auto fine, detail::fine_positions(setpoint, config_));
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      fine_[axis] = fine[axis];
      counts_[axis] = steps_of_fine_position(fine[axis]);
    }
    tick_ = setpoint.tick;
    return ok();
  }

  /// Moves to the next setpoint (the next control tick): fills `batch` with the tick's edges, sorted
  /// by time, starting at tick() * period_ticks(). Fails, leaving the generator and the batch
  /// unchanged, with StepCountOverflow / NotFinite (index = axis), StepRateTooHigh (index = axis)
  /// if a tick holds more steps than the timing allows, or BufferTooSmall if Capacity is too small
  /// for this tick's edges (a batch of max_events_per_tick() never is).
  template <Scalar S, std::size_t Capacity>
  [[nodiscard]] constexpr Result<void> advance(const Setpoint<S>& next, StepBatch<Capacity>& batch) noexcept {
    CURVESTEP_TRY(const auto target, detail::fine_positions(next, config_));
    std::array<detail::AxisMove, motion_axes> moves{};
    std::size_t events = 0;
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      moves[axis] = detail::AxisMove{fine_[axis], target[axis], counts_[axis], steps_of_fine_position(target[axis])};
      if (!moves[axis].fits(config_)) return fail(Error::StepRateTooHigh, axis);
      const std::uint32_t steps = moves[axis].steps();
      events += 2 * std::size_t{steps};
      if (steps != 0 && direction_[axis] != direction_of(moves[axis])) ++events;
    }
    if (events > Capacity) return fail(Error::BufferTooSmall);

    batch.clear(tick_ * config_.period_ticks());
    std::array<AxisCursor, motion_axes> cursors{};
    for (std::size_t axis = 0; axis < motion_axes; ++axis) start_cursor(cursors[axis], moves[axis], axis);
    // Merge of the axes' time-ordered edge sequences; ties go to the lower axis.
    for (;;) {
      std::size_t chosen = 0;
      for (std::size_t axis = 1; axis < motion_axes; ++axis) {
        if (cursors[axis].time < cursors[chosen].time) chosen = axis;
      }
      AxisCursor& cursor = cursors[chosen];
      if (cursor.time == idle_time) break;
      const bool stored = batch.try_push(StepEvent{cursor.time, static_cast<std::uint8_t>(chosen), cursor.edge});
      CURVESTEP_EXPECTS(stored);
      step_cursor(cursor);
    }
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      fine_[axis] = target[axis];
      counts_[axis] = moves[axis].count_to;
    }
    ++tick_;
    return ok();
  }

  /// The step count of an axis (its position in steps as the driver has been told).
  [[nodiscard]] constexpr std::int32_t count(std::size_t axis) const {
    CURVESTEP_EXPECTS(axis < motion_axes);
    return counts_[axis];
  }
  /// The tick of the last setpoint (the next batch starts at tick() * period_ticks()).
  [[nodiscard]] constexpr std::uint64_t tick() const noexcept { return tick_; }
  /// The configuration.
  [[nodiscard]] constexpr const StepConfig& config() const noexcept { return config_; }

 private:
  /// Time of a cursor with no edges left (offsets are below 2^23).
  static constexpr std::uint32_t idle_time = 0xFFFFFFFFu;

  /// One axis's edges within the tick being generated.
  struct AxisCursor {
    std::uint32_t time = idle_time;   // offset of the next edge
    StepEdge edge = StepEdge::StepHigh;
    std::uint32_t remaining = 0;      // rising edges still to emit
    std::uint32_t rise = 0;           // S + floor(d_j * R / D): offset of the current step's rise
    std::uint32_t increment = 0;      // floor(65536 * R / D) (< 2^23 when two or more steps)
    std::uint64_t remainder = 0;      // (d_j * R) mod D
    std::uint64_t increment_remainder = 0;  // (65536 * R) mod D
    std::uint64_t divisor = 0;        // D
  };

  static constexpr std::int8_t direction_of(const detail::AxisMove& move) noexcept {
    return move.count_to > move.count_from ? 1 : -1;
  }

  /// n / d with the remainder; one hardware 32-bit division when both fit (the usual case: fewer
  /// than 65536 steps per tick, a window below 2^16 ticks), else the 64-bit library routine.
  static constexpr std::uint64_t divide(std::uint64_t n, std::uint64_t d, std::uint64_t& remainder) noexcept {
    if ((n >> 32) == 0 && (d >> 32) == 0) {
      const auto n32 = static_cast<std::uint32_t>(n);
      const auto d32 = static_cast<std::uint32_t>(d);
      remainder = n32 % d32;
      return n32 / d32;
    }
    remainder = n % d;
    return n / d;
  }

  constexpr void start_cursor(AxisCursor& cursor, const detail::AxisMove& move, std::size_t axis) noexcept {
    const std::uint32_t steps = move.steps();
    if (steps == 0) return;
    const std::int8_t direction = direction_of(move);
    // Distance from the start to the first half-step threshold: |u0 - round(u0)| <= 1/2 step.
    const std::int64_t threshold = std::int64_t{move.count_from} * fine_steps_per_step +
                                   (direction > 0 ? fine_steps_per_step / 2 : -fine_steps_per_step / 2);
    const std::int64_t first = direction > 0 ? threshold - move.fine_from : move.fine_from - threshold;
    const std::uint64_t window = config_.window_ticks();
    const std::uint64_t numerator = static_cast<std::uint64_t>(first) * window;  // <= 2^16 * 2^23
    cursor.divisor = move.fine_distance();
    cursor.rise = config_.setup_ticks() + static_cast<std::uint32_t>(divide(numerator, cursor.divisor, cursor.remainder));
    if (steps > 1) {  // a single step needs no spacing
      cursor.increment = static_cast<std::uint32_t>(divide(window << fine_step_bits, cursor.divisor, cursor.increment_remainder));
    }
    cursor.remaining = steps;
    if (direction_[axis] != direction) {
      direction_[axis] = direction;
      cursor.time = 0;
      cursor.edge = direction > 0 ? StepEdge::DirectionPositive : StepEdge::DirectionNegative;
    } else {
      cursor.time = cursor.rise;
      cursor.edge = StepEdge::StepHigh;
    }
  }

  constexpr void step_cursor(AxisCursor& cursor) const noexcept {
    switch (cursor.edge) {
      case StepEdge::DirectionPositive:
      case StepEdge::DirectionNegative:
        cursor.time = cursor.rise;
        cursor.edge = StepEdge::StepHigh;
        return;
      case StepEdge::StepHigh:
        cursor.time = cursor.rise + config_.pulse_ticks();
        cursor.edge = StepEdge::StepLow;
        return;
      case StepEdge::StepLow:
        if (--cursor.remaining == 0) {
          cursor.time = idle_time;
          return;
        }
        cursor.rise += cursor.increment;
        cursor.remainder += cursor.increment_remainder;
        if (cursor.remainder >= cursor.divisor) {
          cursor.remainder -= cursor.divisor;
          ++cursor.rise;
        }
        cursor.time = cursor.rise;
        cursor.edge = StepEdge::StepHigh;
        return;
    }
  }

  StepConfig config_;
  std::array<std::int64_t, motion_axes> fine_{};
  std::array<std::int32_t, motion_axes> counts_{};
  std::array<std::int8_t, motion_axes> direction_{};  // 0: not written yet, +1, -1
  std::uint64_t tick_ = 0;
};

}  // namespace curvestep
