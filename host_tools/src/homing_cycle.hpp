// SPDX-License-Identifier: MIT
// run_homing_cycle: the homing cycle of the machine file's "homing" section (`curvestep home`,
// the `h` key of `curvestep console`), one axis at a time in its order. Per axis, each move a
// ControllerMoves::homing_move:
//   0. standing on the switch already: pull off first (motion away from a closed switch is allowed);
//   1. seek toward the switch at the seek speed for up to "distance" (SeekSwitch: the controller
//      ends the move where the switch closes and reports that position, SwitchReport);
//   2. pull off by "pull_off" (the switch must open again);
//   3. locate: toward the switch at the locate speed for up to twice the pull-off (SeekSwitch);
//   4. pull off again, and SetPosition: the axis is at "position".
// No soft limits apply while homing (the position is not known yet); hard limits do. The operator
// can abort at any time (Esc, Ctrl-X, Ctrl-C, SIGTERM): a running move stops at once (Abort) and the
// cycle ends with HomingAborted once the controller stands.
#pragma once

#include <array>
#include <ostream>
#include <stdexcept>
#include <string>

#include <curvestep/host/machine_file.hpp>

#include "controller_moves.hpp"

namespace curvestep::host {

/// The operator aborted the homing cycle; the controller stands (a running move was aborted and
/// the controller reported it stopped). The message says which axis and where it stands.
class HomingAborted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A switch did not behave: it did not close within the move, or stayed closed after the pull-off.
/// The message names the switch and the key of the "homing" section to change.
class HomingSwitchError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Homes the axes of `cycle` that `wanted` names (x, y, z), in its order; prints one line per axis
/// to `out` (`  x: x min switch closed at -3.3 mm (seek, setpoint 335) and -3.294 mm (locate,
/// setpoint 498); now at 0 mm`). Throws HomingAborted, HomingSwitchError, StreamError, LinkError or
/// TransportError for the controller or the link.
void run_homing_cycle(ControllerMoves& moves, const HomingCycle& cycle, const std::array<bool, 3>& wanted, std::ostream& out);

}  // namespace curvestep::host
