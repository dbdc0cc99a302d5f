// SPDX-License-Identifier: MIT
// fast_tick_allowed: the tick rule of the host board's fast mode (run_device, DeviceOptions::fast),
// also used by tests that run an App in their own process. A fast device ticks as fast as the link
// allows, never sooner than a real-time device fed in time would have what the tick needs:
//   * the App is moving and ready (App::ready_to_tick: room in the setpoint stream, and without a
//     planner the piece the next setpoint needs);
//   * not held or starved (nothing moves until the host resumes or refills);
//   * with a planner, the queue holds its look-ahead window (Lookahead + 2 entries, so the next
//     segment is planned with a full window), unless the job's last segment has arrived, the
//     controller is braking, or the App has no credit left to give (machine events fill its ring:
//     more cannot come before the motion works them off, App::wait_at_joint).
#pragma once

#include <curvestep/core/motion/controller_state.hpp>

namespace curvestep::boards::host {

/// True if `app` (a firmware::App) may run on_tick() now in fast mode (see the header comment).
template <class Application>
[[nodiscard]] bool fast_tick_allowed(const Application& app) noexcept {
  if (!app.moving() || !app.ready_to_tick()) return false;
  const auto& controller = app.controller();
  if (controller.state() == ControllerState::Held || controller.state() == ControllerState::Starved) return false;
  if constexpr (requires { Application::Controller::lookahead; }) {  // a planner on board
    const bool window_full = controller.queued() >= Application::Controller::lookahead + 2;
    const bool braking = controller.state() != ControllerState::Running;
    return window_full || app.job_end_known() || braking || app.free_segments() == 0;
  }
  return true;
}

}  // namespace curvestep::boards::host
