// SPDX-License-Identifier: MIT
// PathSegment: one piece of a job (line, circular/helical arc, Bézier, rational Bézier) in 3 axes.
//
// Geometry is held in double so that planning and evaluation are bit-identical on every target
// (IEEE +, -, *, /, sqrt and the deterministic sin/cos of deterministic_math.hpp only). A firmware
// receives coordinates as Q16.16 and converts them exactly; the simulator quantises job files to
// Q16.16 first, so both see the same numbers. Every kind is parametrised on u in [0,1]:
//   line    p(u) = (1-u) a + u b
//   arc     p(u) = c + cos(uθ) a + sin(uθ) J a (+ u Δz on the third axis), θ the signed sweep
//   Bézier  de Casteljau; rational Bézier in homogeneous coordinates.
// B-spline/NURBS jobs are extracted into (rational) Bézier segments before they get here.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

#include <curvestep/core/curve/bezier.hpp>
#include <curvestep/core/curve/circular_arc.hpp>
#include <curvestep/core/curve/rational_bezier.hpp>
#include <curvestep/core/motion/deterministic_math.hpp>
#include <curvestep/core/motion/machine_limits.hpp>

namespace curvestep {

/// What kind of curve a segment is.
enum class SegmentKind : std::uint8_t {
  Line = 0,            ///< straight line
  Arc = 1,             ///< circular arc in the XY plane, optionally helical in Z
  Bezier = 2,          ///< polynomial Bézier, degree 1..7
  RationalBezier = 3,  ///< rational Bézier with positive weights, degree 1..7
};

/// A point in machine space (mm).
using MachinePoint = Vec<double, motion_axes>;

/// A PathSegment as the motion queue keeps it (MotionController): only the numbers that define
/// the segment (control points, weights or arc data, one array for every kind) instead of the
/// full PathSegment with its polynomial, rational and arc members side by side (272 bytes
/// against 776 on Cortex-M). PathSegment::compact() copies the doubles and PathSegment::expand()
/// rebuilds the segment from them, so an expanded segment evaluates bit for bit like the original.
///   Line, Bezier     values[3i + axis] = control point i (degree + 1 points)
///   RationalBezier   the same, and values[24 + i] = weight i
///   Arc              start 0..2, end 3..5, centre 6..8, radius 9, sweep 10, Δz 11, end radius scale 12
struct CompactSegment {
  static constexpr std::size_t value_count = 32;  ///< (max degree 7 + 1) × (3 axes + a weight)
  std::array<double, value_count> values{};       ///< the kind's numbers (above)
  double feed_mm_per_s = 0;                        ///< programmed feed (0: the machine's default)
  SegmentKind kind = SegmentKind::Line;            ///< what the values mean
  std::uint8_t degree = 1;                         ///< Bézier degree (Line: 1, Arc: unused)
  bool rapid = false;                              ///< rapid move
};

/// One segment of a path; construct with the make_* functions, which validate.
class PathSegment {
 public:
  static constexpr std::size_t max_degree = 7;
  static constexpr std::size_t capacity = max_degree + 1;  ///< control points at most
  using Polynomial = curvestep::Bezier<double, motion_axes, max_degree>;
  using Rational = curvestep::RationalBezier<double, motion_axes, max_degree>;

  constexpr PathSegment() = default;

  /// A straight line from a to b. DegenerateCurve if a == b (zero-length moves are dropped by callers);
  /// NotFinite for NaN/inf coordinates or b - a beyond double.
  [[nodiscard, gnu::noinline]] static Result<PathSegment> make_line(const MachinePoint& a, const MachinePoint& b) noexcept {
    Result<PathSegment> out(std::in_place);  // built in place and returned by name (no copy)
    if (const auto made = out.value().set_line(a, b); !made) out = made.failure();
    return out;
  }

