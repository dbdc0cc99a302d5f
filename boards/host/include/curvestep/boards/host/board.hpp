// SPDX-License-Identifier: MIT
// HostBoard: the facts of the Linux host board (serial descriptor, millisecond clock, step
// timer rate, step/dir output) in the shape firmware::Board asks for.
//
// The serial line is a file descriptor in non-blocking mode (a tty or a pseudo-terminal, raw);
// read() and write() never wait, as the Board concept requires. The step/dir edges go to an
// Output that satisfies the core's StepOutput concept: GpiodStepOutput on a Raspberry-Pi-class
// board, RecordingStepOutput in tests, CountingStepOutput when no pins are wired (a virtual
// device). Choosing the output is a template parameter, so the tick path has no virtual call.
// Machine events are logged, and with MachineOutputHooks (machine_outputs.hpp: spindle, coolant,
// digital outputs and a servo pen on GPIO lines) also driven; an event is rare, one virtual call.
#pragma once

#include <cerrno>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <span>
#include <unistd.h>

#include <curvestep/boards/host/machine_outputs.hpp>
#include <curvestep/boards/host/monotonic_time.hpp>
#include <curvestep/core/motion/step_generator.hpp>
#include <curvestep/core/motion/step_output.hpp>
#include <curvestep/firmware/board.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::boards::host {

/// Clocks of the host board.
struct SystemClock {
  static constexpr std::uint32_t step_timer_hz = 1000000;  ///< step-timer resolution: 1 us
};

/// A StepOutput that only counts edges (a virtual device without pins).
class CountingStepOutput {
 public:
  /// Counts a direction edge.
  void set_direction(std::uint64_t, std::uint8_t, bool) noexcept { ++direction_edges_; }
  /// Counts a step edge (rising edges are steps).
  void set_step(std::uint64_t, std::uint8_t axis, bool high) noexcept {
    if (high && axis < 3) ++steps_[axis];
  }
  /// Nothing scheduled to forget.
  void fault_stop() noexcept {}
  /// Rising step edges per axis.
  [[nodiscard]] const std::uint64_t* steps() const noexcept { return steps_; }

 private:
  std::uint64_t steps_[3] = {0, 0, 0};
  std::uint64_t direction_edges_ = 0;
};

/// The Linux board around a serial descriptor and a step/dir output.
template <StepOutput Output>
class HostBoard {
 public:
  /// Axes the board drives.
  static constexpr std::uint8_t axis_count = 3;
  /// Edges one control tick may produce (RAM is plentiful here).
  static constexpr std::size_t step_events_per_tick = 4096;
  /// Setpoint-batch frames that may be unacknowledged at once (firmware::App's window).
  static constexpr std::size_t setpoint_window = 8;
  /// Step timer and driver timing (typical stepper drivers: 2 us pulses, 1 us set-up and hold).
  [[nodiscard]] static constexpr StepTiming step_timing() noexcept {
    return StepTiming{SystemClock::step_timer_hz, 2000, 2000, 1000, 1000};
  }

  /// A board on the non-blocking descriptor `serial_fd` (not owned) driving `output`, and the
  /// machine outputs `machine_outputs` (not owned; null: machine events are only logged).
  HostBoard(int serial_fd, Output& output, MachineOutputHooks* machine_outputs = nullptr) noexcept
      : fd_(serial_fd), output_(output), machine_outputs_(machine_outputs), epoch_ns_(to_nanoseconds(monotonic_now())) {}

