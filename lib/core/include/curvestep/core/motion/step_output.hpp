// SPDX-License-Identifier: MIT
// Step/dir output: timed edges (StepEvent), one tick's batch of them, the StepOutput concept a
// board implements, and two allocation-free outputs for simulators and tests.
//
// The step generator does not touch pins. For every control tick it fills a StepBatch with the
// edges of that tick, sorted by time, each as an offset in step-timer ticks from the start of the
// tick. A board replays the batch from a timer-compare interrupt (one pin write and one compare
// register write per edge, estimated at 20 to 40 cycles on a Cortex-M3), or hands it to play() with an
// output that writes GPIO lines at the given times. Keeping the pins out of the generator is what
// lets the host simulator, the Linux GPIO board and the tests share the same edges (design.md:
// "the waveform logic is tested through the same output interface with a recording
// implementation").
#pragma once

#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>

#include <curvestep/core/container/inline_vector.hpp>
#include <curvestep/core/contract.hpp>
#include <curvestep/core/motion/machine_limits.hpp>

namespace curvestep {

/// What happens on a line at one instant. Direction levels: Positive makes the count go up.
enum class StepEdge : std::uint8_t {
  DirectionPositive = 0,  ///< direction line to the level that counts steps up
  DirectionNegative = 1,  ///< direction line to the level that counts steps down
  StepHigh = 2,           ///< rising edge of the step line: the driver takes a step here
  StepLow = 3,            ///< falling edge of the step line (ends the pulse)
};

/// One timed edge of one tick.
struct StepEvent {
  std::uint32_t offset_ticks = 0;            ///< step-timer ticks after the start of the tick
  std::uint8_t axis = 0;                     ///< 0 x, 1 y, 2 z
  StepEdge edge = StepEdge::DirectionPositive;  ///< which line and level

  /// Same time, axis and edge.
  friend constexpr bool operator==(const StepEvent&, const StepEvent&) = default;
};

/// The edges of one control tick, sorted by offset (ties: lower axis first), with the tick's start
/// time in step-timer ticks. Capacity is the most edges one tick may hold (see
/// StepConfig::max_events_per_tick()).
template <std::size_t Capacity>
class StepBatch : public InlineVector<StepEvent, Capacity> {
 public:
  /// Step-timer time of the start of the tick (offsets are relative to it).
  [[nodiscard]] constexpr std::uint64_t start_ticks() const noexcept { return start_ticks_; }

  /// Empties the batch and sets the start time of the next tick.
  constexpr void clear(std::uint64_t start_ticks = 0) noexcept {
    InlineVector<StepEvent, Capacity>::clear();
    start_ticks_ = start_ticks;
  }

 private:
  std::uint64_t start_ticks_ = 0;
};

/// What a board (or a simulator) provides to put edges on lines: times are absolute step-timer
/// ticks, `level` true means high (step) or positive (direction).
template <class O>
concept StepOutput = requires(O& output, std::uint64_t time_ticks, std::uint8_t axis, bool level) {
  output.set_direction(time_ticks, axis, level);
  output.set_step(time_ticks, axis, level);
};

/// Hands every edge of `batch` to `output`, in order, at its absolute time.
template <StepOutput O, std::size_t Capacity>
constexpr void play(const StepBatch<Capacity>& batch, O& output) {
  for (const StepEvent& event : batch) {
    const std::uint64_t time = batch.start_ticks() + event.offset_ticks;
    switch (event.edge) {
      case StepEdge::DirectionPositive: output.set_direction(time, event.axis, true); break;
      case StepEdge::DirectionNegative: output.set_direction(time, event.axis, false); break;
      case StepEdge::StepHigh: output.set_step(time, event.axis, true); break;
      case StepEdge::StepLow: output.set_step(time, event.axis, false); break;
    }
  }
}

/// One edge as recorded by RecordingStepOutput.
struct RecordedEdge {
  std::uint64_t time_ticks = 0;                 ///< absolute step-timer time
  std::uint8_t axis = 0;                        ///< 0 x, 1 y, 2 z
  StepEdge edge = StepEdge::DirectionPositive;  ///< which line and level

  /// Same time, axis and edge.
  friend constexpr bool operator==(const RecordedEdge&, const RecordedEdge&) = default;
};

/// A StepOutput that records up to Capacity edges with their times (for tests and the simulator).
/// Edges beyond the capacity are counted in dropped(), not stored.
template <std::size_t Capacity>
class RecordingStepOutput : private InlineVector<RecordedEdge, Capacity> {
  using Edges = InlineVector<RecordedEdge, Capacity>;

 public:
  /// Records a direction edge.
  constexpr void set_direction(std::uint64_t time_ticks, std::uint8_t axis, bool positive) noexcept {
    record(RecordedEdge{time_ticks, axis, positive ? StepEdge::DirectionPositive : StepEdge::DirectionNegative});
  }
  /// Records a step-line edge.
  constexpr void set_step(std::uint64_t time_ticks, std::uint8_t axis, bool high) noexcept {
    record(RecordedEdge{time_ticks, axis, high ? StepEdge::StepHigh : StepEdge::StepLow});
  }

  using Edges::begin;      ///< iteration over the recorded edges
  using Edges::capacity;   ///< room for this many edges
  using Edges::end;        ///< one past the last recorded edge
  using Edges::operator[]; ///< the edge at `index` (contract: index < size())
  using Edges::size;       ///< number of edges recorded
  /// Edges that arrived while full (0 in a valid recording).
  [[nodiscard]] constexpr std::size_t dropped() const noexcept { return dropped_; }
  /// Forgets every edge.
  constexpr void clear() noexcept {
    Edges::clear();
    dropped_ = 0;
  }

 private:
  constexpr void record(const RecordedEdge& edge) noexcept {
    if (!Edges::try_push(edge)) ++dropped_;
  }

  std::size_t dropped_ = 0;
};

/// A StepOutput that only counts: the signed step count per axis as a driver would see it (a
/// rising step edge moves one step in the direction last set). For long simulations.
class CountingStepOutput {
 public:
  /// Latches the direction level of an axis.
  constexpr void set_direction(std::uint64_t, std::uint8_t axis, bool positive) {
    CURVESTEP_EXPECTS(axis < motion_axes);
    direction_[axis] = positive ? 1 : -1;
  }
  /// Counts a rising step edge in the latched direction.
  constexpr void set_step(std::uint64_t, std::uint8_t axis, bool high) {
    CURVESTEP_EXPECTS(axis < motion_axes);
    if (!high) return;
    if (direction_[axis] == 0) {
      ++steps_without_direction_;
      return;
    }
    counts_[axis] += direction_[axis];
  }
  /// Signed step count of an axis.
  [[nodiscard]] constexpr std::int64_t count(std::size_t axis) const {
    CURVESTEP_EXPECTS(axis < motion_axes);
    return counts_[axis];
  }
  /// Rising edges seen before any direction was set on their axis (0 in a valid stream).
  [[nodiscard]] constexpr std::size_t steps_without_direction() const noexcept { return steps_without_direction_; }

 private:
  std::array<std::int64_t, motion_axes> counts_{};
  std::array<std::int8_t, motion_axes> direction_{};
  std::size_t steps_without_direction_ = 0;
};

}  // namespace curvestep