  /// An arc in the XY plane about `center` (its z ignored) from `start` to `end` in `direction`,
  /// plus `full_turns` extra whole turns; z moves linearly from start.z to end.z (a helix).
  /// start == end (in XY) with full_turns == 0 is a full circle. InvalidArgument if the radii of
  /// start and end differ by more than `radius_tolerance_mm`; DegenerateCurve for zero radius;
  /// NotFinite for NaN/inf in the XY radii or the height change.
  [[nodiscard, gnu::noinline]] static Result<PathSegment> make_arc(const MachinePoint& start, const MachinePoint& end, const MachinePoint& center,
                                                    ArcDirection direction, std::uint32_t full_turns,
                                                    double radius_tolerance_mm) noexcept {
    Result<PathSegment> out(std::in_place);
    if (const auto made = out.value().set_arc(start, end, center, direction, full_turns, radius_tolerance_mm); !made) {
      out = made.failure();
    }
    return out;
  }

  /// A polynomial Bézier from 2..8 control points. NotFinite for NaN/inf, or derivatives beyond double.
  [[nodiscard, gnu::noinline]] static Result<PathSegment> make_bezier(std::span<const MachinePoint> control) noexcept {
    Result<PathSegment> out(std::in_place);
    if (const auto made = out.value().set_bezier(control); !made) out = made.failure();
    return out;
  }

  /// A rational Bézier from 2..8 control points and positive weights. NotFinite for NaN/inf, or
  /// weights and points so extreme that the derivatives could overflow (check_rational_derivatives).
  [[nodiscard, gnu::noinline]] static Result<PathSegment> make_rational_bezier(std::span<const MachinePoint> control,
                                                                std::span<const double> weights) noexcept {
    Result<PathSegment> out(std::in_place);
    if (const auto made = out.value().set_rational_bezier(control, weights); !made) out = made.failure();
    return out;
  }

  [[nodiscard]] constexpr SegmentKind kind() const noexcept { return kind_; }
  /// Rapid (travel, pen-up) move rather than a feed move.
  [[nodiscard]] constexpr bool rapid() const noexcept { return rapid_; }
  constexpr void set_rapid(bool rapid) noexcept { rapid_ = rapid; }
  /// Programmed feed in mm/s (0: the machine's default).
  [[nodiscard]] constexpr double feed_mm_per_s() const noexcept { return feed_; }
  constexpr void set_feed_mm_per_s(double feed) noexcept { feed_ = feed; }

  /// Arc data (meaningful for SegmentKind::Arc).
  [[nodiscard]] constexpr const MachinePoint& arc_center() const noexcept { return is_arc() ? geometry_.arc.center : no_point; }
  [[nodiscard]] constexpr double arc_radius() const noexcept { return is_arc() ? geometry_.arc.radius : 0.0; }
  [[nodiscard]] constexpr double arc_sweep_rad() const noexcept { return is_arc() ? geometry_.arc.sweep : 0.0; }
  /// Bézier data (meaningful for Line and Bezier; an empty curve for the other kinds).
  [[nodiscard]] constexpr const Polynomial& polynomial() const noexcept {
    return kind_ == SegmentKind::Line || kind_ == SegmentKind::Bezier ? geometry_.polynomial : no_polynomial;
  }
  /// Rational data (meaningful for RationalBezier; an empty curve for the other kinds).
  [[nodiscard]] constexpr const Rational& rational() const noexcept {
    return kind_ == SegmentKind::RationalBezier ? geometry_.rational : no_rational;
  }

  /// Start and end points (exact: the values the segment was built from).
  [[nodiscard]] constexpr MachinePoint start() const noexcept {
    switch (kind_) {
      case SegmentKind::Arc: return geometry_.arc.start;
      case SegmentKind::RationalBezier: return geometry_.rational.front();
      default: return geometry_.polynomial.front();
    }
  }
  [[nodiscard]] constexpr MachinePoint end() const noexcept {
    switch (kind_) {
      case SegmentKind::Arc: return geometry_.arc.end;
      case SegmentKind::RationalBezier: return geometry_.rational.back();
      default: return geometry_.polynomial.back();
    }
  }

