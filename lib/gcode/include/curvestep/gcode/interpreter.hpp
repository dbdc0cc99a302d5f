// SPDX-License-Identifier: MIT
// G-code modal interpreter: Blocks -> motions (rapid, line, arc, cubic, quadratic, NURBS), LinuxCNC semantics.
//
// Geometry is computed in double, as PathSegment holds it (motion/path_segment.hpp): the motions
// feed PathSegments on every target, so working in double here loses nothing and keeps host and
// firmware identical. All lengths leave in millimetres (G20 values are multiplied by 25.4).
//
// Semantics (LinuxCNC g-code reference):
//   G0/G1 X Y Z        rapid / feed line to the end point (G90 absolute, G91 incremental).
//   G2/G3 X Y Z I J P  arc in the XY plane (G17; G18, G19 below), clockwise / counter-clockwise; centre = start +
//                      (I,J) in G91.1 (the default) or (I,J) in G90.1. Z moving makes a helix. End
//                      equal to start is a full circle; P n adds n-1 extra turns. The radii to start
//                      r0 and end r1 must agree within LinuxCNC's tolerance t = 2·0.01·√2 mm (2·0.001·√2 in
//                      under G20): error if |r0-r1| > 100·t, or if |r0-r1| > t and > 0.1 % of max(r0, r1).
//   G2/G3 X Y Z R      radius form: centre on the perpendicular bisector of the chord at distance
//                      sqrt(R² - (c/2)²); R > 0 the arc of at most half a turn, R < 0 the longer one.
//   G5 X Y I J P Q     cubic Bézier with control points P0, P0+(I,J), P1+(P,Q), P1 (offsets always
//                      relative). Omitting I and J continues the previous G5's end tangent:
//                      (I,J) = -(P,Q) of the previous G5 — an error if the previous motion was not
//                      a G5. P and Q are required; I without J (or J without I) is an error.
//   G5.1 X Y I J       quadratic Bézier P0, P0+(I,J), P1; I and J both required (as LinuxCNC).
//   G5.2 [X Y] [P] [L] opens a NURBS block: the current point is the first control point (weight P
//                      when the G5.2 line has no X Y, else weight 1 and X Y is the second control
//                      point with weight P); following lines "X Y [P]" add control points (weight
//                      default 1); G5.3 closes the block and emits the curve of order L (default 3,
//                      degree L-1) with a clamped uniform knot vector.
//   Splines only in G17 (GcodeSplineNotG17) and only in X and Y (a Z word is GcodeConflictingWords).
//   G17/G18/G19, G20/G21, G90/G91, G90.1/G91.1 are modal; F is modal (per minute, in units);
//   M2/M30 end the program.
//   G93 / G94          inverse-time / units-per-minute feed. In G93 every G1 G2 G3 carries its own F
//                      and takes 1/F minutes: its feed is its length × F (inverse_time.hpp); F is
//                      not modal and an F elsewhere is ignored; G0 is unaffected; splines and canned
//                      cycles are refused. G94 after G93 leaves no feed in force: the next feed move
//                      needs an F (LinuxCNC). Why a block was refused: refused_feed().
//   G43 H / G43.1 Z / G49  tool length offset from the tool table / given directly (Z in the
//                      program's units, replacing the offset in force; G91 does not apply; X Y
//                      refused on this 3-axis machine; no motion word on the line) / cancelled.
//                      None of them while cutter compensation is on (LinuxCNC).
//   G73 G81 G82 G83 G85 G86 G89 canned cycles (G17): MotionKind::Cycle with the holes and levels
//                      resolved (canned_cycle.hpp expands them); Z R Q P sticky through the series;
//                      G98 (default) / G99 retract modes; G80 cancels.
//   G40 G41 G42 G41.1 G42.1 cutter radius compensation (G17, G18): the interpreter keeps producing the
//                      *programmed* path and tells each Motion the side and tool radius in force; the
//                      host offsets it (host_tools/src/gcode/cutter_compensation.hpp). G41/G42 D<tool>
//                      take the radius from the tool table (set_tool_diameter_mm; no D: the loaded
//                      tool; tool 0: radius 0), G41.1/G42.1 D<diameter> directly (L only as 0; a negative
//                      diameter compensates on the other side, as in LinuxCNC).
//                      Refused while on: G41/G42 again, a plane change, G28/G30, G53, splines, cycles.
//   @ ^                LinuxCNC's polar coordinates, instead of X Y (G17 only): @ the distance, ^ the
//                      angle in degrees (counter-clockwise from +X), about the XY origin of the coordinate
//                      system in force; G90 replaces the current point's distance/angle, G91 adds to them
//                      (see polar_end_point). With G0 G1 G2 G3, canned cycles, and G5 G5.1 (their end
//                      point, as LinuxCNC's find_ends gives it); refused on G5.2 control points
//                      (LinuxCNC adds one only for X and Y together).
//   G10 L2 P R         LinuxCNC's rotation of coordinate system P about Z, R degrees counter-clockwise
//                      (R not allowed on G10 L20). Program XY turn about the system's origin:
//                      machine = R(program + G92) + work offset (xy_rotation.hpp); Z never turns. G91
//                      increments, I J of arcs, I J P Q of splines, polar angles and cycle holes are
//                      along the turned axes; G53 and the G28/G30 stored positions are machine
//                      coordinates. G18/G19 arcs in a rotated system are refused (their plane would tilt).
// Arcs turn in the selected plane: G17 X Y with I J (K refused), G18 Z X with K I (J refused), G19
// Y Z with J K (I refused); the third axis makes a helix. Motion::plane says which.
//
// Errors carry the 1-based column of the word at fault (Failure::index).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <numbers>
#include <span>
#include <string_view>

#include <curvestep/core/curve/circular_arc.hpp>
#include <curvestep/core/geometry/vec.hpp>
#include <curvestep/core/result.hpp>
#include <curvestep/gcode/canned_cycle.hpp>
#include <curvestep/gcode/inverse_time.hpp>
#include <curvestep/gcode/parser.hpp>
#include <curvestep/gcode/xy_rotation.hpp>

