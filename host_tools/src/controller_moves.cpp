// SPDX-License-Identifier: MIT
#include "controller_moves.hpp"

#include <utility>

#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/host/csv.hpp>
#include <curvestep/host/link/status_query.hpp>
#include <curvestep/host/swept_extent.hpp>

#include "jog_move.hpp"

namespace curvestep::host {

ControllerMoves::ControllerMoves(link::Transport& transport, const MachineFile& machine_file, const MachineLimits& machine,
                                 link::StreamOptions options)
    : transport_(transport), machine_file_(machine_file), machine_(machine), options_(std::move(options)) {
  refresh();
}

link::StreamResult ControllerMoves::jog(const std::array<double, 3>& distance_mm, double feed_mm_per_s) {
  return move(distance_mm, feed_mm_per_s, machine_file_.travel);
}

link::StreamResult ControllerMoves::homing_move(std::size_t axis, double distance_mm, double feed_mm_per_s,
                                                std::optional<std::uint8_t> seek) {
  std::array<double, 3> delta{};
  delta[axis] = distance_mm;
  options_.seek_switch = seek;
  link::StreamResult result = move(delta, feed_mm_per_s, MachineTravel{});
  options_.seek_switch.reset();
  return result;
}

link::StreamResult ControllerMoves::move(const std::array<double, 3>& distance_mm, double feed_mm_per_s,
                                         const MachineTravel& soft_limits) {
  const Job job = jog_job(position_mm(), distance_mm, feed_mm_per_s);
  check_travel(job, soft_limits, machine_file_.name);
  options_.travel = soft_limits;
  link::StreamResult result = link::stream_job(transport_, job, machine_, options_);
  refresh();
  return result;
}

void ControllerMoves::set_position(std::size_t axis, double position_mm) {
  protocol::SetPosition m;
  m.axes = static_cast<std::uint8_t>(1u << axis);
  const std::int32_t raw = Q16_16::from_double(position_mm).value().raw();
  (axis == 0 ? m.x : axis == 1 ? m.y : m.z) = raw;
  status_ = link::set_position(transport_, options_.link, m);
}

void ControllerMoves::refresh() { status_ = link::read_status(transport_, options_.link); }

bool ControllerMoves::abort_requested() {
  return options_.operator_command && options_.operator_command() == link::OperatorCommand::Abort;
}

std::array<double, 3> ControllerMoves::position_mm() const noexcept {
  std::array<double, 3> position{};
  for (std::size_t a = 0; a < 3; ++a) position[a] = static_cast<double>(status_.position[a]) / 65536.0;
  return position;
}

std::string format_position(const std::array<double, 3>& position_mm) {
  std::string text;
  for (std::size_t a = 0; a < 3; ++a) text += std::string(a == 0 ? "" : " ") + "xyz"[a] + " " + format_number(position_mm[a]);
  return text;
}

}  // namespace curvestep::host
