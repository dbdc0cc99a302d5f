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
class StepBatch {
  static_assert(Capacity > 0, "a StepBatch needs room for at least one edge");

 public:
  /// Room for this many edges.
  [[nodiscard]] static constexpr std::size_t capacity() noexcept { return Capacity; }
  /// Number of edges held.
  [[nodiscard]] constexpr std::size_t size() const noexcept { return size_; }
  /// True if no edges are held.
  [[nodiscard]] constexpr bool empty() const noexcept { return size_ == 0; }
  /// True if no more edges fit.
  [[nodiscard]] constexpr bool full() const noexcept { return size_ == Capacity; }
  /// Free room in edges.
  [[nodiscard]] constexpr std::size_t available() const noexcept { return Capacity - size_; }

  /// The edge at `index` (contract: index < size()).
  [[nodiscard]] constexpr const StepEvent& operator[](std::size_t index) const {
    CURVESTEP_EXPECTS(index < size_);
    return events_[index];
  }
  /// Iteration over the held edges.
  [[nodiscard]] constexpr const StepEvent* begin() const noexcept { return events_.data(); }
  /// One past the last held edge.
  [[nodiscard]] constexpr const StepEvent* end() const noexcept { return events_.data() + size_; }

  /// Step-timer time of the start of the tick (offsets are relative to it).
  [[nodiscard]] constexpr std::uint64_t start_ticks() const noexcept { return start_ticks_; }

  /// Empties the batch and sets the start time of the next tick.
  constexpr void clear(std::uint64_t start_ticks = 0) noexcept {
    size_ = 0;
    start_ticks_ = start_ticks;
  }
  /// Appends an edge; false (and nothing stored) if full.
  [[nodiscard]] constexpr bool try_push(const StepEvent& event) noexcept {
    if (size_ == Capacity) return false;
    events_[size_++] = event;
    return true;
  }

 private:
  std::array<StepEvent, Capacity> events_{};
  std::size_t size_ = 0;
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
class RecordingStepOutput {
  static_assert(Capacity > 0, "a RecordingStepOutput needs room for at least one edge");

 public:
  /// Records a direction edge.
  constexpr void set_direction(std::uint64_t time_ticks, std::uint8_t axis, bool positive) noexcept {
    record(RecordedEdge{time_ticks, axis, positive ? StepEdge::DirectionPositive : StepEdge::DirectionNegative});
  }
  /// Records a step-line edge.
  constexpr void set_step(std::uint64_t time_ticks, std::uint8_t axis, bool high) noexcept {
    record(RecordedEdge{time_ticks, axis, high ? StepEdge::StepHigh : StepEdge::StepLow});
  }

  /// Room for this many edges.
  [[nodiscard]] static constexpr std::size_t capacity() noexcept { return Capacity; }
  /// Number of edges recorded.
  [[nodiscard]] constexpr std::size_t size() const noexcept { return size_; }
  /// Edges that arrived while full (0 in a valid recording).
  [[nodiscard]] constexpr std::size_t dropped() const noexcept { return dropped_; }
  /// The edge at `index` (contract: index < size()).
  [[nodiscard]] constexpr const RecordedEdge& operator[](std::size_t index) const {
    CURVESTEP_EXPECTS(index < size_);
    return edges_[index];
  }
  /// Iteration over the recorded edges.
  [[nodiscard]] constexpr const RecordedEdge* begin() const noexcept { return edges_.data(); }
  /// One past the last recorded edge.
  [[nodiscard]] constexpr const RecordedEdge* end() const noexcept { return edges_.data() + size_; }
  /// Forgets every edge.
  constexpr void clear() noexcept {
    size_ = 0;
    dropped_ = 0;
  }

 private:
  constexpr void record(const RecordedEdge& edge) noexcept {
    if (size_ == Capacity) {
      ++dropped_;
      return;
    }
    edges_[size_++] = edge;
  }

  std::array<RecordedEdge, Capacity> edges_{};
  std::size_t size_ = 0;
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