  /// p(u), u in [0,1] (contract). The ends return start() and end() exactly.
  [[nodiscard]] MachinePoint point(double u) const {
    CURVESTEP_EXPECTS(u >= 0 && u <= 1);
    if (u == 0) return start();
    if (u == 1) return end();
    switch (kind_) {
      case SegmentKind::Arc:
        return rotated_radius(u * geometry_.arc.sweep, radius_scale(u)) + MachinePoint{{geometry_.arc.center[0], geometry_.arc.center[1], geometry_.arc.start[2] + u * geometry_.arc.dz}};
      case SegmentKind::RationalBezier: return geometry_.rational.point_at(u);
      default: return geometry_.polynomial.point_at(u);
    }
  }

  /// d^order p / du^order at u in [0,1], order 1..3.
  [[nodiscard]] MachinePoint derivative(double u, std::size_t order) const {
    CURVESTEP_EXPECTS(u >= 0 && u <= 1 && order >= 1 && order <= 3);
    switch (kind_) {
      case SegmentKind::Arc: return arc_derivative(u, order);
      case SegmentKind::RationalBezier: return geometry_.rational.derivative_at_most<3>(u, order).value();
      default: return geometry_.polynomial.derivative_at(u, order).value();
    }
  }

  /// The segment's defining numbers (exact copies), for the motion queue.
  [[nodiscard]] constexpr CompactSegment compact() const noexcept {
    CompactSegment c;
    c.kind = kind_;
    c.rapid = rapid_;
    c.feed_mm_per_s = feed_;
    const auto store = [&c](std::size_t first, const MachinePoint& p) {
      for (std::size_t axis = 0; axis < motion_axes; ++axis) c.values[first + axis] = p[axis];
    };
    switch (kind_) {
      case SegmentKind::Arc:
        store(0, geometry_.arc.start);
        store(3, geometry_.arc.end);
        store(6, geometry_.arc.center);
        c.values[9] = geometry_.arc.radius;
        c.values[10] = geometry_.arc.sweep;
        c.values[11] = geometry_.arc.dz;
        c.values[12] = geometry_.arc.end_radius_scale;
        break;
      case SegmentKind::RationalBezier: {
        const auto points = geometry_.rational.control_points();
        c.degree = static_cast<std::uint8_t>(geometry_.rational.degree());
        for (std::size_t i = 0; i < points.size(); ++i) {
          store(3 * i, points[i]);
          c.values[3 * capacity + i] = geometry_.rational.weight(i);
        }
        break;
      }
      default: {
        const auto points = geometry_.polynomial.control_points();
        c.degree = static_cast<std::uint8_t>(geometry_.polynomial.degree());
        for (std::size_t i = 0; i < points.size(); ++i) store(3 * i, points[i]);
        break;
      }
    }
    return c;
  }

  /// The segment whose compact() gave `c`: the same control points, weights and arc data, so it
  /// evaluates, differentiates and splits bit for bit like the original. NotFinite and the other
  /// errors of Bezier::create / RationalBezier::create for numbers no PathSegment holds.
  [[nodiscard, gnu::noinline]] static Result<PathSegment> expand(const CompactSegment& c) noexcept {
    Result<PathSegment> out(std::in_place);  // built in place and returned by name (no copy)
    if (const auto made = out.value().set_compact(c); !made) out = made.failure();
    return out;
  }

  /// The two pieces on [0,u] and [u,1] (Bézier kinds only; lines and arcs have no cusps to split at).
  /// InvalidArgument for other kinds or u outside (0,1); DegenerateCurve if a piece collapses.
  [[nodiscard]] Result<SplitCurves<PathSegment>> split(double u) const noexcept {
    SplitCurves<PathSegment> pieces;
    pieces.right = *this;
    CURVESTEP_CHECK(pieces.right.split_off(u, pieces.left));
    return pieces;
  }

