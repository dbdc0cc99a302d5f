// SPDX-License-Identifier: MIT
// Probe: the motion controller (queue, planner, interpolator) producing Q16.16 and float setpoints.
#include <curvestep/core/motion/motion_controller.hpp>

#include "probe.hpp"

namespace curvestep::probe {
namespace {

template <Scalar S>
void exercise_motion(double scale) {
  MotionController<S, 8, 4, 32> controller;
  MachineLimits machine;
  if (!controller.configure(machine)) return;
  const MachinePoint a{{0, 0, 0}};
  const MachinePoint b{{10 * scale, 0, 0}};
  const MachinePoint c{{10 * scale, 10 * scale, 0}};
  const std::array<MachinePoint, 4> cubic{b, MachinePoint{{20 * scale, 0, 0}}, MachinePoint{{20 * scale, 10 * scale, 0}}, c};
  if (auto line = PathSegment::make_line(a, b)) (void)controller.try_push(line.value(), 0);
  if (auto curve = PathSegment::make_bezier(cubic)) (void)controller.try_push(curve.value(), 1);
  if (auto arc = PathSegment::make_arc(c, a, MachinePoint{{5 * scale, 5 * scale, 0}}, ArcDirection::CounterClockwise, 0, 0.01)) {
    (void)controller.try_push(arc.value(), 2);
  }
  controller.end_of_job();
  if (!controller.start()) return;
  for (int i = 0; i < 100000 && !controller.finished(); ++i) {
    const auto sp = controller.next_setpoint();
    if (!sp) return;
    if (i == 50) controller.hold();
    if (controller.state() == ControllerState::Held) (void)controller.resume();
    sink = sink + static_cast<std::int32_t>(to_double(sp.value().position[0]));
  }
}

}  // namespace

void probe_motion() {
  exercise_motion<Q16_16>(1.0 + sink * 1e-9);
  exercise_motion<float>(1.0 + sink * 1e-9);
}

}  // namespace curvestep::probe
