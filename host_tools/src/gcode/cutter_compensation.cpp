// SPDX-License-Identifier: MIT
// Cutter radius compensation in XY: offsets, corners, entry and exit moves (cutter_compensation.hpp).
#include "cutter_compensation.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <curvestep/host/csv.hpp>

namespace curvestep::host {
namespace {

constexpr double two_pi = 6.283185307179586;
/// Joints whose tangents differ by less than this (sine of the angle) are tangent: no corner.
constexpr double tangent_tolerance = 1e-9;
/// Lengths below this are one point, mm (far below the 2^-16 mm grid's effect on a corner).
constexpr double length_tolerance_mm = 1e-6;
/// A corner gap or an arc shorter than this is joined directly / emitted as a line, mm.
constexpr double tiny_mm = 1e-4;
/// An inside corner turning to within this of a reversal, radians, whose offsets do not meet is
/// gone around like an outside corner (LinuxCNC's TOLERANCE_CONCAVE_CORNER).
constexpr double reversal_tolerance_rad = 0.05;
/// An entry arc whose tool stands within this (cosine) of the offset end's tangent has no centre
/// (LinuxCNC's TOLERANCE_EQUAL on the same cosine).
constexpr double entry_arc_cos_tolerance = 1e-6;

struct P2 {
  double x = 0, y = 0;
};
P2 operator+(P2 a, P2 b) { return {a.x + b.x, a.y + b.y}; }
P2 operator-(P2 a, P2 b) { return {a.x - b.x, a.y - b.y}; }
P2 operator*(P2 a, double k) { return {a.x * k, a.y * k}; }
double dot(P2 a, P2 b) { return a.x * b.x + a.y * b.y; }
double cross(P2 a, P2 b) { return a.x * b.y - a.y * b.x; }
double length(P2 a) { return std::hypot(a.x, a.y); }
P2 perp(P2 a) { return {-a.y, a.x}; }  ///< turned a quarter counter-clockwise
P2 unit(P2 a) { return a * (1.0 / length(a)); }
P2 xy(const MachinePoint& p) { return {p[0], p[1]}; }
void set_xy(MachinePoint& p, P2 v) {
  p[0] = v.x;
  p[1] = v.y;
}
double turn(ArcDirection d) { return d == ArcDirection::CounterClockwise ? 1.0 : -1.0; }

/// The direction of travel at `at`, a point of the move.
P2 tangent(const PlanarMove& m, const MachinePoint& at) {
  if (!m.arc) return unit(xy(m.end) - xy(m.start));
  return unit(perp(xy(at) - xy(m.center))) * turn(m.direction);
}

/// The angle turned from `from` to `to` about `center` in `direction`, in [0, 2π).
double angle_between(P2 from, P2 to, P2 center, ArcDirection direction) {
  const double a0 = std::atan2(from.y - center.y, from.x - center.x);
  const double a1 = std::atan2(to.y - center.y, to.x - center.x);
  const double a = std::fmod(turn(direction) * (a1 - a0) + 2 * two_pi, two_pi);
  return a >= two_pi ? 0.0 : a;
}

/// An arc's angle as the importer reads it: end = start is a full turn; plus the extra turns.
double sweep_of(const PlanarMove& m) {
  const P2 s = xy(m.start);
  const P2 e = xy(m.end);
  double sweep = s.x == e.x && s.y == e.y ? two_pi : angle_between(s, e, xy(m.center), m.direction);
  if (sweep == 0) sweep = two_pi;
  return sweep + two_pi * static_cast<double>(m.full_turns);
}

std::string mm(double v) { return format_number(v) + " mm"; }

/// The points where the offset paths of `a` (near its end) and `b` (near its start) cross.
std::vector<P2> crossings(const PlanarMove& a, const PlanarMove& b, P2 ta, P2 tb) {
  std::vector<P2> out;
  const auto line_circle = [&out](P2 p, P2 t, P2 c, double r) {
    const P2 d = p - c;
    const double half_b = dot(t, d);
    const double disc = half_b * half_b - (dot(d, d) - r * r);
    if (disc < 0) return;
    const double root = std::sqrt(disc);
    out.push_back(p + t * (-half_b - root));
    out.push_back(p + t * (-half_b + root));
  };
  if (!a.arc && !b.arc) {
    const double c = cross(ta, tb);
    if (std::fabs(c) < tangent_tolerance) return out;
    const P2 p = xy(a.end);
    out.push_back(p + ta * (cross(xy(b.start) - p, tb) / c));
  } else if (!a.arc) {
    line_circle(xy(a.end), ta, xy(b.center), length(xy(b.start) - xy(b.center)));
  } else if (!b.arc) {
    line_circle(xy(b.start), tb, xy(a.center), length(xy(a.end) - xy(a.center)));
  } else {
    const P2 c0 = xy(a.center);
    const P2 c1 = xy(b.center);
    const double r0 = length(xy(a.end) - c0);
    const double r1 = length(xy(b.start) - c1);
    const double d = length(c1 - c0);
    if (d < length_tolerance_mm || d > r0 + r1 || d < std::fabs(r0 - r1)) return out;
    const double along = (d * d + r0 * r0 - r1 * r1) / (2 * d);
    const double h = std::sqrt(std::max(0.0, r0 * r0 - along * along));
    const P2 u = unit(c1 - c0);
    const P2 m = c0 + u * along;
    out.push_back(m + perp(u) * h);
    out.push_back(m - perp(u) * h);
  }
  return out;
}

/// How far round `arc` from its start its point `q` lies (q within 1 µm before the start counts as
/// the start), and that 1 µm as an angle.
struct AngleOn {
  double at = 0, eps = 0;
};
AngleOn angle_on(const PlanarMove& arc, P2 q) {
  const P2 c = xy(arc.center);
  const double eps = length_tolerance_mm / length(q - c);
  const double at = angle_between(xy(arc.start), q, c, arc.direction);
  return {at > two_pi - eps ? 0.0 : at, eps};
}

/// Why the crossing `q` does not lie on both offset paths (nullopt: it does): on `a` (tangent `ta`
/// at its end) from its start, and on `next` (tangent `tb` at its start) before its end. The arcs'
/// sweeps (in: whole; out: cut back to q) are `a_sweep` and `next_sweep`.
std::optional<std::string> crossing_problem(const PlanarMove& a, double& a_sweep, const PlanarMove& next, double& next_sweep, P2 q, P2 ta,
                                            P2 tb, double radius) {
  // Within the previous move's offset (from its current start to its end)?
  if (!a.arc) {
    if (dot(q - xy(a.start), ta) < -length_tolerance_mm) {
      return "gouging: the previous move is too short for the tool radius " + mm(radius) + " to reach the inside corner with this move";
    }
  } else {
    const auto [at, eps] = angle_on(a, q);
    if (at > a_sweep + eps) {
      return "gouging: the previous arc is too short for the tool radius " + mm(radius) + " to reach the inside corner with this move";
    }
    a_sweep = at + two_pi * std::floor((a_sweep + eps - at) / two_pi);
  }
  // Within this move's offset (from its start to its end)?
  if (!next.arc) {
    if (dot(q - xy(next.end), tb) > length_tolerance_mm) {
      return "gouging: this move is too short for the tool radius " + mm(radius) + " to follow the inside corner at its start";
    }
  } else {
    const auto [at, eps] = angle_on(next, q);
    if (at > next_sweep + eps) {
      return "gouging: this arc is too short for the tool radius " + mm(radius) + " to follow the inside corner at its start";
    }
    next_sweep = std::max(0.0, next_sweep - at);
  }
  return std::nullopt;
}


}  // namespace

void CutterCompensation::start(Side side, double radius_mm, const MachinePoint& tool) {
  state_ = State::Entry;
  side_ = side == Side::Left ? 1.0 : -1.0;
  radius_ = radius_mm;
  entry_pending_ = false;
  pending_.reset();
  tool_ = tool;
}

CutterCompensation::Offset CutterCompensation::offset(const PlanarMove& programmed) const {
  Offset o{programmed, programmed, 0};
  if (!programmed.arc) {
    const P2 shift = perp(tangent(programmed, programmed.start)) * (side_ * radius_);
    set_xy(o.path.start, xy(programmed.start) + shift);
    set_xy(o.path.end, xy(programmed.end) + shift);
    return o;
  }
  // Left of a counter-clockwise arc is towards its centre: the radius shrinks by side·turn·r.
  const P2 c = xy(programmed.center);
  const double change = -side_ * turn(programmed.direction) * radius_;
  for (MachinePoint* p : {&o.path.start, &o.path.end}) {
    const double r = length(xy(*p) - c);
    if (!(r + change > length_tolerance_mm)) {
      throw CompensationError("gouging: the concave arc's radius " + mm(r) + " is not larger than the tool radius " + mm(radius_) +
                              " (the tool does not fit inside it)");
    }
    set_xy(*p, c + (xy(*p) - c) * ((r + change) / r));
  }
  o.sweep = sweep_of(programmed);
  return o;
}

CutterCompensation::Offset CutterCompensation::entry_arc(const PlanarMove& programmed) const {
  Offset o = offset(programmed);  // its end: the programmed end's offset, square to the arc there
  const P2 tool = xy(tool_);
  const P2 end = xy(o.path.end);
  // The centre lies on the line from the offset end towards the programmed centre (so the arc ends
  // tangent to the offset arc) and is as far from the tool as from that end.
  const P2 toward = unit(xy(programmed.center) - end);
  const P2 chord = tool - end;
  const double along = dot(chord, toward);
  if (!(std::fabs(along) > entry_arc_cos_tolerance * length(chord))) {
    throw CompensationError("the entry arc cannot reach its offset end: the tool stands on the tangent to the offset arc at its "
                            "end (no arc from the tool ends square to the programmed end); start the compensation elsewhere");
  }
  set_xy(o.path.start, tool);
  set_xy(o.path.center, end + toward * (dot(chord, chord) / (2 * along)));
  o.sweep = angle_between(tool, end, xy(o.path.center), programmed.direction) + two_pi * static_cast<double>(programmed.full_turns);
  return o;
}

PlanarMove CutterCompensation::corner_arc(const Offset& next) const {
  // An arc of the tool radius about the programmed corner, turning the way the path turns
  // (clockwise with the tool on the left).
  PlanarMove arc;
  arc.arc = true;
  arc.rapid = next.programmed.rapid;
  arc.start = next.path.start;
  set_xy(arc.start, xy(pending_->path.end));
  arc.end = next.path.start;
  arc.center = next.path.start;
  set_xy(arc.center, xy(pending_->programmed.end));
  arc.direction = side_ > 0 ? ArcDirection::Clockwise : ArcDirection::CounterClockwise;
  arc.tag = next.programmed.tag;
  return arc;
}

std::optional<PlanarMove> CutterCompensation::corner(Offset& next) {
  const Offset& a = *pending_;
  const P2 ta = tangent(a.programmed, a.programmed.end);
  const P2 tb = tangent(next.programmed, next.programmed.start);
  const double turning = cross(ta, tb);
  const double gap = length(xy(next.path.start) - xy(a.path.end));
  if ((std::fabs(turning) < tangent_tolerance && dot(ta, tb) > 0) || gap < tiny_mm) {
    set_xy(next.path.start, xy(a.path.end));  // tangent: the offsets meet
    return std::nullopt;
  }
  const bool outside = side_ * turning < 0 || std::fabs(turning) < tangent_tolerance;  // a reversal goes around
  const bool near_reversal = dot(ta, tb) < -std::cos(reversal_tolerance_rad);
  // LinuxCNC's "h" shape: a near-reversal onto an arc that curves away from the tool (or from such an
  // arc onto a line) is cut at the offsets' crossing whichever way it turns.
  const bool h_shape = near_reversal && (next.programmed.arc ? tool_outside(next.programmed) : a.programmed.arc && tool_outside(a.programmed));
  if (!outside || h_shape) {
    const std::optional<std::string> refused = cut_inside_corner(next);
    if (!refused) return std::nullopt;
    // LinuxCNC counts a corner within TOLERANCE_CONCAVE_CORNER of a reversal as convex and goes
    // around it; so does this, where the offsets do not meet.
    if (!outside && !near_reversal) throw CompensationError(*refused);
  }
  return corner_arc(next);
}

bool CutterCompensation::tool_outside(const PlanarMove& arc) const { return side_ * turn(arc.direction) < 0; }

std::optional<std::string> CutterCompensation::cut_inside_corner(Offset& next) {
  Offset& a = *pending_;
  const P2 corner_point = xy(a.programmed.end);
  const P2 ta = tangent(a.programmed, a.programmed.end);
  const P2 tb = tangent(next.programmed, next.programmed.start);
  const std::vector<P2> found = crossings(a.path, next.path, ta, tb);
  if (found.empty()) {
    return "gouging: the offsets of the previous move and this one do not meet at their inside corner (a move too short or too "
           "curved for the tool radius " + mm(radius_) + ")";
  }
  // The crossing nearest the corner that lies on both offset moves.
  std::vector<P2> candidates = found;
  std::sort(candidates.begin(), candidates.end(),
            [&corner_point](P2 p, P2 q) { return length(p - corner_point) < length(q - corner_point); });
  std::optional<std::string> nearest_problem;
  for (const P2& q : candidates) {
    double a_sweep = a.sweep;
    double next_sweep = next.sweep;
    std::optional<std::string> problem = crossing_problem(a.path, a_sweep, next.path, next_sweep, q, ta, tb, radius_);
    if (!problem) {
      a.sweep = a_sweep;
      next.sweep = next_sweep;
      set_xy(a.path.end, q);
      set_xy(next.path.start, q);
      return std::nullopt;
    }
    if (!nearest_problem) nearest_problem = std::move(problem);
  }
  return nearest_problem;
}

/// The offset's path as a move: whole turns from its sweep; an arc too short to be one is a line.
static PlanarMove finished_path(const PlanarMove& path, double sweep) {
  PlanarMove out = path;
  if (!out.arc) return out;
  const double radius = std::hypot(out.start[0] - out.center[0], out.start[1] - out.center[1]);
  const bool closed = std::hypot(out.end[0] - out.start[0], out.end[1] - out.start[1]) < length_tolerance_mm;
  if (sweep * radius < tiny_mm) {
    out.arc = false;
    return out;
  }
  if (closed) {
    out.end[0] = out.start[0];
    out.end[1] = out.start[1];
    const double turns = std::round(sweep / two_pi);
    out.full_turns = static_cast<std::uint32_t>(std::max(1.0, turns) - 1);
  } else {
    out.full_turns = static_cast<std::uint32_t>(std::floor(sweep / two_pi));
  }
  return out;
}

void CutterCompensation::finish(CompensatedMoves& out) {
  out.finished = finished_path(pending_->path, pending_->sweep);
  tool_ = out.finished->end;
  pending_.reset();
}

CompensatedMoves CutterCompensation::add(const PlanarMove& programmed) {
  CompensatedMoves out;
  switch (state_) {
    case State::Off: out.finished = programmed; return out;
    case State::Exit: {
      if (programmed.arc) {
        throw CompensationError("the exit move (the first move after G40) must be a straight line (G0/G1): it goes from the "
                                "compensated point to the programmed end");
      }
      PlanarMove exit = programmed;
      set_xy(exit.start, xy(tool_));
      out.finished = exit;
      tool_ = exit.end;
      state_ = State::Off;
      return out;
    }
    case State::Entry: {
      const double distance = length(xy(programmed.end) - xy(tool_));
      if (!(distance > radius_)) {
        throw CompensationError("the entry move (the first move after G41/G42) must end farther than the tool radius " + mm(radius_) +
                                " from the tool: it ends " + mm(distance) + " away");
      }
      if (programmed.arc) {
        pending_ = entry_arc(programmed);
        state_ = State::On;
        return out;
      }
      Offset entry{programmed, programmed, 0};
      set_xy(entry.path.start, xy(tool_));
      pending_ = entry;
      entry_pending_ = true;
      state_ = State::On;
      return out;
    }
    case State::On: break;
  }
  Offset next = offset(programmed);
  if (entry_pending_) {
    // The entry move ends where the first compensated move begins.
    set_xy(pending_->path.end, xy(next.path.start));
    entry_pending_ = false;
  } else {
    out.corner = corner(next);
  }
  finish(out);
  if (out.corner) tool_ = out.corner->end;
  pending_ = next;
  return out;
}

std::optional<PlanarMove> CutterCompensation::stop() {
  if (state_ == State::Entry) {
    state_ = State::Exit;  // the tool stays where it is; the exit move starts there
    return std::nullopt;
  }
  if (state_ != State::On) return std::nullopt;
  state_ = State::Exit;
  if (!pending_) return std::nullopt;
  if (entry_pending_) {
    // An entry move with nothing after it: it ends square to itself.
    const Offset self = offset(pending_->programmed);
    set_xy(pending_->path.end, xy(self.path.end));
    entry_pending_ = false;
  }
  CompensatedMoves out;
  finish(out);
  return out.finished;
}

}  // namespace curvestep::host