  /// split(u) in place, with less memory: `left` becomes the piece on [0,u] and this segment the
  /// piece on [u,1] (the same pieces, bit for bit). On an error both are left unchanged.
  [[nodiscard]] Result<void> split_off(double u, PathSegment& left) noexcept {
    if (!(u > 0 && u < 1)) return fail(Error::InvalidArgument);
    if (kind_ == SegmentKind::Bezier) return split_off_curve(geometry_.polynomial, u, left, left.geometry_.polynomial);
    if (kind_ == SegmentKind::RationalBezier) return split_off_curve(geometry_.rational, u, left, left.geometry_.rational);
    return fail(Error::InvalidArgument);
  }

 private:
  [[nodiscard]] constexpr bool is_arc() const noexcept { return kind_ == SegmentKind::Arc; }

  /// split_off() for one curve kind (one frame per kind: the rational halves alone take 0.9 KiB).
  template <class Curve>
  [[nodiscard, gnu::noinline]] Result<void> split_off_curve(Curve& curve, double u, PathSegment& left, Curve& left_curve) noexcept {
    Curve left_half;
    Curve right_half;
    CURVESTEP_CHECK(curve.split(u, left_half, right_half));
    if (is_point(left_half.control_points()) || is_point(right_half.control_points())) return fail(Error::DegenerateCurve);
    left = *this;
    left_curve = left_half;
    curve = right_half;
    return ok();
  }

  // The make_* functions and expand() fill a PathSegment in place (inside the Result they
  // return): on a microcontroller's stack a PathSegment copy is half a kilobyte.

  [[nodiscard]] Result<void> set_line(const MachinePoint& a, const MachinePoint& b) noexcept {
    if (a == b) return fail(Error::DegenerateCurve);
    kind_ = SegmentKind::Line;
    const std::array<MachinePoint, 2> ends{a, b};
    std::construct_at(&geometry_.polynomial);  // the union's active member follows the kind
    CURVESTEP_CHECK(Polynomial::create_into(geometry_.polynomial, ends));
    return check_derivatives();
  }

  [[nodiscard]] Result<void> set_arc(const MachinePoint& start, const MachinePoint& end, const MachinePoint& center,
                                     ArcDirection direction, std::uint32_t full_turns, double radius_tolerance_mm) noexcept {
    const double ax = start[0] - center[0];
    const double ay = start[1] - center[1];
    const double bx = end[0] - center[0];
    const double by = end[1] - center[1];
    const double r = std::sqrt(ax * ax + ay * ay);
    const double rb = std::sqrt(bx * bx + by * by);
    if (!std::isfinite(r) || !std::isfinite(rb) || !std::isfinite(end[2] - start[2])) return fail(Error::NotFinite);
    if (r == 0) return fail(Error::DegenerateCurve);
    if (!(std::fabs(r - rb) <= radius_tolerance_mm)) return fail(Error::InvalidArgument, 1);  // NaN tolerance too
    double sweep = detail::atan2(ax * by - ay * bx, ax * bx + ay * by);  // (-π, π]
    const bool ccw = direction == ArcDirection::CounterClockwise;
    if (ccw && sweep <= 0) sweep += 2 * detail::pi;
    if (!ccw && sweep >= 0) sweep -= 2 * detail::pi;
    sweep += (ccw ? 2 : -2) * detail::pi * static_cast<double>(full_turns);
    kind_ = SegmentKind::Arc;
    geometry_.arc = ArcData{start, end, MachinePoint{{center[0], center[1], start[2]}}, r, sweep, end[2] - start[2], rb / r};
    return ok();
  }