namespace curvestep::gcode {

/// A point in machine space, mm.
using Point = Vec<double, 3>;

/// What a block commands.
enum class MotionKind : std::uint8_t {
  None,       ///< nothing moves (modal settings only, a NURBS control point, zero-length move)
  Rapid,      ///< G0 straight traverse
  Line,       ///< G1 straight feed
  Arc,        ///< G2/G3 circular or helical arc (XY plane)
  Cubic,      ///< G5 cubic Bézier, control[0..3]
  Quadratic,  ///< G5.1 quadratic Bézier, control[0..2]
  Nurbs,      ///< G5.3 closed a NURBS block; control points and weights in the interpreter
  Cycle,      ///< a canned cycle (G73 G81 G82 G83 G85 G86 G89): `cycle`, expanded by expand_cycle()
};

/// Active plane (G17, G18, G19).
enum class Plane : std::uint8_t { XY, ZX, YZ };
/// Active units (G21, G20).
enum class Units : std::uint8_t { Millimetres, Inches };

/// Feed mode (G94 units per minute, G93 inverse time).
enum class FeedMode : std::uint8_t { UnitsPerMinute, InverseTime };

/// Why a block was refused for its feed, where the error code and the word do not say it
/// (Interpreter::refused_feed()).
enum class FeedRefusal : std::uint8_t {
  None,                 ///< not refused for its feed
  InverseTimeWithoutF,  ///< a G1 G2 G3 in G93 without its F (GcodeMissingWord)
  NoFeedAfterG94,       ///< a feed move after G93 -> G94 before any new F (GcodeMissingWord)
  SplineInInverseTime,  ///< G5, G5.1, G5.2 in G93 (GcodeUnsupportedWord)
  CycleInInverseTime,   ///< a canned cycle in G93 (GcodeCannedCycle)
};

/// Cutter radius compensation in force (G40, G41/G41.1 left of the path, G42/G42.1 right).
enum class CompensationSide : std::uint8_t { Off, Left, Right };

/// A machine word that is not motion (docs/gcode.md), in LinuxCNC's order of execution.
enum class MachineEventKind : std::uint8_t {
  SpindleSpeed,   ///< S while the spindle runs (value rev/min)
  ToolChange,     ///< M6 (value: the tool selected with T)
  SpindleOn,      ///< M3 (flag false) / M4 (flag true), value rev/min
  SpindleOff,     ///< M5
  CoolantMist,    ///< M7
  CoolantFlood,   ///< M8
  CoolantOff,     ///< M9
  DigitalOutput,  ///< M62/M64 on (flag true), M63/M65 off; value: output P
  Dwell,          ///< G4 (value: seconds)
  Pause,          ///< M0 / M1, after the block's motion
  ProgramEnd,     ///< M2 / M30, after the block's motion
};

/// One machine event of a block.
struct MachineEvent {
  MachineEventKind kind = MachineEventKind::Dwell;
  double value = 0;
  bool flag = false;
  std::uint16_t column = 0;  ///< column of its word
};

/// Events one block may carry.
inline constexpr std::size_t max_block_events = 8;

/// One motion produced by a block.
struct Motion {
  MotionKind kind = MotionKind::None;         ///< what moves
  Point start{};                              ///< where the motion starts, mm
  Point end{};                                ///< where it ends, mm
  Point center{};                             ///< arc centre (its normal coordinate = the start's), mm
  Plane plane = Plane::XY;                    ///< arc: the plane it turns in (G17, G18, G19)
  ArcDirection direction = ArcDirection::Clockwise;  ///< arc direction (G2 clockwise, G3 counter-clockwise)
  std::uint32_t full_turns = 0;               ///< arc: extra whole turns (P - 1)
  double radius_difference_mm = 0;            ///< arc: |r_end - r_start|, already within tolerance
  std::array<Point, 4> control{};             ///< Cubic: 4, Quadratic: 3 control points
  std::size_t nurbs_order = 0;                ///< Nurbs: order (degree + 1)
  double feed_mm_per_min = 0;                 ///< modal feed, 0 if none was given (G93: this move's length × F)
  bool feed_given = false;                    ///< an F word has been given (so 0 is an explicit F0)
  std::uint16_t column = 0;                   ///< column of the word that commanded the motion
  bool program_end = false;                   ///< the block held M2 or M30
  std::array<MachineEvent, max_block_events> events{};  ///< the block's machine events, in execution order
  std::size_t event_count = 0;                ///< how many of `events` are used
  bool has_pre_rapid = false;                 ///< G28/G30 with axis words: a rapid to `pre_rapid` comes first
  Point pre_rapid{};                          ///< that intermediate point, mm (machine coordinates)
  double path_tolerance_mm = 0;               ///< path control in force: 0 G64, > 0 G64 P, < 0 G61/G61.1 (exact stop)
  CannedCycle cycle{};                        ///< Cycle: the holes and levels, machine coordinates
  CompensationSide compensation_side = CompensationSide::Off;  ///< cutter compensation in force for this motion
  double compensation_radius_mm = 0;          ///< its tool radius, mm (0 with D0)
  /// The events, in execution order (the Pause and ProgramEnd kinds happen after the motion).
  [[nodiscard]] constexpr std::span<const MachineEvent> machine_events() const noexcept { return {events.data(), event_count}; }
};

/// Factor from inches to millimetres.
inline constexpr double millimetres_per_inch = 25.4;
/// Largest coordinate magnitude accepted, mm (inside the Q16.16 range of ±32768 mm).
inline constexpr double max_coordinate_mm = 32767.0;
/// Largest number of turns (P on G2/G3).
inline constexpr double max_arc_turns = 10000.0;
/// Largest repeat count L of a canned cycle.
inline constexpr double max_cycle_repeats = 10000.0;

/// Whether `code_tenths` is a G code of the motion group (G0 G1 G2 G3 G5 G5.1 G5.2 G5.3 G80 and the cycles).
[[nodiscard]] constexpr bool is_motion_code(std::int32_t code_tenths) noexcept {
  switch (code_tenths) {
    case 0: case 10: case 20: case 30: case 50: case 51: case 52: case 53: case 800:
    case 730: case 810: case 820: case 830: case 850: case 860: case 890:
      return true;
    default:
      return false;
  }
}

/// G80 beside G0, G1, G2 or G3 on one line, in either order: Fanuc gives G80 a group of its own, so
/// posts write safety lines such as `G0 G17 G40 G49 G80 G90`. LinuxCNC refuses two motion-group
/// codes; here the move is kept, the cycle ended (as the move alone ends it).
[[nodiscard]] constexpr bool is_g80_with_move(const Word& first, const Word& second) noexcept {
  const auto is_move = [](std::int32_t code) { return code == 0 || code == 10 || code == 20 || code == 30; };
  return (first.code_tenths == 800 && is_move(second.code_tenths)) || (second.code_tenths == 800 && is_move(first.code_tenths));
}

/// Whether `code_tenths` is a canned cycle this interpreter runs.
[[nodiscard]] constexpr bool is_cycle_code(std::int32_t code_tenths) noexcept {
  return code_tenths == 730 || (code_tenths >= 810 && code_tenths <= 890 && code_tenths != 840 && code_tenths != 870 && code_tenths != 880);
}

/// LinuxCNC's centre-format arc tolerance in mm for the program's units (rs274ngc
/// CENTER_ARC_RADIUS_TOLERANCE_MM/_INCH: 2·0.01·√2 mm, 2·0.001·√2 in, so that an arc whose end and
/// centre were rounded to 0.01 mm or 0.001 in passes).
[[nodiscard]] inline double arc_radius_tolerance_mm(Units units) noexcept {
  return units == Units::Inches ? 2 * 0.001 * std::numbers::sqrt2 * millimetres_per_inch : 2 * 0.01 * std::numbers::sqrt2;
}
/// LinuxCNC's relative arc tolerance (SPIRAL_RELATIVE_TOLERANCE): 0.1 % of the larger radius.
inline constexpr double arc_relative_tolerance = 0.001;
/// Below this radius (mm) an arc is LinuxCNC's "zero-radius arc" (RADIUS_TOLERANCE_INCH 0.00005 in,
/// the same length under G21).
inline constexpr double arc_zero_radius_mm = 0.00005 * millimetres_per_inch;

/// Whether radii r0 (start) and r1 (end), in mm, disagree beyond LinuxCNC's tolerance t for the
/// program's units (interp_arc.cc, arc_data_ijk): by more than 100·t, or by more than t and more
/// than 0.1 % of the larger radius.
[[nodiscard]] inline bool arc_radii_mismatch(double r0, double r1, Units units = Units::Millimetres) noexcept {
  const double difference = std::fabs(r1 - r0);
  const double tolerance = arc_radius_tolerance_mm(units);
  return difference > 100 * tolerance || (difference > tolerance && difference > arc_relative_tolerance * std::fmax(r0, r1));
}

/// The axes of a plane: the arc's first and second axis (counter-clockwise from first to second,
/// seen from the positive normal) and the normal (the helix axis). G17 X Y Z, G18 Z X Y, G19 Y Z X.
struct PlaneAxes {
  std::size_t first, second, normal;
};
[[nodiscard]] constexpr PlaneAxes axes_of(Plane plane) noexcept {
  switch (plane) {
    case Plane::ZX: return {2, 0, 1};
    case Plane::YZ: return {1, 2, 0};
    default: return {0, 1, 2};
  }
}

/// The modal interpreter; MaxNurbsPoints bounds the control points of one G5.2 block.
template <std::size_t MaxNurbsPoints = 64>
class Interpreter {
  static_assert(MaxNurbsPoints >= 2, "a NURBS block needs at least two control points");

 public:
  /// Current position, mm.
  [[nodiscard]] constexpr const Point& position() const noexcept { return position_; }
  [[nodiscard]] constexpr Plane plane() const noexcept { return plane_; }
  [[nodiscard]] constexpr Units units() const noexcept { return units_; }
  /// Millimetres per program unit: 25.4 under G20, 1 under G21.
  [[nodiscard]] constexpr double scale() const noexcept { return units_ == Units::Inches ? millimetres_per_inch : 1.0; }
  [[nodiscard]] constexpr bool incremental() const noexcept { return incremental_; }
  [[nodiscard]] constexpr bool arc_centers_absolute() const noexcept { return arc_absolute_; }
  /// The motion mode in force: its G code × 10 (G2: 20, G81: 810), -1 if none.
  [[nodiscard]] constexpr std::int32_t motion_mode() const noexcept { return mode_; }
  /// Inside a G5.2 … G5.3 block.
  [[nodiscard]] constexpr bool in_nurbs_block() const noexcept { return in_nurbs_; }
  /// M2 or M30 was executed.
  [[nodiscard]] constexpr bool ended() const noexcept { return ended_; }
  /// The last NURBS block's control points and weights (valid after a Nurbs motion until the next G5.2).
  [[nodiscard]] constexpr std::span<const Point> nurbs_points() const noexcept { return {nurbs_points_.data(), nurbs_count_}; }
  [[nodiscard]] constexpr std::span<const double> nurbs_weights() const noexcept { return {nurbs_weights_.data(), nurbs_count_}; }
  [[nodiscard]] static constexpr std::size_t nurbs_capacity() noexcept { return MaxNurbsPoints; }

  /// The work offset of coordinate system `index` (0 = G54 … 8 = G59.3), mm.
  [[nodiscard]] constexpr const Point& work_offset(std::size_t index) const noexcept { return work_offsets_[index]; }
  /// The coordinate system in use (0 = G54 … 8 = G59.3).
  [[nodiscard]] constexpr std::size_t coordinate_system() const noexcept { return coordinate_system_; }
  /// The G92 offset in force, mm.
  [[nodiscard]] constexpr const Point& g92_offset() const noexcept { return g92_offset_; }
  /// The rotation about Z of coordinate system `index` (0 = G54 … 8 = G59.3), degrees (G10 L2 R).
  [[nodiscard]] constexpr double rotation_deg(std::size_t index) const noexcept { return rotations_deg_[index]; }
  /// The current position in the coordinate system in use (work offset, rotation, G92 and tool length
  /// removed), mm, as LinuxCNC's #5420-#5422 report it (in the program's units: divide by 25.4 in G20).
  [[nodiscard]] Point program_position() const noexcept { return to_program(position_); }
  /// The tool loaded by the last M6.
  [[nodiscard]] constexpr std::size_t loaded_tool() const noexcept { return loaded_tool_; }
  /// The radii to start and end (mm, in the arc's plane) of the last centre-form arc refused with
  /// GcodeArcRadiusMismatch, for a message that quotes them.
  [[nodiscard]] constexpr const std::array<double, 2>& refused_arc_radii() const noexcept { return refused_arc_radii_; }
  /// The spindle speed last set with S, rev/min, and the direction of the last M3/M4.
  [[nodiscard]] constexpr double spindle_rpm() const noexcept { return spindle_rpm_; }
  [[nodiscard]] constexpr bool spindle_counter_clockwise() const noexcept { return spindle_ccw_; }
  /// G98 (return to the initial level) rather than G99 (return to R) is in force.
  [[nodiscard]] constexpr bool retract_to_initial_level() const noexcept { return retract_to_initial_; }
  /// The feed mode in force (G93, G94).
  [[nodiscard]] constexpr FeedMode feed_mode() const noexcept { return inverse_time_ ? FeedMode::InverseTime : FeedMode::UnitsPerMinute; }
  /// Why the last block was refused for its feed (FeedRefusal::None if it was not).
  [[nodiscard]] constexpr FeedRefusal refused_feed() const noexcept { return refused_feed_; }
  /// The tool length offset in force (G43, G43.1), mm.
  [[nodiscard]] constexpr double tool_length_offset_mm() const noexcept { return tool_length_mm_; }
  /// Sets the work offset of coordinate system `index` (0 = G54 … 8 = G59.3), mm, as G10 L2 would.
  constexpr void set_work_offset(std::size_t index, const Point& offset) noexcept {
    if (index < work_offsets_.size()) work_offsets_[index] = offset;
  }
  /// Sets the rotation of coordinate system `index` about Z, degrees, as G10 L2 R would.
  constexpr void set_rotation_deg(std::size_t index, double degrees) noexcept {
    if (index < rotations_deg_.size()) rotations_deg_[index] = degrees;
  }
  /// Sets the G92 offset, mm, as G92 would.
  constexpr void set_g92_offset(const Point& offset) noexcept { g92_offset_ = offset; }
  /// Sets the length of tool number `tool` for G43, mm (the machine file's tool table). False if
  /// the number is above max_tool_number or the table already holds max_tools other tools.
  constexpr bool set_tool_length_mm(std::size_t tool, double length_mm) noexcept {
    ToolEntry* entry = tool_entry(tool);
    if (entry != nullptr) entry->length_mm = length_mm;
    return entry != nullptr;
  }
  /// Sets the diameter of tool number `tool` for G41/G42 D, mm (the machine file's tool table); a
  /// negative diameter marks it unknown (then G41/G42 with that tool is refused). False as above.
  constexpr bool set_tool_diameter_mm(std::size_t tool, double diameter_mm) noexcept {
    ToolEntry* entry = tool_entry(tool);
    if (entry != nullptr) entry->diameter_mm = diameter_mm;
    return entry != nullptr;
  }
  /// The diameter of tool number `tool`, mm; negative if the tool table does not give it.
  [[nodiscard]] constexpr double tool_diameter_mm(std::size_t tool) const noexcept {
    const ToolEntry* entry = find_tool(tool);
    return entry != nullptr ? entry->diameter_mm : -1.0;
  }
  /// The length of tool number `tool`, mm; 0 if the tool table does not give it.
  [[nodiscard]] constexpr double tool_length_mm(std::size_t tool) const noexcept {
    const ToolEntry* entry = find_tool(tool);
    return entry != nullptr ? entry->length_mm : 0.0;
  }
  /// Cutter radius compensation in force and its tool radius, mm.
  [[nodiscard]] constexpr CompensationSide compensation_side() const noexcept { return compensation_side_; }
  [[nodiscard]] constexpr double compensation_radius_mm() const noexcept { return compensation_radius_mm_; }
  /// Sets the G28 / G30 positions (machine coordinates, mm; the machine file's).
  constexpr void set_home_positions(const Point& g28, const Point& g30) noexcept {
    home28_ = g28;
    home30_ = g30;
  }
  /// Tools a tool table may hold.
  static constexpr std::size_t max_tools = 100;
  /// Largest tool number of a T, H or D word (CAM posts number tools freely, e.g. T102).
  static constexpr std::size_t max_tool_number = 99999;

