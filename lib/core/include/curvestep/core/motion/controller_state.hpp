// SPDX-License-Identifier: MIT
// ControllerState: the progress states of a MotionController and of a PieceExecutor.
#pragma once

#include <cstdint>

namespace curvestep {

/// Progress states of a MotionController or a PieceExecutor (never errors: those are Result values).
enum class ControllerState : std::uint8_t {
  Idle = 0,      ///< configured, not started
  Running = 1,   ///< following the path
  Holding = 2,   ///< braking for a feed hold
  Held = 3,      ///< stopped on the path by a feed hold; resume() continues
  Starved = 4,   ///< the queue ran out before the end of the job; stopped on the path
  Finished = 5,  ///< the last setpoint (the job's end point) has been produced
  Aborted = 6,   ///< stopped at once, queue flushed
  Fault = 7,     ///< an error stopped the controller (see fault())
};

}  // namespace curvestep
