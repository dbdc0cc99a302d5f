// SPDX-License-Identifier: MIT
// What the App derives from its board type (board.hpp) at compile time or from the board's
// optional members: the Capabilities it announces, whether it can time its ticks (a cycle
// clock), the board's running count of lost step edges, and the step configuration whose
// busiest tick fits the board's StepBatch (docs/firmware.md, "Step edges and the board's batch").
#pragma once

#include <concepts>
#include <cstddef>
#include <cstdint>

#include <curvestep/core/motion/step_generator.hpp>
#include <curvestep/core/result.hpp>
#include <curvestep/firmware/board.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::firmware {

/// True if board B has a free-running cycle counter to time the ticks with.
template <class B>
inline constexpr bool has_cycle_clock = requires(B& b) {
  { b.cycle_count() } -> std::convertible_to<std::uint32_t>;
  { b.cycles_per_second() } -> std::convertible_to<std::uint32_t>;
};

/// The Capabilities an App on board B announces: `queue` slots, the board's axes and step-timer
/// rate, `lookahead` segments (0: no planner, so no segments and max_degree 0).
template <Board B>
[[nodiscard]] constexpr protocol::Capabilities board_capabilities(std::size_t queue, std::size_t lookahead) noexcept {
  protocol::Capabilities c;
  c.queue_capacity = static_cast<std::uint16_t>(queue);
  c.axis_count = static_cast<std::uint8_t>(B::axis_count);
  c.max_degree = lookahead > 0 ? static_cast<std::uint8_t>(protocol::max_segment_degree) : 0;  // no segments without a planner
  c.tick_rate_hz = B::step_timing().timer_hz;
  c.lookahead = static_cast<std::uint16_t>(lookahead);
  return c;
}

/// The board's running count of lost step/dir edges (a board that buffers edges reports
/// edges_dropped(); one that does not loses none).
template <class B>
[[nodiscard]] std::uint32_t edges_dropped_by(B& board) noexcept {
  if constexpr (requires { board.edges_dropped(); }) {
    return board.edges_dropped();
  } else {
    return 0;
  }
}

/// The step configuration for `limits` and board B's timing, with max_step_rate_hz lowered
/// until the busiest possible tick fits the board's StepBatch (the planner does not use that
/// field, so the plan is unchanged; a faster job then faults with StepRateTooHigh instead of
/// overflowing the batch). BufferTooSmall if not even one step per tick fits.
template <Board B>
[[nodiscard]] Result<StepConfig> fit_step_config(MachineLimits& limits) noexcept {
  for (int attempt = 0; attempt < 32; ++attempt) {
    CURVESTEP_TRY(const StepConfig config, StepConfig::create(limits, B::step_timing()));
    const std::size_t events = config.max_events_per_tick();
    if (events <= B::step_events_per_tick) return config;
    double scale = static_cast<double>(B::step_events_per_tick) / static_cast<double>(events);
    if (scale > 0.9) scale = 0.9;
    limits.max_step_rate_hz *= scale;
  }
  return fail(Error::BufferTooSmall, B::step_events_per_tick);
}

}  // namespace curvestep::firmware
