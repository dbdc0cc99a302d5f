// SPDX-License-Identifier: MIT
// Cutter radius compensation in one plane (G41/G42, LinuxCNC's rules; docs/gcode.md).
//
// Works in the plane's own coordinates: [0] and [1] are its first and second axis (G17: X Y; G18:
// Z X, left and counter-clockwise as seen from +Y, as LinuxCNC defines them), [2] the normal axis,
// which passes through unchanged; the caller maps machine axes to these.
// Takes the programmed moves (lines and arcs in the plane) in order and gives back the tool-centre
// moves, with one move of look-ahead: a move's end is final only when the next one shows the corner.
// Outside corners get an arc of the tool radius about the programmed corner; at inside corners the
// offset moves are cut at their intersection (the one nearest the corner on both moves). As in
// LinuxCNC, an inside corner within 0.05 rad of a reversal whose offsets do not meet is gone around
// like an outside one, and a near-reversal onto an arc curving away from the tool (its "h" shape) is
// cut at the crossing where there is one. The first move after start() (the entry move): a line
// ends where the next move's offset begins; an arc ends square to its programmed end, on an arc
// from the tool whose centre lies on the line from that end to the programmed centre (LinuxCNC's
// rule). The first move after stop() (the exit move) must be a line and starts where the tool is.
// Geometry errors throw CompensationError (the caller names the line).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

#include <curvestep/core/curve/circular_arc.hpp>
#include <curvestep/core/motion/path_segment.hpp>

namespace curvestep::host {

/// A move in the compensation plane: a line (G0/G1) or an arc about `center` (helix if [2] changes).
struct PlanarMove {
  bool arc = false;
  bool rapid = false;                               ///< G0 (lines and corner arcs of G0 moves)
  MachinePoint start{}, end{}, center{};            ///< mm, plane coordinates; centre [2] unused
  ArcDirection direction = ArcDirection::CounterClockwise;
  std::uint32_t full_turns = 0;                     ///< arc: extra whole turns
  std::size_t tag = 0;                              ///< the caller's; a corner arc carries the next move's
};

/// A move the compensation cannot follow (gouge, arc exit move ...); what() says why.
class CompensationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Compensated moves that became final after one call, in path order.
struct CompensatedMoves {
  std::optional<PlanarMove> finished;  ///< the previous move, its end now known
  std::optional<PlanarMove> corner;    ///< the arc around an outside corner, before the new move
};

class CutterCompensation {
 public:
  enum class Side : std::uint8_t { Left, Right };

  /// G41/G42 with a tool radius, mm (> 0); the tool stands at `tool`. The next move is the entry move.
  void start(Side side, double radius_mm, const MachinePoint& tool);
  /// G40: the pending move ends offset square to its end; the next move is the exit move.
  [[nodiscard]] std::optional<PlanarMove> stop();
  /// A programmed move that moves in the plane (its start is the programmed current point).
  [[nodiscard]] CompensatedMoves add(const PlanarMove& programmed);

  /// Compensation on (G41/G42), or off with the exit move still to come.
  [[nodiscard]] bool active() const noexcept { return state_ != State::Off; }
  /// Off, with the exit move (the first move after G40) still to come.
  [[nodiscard]] bool exiting() const noexcept { return state_ == State::Exit; }
  /// A move is held back waiting for the next one.
  [[nodiscard]] bool holding() const noexcept { return pending_.has_value(); }
  /// Where the tool centre is in the plane now (valid when not holding).
  [[nodiscard]] const MachinePoint& tool() const noexcept { return tool_; }

 private:
  enum class State : std::uint8_t { Off, Entry, On, Exit };
  /// A programmed move and its offset (start possibly cut back; end square to the move until finished).
  struct Offset {
    PlanarMove programmed;
    PlanarMove path;
    double sweep = 0;  ///< path's angle, radians (arcs)
  };

  [[nodiscard]] Offset offset(const PlanarMove& programmed) const;
  /// The entry move when it is an arc: from the tool to the programmed end's offset.
  [[nodiscard]] Offset entry_arc(const PlanarMove& programmed) const;
  /// Cuts pending_ and `next` back to their crossing at an inside corner; why not, if they do not meet.
  [[nodiscard]] std::optional<std::string> cut_inside_corner(Offset& next);
  /// The tool is on the outside of `arc` (away from its centre).
  [[nodiscard]] bool tool_outside(const PlanarMove& arc) const;
  /// The arc of the tool radius about the programmed corner from pending_'s end to `next`'s start.
  [[nodiscard]] PlanarMove corner_arc(const Offset& next) const;
  /// Joins `next` to pending_ at their corner; returns the corner arc of an outside corner.
  [[nodiscard]] std::optional<PlanarMove> corner(Offset& next);
  void finish(CompensatedMoves& out);

  State state_ = State::Off;
  double side_ = 1;  ///< +1 left, -1 right
  double radius_ = 0;
  bool entry_pending_ = false;
  std::optional<Offset> pending_;
  MachinePoint tool_{};
};

}  // namespace curvestep::host