  /// Executes one block. Failures carry the column of the word at fault.
  template <std::size_t Capacity>
  [[nodiscard]] Result<Motion> execute(const Block<Capacity>& block) noexcept {
    // ---- classify the words by modal group ----
    const Word* motion_word = nullptr;
    const Word* plane_word = nullptr;
    const Word* units_word = nullptr;
    const Word* distance_word = nullptr;
    const Word* arc_distance_word = nullptr;
    const Word* feed_mode_word = nullptr;
    const Word* compensation_word = nullptr;
    const Word* tool_length_word = nullptr;
    const Word* coordinate_word = nullptr;
    const Word* path_word = nullptr;
    const Word* retract_word = nullptr;
    const Word* group0_word = nullptr;
    const Word* g53_word = nullptr;
    const Word* stop_word = nullptr;
    const Word* spindle_word = nullptr;
    const Word* tool_change_word = nullptr;
    const Word* coolant_word = nullptr;
    const Word* coolant_off_word = nullptr;
    const Word* output_word = nullptr;
    const Word* override_word = nullptr;
    const Word* cancel_beside_move = nullptr;  // a G80 beside G0-G3 (is_g80_with_move)
    for (const Word& w : block.words()) {
      const Word** slot = nullptr;
      if (w.letter == 'G') {
        switch (w.code_tenths) {
          case 0: case 10: case 20: case 30: case 50: case 51: case 52: case 53: case 800:
          case 730: case 810: case 820: case 830: case 850: case 860: case 890: slot = &motion_word; break;
          case 170: case 180: case 190: slot = &plane_word; break;
          case 200: case 210: slot = &units_word; break;
          case 900: case 910: slot = &distance_word; break;
          case 901: case 911: slot = &arc_distance_word; break;
          case 930: case 940: slot = &feed_mode_word; break;
          case 400: case 410: case 411: case 420: case 421: slot = &compensation_word; break;
          case 430: case 431: case 490: slot = &tool_length_word; break;
          case 540: case 550: case 560: case 570: case 580: case 590: case 591: case 592: case 593: slot = &coordinate_word; break;
          case 610: case 611: case 640: slot = &path_word; break;
          case 980: case 990: slot = &retract_word; break;
          case 40: case 100: case 280: case 281: case 300: case 301: case 920: case 921: case 922: case 923: slot = &group0_word; break;
          case 530: slot = &g53_word; break;
          default: return fail(Error::GcodeUnsupportedWord, w.column);
        }
      } else if (w.letter == 'M') {
        switch (w.code_tenths) {
          case 0: case 10: case 20: case 300: slot = &stop_word; break;
          case 30: case 40: case 50: slot = &spindle_word; break;
          case 60: slot = &tool_change_word; break;
          case 70: case 80: slot = coolant_word == nullptr ? &coolant_word : nullptr; break;  // M7 and M8 together
          case 90: slot = &coolant_off_word; break;
          case 620: case 630: case 640: case 650: slot = &output_word; break;
          case 480: case 490: case 500: case 510: case 520: case 530: slot = &override_word; break;
          default: return fail(Error::GcodeUnsupportedWord, w.column);
        }
        if (slot == nullptr) continue;  // the second of M7/M8
      }
      if (slot == &motion_word && motion_word != nullptr && cancel_beside_move == nullptr && is_g80_with_move(*motion_word, w)) {
        cancel_beside_move = w.code_tenths == 800 ? &w : motion_word;  // once: a second G80 is a conflict
        if (w.code_tenths != 800) motion_word = &w;                    // the move stays; a move ends the cycle anyway
        continue;
      }
      if (slot != nullptr) {
        if (*slot != nullptr) return fail(Error::GcodeConflictingWords, w.column);
        *slot = &w;
      }
    }
    if (coolant_word != nullptr && coolant_off_word != nullptr) return fail(Error::GcodeConflictingWords, coolant_off_word->column);
    const bool uses_axes = group0_word != nullptr && group0_word->code_tenths != 40 && group0_word->code_tenths != 281 &&
                           group0_word->code_tenths != 301 && group0_word->code_tenths != 921 &&
                           group0_word->code_tenths != 922 && group0_word->code_tenths != 923;
    if (uses_axes && motion_word != nullptr) return fail(Error::GcodeConflictingWords, motion_word->column);
    // G43.1 takes the axis words as its offsets: no motion word, no other code using them (LinuxCNC).
    const bool dynamic_tool_length = tool_length_word != nullptr && tool_length_word->code_tenths == 431;
    if (dynamic_tool_length && (uses_axes || motion_word != nullptr)) {
      return fail(Error::GcodeConflictingWords, motion_word != nullptr ? motion_word->column : group0_word->column);
    }
    // Polar words are for motion only (LinuxCNC): not with G10, G28, G30, G53, G92.
    if (const Word* polar = polar_word(block); polar != nullptr && (uses_axes || g53_word != nullptr)) {
      return fail(Error::GcodeConflictingWords, polar->column);
    }
    if (in_nurbs_ && (group0_word != nullptr || g53_word != nullptr)) {
      return fail(Error::GcodeNurbsBlock, (group0_word != nullptr ? group0_word : g53_word)->column);
    }
    if (in_nurbs_ && compensation_word != nullptr && compensation_word->code_tenths != 400) {
      return fail(Error::GcodeNurbsBlock, compensation_word->column);
    }

    Motion motion;
    motion.start = position_;
    motion.end = position_;
    refused_feed_ = FeedRefusal::None;
    // ---- LinuxCNC's order of execution: feed mode, feed, S, T, M6, M3-M5, M7-M9, outputs, dwell, plane,
    // units, compensation, tool length, coordinate system, path control, distance modes, group 0, motion, stop ----
    if (feed_mode_word != nullptr) {
      const bool inverse_time = feed_mode_word->code_tenths == 930;
      if (inverse_time_ && !inverse_time) {  // G94 after G93 (LinuxCNC's convert_feed_mode): no feed rate in force
        feed_value_ = 0;
        feed_given_ = false;
        feed_needed_ = true;
      }
      inverse_time_ = inverse_time;
    }
    if (const Word* f = block.find('F')) {
      if (!(f->value >= 0)) return fail(Error::GcodeBadNumber, f->column);
      if (!inverse_time_) {  // in G93, F belongs to this block's G1 G2 G3 alone
        feed_value_ = f->value;
        feed_given_ = true;
        feed_needed_ = false;
      }
    }
    const auto add_event = [&motion](MachineEventKind kind, double value, bool flag, std::uint16_t column) {
      if (motion.event_count < max_block_events) motion.events[motion.event_count++] = MachineEvent{kind, value, flag, column};
    };
    if (const Word* sw = block.find('S')) {
      if (!(sw->value >= 0)) return fail(Error::GcodeBadNumber, sw->column);
      spindle_rpm_ = sw->value;
      if (spindle_on_ && spindle_word == nullptr) add_event(MachineEventKind::SpindleSpeed, spindle_rpm_, spindle_ccw_, sw->column);
    }
    if (const Word* t = block.find('T')) {
      if (!valid_tool_number(t->value)) return fail(Error::GcodeBadNumber, t->column);
      selected_tool_ = static_cast<std::size_t>(t->value);
    }
    if (tool_change_word != nullptr) {
      loaded_tool_ = selected_tool_;
      add_event(MachineEventKind::ToolChange, static_cast<double>(loaded_tool_), false, tool_change_word->column);
    }
    if (spindle_word != nullptr) {
      if (spindle_word->code_tenths == 50) {
        spindle_on_ = false;
        add_event(MachineEventKind::SpindleOff, 0, false, spindle_word->column);
      } else {
        spindle_on_ = true;
        spindle_ccw_ = spindle_word->code_tenths == 40;
        add_event(MachineEventKind::SpindleOn, spindle_rpm_, spindle_ccw_, spindle_word->column);
      }
    }
    if (coolant_word != nullptr) {
      for (const Word& w : block.words()) {
        if (w.letter == 'M' && (w.code_tenths == 70 || w.code_tenths == 80)) {
          add_event(w.code_tenths == 70 ? MachineEventKind::CoolantMist : MachineEventKind::CoolantFlood, 0, false, w.column);
        }
      }
    }
    if (coolant_off_word != nullptr) add_event(MachineEventKind::CoolantOff, 0, false, coolant_off_word->column);
    if (output_word != nullptr) {
      const Word* p = block.find('P');
      if (p == nullptr) return fail(Error::GcodeMissingWord, output_word->column);
      if (!(p->value >= 0) || p->value != std::floor(p->value)) return fail(Error::GcodeBadNumber, p->column);
      add_event(MachineEventKind::DigitalOutput, p->value, output_word->code_tenths == 620 || output_word->code_tenths == 640,
                output_word->column);
    }
    if (group0_word != nullptr && group0_word->code_tenths == 40) {
      const Word* p = block.find('P');
      if (p == nullptr) return fail(Error::GcodeMissingWord, group0_word->column);
      if (!(p->value >= 0 && p->value <= 1e6)) return fail(Error::GcodeBadNumber, p->column);
      add_event(MachineEventKind::Dwell, p->value, false, group0_word->column);
    }
    if (plane_word != nullptr) {
      const Plane plane = plane_word->code_tenths == 170 ? Plane::XY : plane_word->code_tenths == 180 ? Plane::ZX : Plane::YZ;
      const bool cancelled = compensation_word != nullptr && compensation_word->code_tenths == 400;
      if (plane != plane_ && compensation_side_ != CompensationSide::Off && !cancelled) {
        return fail(Error::GcodeCutterCompensation, plane_word->column);
      }
      plane_ = plane;
    }
    if (units_word != nullptr) units_ = units_word->code_tenths == 200 ? Units::Inches : Units::Millimetres;
    if (compensation_word != nullptr) CURVESTEP_CHECK(compensation(block, *compensation_word));
    if (compensation_side_ != CompensationSide::Off) {
      if (group0_word != nullptr && (group0_word->code_tenths == 280 || group0_word->code_tenths == 300)) {
        return fail(Error::GcodeCutterCompensation, group0_word->column);
      }
      if (g53_word != nullptr) return fail(Error::GcodeCutterCompensation, g53_word->column);
    }
    motion.compensation_side = compensation_side_;
    motion.compensation_radius_mm = compensation_radius_mm_;
    if (tool_length_word != nullptr) {
      if (compensation_side_ != CompensationSide::Off) return fail(Error::GcodeCutterCompensation, tool_length_word->column);
      if (tool_length_word->code_tenths == 490) {
        tool_length_mm_ = 0;
      } else if (dynamic_tool_length) {
        CURVESTEP_CHECK(dynamic_tool_length_offset(block));
      } else {
        std::size_t tool = loaded_tool_;
        if (const Word* h = block.find('H')) {
          if (!valid_tool_number(h->value)) return fail(Error::GcodeBadNumber, h->column);
          tool = static_cast<std::size_t>(h->value);
        }
        tool_length_mm_ = tool_length_mm(tool);
      }
    }
    if (coordinate_word != nullptr) {
      const std::int32_t c = coordinate_word->code_tenths;
      coordinate_system_ = c <= 590 ? static_cast<std::size_t>((c - 540) / 10) : static_cast<std::size_t>(c - 591 + 6);
    }
    if (path_word != nullptr) {
      if (path_word->code_tenths == 640) {
        path_tolerance_mm_ = 0;
        if (const Word* p = block.find('P')) {
          if (!(p->value >= 0 && p->value * scale() <= max_coordinate_mm)) return fail(Error::GcodeBadNumber, p->column);
          path_tolerance_mm_ = p->value * scale();
        }
      } else {
        path_tolerance_mm_ = -1;
      }
    }
    if (distance_word != nullptr) incremental_ = distance_word->code_tenths == 910;
    if (retract_word != nullptr) retract_to_initial_ = retract_word->code_tenths == 980;
    if (arc_distance_word != nullptr) arc_absolute_ = arc_distance_word->code_tenths == 901;
    motion.path_tolerance_mm = path_tolerance_mm_;
    motion.feed_mm_per_min = feed_value_ * scale();  // F is read in the units active at the motion
    motion.feed_given = feed_given_;
    motion.program_end = stop_word != nullptr && (stop_word->code_tenths == 20 || stop_word->code_tenths == 300);

    // ---- the words the motion uses: everything not consumed above or by group 0 ----
    Block<Capacity> motion_block;
    for (const Word& w : block.words()) {
      bool consumed = w.letter == 'S' || w.letter == 'T' || w.letter == 'H' || w.letter == 'D';
      if (w.letter == 'G' && !is_motion_code(w.code_tenths)) {
        consumed = true;  // modal settings already applied (the motion functions know only motion G words)
      }
      if (w.letter == 'M') consumed = true;
      if (w.letter == 'P' && (output_word != nullptr || (group0_word != nullptr && group0_word->code_tenths == 40) ||
                              (group0_word != nullptr && group0_word->code_tenths == 100) ||
                              (path_word != nullptr && path_word->code_tenths == 640))) {
        consumed = true;
      }
      if (w.letter == 'Q' && path_word != nullptr && path_word->code_tenths == 640) consumed = true;
      if ((w.letter == 'L' || w.letter == 'R') && group0_word != nullptr && group0_word->code_tenths == 100) consumed = true;
      if (w.letter == 'L' && compensation_word != nullptr && compensation_word->code_tenths % 10 == 1) consumed = true;
      if ((uses_axes || dynamic_tool_length) && (w.letter == 'X' || w.letter == 'Y' || w.letter == 'Z')) consumed = true;
      if (!consumed) (void)motion_block.try_push(w);
    }
    if (group0_word != nullptr) {
      switch (group0_word->code_tenths) {
        case 281: home28_ = position_; break;
        case 301: home30_ = position_; break;
        case 921: g92_offset_ = Point{}; g92_saved_ = Point{}; break;
        case 922: g92_offset_ = Point{}; break;
        case 923: g92_offset_ = g92_saved_; break;
        default: break;
      }
    }
    if (uses_axes) CURVESTEP_CHECK(group_zero(block, *group0_word, motion));
    if (motion_word != nullptr && motion_word->code_tenths == 800) {
      mode_ = -1;  // G80: no motion mode until the next motion G word
      cycle_sticky_ = {};
      CURVESTEP_CHECK(only(motion_block, "", Error::GcodeConflictingWords));
    } else {
      machine_coordinates_ = g53_word != nullptr;
      if (machine_coordinates_ && incremental_) return fail(Error::GcodeConflictingWords, g53_word->column);
      if (in_nurbs_) {
        CURVESTEP_TRY(motion, nurbs_line(motion_block, motion_word, motion));
      } else {
        CURVESTEP_TRY(motion, motion_line(motion_block, motion_word, motion));
      }
      machine_coordinates_ = false;
    }
    if (stop_word != nullptr) {
      if (in_nurbs_) return fail(Error::GcodeNurbsBlock, stop_word->column);
      const bool end = stop_word->code_tenths == 20 || stop_word->code_tenths == 300;
      add_event(end ? MachineEventKind::ProgramEnd : MachineEventKind::Pause, stop_word->code_tenths == 10 ? 1.0 : 0.0, false,
                stop_word->column);
      if (end) {
        ended_ = true;
        // M2/M30 reset (LinuxCNC): G54, G17, G90, G94, G40, G49 cancelled offsets kept, G92 kept, M5, M9.
        coordinate_system_ = 0;
        plane_ = Plane::XY;
        incremental_ = false;
        spindle_on_ = false;
        inverse_time_ = false;
        compensation_side_ = CompensationSide::Off;
        compensation_radius_mm_ = 0;
      }
    }
    return motion;
  }

