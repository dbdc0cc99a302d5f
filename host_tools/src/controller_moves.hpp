// SPDX-License-Identifier: MIT
// ControllerMoves: relative moves on one controller from where it stands, each a one-line job
// (jog_move.hpp) planned with the machine's limits and sent through the normal link (stream_job):
// jogs (checked against the machine's travel before anything moves, sent with it as soft limits)
// for `jog` and `console`, and the homing cycle's moves (no soft limits: the position is not known
// yet) for `home` and `console`. After each move it reads the controller's StatusReport again.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include <curvestep/core/motion/machine_limits.hpp>
#include <curvestep/host/link/streamer.hpp>
#include <curvestep/host/link/transport.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::host {

/// Moves on one controller; `options` carry the link settings and the operator (keys, signals).
class ControllerMoves {
 public:
  /// Reads where the controller stands. Throws LinkError or TransportError.
  ControllerMoves(link::Transport& transport, const MachineFile& machine_file, const MachineLimits& machine,
                  link::StreamOptions options);

  /// Moves by `distance_mm` (x, y, z; one straight line) at `feed_mm_per_s` (0: the machine's feed).
  /// Refused before anything moves if the line leaves the machine's travel (LoadError, OutsideTravel,
  /// naming the axis and the file); StreamResult::aborted if the operator aborted it. Throws
  /// StreamError or TransportError if the controller or the link fails.
  link::StreamResult jog(const std::array<double, 3>& distance_mm, double feed_mm_per_s);
  /// A homing move of `axis` by `distance_mm` at `feed_mm_per_s`, without soft limits; with `seek`
  /// it ends where that switch closes (StreamResult::switch_closed). Throws as jog.
  link::StreamResult homing_move(std::size_t axis, double distance_mm, double feed_mm_per_s, std::optional<std::uint8_t> seek);
  /// Tells the controller that `axis` stands at `position_mm` (SetPosition).
  void set_position(std::size_t axis, double position_mm);
  /// Reads the controller's StatusReport again.
  void refresh();
  /// Asks the operator between moves (keys, signals): true if they want to abort.
  [[nodiscard]] bool abort_requested();

  /// The controller's last StatusReport.
  [[nodiscard]] const protocol::StatusReport& status() const noexcept { return status_; }
  /// Where the controller stands (its commanded position), mm.
  [[nodiscard]] std::array<double, 3> position_mm() const noexcept;
  /// True if `limit_switch` (bit 2 × axis, + 1 for max) is closed.
  [[nodiscard]] bool closed(std::uint8_t limit_switch) const noexcept { return (status_.limit_switches & (1u << limit_switch)) != 0; }

 private:
  link::StreamResult move(const std::array<double, 3>& distance_mm, double feed_mm_per_s, const MachineTravel& soft_limits);

  link::Transport& transport_;
  const MachineFile& machine_file_;
  MachineLimits machine_;
  link::StreamOptions options_;
  protocol::StatusReport status_{};
};

/// A position as text: "x 1.5 y 0 z -2" (mm, no unit).
[[nodiscard]] std::string format_position(const std::array<double, 3>& position_mm);

}  // namespace curvestep::host
