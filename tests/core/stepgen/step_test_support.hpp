// SPDX-License-Identifier: MIT
// Test helpers for the step generator: a growable recorder and a waveform checker that measures
// edges the way a logic analyser would (it knows nothing about how the generator places them).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include <curvestep/core/motion/step_generator.hpp>
#include <curvestep/core/motion/step_output.hpp>

namespace curvestep::testing {

/// A StepOutput for long test jobs (tests may allocate; lib/ may not).
struct VectorStepRecorder {
  std::vector<RecordedEdge> edges;
  void set_direction(std::uint64_t time, std::uint8_t axis, bool positive) {
    edges.push_back(RecordedEdge{time, axis, positive ? StepEdge::DirectionPositive : StepEdge::DirectionNegative});
  }
  void set_step(std::uint64_t time, std::uint8_t axis, bool high) {
    edges.push_back(RecordedEdge{time, axis, high ? StepEdge::StepHigh : StepEdge::StepLow});
  }
};

/// What the waveform checker measured on one axis.
struct AxisWaveform {
  std::vector<std::uint64_t> rises;        ///< rising step edges
  std::vector<std::uint64_t> falls;        ///< falling step edges
  std::vector<std::uint64_t> directions;   ///< direction edges
  std::int64_t count = 0;                  ///< signed steps, direction latched as a driver does
  std::uint64_t min_high_ticks = UINT64_MAX;   ///< shortest pulse
  std::uint64_t min_low_ticks = UINT64_MAX;    ///< shortest low time between pulses
  std::uint64_t min_rise_spacing = UINT64_MAX; ///< shortest time between two rising edges
  std::uint64_t min_setup_ticks = UINT64_MAX;  ///< shortest direction edge -> next rising edge
  std::uint64_t min_hold_ticks = UINT64_MAX;   ///< shortest falling edge -> next direction edge
  std::size_t steps_without_direction = 0;     ///< rising edges before any direction edge
  std::size_t redundant_direction_edges = 0;   ///< direction edges that do not change the level
};

/// Measures a recording. Fails the test on malformed waveforms (unsorted times, two rising edges
/// without a fall, a direction change while the step line is high).
inline std::array<AxisWaveform, motion_axes> measure(std::span<const RecordedEdge> edges) {
  std::array<AxisWaveform, motion_axes> axes;
  std::array<bool, motion_axes> high{};
  std::array<int, motion_axes> direction{};
  std::array<bool, motion_axes> have_fall{};
  std::array<bool, motion_axes> have_direction{};
  std::array<std::uint64_t, motion_axes> last_direction{};
  std::uint64_t previous_time = 0;
  for (const RecordedEdge& e : edges) {
    if (e.time_ticks < previous_time) FAIL("edges out of time order at " << e.time_ticks);
    previous_time = e.time_ticks;
    if (e.axis >= motion_axes) FAIL("edge on axis " << int{e.axis});
    AxisWaveform& w = axes[e.axis];
    switch (e.edge) {
      case StepEdge::DirectionPositive:
      case StepEdge::DirectionNegative: {
        if (high[e.axis]) FAIL("direction changed while the step line is high at " << e.time_ticks);
        const int level = e.edge == StepEdge::DirectionPositive ? 1 : -1;
        if (level == direction[e.axis]) ++w.redundant_direction_edges;
        direction[e.axis] = level;
        if (have_fall[e.axis]) w.min_hold_ticks = std::min(w.min_hold_ticks, e.time_ticks - w.falls.back());
        w.directions.push_back(e.time_ticks);
        have_direction[e.axis] = true;
        last_direction[e.axis] = e.time_ticks;
        break;
      }
      case StepEdge::StepHigh:
        if (high[e.axis]) FAIL("two rising edges without a fall at " << e.time_ticks);
        high[e.axis] = true;
        if (!w.rises.empty()) w.min_rise_spacing = std::min(w.min_rise_spacing, e.time_ticks - w.rises.back());
        if (have_fall[e.axis]) w.min_low_ticks = std::min(w.min_low_ticks, e.time_ticks - w.falls.back());
        if (have_direction[e.axis]) {
          w.min_setup_ticks = std::min(w.min_setup_ticks, e.time_ticks - last_direction[e.axis]);
          w.count += direction[e.axis];
        } else {
          ++w.steps_without_direction;
        }
        w.rises.push_back(e.time_ticks);
        break;
      case StepEdge::StepLow:
        if (!high[e.axis]) FAIL("falling edge without a rise at " << e.time_ticks);
        high[e.axis] = false;
        w.min_high_ticks = std::min(w.min_high_ticks, e.time_ticks - w.rises.back());
        w.falls.push_back(e.time_ticks);
        have_fall[e.axis] = true;
        break;
    }
  }
  for (std::size_t axis = 0; axis < motion_axes; ++axis) {
    if (high[axis]) FAIL("step line left high on axis " << axis);
  }
  return axes;
}

/// True if `ticks` of a `timer_hz` timer last at least `ns` nanoseconds (exact integer test).
inline bool lasts_at_least(std::uint64_t ticks, std::uint32_t timer_hz, std::uint32_t ns) {
  const std::uint64_t product = std::uint64_t{ns} * timer_hz;  // ticks * 1e9 >= product?
  const std::uint64_t needed = product / 1000000000u + (product % 1000000000u != 0 ? 1 : 0);
  return ticks >= needed;
}

/// Checks every electrical rule of `timing` and `max_step_rate_hz` on measured axes.
inline void require_driver_timing(const std::array<AxisWaveform, motion_axes>& axes, const StepTiming& timing,
                                  double max_step_rate_hz) {
  for (std::size_t axis = 0; axis < motion_axes; ++axis) {
    const AxisWaveform& w = axes[axis];
    INFO("axis " << axis);
    CHECK(w.steps_without_direction == 0);
    CHECK(w.redundant_direction_edges == 0);
    if (w.min_high_ticks != UINT64_MAX) CHECK(lasts_at_least(w.min_high_ticks, timing.timer_hz, timing.min_pulse_ns));
    if (w.min_low_ticks != UINT64_MAX) CHECK(lasts_at_least(w.min_low_ticks, timing.timer_hz, timing.min_low_ns));
    if (w.min_setup_ticks != UINT64_MAX) {
      CHECK(lasts_at_least(w.min_setup_ticks, timing.timer_hz, timing.direction_setup_ns));
    }
    if (w.min_hold_ticks != UINT64_MAX) CHECK(lasts_at_least(w.min_hold_ticks, timing.timer_hz, timing.direction_hold_ns));
    if (w.min_rise_spacing != UINT64_MAX) {
      // rate = timer_hz / spacing must not exceed the limit.
      CHECK(static_cast<double>(timing.timer_hz) / static_cast<double>(w.min_rise_spacing) <= max_step_rate_hz);
    }
  }
}

/// round(raw * numerator / (denominator * 65536)), half away from zero, in exact integers: the
/// step count of a Q16.16 position at steps_per_mm = numerator / denominator.
inline std::int64_t expected_q16_steps(std::int64_t raw, std::int64_t numerator, std::int64_t denominator) {
  const std::int64_t n = raw * numerator;
  const std::int64_t d = denominator * 65536;
  const std::int64_t magnitude = n < 0 ? -n : n;
  const std::int64_t q = (2 * magnitude + d) / (2 * d);  // floor(|n|/d + 1/2)
  return n < 0 ? -q : q;
}

}  // namespace curvestep::testing
