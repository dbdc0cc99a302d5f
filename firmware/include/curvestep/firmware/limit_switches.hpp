// SPDX-License-Identifier: MIT
// Limit switches: the optional switch inputs of a board and the hard-limit rule App applies.
//
// A board with limit switches implements (both optional, board.hpp):
//
//   std::uint8_t limit_switches();   // the switches closed now: bit 2a = axis a's min switch,
//                                    // bit 2a + 1 its max switch (LimitSwitch); never waits
//   void position_declared(const std::array<std::int32_t, 3>& steps);  // the App declared the
//                                    // machine's position without moving (a job's first setpoint
//                                    // after power-up, a new session or configuration), in steps
//
// The rule (hard_limit_hit): after a tick's edges went to the board, a closed switch whose axis
// moved toward it in that tick (the min switch while the axis went down, the max switch while it
// went up) is a hard limit: the App stops at once (fault_stop, state Fault) and reports
// ErrorReport(HardLimit, index = the switch's bit number). A switch that is already closed stops
// only motion toward it, so the machine can move off a switch it stands on (after Abort), and
// homing can pull off. An axis that does not move in a tick never faults there.
//
// Homing (SeekSwitch, docs/firmware.md "Homing"): while a seek is armed, its switch closing ends
// the job where it stands instead (seek_closed; not a fault), whichever way the axis moved.
//
// Cost per tick: one board read and at most six comparisons; a board without switches compiles
// the check away.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include <curvestep/protocol/messages.hpp>

namespace curvestep::firmware {

/// The bit of a switch in the mask limit_switches() returns: 2 x axis, + 1 for the max side.
[[nodiscard]] constexpr std::uint8_t limit_switch_bit(std::size_t axis, bool max_side) noexcept {
  return static_cast<std::uint8_t>(2 * axis + (max_side ? 1 : 0));
}

/// No switch (hard_limit_hit found none).
inline constexpr std::uint8_t no_limit_switch = 0xFF;

/// True if board B has limit switch inputs.
template <class B>
inline constexpr bool has_limit_switches = requires(B& board) {
  { board.limit_switches() } -> std::convertible_to<std::uint8_t>;
};

/// The switches closed now (0 on a board without switch inputs).
template <class B>
[[nodiscard]] std::uint8_t read_limit_switches(B& board) noexcept {
  if constexpr (has_limit_switches<B>) {
    return static_cast<std::uint8_t>(board.limit_switches());
  } else {
    return 0;
  }
}

/// Tells a board that wants to know (position_declared) where the App declared the machine to be.
template <class B>
void declare_position(B& board, const std::array<std::int32_t, 3>& steps) noexcept {
  if constexpr (requires { board.position_declared(steps); }) board.position_declared(steps);
}

/// True if the seek switch `seek` (SeekSwitch; no_limit_switch: none armed) is in `closed`.
[[nodiscard]] constexpr bool seek_closed(std::uint8_t closed, std::uint8_t seek) noexcept {
  return seek < 8 && (closed & (1u << seek)) != 0;
}

/// The first switch in `closed` whose axis moved toward it from `from` to `to` (axes below
/// `axis_count`), or no_limit_switch.
[[nodiscard]] constexpr std::uint8_t hard_limit_hit(std::uint8_t closed, const protocol::WirePoint& from,
                                                    const protocol::WirePoint& to, std::size_t axis_count) noexcept {
  if (closed == 0) return no_limit_switch;
  for (std::size_t axis = 0; axis < axis_count && axis < from.size(); ++axis) {
    const bool down = to[axis] < from[axis];
    const bool up = to[axis] > from[axis];
    if (down && (closed & (1u << limit_switch_bit(axis, false))) != 0) return limit_switch_bit(axis, false);
    if (up && (closed & (1u << limit_switch_bit(axis, true))) != 0) return limit_switch_bit(axis, true);
  }
  return no_limit_switch;
}

}  // namespace curvestep::firmware
