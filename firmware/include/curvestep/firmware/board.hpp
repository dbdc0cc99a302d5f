// SPDX-License-Identifier: MIT
// concept Board: everything the firmware needs from a target, checked at compile time.
//
// A board is a plain class (no virtual functions, no base class) that App<Board> calls directly;
// a missing or misspelled function is a compile error naming this concept. This file is the
// documentation of a board port: implement the members below and instantiate App<YourBoard>
// once in the board's main.cpp.
//
//   class MyBoard {
//    public:
//     static constexpr std::uint8_t axis_count = 3;              // 2 or 3 driven axes
//     static constexpr std::size_t step_events_per_tick = 64;    // StepBatch capacity (RAM!)
//     static constexpr StepTiming step_timing() { return {...}; } // step timer and driver timing
//     std::uint32_t now_ms();                                    // free-running millisecond clock
//     std::size_t read(std::span<std::byte> into);               // serial RX, never blocks
//     std::size_t write(std::span<const std::byte> bytes);       // serial TX, never blocks
//     void set_direction(std::uint64_t time_ticks, std::uint8_t axis, bool positive);
//     void set_step(std::uint64_t time_ticks, std::uint8_t axis, bool high);
//     void fault_stop();                                         // drop scheduled edges now
//     std::uint32_t edges_dropped();  // optional: edges that found the board's edge buffer full
//     std::uint32_t cycle_count();       // optional, with cycles_per_second(): a free-running
//     std::uint32_t cycles_per_second(); //   32-bit cycle counter that times the ticks (TickWatch)
//     std::uint8_t limit_switches();  // optional: closed limit switches, read every tick while
//                                     //   moving (limit_switches.hpp: bit 2 axis min, 2 axis + 1 max)
//     void position_declared(const std::array<std::int32_t, 3>& steps);  // optional (simulators)
//   };
//
// Timing contract:
//   * read() returns at once with the bytes already received (0 if none); write() takes as
//     many bytes as fit in the transmitter right now and returns that count (the App keeps the
//     rest and offers it again on the next poll()).
//   * set_direction / set_step receive the edges of one control tick, in time order, with
//     absolute step-timer times (StepTiming::timer_hz; one control tick is timer_hz / rate
//     step-timer ticks, and the edges of tick k lie in [k P, (k + 1) P)). A bare-metal board
//     stores them in a small ring replayed by a timer-compare interrupt; the Linux board writes
//     GPIO lines at those times; a test board records them.
//   * fault_stop() is called on Abort and on a fault: forget every edge not yet on the pins
//     and leave the step lines low. It must return at once.
//   * now_ms() wraps at 2^32 ms; the App uses differences only.
//   * edges_dropped() (optional, for boards that buffer edges): a running count of edges the
//     board could not keep. Any increase after a tick's edges were handed over is a fault
//     (StepsLost, with the segment's index): a lost edge is a lost step.
//   * cycle_count() (optional): wraps at 2^32, read at the start and end of every tick; the App
//     counts overruns and faults on a missed deadline (tick_watch.hpp, AppSettings).
#pragma once

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>

#include <curvestep/core/motion/step_generator.hpp>
#include <curvestep/core/motion/step_output.hpp>

namespace curvestep::firmware {

/// What a target provides to App: clock, serial bytes, step/dir edges, an emergency stop, facts.
template <class B>
concept Board = StepOutput<B> && requires(B& board, std::span<std::byte> into, std::span<const std::byte> bytes) {
  { board.now_ms() } -> std::same_as<std::uint32_t>;
  { board.read(into) } -> std::same_as<std::size_t>;
  { board.write(bytes) } -> std::same_as<std::size_t>;
  board.fault_stop();
  { B::step_timing() } -> std::same_as<StepTiming>;
  { B::axis_count } -> std::convertible_to<std::uint8_t>;
  { B::step_events_per_tick } -> std::convertible_to<std::size_t>;
};

}  // namespace curvestep::firmware