 private:


  /// Program coordinates -> machine coordinates: work offset + G92 offset + tool length (z), or
  /// nothing for a G53 move.
  [[nodiscard]] constexpr Point offset_in_force() const noexcept {
    if (machine_coordinates_) return Point{};
    Point o = work_offsets_[coordinate_system_] + g92_offset_;
    o[2] += tool_length_mm_;
    return o;
  }

  /// G43.1 Z: the tool length offset becomes Z (program units; G91 does not apply, as in LinuxCNC's
  /// convert_tool_length_offset); without Z it stays. X and Y (a lathe's tool offsets) are refused.
  template <std::size_t Capacity>
  [[nodiscard]] Result<void> dynamic_tool_length_offset(const Block<Capacity>& block) noexcept {
    for (const char letter : {'X', 'Y'}) {
      if (const Word* w = block.find(letter)) return fail(Error::GcodeUnsupportedWord, w->column);
    }
    if (const Word* z = block.find('Z')) {
      if (!(std::fabs(z->value * scale()) <= max_coordinate_mm)) return fail(Error::GcodeBadNumber, z->column);
      tool_length_mm_ = z->value * scale();
    }
    return ok();
  }

  /// The rotation of the coordinate system in use (none for a G53 move).
  [[nodiscard]] XyRotation rotation_in_force() const noexcept {
    return machine_coordinates_ ? XyRotation{} : XyRotation(rotations_deg_[coordinate_system_]);
  }

  /// Program coordinates -> machine coordinates, as LinuxCNC's canon does: X Y of (program + G92)
  /// turned by the system's rotation, then + work offset; Z + work offset + G92 + tool length.
  [[nodiscard]] Point to_machine(const Point& program) const noexcept {
    const XyRotation rotation = rotation_in_force();
    if (rotation.none()) return program + offset_in_force();
    Point machine = rotation.turned(program + g92_offset_) + work_offsets_[coordinate_system_];
    machine[2] = program[2] + offset_in_force()[2];
    return machine;
  }

  /// Machine coordinates -> program coordinates of the system in use (the inverse of to_machine).
  [[nodiscard]] Point to_program(const Point& machine) const noexcept {
    if (rotation_in_force().none()) return machine - offset_in_force();
    return program_point_in(coordinate_system_, machine);
  }

  /// Machine point `machine` in the program coordinates of coordinate system `system` (LinuxCNC's
  /// find_current_in_system): X Y turned back by that system's rotation after removing its offset,
  /// then less G92; Z less offset, G92 and tool length.
  [[nodiscard]] Point program_point_in(std::size_t system, const Point& machine) const noexcept {
    Point program = XyRotation(rotations_deg_[system]).turned_back(machine - work_offsets_[system]) - g92_offset_;
    program[2] -= tool_length_mm_;
    return program;
  }

  /// G40 / G41 / G42 / G41.1 / G42.1 (LinuxCNC semantics, G17 and G18).
  template <std::size_t Capacity>
  [[nodiscard]] Result<void> compensation(const Block<Capacity>& block, const Word& g) noexcept {
    if (g.code_tenths == 400) {
      compensation_side_ = CompensationSide::Off;
      compensation_radius_mm_ = 0;
      return ok();
    }
    if (plane_ == Plane::YZ) return fail(Error::GcodeUnsupportedWord, g.column);  // LinuxCNC: XY or XZ only
    if (compensation_side_ != CompensationSide::Off) return fail(Error::GcodeCutterCompensation, g.column);
    const Word* d = block.find('D');
    double radius = 0;
    if (g.code_tenths % 10 == 1) {  // G41.1 / G42.1 D<diameter> [L0]
      if (d == nullptr) return fail(Error::GcodeMissingWord, g.column);
      if (!(std::fabs(d->value) * scale() <= max_coordinate_mm)) return fail(Error::GcodeBadNumber, d->column);
      if (const Word* l = block.find('L'); l != nullptr && l->value != 0) return fail(Error::GcodeCutterCompensation, l->column);
      radius = d->value * scale() / 2;  // negative: the other side (below)
    } else {  // G41 / G42 [D<tool>]: the tool table's diameter; no D: the loaded tool; tool 0: no offset
      std::size_t tool = loaded_tool_;
      if (d != nullptr) {
        if (!valid_tool_number(d->value)) return fail(Error::GcodeBadNumber, d->column);
        tool = static_cast<std::size_t>(d->value);
      }
      if (tool != 0) {
        const double diameter = tool_diameter_mm(tool);
        if (!(diameter >= 0)) {
          return d != nullptr ? fail(Error::GcodeCutterCompensation, d->column) : fail(Error::GcodeMissingWord, g.column);
        }
        radius = diameter / 2;
      }
    }
    const bool left = g.code_tenths / 10 == 41;
    // LinuxCNC (convert_cutter_compensation_on): a negative radius switches the side and keeps its size.
    compensation_side_ = (left != (radius < 0)) ? CompensationSide::Left : CompensationSide::Right;
    compensation_radius_mm_ = std::fabs(radius);
    return ok();
  }

