// SPDX-License-Identifier: MIT
// Phase: where the App's session and job are; the rows of the state table in docs/protocol.md.
#pragma once

#include <cstdint>

#include <curvestep/protocol/messages.hpp>

namespace curvestep::firmware {

/// The App's session and job phase (docs/protocol.md, "State table").
enum class Phase : std::uint8_t {
  NotConnected,  ///< no Hello yet: the link answers every command Nak(NotConnected)
  Connected,     ///< a session, no machine configuration
  Configured,    ///< a configuration, the queue empty, no job started
  Queued,        ///< segments (or pieces) queued, Start not yet received
  Running,       ///< Start accepted: armed until the start rule holds, then moving (or starved)
  Holding,       ///< FeedHold or link loss: braking, stopped on the path, or held before the start
  Fault,         ///< stopped by a fault; Abort leaves it
  StreamFailed,  ///< the setpoint stream gave up (RetransmitLimit): reported Fault, only a new session leaves it
};

/// Whether the App's interpolator runs, beside the Phase (armed, held or starved while Moving is
/// the controller's business). One value, not a `moving` and a `paused` flag: a pause only ever
/// stops a moving job, and a job that ends or faults is Idle, so a pause never outlives its job.
///
/// | motion  | on_tick()                  | entered by                                  | left by                                   |
/// |---------|----------------------------|---------------------------------------------|-------------------------------------------|
/// | Idle    | nothing                    | power-up, the job's last setpoint, a fault, | the start rule holds (controller started) |
/// |         |                            | Abort or a new session (stop_job)           |   -> Moving                               |
/// | Moving  | makes the next setpoint    | the start rule; Resume after a pause        | a pause event going due -> Paused; the    |
/// |         |                            |                                             | job's end, a fault, Abort -> Idle         |
/// | Paused  | nothing (until Resume)     | a pause event (M0/M1, M6, layer change)     | Resume -> Moving; a fault, Abort -> Idle  |
enum class JobMotion : std::uint8_t {
  Idle,    ///< no job in motion (not started, armed, finished or stopped)
  Moving,  ///< the interpolator produces setpoints (started, not finished)
  Paused,  ///< a pause event holds the moving job until Resume
};

/// The state a StatusReport carries for `phase`.
[[nodiscard]] constexpr protocol::MachineState reported_state(Phase phase) noexcept {
  switch (phase) {
    case Phase::Running: return protocol::MachineState::Running;
    case Phase::Holding: return protocol::MachineState::Holding;
    case Phase::Fault:
    case Phase::StreamFailed: return protocol::MachineState::Fault;
    default: return protocol::MachineState::Idle;
  }
}

/// True in the phases that take segments (or pieces) under the credit.
[[nodiscard]] constexpr bool takes_segments(Phase phase) noexcept {
  return phase == Phase::Configured || phase == Phase::Queued || phase == Phase::Running || phase == Phase::Holding;
}

/// True in the phases of a job that has been started (Running or Holding).
[[nodiscard]] constexpr bool job_started(Phase phase) noexcept { return phase == Phase::Running || phase == Phase::Holding; }

}  // namespace curvestep::firmware
