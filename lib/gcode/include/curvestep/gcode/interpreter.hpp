// SPDX-License-Identifier: MIT
// G-code modal interpreter: Blocks -> motions (rapid, line, arc, cubic, quadratic, NURBS), LinuxCNC semantics.
//
// Geometry is computed in double, as PathSegment holds it (motion/path_segment.hpp): the motions
// feed PathSegments on every target, so working in double here loses nothing and keeps host and
// firmware identical. All lengths leave in millimetres (G20 values are multiplied by 25.4).
//
// Semantics (LinuxCNC g-code reference):
//   G0/G1 X Y Z        rapid / feed line to the end point (G90 absolute, G91 incremental).
//   G2/G3 X Y Z I J P  arc in the XY plane (G17), clockwise / counter-clockwise; centre = start +
//                      (I,J) in G91.1 (the default) or (I,J) in G90.1. Z moving makes a helix. End
//                      equal to start is a full circle; P n adds n-1 extra turns. The radii to start
//                      r0 and end r1 must agree: error if |r0-r1| > 0.5 mm, or if |r0-r1| > 0.005 mm
//                      and > 0.1 % of r0 (LinuxCNC's documented tolerance, applied in mm).
//   G2/G3 X Y Z R      radius form: centre on the perpendicular bisector of the chord at distance
//                      sqrt(R² - (c/2)²); R > 0 the arc of at most half a turn, R < 0 the longer one.
//   G5 X Y I J P Q     cubic Bézier with control points P0, P0+(I,J), P1+(P,Q), P1 (offsets always
//                      relative). Omitting I and J continues the previous G5's end tangent:
//                      (I,J) = -(P,Q) of the previous G5 — an error if the previous motion was not
//                      a G5. P and Q are required; I without J (or J without I) is an error.
//   G5.1 X Y I J       quadratic Bézier P0, P0+(I,J), P1; I and J may not both be omitted.
//   G5.2 [X Y] [P] [L] opens a NURBS block: the current point is the first control point (weight P
//                      when the G5.2 line has no X Y, else weight 1 and X Y is the second control
//                      point with weight P); following lines "X Y [P]" add control points (weight
//                      default 1); G5.3 closes the block and emits the curve of order L (default 3,
//                      degree L-1) with a clamped uniform knot vector.
//   Splines only in G17 (GcodeSplineNotG17) and only in X and Y (a Z word is GcodeConflictingWords).
//   G17/G18/G19, G20/G21, G90/G91, G90.1/G91.1 are modal; F is modal (per minute, in units);
//   M2/M30 end the program.
// Arcs in G18/G19 are not supported (GcodeUnsupportedWord at the arc's G word), because a
// PathSegment arc lies in the XY plane.
//
// Errors carry the 1-based column of the word at fault (Failure::index).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include <curvestep/core/curve/circular_arc.hpp>
#include <curvestep/core/geometry/vec.hpp>
#include <curvestep/core/result.hpp>
#include <curvestep/gcode/parser.hpp>

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
};

/// Active plane (G17, G18, G19).
enum class Plane : std::uint8_t { XY, ZX, YZ };
/// Active units (G21, G20).
enum class Units : std::uint8_t { Millimetres, Inches };

/// One motion produced by a block.
struct Motion {
  MotionKind kind = MotionKind::None;         ///< what moves
  Point start{};                              ///< where the motion starts, mm
  Point end{};                                ///< where it ends, mm
  Point center{};                             ///< arc centre (z = start z), mm
  ArcDirection direction = ArcDirection::Clockwise;  ///< arc direction (G2 clockwise, G3 counter-clockwise)
  std::uint32_t full_turns = 0;               ///< arc: extra whole turns (P - 1)
  double radius_difference_mm = 0;            ///< arc: |r_end - r_start|, already within tolerance
  std::array<Point, 4> control{};             ///< Cubic: 4, Quadratic: 3 control points
  std::size_t nurbs_order = 0;                ///< Nurbs: order (degree + 1)
  double feed_mm_per_min = 0;                 ///< modal feed, 0 if none was given
  std::uint16_t column = 0;                   ///< column of the word that commanded the motion
  bool program_end = false;                   ///< the block held M2 or M30
};