  /// One tool of the tool table: its number, length (G43) and diameter (G41/G42; negative: unknown), mm.
  struct ToolEntry {
    std::size_t number = 0;
    double length_mm = 0;
    double diameter_mm = -1.0;
  };

  /// A T, H or D value: a whole number 0 .. max_tool_number.
  [[nodiscard]] static constexpr bool valid_tool_number(double value) noexcept {
    return value >= 0 && value <= static_cast<double>(max_tool_number) && value == std::floor(value);
  }

  /// The tool table's entry of tool `number`, or null.
  [[nodiscard]] constexpr const ToolEntry* find_tool(std::size_t number) const noexcept {
    for (std::size_t i = 0; i < tool_count_; ++i) {
      if (tools_[i].number == number) return &tools_[i];
    }
    return nullptr;
  }
  /// The entry of tool `number`, added if new; null if the number is out of range or the table is full.
  constexpr ToolEntry* tool_entry(std::size_t number) noexcept {
    if (number > max_tool_number) return nullptr;
    if (const ToolEntry* found = find_tool(number)) return &tools_[static_cast<std::size_t>(found - tools_.data())];
    if (tool_count_ == max_tools) return nullptr;
    tools_[tool_count_] = ToolEntry{number, 0.0, -1.0};
    return &tools_[tool_count_++];
  }

  /// G10 L2/L20, G28/G30, G92: the group-0 codes that use the axis words (LinuxCNC semantics).
  template <std::size_t Capacity>
  [[nodiscard]] Result<void> group_zero(const Block<Capacity>& block, const Word& g, Motion& motion) noexcept {
    constexpr std::array<char, 3> axes{'X', 'Y', 'Z'};
    const auto value_of = [&](std::size_t axis, double& out) -> Result<bool> {
      const Word* w = block.find(axes[axis]);
      if (w == nullptr) return false;
      out = w->value * scale();
      if (!(std::fabs(out) <= max_coordinate_mm)) return fail(Error::GcodeBadNumber, w->column);
      return true;
    };
    switch (g.code_tenths) {
      case 100: {  // G10 L2 / L20 P<system> X Y Z
        const Word* l = block.find('L');
        const Word* p = block.find('P');
        if (l == nullptr || p == nullptr) return fail(Error::GcodeMissingWord, g.column);
        if (l->value != 2 && l->value != 20) return fail(Error::GcodeUnsupportedWord, l->column);
        if (!(p->value >= 0 && p->value <= 9) || p->value != std::floor(p->value)) return fail(Error::GcodeBadNumber, p->column);
        // R: LinuxCNC's rotation of the system about Z, degrees; G10 L2 only ("R not allowed in G10 L20").
        const Word* r = block.find('R');
        if (r != nullptr && l->value != 2) return fail(Error::GcodeUnsupportedWord, r->column);
        const std::size_t system = p->value == 0 ? coordinate_system_ : static_cast<std::size_t>(p->value) - 1;
        // LinuxCNC: "Cannot change the active coordinate system with cutter radius compensation on".
        if (system == coordinate_system_ && compensation_side_ != CompensationSide::Off) return fail(Error::GcodeCutterCompensation, g.column);
        std::array<double, 3> values{};
        std::array<bool, 3> given{};
        for (std::size_t axis = 0; axis < 3; ++axis) {
          CURVESTEP_TRY(given[axis], value_of(axis, values[axis]));
        }
        if (l->value == 2) {
          for (std::size_t axis = 0; axis < 3; ++axis) {
            if (given[axis]) work_offsets_[system][axis] = values[axis];
          }
          if (r != nullptr) rotations_deg_[system] = r->value;
          return ok();
        }
        set_origin_here(system, values, given);
        return ok();
      }
      case 280:
      case 300: {  // G28 / G30 [X Y Z]: through the given point (program coordinates) to the stored position
        const Point& home = g.code_tenths == 280 ? home28_ : home30_;
        Point intermediate = position_;
        Point target = position_;
        bool any = false;
        const Point offset = offset_in_force();
        std::array<bool, 3> given{};
        for (std::size_t axis = 0; axis < 3; ++axis) {
          double v = 0;
          CURVESTEP_TRY(given[axis], value_of(axis, v));
          if (!given[axis]) continue;
          any = true;
          intermediate[axis] = incremental_ ? position_[axis] + v : v + offset[axis];
          target[axis] = home[axis];
        }
        if (!any) target = home;
        if ((given[0] || given[1]) && !rotation_in_force().none()) CURVESTEP_CHECK(rotated_home_moves(block, home, given, intermediate, target));
        motion.start = position_;
        if (any && !(intermediate == position_)) {
          motion.has_pre_rapid = true;
          motion.pre_rapid = intermediate;
          motion.start = intermediate;
        }
        motion.end = target;
        motion.column = g.column;
        motion.kind = target == motion.start ? (motion.has_pre_rapid ? MotionKind::Rapid : MotionKind::None) : MotionKind::Rapid;
        position_ = target;
        previous_cubic_ = false;
        return ok();
      }
      case 920: {  // G92 X Y Z: the current position becomes the given values
        bool any = false;
        for (std::size_t axis = 0; axis < 3; ++axis) {
          double v = 0;
          CURVESTEP_TRY(const bool given, value_of(axis, v));
          if (!given) continue;
          any = true;
          const XyRotation rotation = rotation_in_force();
          if (rotation.none()) {
            g92_offset_[axis] = position_[axis] - v - work_offsets_[coordinate_system_][axis] - (axis == 2 ? tool_length_mm_ : 0.0);
          } else {  // LinuxCNC adds G92 before the rotation: it is measured along the system's turned axes
            g92_offset_[axis] = rotation.turned_back(position_ - work_offsets_[coordinate_system_])[axis] - v - (axis == 2 ? tool_length_mm_ : 0.0);
          }
        }
        if (!any) return fail(Error::GcodeMissingWord, g.column);
        g92_saved_ = g92_offset_;
        return ok();
      }
      default: return ok();
    }
  }

  /// G10 L20 P<system>: the current position becomes `values` (the axes `given`) in that system, as
  /// LinuxCNC's convert_setup does: its X Y are measured along the system's turned axes, so the new
  /// offset is old offset + R(current) - R(wanted), both in that system's program coordinates.
  void set_origin_here(std::size_t system, const std::array<double, 3>& values, const std::array<bool, 3>& given) noexcept {
    const XyRotation rotation(rotations_deg_[system]);
    if (rotation.none()) {
      for (std::size_t axis = 0; axis < 3; ++axis) {
        if (given[axis]) work_offsets_[system][axis] = position_[axis] - values[axis] - g92_offset_[axis] - (axis == 2 ? tool_length_mm_ : 0.0);
      }
      return;
    }
    const Point current = program_point_in(system, position_);
    Point wanted = current;
    for (std::size_t axis = 0; axis < 3; ++axis) {
      if (given[axis]) wanted[axis] = values[axis];
    }
    const Point shift = rotation.turned(current) - rotation.turned(wanted);
    work_offsets_[system][0] += shift[0];
    work_offsets_[system][1] += shift[1];
    if (given[2]) work_offsets_[system][2] = position_[2] - values[2] - g92_offset_[2] - tool_length_mm_;
  }

  /// G28/G30 with axis words in a rotated system (LinuxCNC's convert_home): the waypoint and the
  /// stored position are taken in program coordinates, and the final point has the stored
  /// position's program coordinate on the given axes and the waypoint's on the others. The stored
  /// position itself is reached when X and Y are both given (or neither); with one of them, the
  /// move keeps the other program coordinate, along the system's turned axes.
  template <std::size_t Capacity>
  [[nodiscard]] Result<void> rotated_home_moves(const Block<Capacity>& block, const Point& home, const std::array<bool, 3>& given,
                                                Point& intermediate, Point& target) const noexcept {
    const Word* x = given[0] ? block.find('X') : nullptr;
    const Word* y = given[1] ? block.find('Y') : nullptr;
    if (x != nullptr || y != nullptr) {
      const Point turned = incremental_ ? position_ + rotation_in_force().turned(Point{{x != nullptr ? x->value * scale() : 0.0,
                                                                                        y != nullptr ? y->value * scale() : 0.0, 0.0}})
                                        : absolute_xy(x, y);
      for (std::size_t axis = 0; axis < 2; ++axis) {
        if (!(std::fabs(turned[axis]) <= max_coordinate_mm)) return fail(Error::GcodeBadNumber, (x != nullptr ? x : y)->column);
        intermediate[axis] = turned[axis];
      }
    }
    Point program = to_program(intermediate);
    const Point home_program = to_program(home);
    for (std::size_t axis = 0; axis < 2; ++axis) {
      if (given[axis]) program[axis] = home_program[axis];
    }
    const Point end = to_machine(program);
    target[0] = end[0];
    target[1] = end[1];
    return ok();
  }

  /// The block's first polar word (@ distance or ^ angle), or nullptr.
  template <std::size_t Capacity>
  [[nodiscard]] static const Word* polar_word(const Block<Capacity>& block) noexcept {
    const Word* distance = block.find('@');
    const Word* angle = block.find('^');
    if (distance == nullptr) return angle;
    if (angle == nullptr) return distance;
    return distance->column < angle->column ? distance : angle;
  }

  /// The end point from X Y Z (absolute or incremental), range-checked; X Y may come from @ ^. In a
  /// rotated coordinate system X and Y are along its turned axes (G91: the increment turns; G90: an
  /// axis not given keeps its program coordinate).
  template <std::size_t Capacity>
  [[nodiscard]] Result<Point> end_point(const Block<Capacity>& block) const noexcept {
    Point end = position_;
    const XyRotation rotation = rotation_in_force();
    constexpr std::array<char, 3> axes{'X', 'Y', 'Z'};
    for (std::size_t axis = 0; axis < 3; ++axis) {
      if (const Word* w = block.find(axes[axis]); w != nullptr && (rotation.none() || axis == 2)) {
        const double v = w->value * scale() + (incremental_ ? position_[axis] : offset_in_force()[axis]);
        if (!(std::fabs(v) <= max_coordinate_mm)) return fail(Error::GcodeBadNumber, w->column);
        end[axis] = v;
      }
    }
    const Word* x = block.find('X');
    const Word* y = block.find('Y');
    if (!rotation.none() && (x != nullptr || y != nullptr)) {
      const double dx = x != nullptr ? x->value * scale() : 0.0;
      const double dy = y != nullptr ? y->value * scale() : 0.0;
      const Point turned = incremental_ ? position_ + rotation.turned(Point{{dx, dy, 0.0}}) : absolute_xy(x, y);
      for (std::size_t axis = 0; axis < 2; ++axis) {
        if (!(std::fabs(turned[axis]) <= max_coordinate_mm)) return fail(Error::GcodeBadNumber, (x != nullptr ? x : y)->column);
        end[axis] = turned[axis];
      }
    }
    if (polar_word(block) != nullptr) CURVESTEP_CHECK(polar_end_point(block, end));
    return end;
  }