  /// derivative() of an arc, kept out of derivative() so that the Bézier kinds' calls do not carry
  /// its frame (the sines and cosines) on a microcontroller's stack.
  [[nodiscard, gnu::noinline]] MachinePoint arc_derivative(double u, std::size_t order) const noexcept {
    // p(u) = c + ρ(u) R(uθ) a with ρ linear (ρ(0) = 1, ρ(1) = r_end / r_start) and
    // d^k/du^k R(uθ) a = |θ|^k R(uθ + k sign(θ) π/2) a, so by Leibniz
    // p^(k) = ρ |θ|^k R(uθ + k s π/2) a + k ρ' |θ|^(k-1) R(uθ + (k-1) s π/2) a.
    const double sign = geometry_.arc.sweep >= 0 ? 1.0 : -1.0;
    const double quarter = sign * detail::pi / 2;
    double power = 1;  // |θ|^(k-1)
    for (std::size_t k = 1; k < order; ++k) power *= std::fabs(geometry_.arc.sweep);
    const double k = static_cast<double>(order);
    auto d = rotated_radius(u * geometry_.arc.sweep + k * quarter, radius_scale(u) * power * std::fabs(geometry_.arc.sweep)) +
             rotated_radius(u * geometry_.arc.sweep + (k - 1) * quarter, k * (geometry_.arc.end_radius_scale - 1) * power);
    d[2] = order == 1 ? geometry_.arc.dz : 0.0;
    return d;
  }

  /// ρ(u): the radius relative to the start radius, linear from 1 to r_end / r_start, so that an
  /// arc whose end radius differs slightly (within the tolerance) still ends exactly at its end.
  [[nodiscard]] constexpr double radius_scale(double u) const noexcept { return 1 + u * (geometry_.arc.end_radius_scale - 1); }

  /// factor * R(angle) (start - center) in XY, z = 0.
  [[nodiscard]] MachinePoint rotated_radius(double angle, double factor) const noexcept {
    const auto sc = detail::sin_cos(angle);
    const double ax = geometry_.arc.start[0] - geometry_.arc.center[0];
    const double ay = geometry_.arc.start[1] - geometry_.arc.center[1];
    return MachinePoint{{factor * (sc.cos * ax - sc.sin * ay), factor * (sc.cos * ay + sc.sin * ax), 0.0}};
  }

  /// NotFinite if a derivative that derivative() evaluates (orders 1..3) overflows double: the
  /// hodographs' control points are then finite, and de Casteljau keeps their combinations finite.
  [[nodiscard]] constexpr Result<void> check_derivatives() const noexcept {
    // derivative_at(0, 3) fails exactly where derivative(3) does (its hodographs are the same
    // steps; de Casteljau at 0 returns a control point), without copies of the curve
    if (!geometry_.polynomial.derivative_at(0.0, 3)) return fail(Error::NotFinite);
    return ok();
  }

  /// NotFinite if the derivatives of orders 1..3 of the rational curve might overflow double.
  /// r = A / w with A = Σ w_i b_i B_i (relative to b_0): by the quotient rule and the hodograph
  /// bounds, |r^(k)| <= c_k ρ^k M and every intermediate term is below c_k w_max ρ^(k-1) M, where
  /// ρ = max w / min w, M = max |b_i - b_0| and c_3 < 1e11 for degree <= 7. Requiring
  /// 1e12 ρ³ M max(1, w_max) to be finite keeps them all finite; it refuses only weight ratios or
  /// sizes far outside any machine (a weight ratio of 1e6 on a 1e5 mm curve passes easily).
  [[nodiscard]] Result<void> check_rational_derivatives() const noexcept {
    double w_min = geometry_.rational.weight(0);
    double w_max = w_min;
    double extent = 0;
    const auto pts = geometry_.rational.control_points();
    for (std::size_t i = 0; i < pts.size(); ++i) {
      w_min = std::fmin(w_min, geometry_.rational.weight(i));
      w_max = std::fmax(w_max, geometry_.rational.weight(i));
      for (std::size_t axis = 0; axis < motion_axes; ++axis) extent = std::fmax(extent, std::fabs(pts[i][axis] - pts[0][axis]));
    }
    const double ratio = w_max / w_min;
    const double bound = 1e12 * ratio * ratio * ratio * extent * std::fmax(1.0, w_max);
    if (!std::isfinite(bound)) return fail(Error::NotFinite);
    return ok();
  }