/// Factor from inches to millimetres.
inline constexpr double millimetres_per_inch = 25.4;
/// Largest coordinate magnitude accepted, mm (inside the Q16.16 range of ±32768 mm).
inline constexpr double max_coordinate_mm = 32767.0;
/// Largest number of turns (P on G2/G3).
inline constexpr double max_arc_turns = 10000.0;

/// Whether radii r0 (start) and r1 (end) disagree beyond LinuxCNC's tolerance: more than 0.5 mm,
/// or more than 0.005 mm and more than 0.1 % of r0.
[[nodiscard]] inline bool arc_radii_mismatch(double r0, double r1) noexcept {
  const double difference = std::fabs(r1 - r0);
  return difference > 0.5 || (difference > 0.005 && difference > 0.001 * r0);
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
  [[nodiscard]] constexpr bool incremental() const noexcept { return incremental_; }
  [[nodiscard]] constexpr bool arc_centers_absolute() const noexcept { return arc_absolute_; }
  /// Inside a G5.2 … G5.3 block.
  [[nodiscard]] constexpr bool in_nurbs_block() const noexcept { return in_nurbs_; }
  /// M2 or M30 was executed.
  [[nodiscard]] constexpr bool ended() const noexcept { return ended_; }
  /// The last NURBS block's control points and weights (valid after a Nurbs motion until the next G5.2).
  [[nodiscard]] constexpr std::span<const Point> nurbs_points() const noexcept { return {nurbs_points_.data(), nurbs_count_}; }
  [[nodiscard]] constexpr std::span<const double> nurbs_weights() const noexcept { return {nurbs_weights_.data(), nurbs_count_}; }
  [[nodiscard]] static constexpr std::size_t nurbs_capacity() noexcept { return MaxNurbsPoints; }

  /// Executes one block. Failures carry the column of the word at fault.
  template <std::size_t Capacity>
  [[nodiscard]] Result<Motion> execute(const Block<Capacity>& block) noexcept {
    // ---- classify the words ----
    const Word* motion_word = nullptr;
    const Word* plane_word = nullptr;
    const Word* units_word = nullptr;
    const Word* distance_word = nullptr;
    const Word* arc_distance_word = nullptr;
    const Word* end_word = nullptr;
    for (const Word& w : block.words()) {
      const Word** slot = nullptr;
      if (w.letter == 'G') {
        switch (w.code_tenths) {
          case 0: case 10: case 20: case 30: case 50: case 51: case 52: case 53: slot = &motion_word; break;
          case 170: case 180: case 190: slot = &plane_word; break;
          case 200: case 210: slot = &units_word; break;
          case 900: case 910: slot = &distance_word; break;
          case 901: case 911: slot = &arc_distance_word; break;
          default: return fail(Error::GcodeUnsupportedWord, w.column);
        }
      } else if (w.letter == 'M') {
        if (w.code_tenths != 20 && w.code_tenths != 300) return fail(Error::GcodeUnsupportedWord, w.column);
        slot = &end_word;
      }
      if (slot != nullptr) {
        if (*slot != nullptr) return fail(Error::GcodeConflictingWords, w.column);
        *slot = &w;
      }
    }
    // ---- modal settings, in LinuxCNC's order: feed, plane, units, distance modes ----
    if (plane_word != nullptr) {
      plane_ = plane_word->code_tenths == 170 ? Plane::XY : plane_word->code_tenths == 180 ? Plane::ZX : Plane::YZ;
    }
    if (units_word != nullptr) units_ = units_word->code_tenths == 200 ? Units::Inches : Units::Millimetres;
    if (const Word* f = block.find('F')) {
      if (!(f->value >= 0)) return fail(Error::GcodeBadNumber, f->column);
      feed_value_ = f->value;
    }
    if (distance_word != nullptr) incremental_ = distance_word->code_tenths == 910;
    if (arc_distance_word != nullptr) arc_absolute_ = arc_distance_word->code_tenths == 901;

    Motion motion;
    motion.start = position_;
    motion.end = position_;
    motion.feed_mm_per_min = feed_value_ * scale();  // F is read in the units active at the motion
    motion.program_end = end_word != nullptr;

    if (in_nurbs_) {
      CURVESTEP_TRY(motion, nurbs_line(block, motion_word, motion));
    } else {
      CURVESTEP_TRY(motion, motion_line(block, motion_word, motion));
    }
    if (end_word != nullptr) {
      if (in_nurbs_) return fail(Error::GcodeNurbsBlock, end_word->column);
      ended_ = true;
    }
    return motion;
  }

 private:
  [[nodiscard]] constexpr double scale() const noexcept { return units_ == Units::Inches ? millimetres_per_inch : 1.0; }

  /// The end point from X Y Z (absolute or incremental), range-checked.
  template <std::size_t Capacity>
  [[nodiscard]] Result<Point> end_point(const Block<Capacity>& block) const noexcept {
    Point end = position_;
    constexpr std::array<char, 3> axes{'X', 'Y', 'Z'};
    for (std::size_t axis = 0; axis < 3; ++axis) {
      if (const Word* w = block.find(axes[axis])) {
        const double v = w->value * scale() + (incremental_ ? position_[axis] : 0.0);
        if (!(std::fabs(v) <= max_coordinate_mm)) return fail(Error::GcodeBadNumber, w->column);
        end[axis] = v;
      }
    }
    return end;
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

  /// A line inside a G5.2 block: a control point, or G5.3.
  template <std::size_t Capacity>
  [[nodiscard]] Result<Motion> nurbs_line(const Block<Capacity>& block, const Word* motion_word, Motion motion) noexcept {
    if (motion_word != nullptr && motion_word->code_tenths != 53) return fail(Error::GcodeNurbsBlock, motion_word->column);
    if (motion_word != nullptr) {  // G5.3
      CURVESTEP_CHECK(only(block, "", Error::GcodeNurbsBlock));
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
      mode_ = motion_word->code_tenths;
      mode_column_ = motion_word->column;
    }
    const bool moves = has_any(block, "XYZIJKRPQL");
    if (!moves) {
      if (motion_word == nullptr) return motion;
      if (mode_ == 52) return start_nurbs(block, *motion_word, motion);
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
    switch (mode_) {
      case 0:
      case 10: {
        CURVESTEP_CHECK(only(block, "XYZ", Error::GcodeConflictingWords));
        CURVESTEP_TRY(motion.end, end_point(block));
        previous_cubic_ = false;
        if (motion.end == position_) return motion;
        motion.kind = mode_ == 0 ? MotionKind::Rapid : MotionKind::Line;
        position_ = motion.end;
        return motion;
      }
      case 20:
      case 30: return arc(block, column, motion);
      case 50: return cubic(block, column, motion);
      case 51: return quadratic(block, column, motion);
      case 52: return start_nurbs(block, Word{'G', 5.2, 52, column}, motion);
      default: return fail(Error::GcodeNurbsBlock, column);  // G5.3 without G5.2
    }
  }

  template <std::size_t Capacity>
  [[nodiscard]] Result<Motion> arc(const Block<Capacity>& block, std::uint16_t column, Motion motion) noexcept {
    if (plane_ != Plane::XY) return fail(Error::GcodeUnsupportedWord, column);
    CURVESTEP_CHECK(only(block, "XYZIJKRP", Error::GcodeConflictingWords));
    if (const Word* k = block.find('K')) return fail(Error::GcodeConflictingWords, k->column);
    const Word* r_word = block.find('R');
    const Word* i_word = block.find('I');
    const Word* j_word = block.find('J');
    if (r_word != nullptr && (i_word != nullptr || j_word != nullptr)) return fail(Error::GcodeConflictingWords, r_word->column);
    CURVESTEP_TRY(motion.end, end_point(block));
    motion.direction = mode_ == 20 ? ArcDirection::Clockwise : ArcDirection::CounterClockwise;
    if (const Word* p = block.find('P')) {
      if (!(p->value >= 1 && p->value <= max_arc_turns) || p->value != std::floor(p->value)) {
        return fail(Error::GcodeBadNumber, p->column);
      }
      motion.full_turns = static_cast<std::uint32_t>(p->value) - 1;
    }
    const Point s = position_;
    const Point& e = motion.end;
    double cx = 0;
    double cy = 0;
    if (r_word != nullptr) {
      CURVESTEP_TRY(const double r, offset(block, 'R'));
      const double dx = e[0] - s[0];
      const double dy = e[1] - s[1];
      const double chord = std::sqrt(dx * dx + dy * dy);
      if (chord == 0) return fail(Error::GcodeMissingWord, r_word->column);  // R cannot make a full circle
      const double half = chord / 2;
      const double radius = std::fabs(r);
      if (radius < half && arc_radii_mismatch(radius, half)) return fail(Error::GcodeArcRadiusMismatch, r_word->column);
      const double height = radius > half ? std::sqrt(radius * radius - half * half) : 0.0;
      double side = motion.direction == ArcDirection::CounterClockwise ? 1.0 : -1.0;
      if (r < 0) side = -side;
      cx = s[0] + dx / 2 - side * height * dy / chord;
      cy = s[1] + dy / 2 + side * height * dx / chord;
    } else {
      if (i_word == nullptr && j_word == nullptr) return fail(Error::GcodeMissingWord, column);
      CURVESTEP_TRY(const double i, offset(block, 'I'));
      CURVESTEP_TRY(const double j, offset(block, 'J'));
      cx = arc_absolute_ ? i : s[0] + i;
      cy = arc_absolute_ ? j : s[1] + j;
    }
    const double r0 = std::sqrt((s[0] - cx) * (s[0] - cx) + (s[1] - cy) * (s[1] - cy));
    const double r1 = std::sqrt((e[0] - cx) * (e[0] - cx) + (e[1] - cy) * (e[1] - cy));
    if (!(r0 > 0) || arc_radii_mismatch(r0, r1)) return fail(Error::GcodeArcRadiusMismatch, column);
    if (!(std::fabs(cx) <= max_coordinate_mm && std::fabs(cy) <= max_coordinate_mm)) {
      return fail(Error::GcodeBadNumber, r_word != nullptr ? r_word->column : column);
    }
    motion.center = Point{{cx, cy, s[2]}};
    motion.radius_difference_mm = std::fabs(r1 - r0);
    motion.kind = MotionKind::Arc;
    position_ = motion.end;
    previous_cubic_ = false;
    return motion;
  }

  template <std::size_t Capacity>
  [[nodiscard]] Result<Motion> cubic(const Block<Capacity>& block, std::uint16_t column, Motion motion) noexcept {
    if (plane_ != Plane::XY) return fail(Error::GcodeSplineNotG17, column);
    CURVESTEP_CHECK(only(block, "XYIJPQ", Error::GcodeConflictingWords));
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
    motion.control = {s, Point{{s[0] + i, s[1] + j, s[2]}}, Point{{e[0] + p, e[1] + q, e[2]}}, e};
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
    CURVESTEP_CHECK(only(block, "XYIJ", Error::GcodeConflictingWords));
    if (block.find('I') == nullptr && block.find('J') == nullptr) return fail(Error::GcodeMissingWord, column);
    CURVESTEP_TRY(const double i, offset(block, 'I'));
    CURVESTEP_TRY(const double j, offset(block, 'J'));
    CURVESTEP_TRY(motion.end, end_point(block));
    // A copy, not a reference: position_ becomes the end below, and `moves` compares with the start.
    const Point s = position_;
    motion.control = {s, Point{{s[0] + i, s[1] + j, s[2]}}, motion.end, Point{}};
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

  Point position_{};
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
  std::int32_t mode_ = -1;
  std::uint16_t mode_column_ = 0;
  std::size_t nurbs_order_ = 3;
  std::size_t nurbs_count_ = 0;
  std::array<Point, MaxNurbsPoints> nurbs_points_{};
  std::array<double, MaxNurbsPoints> nurbs_weights_{};
};

}  // namespace curvestep::gcode