  /// The machine point of G90 X and/or Y: the program coordinates given, an axis not given keeping
  /// the current point's (in a rotated system both machine X and Y change), Z the current one.
  [[nodiscard]] Point absolute_xy(const Word* x, const Word* y) const noexcept {
    Point program = to_program(position_);
    if (x != nullptr) program[0] = x->value * scale();
    if (y != nullptr) program[1] = y->value * scale();
    Point machine = to_machine(program);
    machine[2] = position_[2];
    return machine;
  }

  /// A block's polar words applied to the current point (about the XY origin in force): the
  /// distance and angle of the end (G90: the given ones replace the current point's; G91: they are
  /// added), the given increments, and whether the current point is at the origin.
  struct PolarMove {
    const Word* word = nullptr;  ///< the first polar word
    Point origin{};              ///< the XY origin in force, machine coordinates
    bool at_origin = false;      ///< the current point is at that origin (its angle undefined)
    bool has_angle = false;      ///< ^ was given
    double step_mm = 0;          ///< @ in mm (0 if absent)
    double step_rad = 0;         ///< ^ in radians (0 if absent)
    double radius_mm = 0;        ///< distance of the end from the origin
    double angle_rad = 0;        ///< angle of the end about the origin
  };
  template <std::size_t Capacity>
  [[nodiscard]] PolarMove polar_move(const Block<Capacity>& block) const noexcept {
    PolarMove p;
    p.word = polar_word(block);
    const Word* distance = block.find('@');
    const Word* angle = block.find('^');
    p.origin = to_machine(Point{});
    const double x = position_[0] - p.origin[0];
    const double y = position_[1] - p.origin[1];
    p.at_origin = x == 0 && y == 0;
    p.has_angle = angle != nullptr;
    p.step_mm = distance != nullptr ? distance->value * scale() : 0.0;
    p.step_rad = angle != nullptr ? angle->value * (std::numbers::pi / 180.0) : 0.0;
    p.radius_mm = std::hypot(x, y);
    p.angle_rad = std::atan2(y, x);
    if (incremental_) {
      p.radius_mm += p.step_mm;
      p.angle_rad += p.step_rad;
    } else {
      if (distance != nullptr) p.radius_mm = p.step_mm;
      // The angle is from the system's +X, which is turned by its rotation.
      if (angle != nullptr) p.angle_rad = p.step_rad + rotation_in_force().radians();
    }
    return p;
  }

  /// LinuxCNC's polar coordinates: X Y of `end` from @ (distance) and ^ (angle, degrees,
  /// counter-clockwise from +X) about the XY origin of the coordinate system in force. G90: the
  /// given ones replace the current point's distance and angle (about that origin); G91: they are
  /// added to them. Errors (at the polar word): X or Y in the block (GcodeConflictingWords); the
  /// current point at the origin, where its angle is undefined, when that angle is needed (G90 @
  /// without ^, any G91 polar move: GcodeMissingWord); the result out of range (GcodeBadNumber).
  template <std::size_t Capacity>
  [[nodiscard]] Result<void> polar_end_point(const Block<Capacity>& block, Point& end) const noexcept {
    const PolarMove p = polar_move(block);
    if (block.find('X') != nullptr || block.find('Y') != nullptr) return fail(Error::GcodeConflictingWords, p.word->column);
    if (p.at_origin && (incremental_ || !p.has_angle)) return fail(Error::GcodeMissingWord, p.word->column);
    const double ex = p.radius_mm * std::cos(p.angle_rad) + p.origin[0];
    const double ey = p.radius_mm * std::sin(p.angle_rad) + p.origin[1];
    if (!(std::fabs(ex) <= max_coordinate_mm && std::fabs(ey) <= max_coordinate_mm)) return fail(Error::GcodeBadNumber, p.word->column);
    end[0] = ex;
    end[1] = ey;
    return ok();
  }

  /// An offset word (I J K P Q R) in mm, or 0 if absent.
  template <std::size_t Capacity>
  [[nodiscard]] Result<double> offset(const Block<Capacity>& block, char letter) const noexcept {
    const Word* w = block.find(letter);
    if (w == nullptr) return 0.0;
    const double v = w->value * scale();
    if (!(std::fabs(v) <= 2 * max_coordinate_mm)) return fail(Error::GcodeBadNumber, w->column);
    return v;
  }

  /// Rejects any word of the block that is not G, M, F or in `allowed`.
  template <std::size_t Capacity>
  [[nodiscard]] static Result<void> only(const Block<Capacity>& block, std::string_view allowed, Error code) noexcept {
    for (const Word& w : block.words()) {
      if (w.letter == 'G' || w.letter == 'M' || w.letter == 'F') continue;
      if (allowed.find(w.letter) == std::string_view::npos) return fail(code, w.column);
    }
    return ok();
  }

  template <std::size_t Capacity>
  [[nodiscard]] static bool has_any(const Block<Capacity>& block, std::string_view letters) noexcept {
    for (const Word& w : block.words()) {
      if (letters.find(w.letter) != std::string_view::npos) return true;
    }
    return false;
  }

  /// The feed a feed move of motion mode mode_ needs, checked before it runs (LinuxCNC): in G93 a G1
  /// G2 G3 needs its own F and splines and canned cycles are refused; after G93 -> G94 a feed move
  /// needs a new F first. Failures name `column` and set refused_feed_.
  template <std::size_t Capacity>
  [[nodiscard]] Result<void> check_feed(const Block<Capacity>& block, std::uint16_t column) noexcept {
    const bool line_or_arc = mode_ == 10 || mode_ == 20 || mode_ == 30;
    const bool spline = mode_ == 50 || mode_ == 51 || mode_ == 52;
    FeedRefusal why = FeedRefusal::None;
    Error code = Error::GcodeMissingWord;
    if (inverse_time_) {
      if (spline) {
        why = FeedRefusal::SplineInInverseTime;
        code = Error::GcodeUnsupportedWord;
      } else if (is_cycle_code(mode_)) {
        why = FeedRefusal::CycleInInverseTime;
        code = Error::GcodeCannedCycle;
      } else if (line_or_arc && block.find('F') == nullptr) {
        why = FeedRefusal::InverseTimeWithoutF;
      }
    } else if (feed_needed_ && (line_or_arc || spline || is_cycle_code(mode_))) {
      why = FeedRefusal::NoFeedAfterG94;
    }
    if (why == FeedRefusal::None) return ok();
    refused_feed_ = why;
    return fail(code, column);
  }

  /// A G1 G2 G3 in G93: the feed that makes it take 1/F minutes (F is on the block, check_feed saw to it).
  template <std::size_t Capacity>
  void set_inverse_time_feed(const Block<Capacity>& block, Motion& motion) const noexcept {
    double length_mm = norm(motion.end - motion.start);
    if (motion.kind == MotionKind::Arc) {
      const PlaneAxes axes = axes_of(motion.plane);
      const auto angle_of = [&](const Point& p) {
        return std::atan2(p[axes.second] - motion.center[axes.second], p[axes.first] - motion.center[axes.first]);
      };
      const double radius = std::hypot(motion.start[axes.first] - motion.center[axes.first],
                                       motion.start[axes.second] - motion.center[axes.second]);
      const double swept = arc_swept_angle_rad(angle_of(motion.start), angle_of(motion.end), motion.direction, motion.full_turns);
      length_mm = helix_length_mm(radius, swept, motion.end[axes.normal] - motion.start[axes.normal]);
    }
    motion.feed_mm_per_min = inverse_time_feed_mm_per_min(length_mm, block.find('F')->value, scale());
    motion.feed_given = true;
  }

  /// A line inside a G5.2 block: a control point, or G5.3.
  template <std::size_t Capacity>
  [[nodiscard]] Result<Motion> nurbs_line(const Block<Capacity>& block, const Word* motion_word, Motion motion) noexcept {
    if (motion_word != nullptr && motion_word->code_tenths != 53) return fail(Error::GcodeNurbsBlock, motion_word->column);
    if (motion_word != nullptr) {  // G5.3
      CURVESTEP_CHECK(only(block, "", Error::GcodeNurbsBlock));
      CURVESTEP_CHECK(check_feed(block, motion_word->column));  // G93 or G94 may have come inside the block
      in_nurbs_ = false;
      mode_ = -1;  // G5.3 leaves no motion mode: axis words after it need a G code
      if (nurbs_count_ < nurbs_order_) return fail(Error::GcodeNurbsBlock, motion_word->column);
      motion.kind = MotionKind::Nurbs;
      motion.nurbs_order = nurbs_order_;
      motion.start = nurbs_points_[0];
      motion.end = nurbs_points_[nurbs_count_ - 1];
      motion.column = motion_word->column;
      position_ = motion.end;
      previous_cubic_ = false;
      return motion;
    }
    if (const Word* l = block.find('L')) return fail(Error::GcodeNurbsBlock, l->column);
    if (const Word* polar = polar_word(block)) return fail(Error::GcodeNurbsBlock, polar->column);  // as in start_nurbs
    CURVESTEP_CHECK(only(block, "XYP", Error::GcodeConflictingWords));
    if (block.find('X') == nullptr && block.find('Y') == nullptr) {
      if (const Word* p = block.find('P')) return fail(Error::GcodeMissingWord, p->column);
      return motion;  // a comment or settings line inside the block
    }
    CURVESTEP_TRY(const Point point, end_point(block));
    double weight = 1;
    const Word* x_or_y = block.find('X') != nullptr ? block.find('X') : block.find('Y');
    if (const Word* p = block.find('P')) {
      if (!(p->value > 0)) return fail(Error::GcodeNurbsBlock, p->column);
      weight = p->value;
    }
    if (nurbs_count_ == MaxNurbsPoints) return fail(Error::GcodeNurbsBlock, x_or_y->column);
    nurbs_points_[nurbs_count_] = point;
    nurbs_weights_[nurbs_count_] = weight;
    ++nurbs_count_;
    position_ = point;
    return motion;
  }