  /// Milliseconds since the board was made (wraps at 2^32).
  [[nodiscard]] std::uint32_t now_ms() const noexcept {
    return static_cast<std::uint32_t>((to_nanoseconds(monotonic_now()) - epoch_ns_) / 1'000'000);
  }
  /// Microseconds since the board was made (wraps at 2^32): the App times its ticks with it.
  [[nodiscard]] std::uint32_t cycle_count() const noexcept {
    return static_cast<std::uint32_t>((to_nanoseconds(monotonic_now()) - epoch_ns_) / 1'000);
  }
  /// Counts of cycle_count() per second.
  [[nodiscard]] static constexpr std::uint32_t cycles_per_second() noexcept { return 1'000'000; }
  /// Bytes already received (0 if none); never waits.
  std::size_t read(std::span<std::byte> into) noexcept {
    const ssize_t n = ::read(fd_, into.data(), into.size());
    if (n <= 0) return 0;
    if (observer_ != nullptr) observer_(observer_context_, into.first(static_cast<std::size_t>(n)));
    return static_cast<std::size_t>(n);
  }
  /// Writes what fits now; remembers a short write (the line is backed up).
  std::size_t write(std::span<const std::byte> bytes) noexcept {
    const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
    const std::size_t written = n > 0 ? static_cast<std::size_t>(n) : 0;
    backed_up_ = written < bytes.size();
    return written;
  }
  /// Forwards a direction edge to the output.
  void set_direction(std::uint64_t time_ticks, std::uint8_t axis, bool positive) noexcept {
    output_.set_direction(time_ticks, axis, positive);
  }
  /// Forwards a step edge to the output.
  void set_step(std::uint64_t time_ticks, std::uint8_t axis, bool high) noexcept { output_.set_step(time_ticks, axis, high); }
  /// Step lines low, scheduled edges forgotten.
  void fault_stop() noexcept {
    if constexpr (requires { output_.fault_stop(); }) output_.fault_stop();
  }

  /// Machine event hook (firmware/board_hooks.hpp): one line on standard error per event,
  /// "curvestep device: event NAME value V flag F at setpoint N" (the HIL tests read it).
  void machine_event(const protocol::QueueEvent& event, std::uint32_t setpoint) noexcept {
    ::dprintf(STDERR_FILENO, "curvestep device: event %s value %u flag %d at setpoint %u\n", protocol::machine_event_name(event.kind),
              static_cast<unsigned>(event.value), event.flag ? 1 : 0, static_cast<unsigned>(setpoint));
  }
  /// Spindle hook: to the machine outputs, if any.
  void spindle(bool on, bool counter_clockwise, std::uint32_t rpm, std::uint32_t) noexcept {
    if (machine_outputs_ != nullptr) machine_outputs_->spindle(on, counter_clockwise, rpm);
  }
  /// Coolant hook: to the machine outputs, if any.
  void coolant(bool mist, bool flood, std::uint32_t) noexcept {
    if (machine_outputs_ != nullptr) machine_outputs_->coolant(mist, flood);
  }
  /// Digital output hook (M62-M65): to the machine outputs, if any.
  void digital_output(std::uint32_t number, bool on, std::uint32_t) noexcept {
    if (machine_outputs_ != nullptr) machine_outputs_->digital_output(number, on);
  }
  /// Pen hook (servo pulse width in µs): to the machine outputs, if any.
  void pen(bool down, std::uint32_t pulse_us, std::uint32_t) noexcept {
    if (machine_outputs_ != nullptr) machine_outputs_->pen(down, pulse_us);
  }

  /// True if the last write could not take every byte (the host is not reading).
  [[nodiscard]] bool backed_up() const noexcept { return backed_up_; }
  /// Clears the backed-up flag (after the line drained).
  void clear_backed_up() noexcept { backed_up_ = false; }
  /// The serial descriptor.
  [[nodiscard]] int fd() const noexcept { return fd_; }
  /// The output.
  [[nodiscard]] Output& output() noexcept { return output_; }
  /// Calls `observer(context, bytes)` with every chunk read (the run loop watches frames with it).
  void set_read_observer(void (*observer)(void*, std::span<const std::byte>), void* context) noexcept {
    observer_ = observer;
    observer_context_ = context;
  }

 private:
  int fd_;
  Output& output_;
  MachineOutputHooks* machine_outputs_;
  std::int64_t epoch_ns_;  ///< CLOCK_MONOTONIC when the board was made
  bool backed_up_ = false;
  void (*observer_)(void*, std::span<const std::byte>) = nullptr;
  void* observer_context_ = nullptr;
};

static_assert(firmware::Board<HostBoard<CountingStepOutput>>, "HostBoard must satisfy firmware::Board");

}  // namespace curvestep::boards::host
