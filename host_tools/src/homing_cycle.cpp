// SPDX-License-Identifier: MIT
#include "homing_cycle.hpp"

#include <cstdint>
#include <optional>

#include <curvestep/host/csv.hpp>

namespace curvestep::host {
namespace {

constexpr std::array<const char*, 3> axis_names{"x", "y", "z"};

/// The coordinate of `axis` in a SwitchReport, mm.
double coordinate(const protocol::SwitchReport& r, std::size_t axis) {
  return static_cast<double>(axis == 0 ? r.x : axis == 1 ? r.y : r.z) / 65536.0;
}

/// The moves of one axis's homing; each ends the cycle if the operator aborts.
class AxisHoming {
 public:
  AxisHoming(ControllerMoves& moves, std::size_t axis) : moves_(moves), axis_(axis) {}

  /// Moves the axis; with `seek`, until that switch closes (where, or none if it never did).
  std::optional<protocol::SwitchReport> move(double distance_mm, double feed_mm_per_s, std::optional<std::uint8_t> seek) {
    stop_if_asked();
    const link::StreamResult result = moves_.homing_move(axis_, distance_mm, feed_mm_per_s, seek);
    if (result.aborted) throw aborted();
    return result.switch_closed;
  }
  /// SetPosition, unless the operator asked to abort.
  void set_position(double position_mm) {
    stop_if_asked();
    moves_.set_position(axis_, position_mm);
  }

 private:
  void stop_if_asked() {
    if (moves_.abort_requested()) throw aborted();
  }
  [[nodiscard]] HomingAborted aborted() const {
    return HomingAborted("homing " + std::string(axis_names[axis_]) + " aborted by the operator: the controller stopped at once and stands at " +
                         format_position(moves_.position_mm()) + " mm; the axes are not homed");
  }

  ControllerMoves& moves_;
  std::size_t axis_;
};

void home_axis(ControllerMoves& moves, std::size_t axis, const HomingAxis& h, std::ostream& out) {
  AxisHoming homing(moves, axis);
  const double toward = h.max_side ? 1.0 : -1.0;
  const auto bit = static_cast<std::uint8_t>(2 * axis + (h.max_side ? 1 : 0));
  const std::string name = std::string(axis_names[axis]) + (h.max_side ? " max" : " min") + " switch";
  const std::string homing_axis = "homing " + std::string(axis_names[axis]) + ": the " + name;
  if (moves.closed(bit)) (void)homing.move(-toward * h.pull_off_mm, h.seek_mm_per_s, std::nullopt);
  const auto seek = homing.move(toward * h.distance_mm, h.seek_mm_per_s, bit);
  if (!seek) throw HomingSwitchError(homing_axis + " did not close within " + format_number(h.distance_mm) + " mm (\"distance\")");
  (void)homing.move(-toward * h.pull_off_mm, h.seek_mm_per_s, std::nullopt);
  if (moves.closed(bit)) {
    throw HomingSwitchError(homing_axis + " is still closed after the pull-off of " + format_number(h.pull_off_mm) + " mm (\"pull_off\")");
  }
  const auto locate = homing.move(toward * 2 * h.pull_off_mm, h.locate_mm_per_s, bit);
  if (!locate) {
    throw HomingSwitchError(homing_axis + " did not close again within " + format_number(2 * h.pull_off_mm) +
                             " mm (twice \"pull_off\") at the locate speed");
  }
  (void)homing.move(-toward * h.pull_off_mm, h.seek_mm_per_s, std::nullopt);
  homing.set_position(h.position_mm);
  out << "  " << axis_names[axis] << ": " << name << " closed at " << format_number(coordinate(*seek, axis)) << " mm (seek, setpoint "
      << seek->setpoint_index << ") and " << format_number(coordinate(*locate, axis)) << " mm (locate, setpoint "
      << locate->setpoint_index << "); now at " << format_number(moves.position_mm()[axis]) << " mm" << std::endl;
}

}  // namespace

void run_homing_cycle(ControllerMoves& moves, const HomingCycle& cycle, const std::array<bool, 3>& wanted, std::ostream& out) {
  for (const std::size_t axis : cycle.order) {
    if (wanted[axis] && cycle.axes[axis]) home_axis(moves, axis, *cycle.axes[axis], out);
  }
}

}  // namespace curvestep::host