  /// A line outside NURBS blocks.
  template <std::size_t Capacity>
  [[nodiscard]] Result<Motion> motion_line(const Block<Capacity>& block, const Word* motion_word, Motion motion) noexcept {
    if (motion_word != nullptr) {
      // R Z Q P stay in force only through a series of canned-cycle blocks.
      if (!is_cycle_code(motion_word->code_tenths) || !is_cycle_code(mode_)) cycle_sticky_ = {};
      mode_ = motion_word->code_tenths;
      mode_column_ = motion_word->column;
    }
    const bool moves = has_any(block, "XYZIJKRPQL@^");
    if (!moves) {
      if (motion_word == nullptr) return motion;
      if (is_cycle_code(mode_)) return fail(Error::GcodeCannedCycle, motion_word->column);  // no X Y Z
      if (mode_ == 52) {
        if (compensation_side_ != CompensationSide::Off) return fail(Error::GcodeCutterCompensation, motion_word->column);
        CURVESTEP_CHECK(check_feed(block, motion_word->column));
        return start_nurbs(block, *motion_word, motion);
      }
      if (mode_ == 53) return fail(Error::GcodeNurbsBlock, motion_word->column);
      return motion;  // a motion mode alone moves nothing
    }
    if (mode_ < 0) {
      for (const Word& w : block.words()) {
        if (w.letter != 'G' && w.letter != 'M' && w.letter != 'F') return fail(Error::GcodeMissingWord, w.column);
      }
    }
    // The column that names the motion: its G word on this line, else the first axis word.
    std::uint16_t column = mode_column_;
    if (motion_word == nullptr) {
      for (const Word& w : block.words()) {
        if (w.letter != 'G' && w.letter != 'M' && w.letter != 'F') {
          column = w.column;
          break;
        }
      }
    }
    motion.column = column;
    if (compensation_side_ != CompensationSide::Off && (mode_ == 50 || mode_ == 51 || mode_ == 52 || is_cycle_code(mode_))) {
      return fail(Error::GcodeCutterCompensation, column);  // splines and cycles cannot be compensated
    }
    if (const Word* polar = polar_word(block); polar != nullptr) {
      // LinuxCNC adds a G5.2 control point only for X and Y together: polar words give none.
      if (mode_ == 52) return fail(Error::GcodeNurbsBlock, polar->column);
      if (plane_ != Plane::XY) return fail(Error::GcodeUnsupportedWord, polar->column);  // polar: G17 only (LinuxCNC)
    }
    CURVESTEP_CHECK(check_feed(block, column));
    switch (mode_) {
      case 0:
      case 10: {
        CURVESTEP_CHECK(only(block, "XYZ@^", Error::GcodeConflictingWords));
        CURVESTEP_TRY(motion.end, end_point(block));
        previous_cubic_ = false;
        if (motion.end == position_) return motion;
        motion.kind = mode_ == 0 ? MotionKind::Rapid : MotionKind::Line;
        position_ = motion.end;
        if (inverse_time_ && mode_ == 10) set_inverse_time_feed(block, motion);
        return motion;
      }
      case 20:
      case 30: {
        CURVESTEP_TRY(motion, arc(block, column, motion));
        if (inverse_time_) set_inverse_time_feed(block, motion);
        return motion;
      }
      case 50: return cubic(block, column, motion);
      case 51: return quadratic(block, column, motion);
      case 52: return start_nurbs(block, Word{'G', 5.2, 52, column}, motion);
      default:
        if (is_cycle_code(mode_)) return canned_cycle(block, column, motion);
        return fail(Error::GcodeNurbsBlock, column);  // G5.3 without G5.2
    }
  }

  template <std::size_t Capacity>
  [[nodiscard]] Result<Motion> arc(const Block<Capacity>& block, std::uint16_t column, Motion motion) noexcept {
    constexpr std::string_view offset_letters = "IJK";  // the centre offsets along X, Y, Z
    const PlaneAxes axes = axes_of(plane_);
    CURVESTEP_CHECK(only(block, "XYZIJKRP@^", Error::GcodeConflictingWords));
    // The offset along the normal has no meaning; CAM posts (FreeCAD's grbl post) write K0 on G17 arcs.
    if (const Word* k = block.find(offset_letters[axes.normal]); k != nullptr && k->value != 0) {
      return fail(Error::GcodeConflictingWords, k->column);
    }
    const Word* r_word = block.find('R');
    const Word* i_word = block.find(offset_letters[axes.first]);
    const Word* j_word = block.find(offset_letters[axes.second]);
    if (r_word != nullptr && (i_word != nullptr || j_word != nullptr)) return fail(Error::GcodeConflictingWords, r_word->column);
    // A rotated system turns a G18/G19 arc's plane off the axes (LinuxCNC draws it tilted); Motion
    // holds arcs in the three axis planes only.
    if (plane_ != Plane::XY && !rotation_in_force().none()) return fail(Error::GcodeUnsupportedWord, column);
    CURVESTEP_TRY(motion.end, end_point(block));
    motion.direction = mode_ == 20 ? ArcDirection::Clockwise : ArcDirection::CounterClockwise;
    motion.plane = plane_;
    if (const Word* p = block.find('P')) {
      if (!(p->value >= 1 && p->value <= max_arc_turns) || p->value != std::floor(p->value)) {
        return fail(Error::GcodeBadNumber, p->column);
      }
      motion.full_turns = static_cast<std::uint32_t>(p->value) - 1;
    }
    // In the plane's own coordinates (u along the first axis, v along the second).
    const Point& s = position_;
    const Point& e = motion.end;
    const double su = s[axes.first];
    const double sv = s[axes.second];
    const double eu = e[axes.first];
    const double ev = e[axes.second];
    double cu = 0;
    double cv = 0;
    if (r_word != nullptr) {
      CURVESTEP_TRY(const double r, offset(block, 'R'));
      const double du = eu - su;
      const double dv = ev - sv;
      const double chord = std::sqrt(du * du + dv * dv);
      if (chord == 0) return fail(Error::GcodeMissingWord, r_word->column);  // R cannot make a full circle
      const double half = chord / 2;
      const double radius = std::fabs(r);
      if (radius < half && arc_radii_mismatch(radius, half, units_)) return fail(Error::GcodeArcRadiusMismatch, r_word->column);
      const double height = radius > half ? std::sqrt(radius * radius - half * half) : 0.0;
      double side = motion.direction == ArcDirection::CounterClockwise ? 1.0 : -1.0;
      if (r < 0) side = -side;
      cu = su + du / 2 - side * height * dv / chord;
      cv = sv + dv / 2 + side * height * du / chord;
    } else {
      if (i_word == nullptr && j_word == nullptr) return fail(Error::GcodeMissingWord, column);
      Point ij{};  // the centre (G90.1) or its offset from the start (G91.1), program axes
      CURVESTEP_TRY(ij[axes.first], offset(block, offset_letters[axes.first]));
      CURVESTEP_TRY(ij[axes.second], offset(block, offset_letters[axes.second]));
      const Point centre = arc_absolute_ ? to_machine(ij) : s + rotation_in_force().turned(ij);
      cu = centre[axes.first];
      cv = centre[axes.second];
    }
    const double r0 = std::sqrt((su - cu) * (su - cu) + (sv - cv) * (sv - cv));
    const double r1 = std::sqrt((eu - cu) * (eu - cu) + (ev - cv) * (ev - cv));
    if (!(r0 >= arc_zero_radius_mm && r1 >= arc_zero_radius_mm) || arc_radii_mismatch(r0, r1, units_)) {
      refused_arc_radii_ = {r0, r1};
      return fail(Error::GcodeArcRadiusMismatch, column);
    }
    if (!(std::fabs(cu) <= max_coordinate_mm && std::fabs(cv) <= max_coordinate_mm)) {
      return fail(Error::GcodeBadNumber, r_word != nullptr ? r_word->column : column);
    }
    motion.center = s;
    motion.center[axes.first] = cu;
    motion.center[axes.second] = cv;
    motion.radius_difference_mm = std::fabs(r1 - r0);
    motion.kind = MotionKind::Arc;
    position_ = motion.end;
    previous_cubic_ = false;
    return motion;
  }

  /// A canned-cycle block (LinuxCNC semantics, canned_cycle.hpp): resolves the holes and levels.
  template <std::size_t Capacity>
  [[nodiscard]] Result<Motion> canned_cycle(const Block<Capacity>& block, std::uint16_t column, Motion motion) noexcept {
    if (plane_ != Plane::XY) return fail(Error::GcodeUnsupportedWord, column);
    CURVESTEP_CHECK(only(block, "XYZRQPL@^", Error::GcodeConflictingWords));
    const Word* x = block.find('X');
    const Word* y = block.find('Y');
    const Word* z = block.find('Z');
    const Word* polar = polar_word(block);
    if (x == nullptr && y == nullptr && z == nullptr && polar == nullptr) return fail(Error::GcodeCannedCycle, column);
    if (polar != nullptr && (x != nullptr || y != nullptr)) return fail(Error::GcodeConflictingWords, polar->column);
    // Sticky words: this block's, else the previous cycle block's.
    const auto sticky = [&](char letter, StickyValue& kept) -> Result<bool> {
      if (const Word* w = block.find(letter)) {
        if (!(std::fabs(w->value) <= max_coordinate_mm)) return fail(Error::GcodeBadNumber, w->column);
        kept = StickyValue{true, w->value};
      }
      return kept.given;
    };
    CURVESTEP_TRY(const bool has_z, sticky('Z', cycle_sticky_.z));
    CURVESTEP_TRY(const bool has_r, sticky('R', cycle_sticky_.r));
    CURVESTEP_TRY(const bool has_q, sticky('Q', cycle_sticky_.q));
    CURVESTEP_TRY(const bool has_p, sticky('P', cycle_sticky_.p));
    if (!has_z || !has_r) return fail(Error::GcodeCannedCycle, column);
    // The column of a word on this line, else the cycle's (a sticky word may come from an earlier line).
    const auto here = [&](char letter) -> std::uint16_t {
      const Word* w = block.find(letter);
      return w != nullptr ? w->column : column;
    };
    CannedCycle c;
    c.code = mode_ / 10;
    if (c.code == 73 || c.code == 83) {
      if (!has_q || !(cycle_sticky_.q.value > 0)) return fail(Error::GcodeCannedCycle, here('Q'));
      c.peck_mm = cycle_sticky_.q.value * scale();
    }
    if (c.code == 82 || c.code == 86 || c.code == 89) {
      if (!has_p || !(cycle_sticky_.p.value >= 0 && cycle_sticky_.p.value <= 1e6)) {
        return fail(Error::GcodeCannedCycle, here('P'));
      }
      c.dwell_s = cycle_sticky_.p.value;
    }
    if (c.code == 86 && !spindle_on_) return fail(Error::GcodeCannedCycle, column);
    if (const Word* l = block.find('L')) {
      if (!(l->value >= 1 && l->value <= max_cycle_repeats) || l->value != std::floor(l->value)) return fail(Error::GcodeBadNumber, l->column);
      c.repeats = static_cast<std::uint32_t>(l->value);
    }
    const double initial_z = position_[2];
    const Point offset = offset_in_force();
    const double dx = x != nullptr ? x->value * scale() : 0.0;
    const double dy = y != nullptr ? y->value * scale() : 0.0;
    const XyRotation rotation = rotation_in_force();
    if (incremental_) {
      // X Y from the current point (and again per repeat, along the system's turned axes), R from
      // the current Z, Z from R.
      c.step = rotation.turned(Point{{dx, dy, 0.0}});
      c.first_hole = Point{{position_[0] + c.step[0], position_[1] + c.step[1], 0.0}};
      c.r_z = initial_z + cycle_sticky_.r.value * scale();
      c.bottom_z = c.r_z + cycle_sticky_.z.value * scale();
    } else {
      if (rotation.none() || (x == nullptr && y == nullptr)) {
        c.first_hole = Point{{x != nullptr ? dx + offset[0] : position_[0], y != nullptr ? dy + offset[1] : position_[1], 0.0}};
      } else {
        const Point hole = absolute_xy(x, y);
        c.first_hole = Point{{hole[0], hole[1], 0.0}};
      }
      c.r_z = cycle_sticky_.r.value * scale() + offset[2];
      c.bottom_z = cycle_sticky_.z.value * scale() + offset[2];
    }
    if (polar != nullptr) CURVESTEP_CHECK(polar_holes(block, c));
    if (c.r_z < c.bottom_z) return fail(Error::GcodeCannedCycle, here('R'));
    c.clear_z = retract_to_initial_ && initial_z > c.r_z ? initial_z : c.r_z;
    const CyclePoint last_hole = cycle_hole(c, c.repeats - 1);
    for (const double v : {c.first_hole[0], c.first_hole[1], last_hole[0], last_hole[1], c.r_z, c.bottom_z}) {
      if (!(std::fabs(v) <= max_coordinate_mm)) return fail(Error::GcodeBadNumber, column);
    }
    motion.kind = MotionKind::Cycle;
    motion.cycle = c;
    motion.end = expand_cycle(c, position_, [](const CycleStep&) {});
    position_ = motion.end;
    previous_cubic_ = false;
    return motion;
  }