  [[nodiscard]] Result<void> set_bezier(std::span<const MachinePoint> control) noexcept {
    if (control.size() < 2) return fail(Error::TooFewPoints, control.size());
    kind_ = SegmentKind::Bezier;
    std::construct_at(&geometry_.polynomial);
    CURVESTEP_CHECK(Polynomial::create_into(geometry_.polynomial, control));
    if (is_point()) return fail(Error::DegenerateCurve);
    return check_derivatives();
  }

  [[nodiscard]] Result<void> set_rational_bezier(std::span<const MachinePoint> control, std::span<const double> weights) noexcept {
    if (control.size() < 2) return fail(Error::TooFewPoints, control.size());
    kind_ = SegmentKind::RationalBezier;
    std::construct_at(&geometry_.rational);  // the union's active member follows the kind
    CURVESTEP_CHECK(Rational::create_into(geometry_.rational, control, weights));
    if (is_point()) return fail(Error::DegenerateCurve);
    return check_rational_derivatives();
  }

  [[nodiscard]] Result<void> set_compact(const CompactSegment& c) noexcept {
    kind_ = c.kind;
    rapid_ = c.rapid;
    feed_ = c.feed_mm_per_s;
    const auto load = [&c](std::size_t first) {
      return MachinePoint{{c.values[first], c.values[first + 1], c.values[first + 2]}};
    };
    if (c.kind == SegmentKind::Arc) {
      geometry_.arc = ArcData{load(0), load(3), load(6), c.values[9], c.values[10], c.values[11], c.values[12]};
      return ok();
    }
    if (c.degree > max_degree) return fail(Error::DegreeAboveCapacity, c.degree);
    const std::size_t count = static_cast<std::size_t>(c.degree) + 1;
    std::array<MachinePoint, capacity> points{};
    for (std::size_t i = 0; i < count; ++i) points[i] = load(3 * i);
    const std::span<const MachinePoint> control(points.data(), count);
    if (c.kind == SegmentKind::RationalBezier) {
      std::construct_at(&geometry_.rational);
      return Rational::create_into(geometry_.rational, control, std::span<const double>(c.values.data() + 3 * capacity, count));
    }
    std::construct_at(&geometry_.polynomial);
    return Polynomial::create_into(geometry_.polynomial, control);
  }

  [[nodiscard]] constexpr bool is_point() const noexcept {
    return is_point(kind_ == SegmentKind::RationalBezier ? geometry_.rational.control_points() : geometry_.polynomial.control_points());
  }
  [[nodiscard]] static constexpr bool is_point(std::span<const MachinePoint> pts) noexcept {
    for (const auto& p : pts) {
      if (!(p == pts[0])) return false;
    }
    return true;
  }

  static_assert(CompactSegment::value_count == 4 * capacity, "compact(): 3 coordinates and a weight per control point");

  /// What an arc needs (SegmentKind::Arc).
  struct ArcData {
    MachinePoint start{}, end{}, center{};  ///< centre z = start z
    double radius = 0;                      ///< start radius
    double sweep = 0;                       ///< signed sweep angle (rad)
    double dz = 0;                          ///< height change
    double end_radius_scale = 1;            ///< end radius / start radius
  };

  static constexpr Polynomial no_polynomial{};  ///< what polynomial() returns for other kinds
  static constexpr Rational no_rational{};      ///< what rational() returns for other kinds
  static constexpr MachinePoint no_point{};     ///< what arc_center() returns for other kinds

  SegmentKind kind_ = SegmentKind::Line;
  bool rapid_ = false;
  double feed_ = 0;
  // One kind's geometry at a time (the active member follows kind_: Line and Bezier polynomial,
  // RationalBezier rational, Arc arc), which keeps a PathSegment at 472 bytes instead of 776 on
  // Cortex-M (every copy on a microcontroller's stack counts). Each member is trivially copyable;
  // a make_* function or expand() starts the member's lifetime for the kind it sets (an arc by
  // assigning it whole, the Bézier kinds by std::construct_at before create_into fills them).
  union Geometry {
    constexpr Geometry() noexcept : polynomial{} {}
    Polynomial polynomial;
    Rational rational;
    ArcData arc;
  } geometry_{};
};

}  // namespace curvestep