  /// The holes of a cycle block with polar words (LinuxCNC's convert_cycle_xy): G90 places the
  /// hole at @ ^ about the XY origin in force (a missing one from the current point; at the origin
  /// the angle is 0, as atan2(0, 0) gives LinuxCNC); G91 adds @ to the distance and ^ to the angle
  /// per repeat (GcodeMissingWord if it starts at the origin, where the angle is undefined).
  template <std::size_t Capacity>
  [[nodiscard]] Result<void> polar_holes(const Block<Capacity>& block, CannedCycle& c) const noexcept {
    const PolarMove p = polar_move(block);
    if (incremental_ && p.at_origin) return fail(Error::GcodeMissingWord, p.word->column);
    c.polar_origin = p.origin;
    c.step = Point{};
    c.polar_steps = incremental_;
    c.step_radius_mm = incremental_ ? p.step_mm : 0.0;
    c.step_angle_rad = incremental_ ? p.step_rad : 0.0;
    c.first_radius_mm = p.radius_mm;
    c.first_angle_rad = p.angle_rad;
    c.first_hole = Point{{p.origin[0] + p.radius_mm * std::cos(p.angle_rad), p.origin[1] + p.radius_mm * std::sin(p.angle_rad), 0.0}};
    const double reach = std::fabs(c.first_radius_mm) + static_cast<double>(c.repeats - 1) * std::fabs(c.step_radius_mm);
    if (!(std::fabs(p.origin[0]) + reach <= max_coordinate_mm && std::fabs(p.origin[1]) + reach <= max_coordinate_mm)) {
      return fail(Error::GcodeBadNumber, p.word->column);
    }
    return ok();
  }

  template <std::size_t Capacity>
  [[nodiscard]] Result<Motion> cubic(const Block<Capacity>& block, std::uint16_t column, Motion motion) noexcept {
    if (plane_ != Plane::XY) return fail(Error::GcodeSplineNotG17, column);
    CURVESTEP_CHECK(only(block, "XYIJPQ@^", Error::GcodeConflictingWords));
    const Word* i_word = block.find('I');
    const Word* j_word = block.find('J');
    if ((i_word == nullptr) != (j_word == nullptr)) return fail(Error::GcodeMissingWord, column);
    if (block.find('P') == nullptr || block.find('Q') == nullptr) return fail(Error::GcodeMissingWord, column);
    double i = 0;
    double j = 0;
    if (i_word == nullptr) {
      if (!previous_cubic_) return fail(Error::GcodeSplineNoTangent, column);
      i = -previous_p_;
      j = -previous_q_;
    } else {
      CURVESTEP_TRY(i, offset(block, 'I'));
      CURVESTEP_TRY(j, offset(block, 'J'));
    }
    CURVESTEP_TRY(const double p, offset(block, 'P'));
    CURVESTEP_TRY(const double q, offset(block, 'Q'));
    CURVESTEP_TRY(motion.end, end_point(block));
    // A copy, not a reference: position_ becomes the end below, and `moves` compares with the start.
    const Point s = position_;
    const Point& e = motion.end;
    // I J and P Q are along the program's axes: a rotated system turns them with it.
    const XyRotation rotation = rotation_in_force();
    motion.control = {s, s + rotation.turned(Point{{i, j, 0.0}}), e + rotation.turned(Point{{p, q, 0.0}}), e};
    for (const Point& c : motion.control) {
      if (!(std::fabs(c[0]) <= max_coordinate_mm && std::fabs(c[1]) <= max_coordinate_mm)) return fail(Error::GcodeBadNumber, column);
    }
    previous_cubic_ = true;
    previous_p_ = p;
    previous_q_ = q;
    position_ = motion.end;
    bool moves = false;
    for (const Point& c : motion.control) moves = moves || !(c == s);
    motion.kind = moves ? MotionKind::Cubic : MotionKind::None;
    return motion;
  }

  template <std::size_t Capacity>
  [[nodiscard]] Result<Motion> quadratic(const Block<Capacity>& block, std::uint16_t column, Motion motion) noexcept {
    if (plane_ != Plane::XY) return fail(Error::GcodeSplineNotG17, column);
    CURVESTEP_CHECK(only(block, "XYIJ@^", Error::GcodeConflictingWords));
    // Both offsets, as LinuxCNC's interpreter requires ("Must specify both I and J with G5.1").
    if (block.find('I') == nullptr || block.find('J') == nullptr) return fail(Error::GcodeMissingWord, column);
    CURVESTEP_TRY(const double i, offset(block, 'I'));
    CURVESTEP_TRY(const double j, offset(block, 'J'));
    CURVESTEP_TRY(motion.end, end_point(block));
    // A copy, not a reference: position_ becomes the end below, and `moves` compares with the start.
    const Point s = position_;
    motion.control = {s, s + rotation_in_force().turned(Point{{i, j, 0.0}}), motion.end, Point{}};
    if (!(std::fabs(motion.control[1][0]) <= max_coordinate_mm && std::fabs(motion.control[1][1]) <= max_coordinate_mm)) {
      return fail(Error::GcodeBadNumber, column);
    }
    previous_cubic_ = false;
    position_ = motion.end;
    const bool moves = !(motion.control[1] == s) || !(motion.end == s);
    motion.kind = moves ? MotionKind::Quadratic : MotionKind::None;
    return motion;
  }

  template <std::size_t Capacity>
  [[nodiscard]] Result<Motion> start_nurbs(const Block<Capacity>& block, const Word& g, Motion motion) noexcept {
    if (plane_ != Plane::XY) return fail(Error::GcodeSplineNotG17, g.column);
    CURVESTEP_CHECK(only(block, "XYPL", Error::GcodeConflictingWords));
    nurbs_order_ = 3;
    if (const Word* l = block.find('L')) {
      if (!(l->value >= 2 && l->value <= 8) || l->value != std::floor(l->value)) return fail(Error::GcodeNurbsBlock, l->column);
      nurbs_order_ = static_cast<std::size_t>(l->value);
    }
    double weight = 1;
    if (const Word* p = block.find('P')) {
      if (!(p->value > 0)) return fail(Error::GcodeNurbsBlock, p->column);
      weight = p->value;
    }
    const bool has_point = block.find('X') != nullptr || block.find('Y') != nullptr;
    nurbs_points_[0] = position_;
    nurbs_weights_[0] = has_point ? 1.0 : weight;
    nurbs_count_ = 1;
    if (has_point) {
      CURVESTEP_TRY(const Point point, end_point(block));
      nurbs_points_[1] = point;
      nurbs_weights_[1] = weight;
      nurbs_count_ = 2;
      position_ = point;
    }
    in_nurbs_ = true;
    previous_cubic_ = false;
    mode_ = 52;
    return motion;
  }

  /// A canned-cycle word kept from an earlier block of the series.
  struct StickyValue {
    bool given = false;
    double value = 0;  ///< as written (program units)
  };
  struct CycleSticky {
    StickyValue z, r, q, p;
  };

  Point position_{};
  std::array<double, 2> refused_arc_radii_{};
  CycleSticky cycle_sticky_{};
  bool retract_to_initial_ = true;  ///< G98 (LinuxCNC's start-up mode); G99 returns to R
  std::array<Point, 9> work_offsets_{};  ///< G54 … G59.3
  std::array<double, 9> rotations_deg_{};  ///< their rotations about Z (G10 L2 R), degrees
  std::size_t coordinate_system_ = 0;
  Point g92_offset_{};
  Point g92_saved_{};
  std::array<ToolEntry, max_tools> tools_{};
  std::size_t tool_count_ = 0;
  CompensationSide compensation_side_ = CompensationSide::Off;
  double compensation_radius_mm_ = 0;
  double tool_length_mm_ = 0;
  std::size_t selected_tool_ = 0;
  std::size_t loaded_tool_ = 0;
  Point home28_{};
  Point home30_{};
  double path_tolerance_mm_ = 0;
  double spindle_rpm_ = 0;
  bool spindle_on_ = false;
  bool spindle_ccw_ = false;
  bool machine_coordinates_ = false;  ///< G53 in the block being executed
  Plane plane_ = Plane::XY;
  Units units_ = Units::Millimetres;
  bool incremental_ = false;
  bool arc_absolute_ = false;
  bool ended_ = false;
  bool in_nurbs_ = false;
  bool previous_cubic_ = false;
  double previous_p_ = 0;
  double previous_q_ = 0;
  double feed_value_ = 0;
  bool feed_given_ = false;
  bool inverse_time_ = false;  ///< G93 in force
  bool feed_needed_ = false;   ///< G94 came after G93 and no F since: a feed move needs one first
  FeedRefusal refused_feed_ = FeedRefusal::None;
  std::int32_t mode_ = -1;
  std::uint16_t mode_column_ = 0;
  std::size_t nurbs_order_ = 3;
  std::size_t nurbs_count_ = 0;
  std::array<Point, MaxNurbsPoints> nurbs_points_{};
  std::array<double, MaxNurbsPoints> nurbs_weights_{};
};

}  // namespace curvestep::gcode
