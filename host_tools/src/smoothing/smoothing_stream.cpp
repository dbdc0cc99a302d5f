// SPDX-License-Identifier: MIT
// Path smoothing one segment at a time (smoothing_stream.hpp): line runs fitted, then corners blended.
#include <curvestep/host/smoothing/smoothing_stream.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <utility>

#include <curvestep/core/motion/path_length_table.hpp>
#include <curvestep/core/motion/segment_plan.hpp>
#include <curvestep/core/motion/velocity_profile.hpp>
#include <curvestep/host/smoothing/line_run_fit.hpp>
#include <curvestep/host/smoothing/segment_geometry.hpp>

namespace curvestep::host::smoothing {
namespace {

constexpr double pi = 3.14159265358979323846;
/// A joint counts as a corner above this deflection (rad); below it, a curvature jump above
/// `curvature_jump_per_mm` still makes it one.
constexpr double corner_deflection_rad = 1e-7;
constexpr double curvature_jump_per_mm = 1e-9;
/// Deflections above this are reversals: kept, the planner stops there.
constexpr double reversal_deflection_deg = 179;

double deflection_cos(const PathSegment& a, const PathSegment& b) {
  return dot(local_frame(a, 1.0).tangent, local_frame(b, 0.0).tangent);
}

/// The machine's speed changes as the planner times them (velocity_profile.hpp): S-curve, or the
/// trapezoid without a jerk limit (smoothing_jerk_mm_per_s3).
ProfileLimits speed_changes(const SmoothingOptions& options) {
  const double jerk = smoothing_jerk_mm_per_s3(options.machine);
  return ProfileLimits{0, options.machine.a_max_mm_per_s2, jerk, jerk < 1e11};
}

/// Time lost against running on at `cruise` when the speed changes to `low` (and back, or from it):
/// the change takes t = speed_change_time(cruise − low) at the mean speed (cruise + low)/2 (S-curve
/// and trapezoid changes are symmetric), so it loses t (cruise − low) / (2 cruise).
double change_loss(double cruise, double low, const SmoothingOptions& options) {
  if (!(cruise > low)) return 0;
  return speed_change_time(cruise - low, speed_changes(options)) * (cruise - low) / (2 * cruise);
}

/// The planner's view of a segment (its caps and end geometry), as the controller will plan it.
std::optional<SegmentPlan> planned(const PathSegment& segment, const MachineLimits& machine) {
  const auto table = PathLengthTable<64>::build(segment);
  if (!table) return std::nullopt;
  auto plan = plan_segment(segment, table.value(), machine);
  if (!plan) return std::nullopt;
  return plan.value();
}

/// planned(item.segment), made once per item (Item::plan).
const std::optional<SegmentPlan>& planned(SmoothingStream::Item& item, const MachineLimits& machine) {
  if (!item.plan) item.plan = planned(item.segment, machine);
  return *item.plan;
}

/// What write_item writes of `segment` between the cut parameters u0 < u1 and the cut points: the
/// whole segment when it is not cut, else its piece (piece_between), or where it cannot be cut a
/// straight connection of the cut points at its feed (a rapid stays a rapid); nothing between equal
/// points.
std::optional<PathSegment> written_piece(const PathSegment& segment, double u0, double u1, const MachinePoint& start,
                                         const MachinePoint& end) {
  if (u0 == 0 && u1 == 1) return segment;
  if (!(u0 < u1) || start == end) return std::nullopt;
  if (auto piece = piece_between(segment, u0, u1, start, end)) return piece;
  auto line = PathSegment::make_line(start, end);
  if (!line) return std::nullopt;
  line.value().set_feed_mm_per_s(segment.feed_mm_per_s());
  line.value().set_rapid(segment.rapid());
  return line.value();
}

/// The planner's corner caps (junction_speed_caps_apart: the segments' own caps are judged apart)
/// where the blend meets what it leaves of its neighbours, as they will be written (piece_between: ends on the Q16.16 grid), and where the blend before `a` meets
/// `a`'s remnant. The blend is G2 with its neighbours, but a short remnant of an arc or a line made
/// between grid points turns its tangent by up to (grid step / its length): 10⁻⁴ rad on a 0.1 mm
/// remnant, which the planner passes at about 44 mm/s (the velocity jump within ½ j Δt² per tick,
/// junction_speed). Blends at both ends of each arc of a spiral of 5 mm arcs left 0.1 mm between
/// them, and the job ran 29 % slower than as programmed.
double blend_joint_speed(const CornerBlend& blend, const SegmentPlan& blend_plan, const SmoothingStream::Item& a,
                         const SmoothingStream::Item& b, const MachineLimits& machine) {
  double speed = std::numeric_limits<double>::infinity();
  const auto rest_of_a = written_piece(a.segment, a.start_u, blend.incoming_u, a.start_point, blend.curve.start());
  if (rest_of_a) {
    const auto plan = planned(*rest_of_a, machine);
    if (plan) {
      speed = std::fmin(speed, junction_speed_caps_apart(*plan, blend_plan, machine));
      if (a.start_blend_plan) speed = std::fmin(speed, junction_speed_caps_apart(*a.start_blend_plan, *plan, machine));
    }
  } else if (a.start_blend_plan) {  // nothing of `a` is written: the two blends meet
    speed = std::fmin(speed, junction_speed_caps_apart(*a.start_blend_plan, blend_plan, machine));
  }
  const auto rest_of_b = written_piece(b.segment, blend.outgoing_u, b.end_u, blend.curve.end(), b.end_point);
  const auto plan_b = rest_of_b ? planned(*rest_of_b, machine) : std::nullopt;
  if (plan_b) speed = std::fmin(speed, junction_speed_caps_apart(blend_plan, *plan_b, machine));
  return speed;
}

/// Whether the planner passes the blend faster than the corner it replaces. Each neighbour runs at
/// up to its speed cap (the planner's, at most what half its length reaches from rest), V_a and V_b.
/// Kept, the corner is passed at the planner's junction speed v_c (near rest at a sharp corner):
/// the loss is the speed change from V_a to v_c and back to V_b. Blended, the speed changes to the
/// blend's entry speed w (its cap, at most V_a and V_b), and the blend runs its length L instead of
/// the cut lengths d_a, d_b at V_a, V_b: at w, or faster where it is gentler than its neighbours (up
/// to what half its length reaches from w, and back). At sharp corners under a jerk limit a
/// tolerance-sized blend is so tight that it is crawled through for longer than a stop takes; at
/// speed even a shallow corner's long, gentle blend can cost more than the stop (5° between 20 mm G0
/// moves at 150 mm/s); and a joint the planner passes at speed (a deflection of the Q16.16 grid)
/// gains nothing from a blend unless the blend is faster than the curves it cuts.
std::optional<SegmentPlan> blend_pays(const CornerBlend& blend, SmoothingStream::Item& a, SmoothingStream::Item& b,
                                      const SmoothingOptions& options) {
  const MachineLimits& machine = options.machine;
  const auto& plan_a = planned(a, machine);
  const auto& plan_b = planned(b, machine);
  const auto plan_blend = planned(blend.curve, machine);
  if (!plan_a || !plan_b || !plan_blend) return std::nullopt;
  const ProfileLimits changes = speed_changes(options);
  const double cruise_a = reachable_speed(0, 0.5 * a.length_mm, plan_a->limits.speed_cap_mm_per_s, changes);
  const double cruise_b = reachable_speed(0, 0.5 * b.length_mm, plan_b->limits.speed_cap_mm_per_s, changes);
  const double junction = junction_speed(*plan_a, *plan_b, machine);
  const double corner = std::fmin(std::fmin(cruise_a, cruise_b), junction);
  const double blend_cap = plan_blend->limits.speed_cap_mm_per_s;
  // A joint the planner passes at least as fast as the blend's cap, between neighbours that allow
  // as much, loses nothing as programmed: the blend could only lower the ceiling there (a spiral of
  // arcs, whose joints are nearly tangent: the from-rest estimate below does not see the speed the
  // machine carries through them). Nor is a blend made that lifts the ceiling by less than 10 %:
  // its gain is below what the estimate can tell (a helix cut into 0.8 mm pieces, blended at each
  // joint for a gain of under 4 ms each, ran 8 % slower than as programmed).
  const double kept_ceiling = std::fmin(junction, std::fmin(plan_a->limits.speed_cap_mm_per_s, plan_b->limits.speed_cap_mm_per_s));
  if (kept_ceiling >= 0.9 * blend_cap) return std::nullopt;
  const double blend_ceiling = std::fmin(blend_cap, blend_joint_speed(blend, *plan_blend, a, b, machine));
  if (kept_ceiling >= 0.9 * blend_ceiling) return std::nullopt;
  const double entry = std::fmin(blend_ceiling, std::fmin(cruise_a, cruise_b));
  if (!(entry > 0) || !(cruise_a > 0) || !(cruise_b > 0)) return std::nullopt;
  const double length = plan_blend->length_mm;
  const double top = reachable_speed(entry, 0.5 * length, blend_cap, changes);
  const double kept = change_loss(cruise_a, corner, options) + change_loss(cruise_b, corner, options);
  const double blended = change_loss(cruise_a, entry, options) + change_loss(cruise_b, entry, options) + length / (0.5 * (entry + top)) -
                         blend.incoming_cut_mm / cruise_a - blend.outgoing_cut_mm / cruise_b;
  if (!(blended < kept)) return std::nullopt;
  return plan_blend;
}

bool fittable_line(const PathSegment& s, const SmoothingOptions& options) {
  return s.kind() == SegmentKind::Line && !s.rapid() && norm(s.end() - s.start()) <= options.fit_max_line_mm;
}

bool smoothing_on(const SmoothingOptions& options) { return options.tolerance_mm > 0; }

}  // namespace

SmoothingStream::SmoothingStream(const SmoothingOptions& options, SegmentHandler downstream)
    : options_(options), cos_max_run_deflection_(std::cos(options.fit_max_deflection_deg * pi / 180)), downstream_(std::move(downstream)) {
  figures_.tolerance_mm = options.tolerance_mm;
}

void SmoothingStream::event(JobEvent event) {
  if (smoothing_on(options_)) {
    if (event.before_segment < pushed_) throw std::logic_error("SmoothingStream: an event came after the segment it precedes");
    events_at_segment_.emplace(event.before_segment, out_.events.size());
  } else {
    event_at(event.before_segment);  // the job as programmed: the numbers stay
  }
  out_.events.push_back(std::move(event));
}

double SmoothingStream::joint_tolerance(const PathSegment& segment, std::optional<double> blend_tolerance_mm) const {
  if (events_at_segment_.count(pushed_) != 0) return 0;
  // A joint between a rapid and a feed move stays as programmed (where the tool enters or leaves
  // the work, and where a laser switches); two rapids are blended like two feed moves (G64 in
  // LinuxCNC blends G0 corners too).
  if (previous_->rapid() != segment.rapid()) return 0;
  double tolerance = options_.tolerance_mm;
  if (blend_tolerance_mm) {
    if (*blend_tolerance_mm < 0) return 0;
    if (*blend_tolerance_mm > 0) tolerance = *blend_tolerance_mm;
  }
  return tolerance;
}

void SmoothingStream::segment(const PathSegment& segment, std::size_t source, std::optional<double> blend_tolerance_mm) {
  if (!smoothing_on(options_)) {  // the job as programmed
    emit(segment, source);
    if (blend_tolerance_mm && !downstream_) out_.blend_tolerance_mm.push_back(*blend_tolerance_mm);
    if (blend_tolerance_mm) figures_.unapplied_tolerance_mm = std::fmax(figures_.unapplied_tolerance_mm, *blend_tolerance_mm);
    ++pushed_;
    return;
  }
  Pending pending;
  if (!fittable_line(segment, options_)) pending.other = std::make_unique<PathSegment>(segment);
  pending.start = segment.start();
  pending.end = segment.end();
  pending.feed_mm_per_s = segment.feed_mm_per_s();
  pending.source = source;
  pending.index = pushed_;
  if (previous_) {
    pending.joint_tolerance_mm = joint_tolerance(segment, blend_tolerance_mm);
    pending.deflection_cos = deflection_cos(*previous_, segment);
  }
  pending_.push_back(std::move(pending));
  previous_ = segment;
  ++pushed_;
  make_items(false);
}

// 1. Runs of short lines -> splines. A run [0, end) of the pending segments is decided once a
// segment that cannot join it arrived (or the job ended).
void SmoothingStream::make_items(bool at_end) {
  while (!pending_.empty()) {
    std::size_t end = 1;
    if (options_.fit_line_runs && pending_[0].fittable()) {
      end = std::max<std::size_t>(end, verified_run_);
      while (end < pending_.size() && end < options_.fit_max_run_lines && pending_[end].fittable() &&
             pending_[end].joint_tolerance_mm > 0 && pending_[end].joint_tolerance_mm == pending_[1].joint_tolerance_mm &&
             pending_[end].feed_mm_per_s == pending_[0].feed_mm_per_s &&
             (pending_[end].deflection_cos >= cos_max_run_deflection_ || jog_below_tolerance(end))) {
        ++end;
      }
      verified_run_ = end;
      if (end == pending_.size() && !at_end) return;  // the run may go on
    } else if (pending_.size() < 2 && !at_end) {
      return;  // the joint after it is not known yet
    }
    std::optional<LineRunFit> fit;
    std::size_t consumed = 1;
    if (end >= 3) {
      // The run whole, unless it is what is left of one that failed whole (a noisy run fitted
      // whole again after each line taken would cost a fit of the run per line).
      std::size_t longest_prefix = end;
      if (end > failed_run_lines_) {
        fit = fit_lines(end);
        if (fit) {
          consumed = end;
        } else {
          failed_run_lines_ = end;
          longest_prefix = end - 1;
        }
      }
      if (!fit) {
        auto prefix = fit_longest_prefix(longest_prefix);
        if (prefix) std::tie(fit, consumed) = std::move(*prefix);
      }
    }
    const bool next_known = consumed < pending_.size();  // false: the job's last segment ends the run
    for (std::size_t i = 0; i < consumed; ++i) {
      const auto [first, last] = events_at_segment_.equal_range(pending_[i].index);
      for (auto e = first; e != last; ++e) events_at_item_.emplace(items_made_, e->second);
      events_at_segment_.erase(first, last);
    }
    if (fit) {
      for (std::size_t p = 0; p < fit->pieces.size(); ++p) {
        add_item(fit->pieces[p], pending_[0].source, true);
        items_.back().run_inside_next = p + 1 < fit->pieces.size();
      }
      ++figures_.runs_fitted;
      figures_.lines_fitted += consumed;
      figures_.fitted_pieces += fit->pieces.size();
      note_deviation(fit->deviation_mm, pending_[1].joint_tolerance_mm);
      if (next_known) items_.back().joint_tolerance_mm = pending_[consumed].joint_tolerance_mm;
    } else {
      add_item(pending_[0].segment(), pending_[0].source, false);
      if (pending_.size() > 1) items_.back().joint_tolerance_mm = pending_[1].joint_tolerance_mm;
    }
    pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(consumed));
    // What is left of the run is still one run (its feed and joint tolerance are the run's), and
    // still one that failed whole, if it did: it is not scanned or fitted whole again.
    verified_run_ = verified_run_ > consumed ? verified_run_ - consumed : 0;
    failed_run_lines_ = failed_run_lines_ > consumed ? failed_run_lines_ - consumed : 0;
    write_items(false);
  }
}

bool SmoothingStream::jog_below_tolerance(std::size_t k) const {
  // The corner at pending_[k].start, between lines k - 1 and k: if one of them is at most a quarter
  // of the tolerance long, the path without that line's turn stays within it (a 1 um jog that CAM
  // rounding leaves). Longer lines are not jogs, even where their corner lies near the chord of its
  // neighbours: a raster's 0.01 mm lines into its 0.2 mm step-over make a turnaround that is faster
  // stopped than fitted.
  const double shorter = std::fmin(norm(pending_[k - 1].end - pending_[k - 1].start), norm(pending_[k].end - pending_[k].start));
  return shorter <= 0.25 * pending_[k].joint_tolerance_mm;
}

std::optional<LineRunFit> SmoothingStream::fit_lines(std::size_t count) const {
  std::vector<MachinePoint> vertices{pending_[0].start};
  vertices.reserve(count + 1);
  for (std::size_t i = 0; i < count; ++i) vertices.push_back(pending_[i].end);
  return fit_line_run(vertices, 0.5 * pending_[1].joint_tolerance_mm, pending_[0].feed_mm_per_s);
}

std::optional<std::pair<LineRunFit, std::size_t>> SmoothingStream::fit_longest_prefix(std::size_t longest) const {
  // Prefixes of 3, 6, 12 ... lines (up to `longest`) while they fit, then bisection between the
  // longest that fits and the shortest that does not: O(log n) fits of at most 2k lines for a prefix
  // of k lines taken.
  std::optional<LineRunFit> best;
  std::size_t fits = 0;            // longest prefix known to fit (0: none)
  std::size_t fails = longest + 1;  // shortest prefix known not to fit
  for (std::size_t count = 3; count <= longest; count = std::min(2 * count, longest)) {
    auto fit = fit_lines(count);
    if (!fit) {
      fails = count;
      break;
    }
    best = std::move(fit);
    fits = count;
    if (count == longest) break;
  }
  if (fits == 0) return std::nullopt;
  while (fails - fits > 1) {
    const std::size_t count = fits + (fails - fits) / 2;
    auto fit = fit_lines(count);
    if (fit) {
      best = std::move(fit);
      fits = count;
    } else {
      fails = count;
    }
  }
  return std::make_pair(std::move(*best), fits);
}

PathSegment SmoothingStream::Pending::segment() const {
  if (other) return *other;
  PathSegment line = PathSegment::make_line(start, end).value();  // it was made from these ends once
  line.set_feed_mm_per_s(feed_mm_per_s);
  return line;
}

void SmoothingStream::add_item(const PathSegment& segment, std::size_t source, bool fitted) {
  Item item;
  item.segment = segment;
  item.source = source;
  item.length_mm = length_between(segment, 0, 1);
  item.fitted = fitted;
  item.start_point = segment.start();
  item.end_point = segment.end();
  items_.push_back(std::move(item));
  ++items_made_;
}

void SmoothingStream::write_items(bool at_end) {
  while (items_.size() >= 2) {
    decide_corner(items_[0], items_[1]);
    write_item(items_[0], &items_[1]);
    items_.pop_front();
  }
  if (at_end && items_.size() == 1) {
    write_item(items_[0], nullptr);
    items_.pop_front();
  }
}

// 2. Corners -> blends.
void SmoothingStream::decide_corner(Item& a, Item& b) {
  front_blend_.reset();
  if (a.run_inside_next || !(a.joint_tolerance_mm > 0)) return;
  const double cos_theta = deflection_cos(a.segment, b.segment);
  const double deflection = std::acos(std::clamp(cos_theta, -1.0, 1.0));
  const double curvature_jump = norm(local_frame(a.segment, 1.0).curvature - local_frame(b.segment, 0.0).curvature);
  if (deflection <= corner_deflection_rad && curvature_jump <= curvature_jump_per_mm) return;
  ++figures_.corners;
  if (deflection * 180 / pi > reversal_deflection_deg) {
    ++figures_.corners_reversed;
    return;
  }
  if (!options_.blend_corners) return;
  if (!can_cut(a.segment) || !can_cut(b.segment)) {
    ++figures_.corners_unblendable;
    return;
  }
  CornerRequest request;
  request.incoming = &a.segment;
  request.incoming_length_mm = a.length_mm;
  request.incoming_available_mm = options_.blend_max_share * a.length_mm;
  request.outgoing = &b.segment;
  request.outgoing_length_mm = b.length_mm;
  request.outgoing_available_mm = options_.blend_max_share * b.length_mm;
  request.tolerance_mm = (a.fitted || b.fitted) ? 0.5 * a.joint_tolerance_mm : a.joint_tolerance_mm;
  request.a_max_mm_per_s2 = options_.machine.a_max_mm_per_s2;
  request.j_max_mm_per_s3 = smoothing_jerk_mm_per_s3(options_.machine);
  auto blend = blend_corner(request);
  if (!blend) {
    ++figures_.corners_unblendable;
    return;
  }
  // The blend takes up to half of each neighbour: it runs at the slower of their feeds, never
  // faster than either was programmed (a feed change is kept).
  const auto feed_of = [&](const PathSegment& s) { return s.feed_mm_per_s() > 0 ? s.feed_mm_per_s() : options_.machine.feed_mm_per_s; };
  blend->curve.set_feed_mm_per_s(std::fmin(feed_of(a.segment), feed_of(b.segment)));
  auto blend_plan = blend_pays(*blend, a, b, options_);
  if (!blend_plan) {
    ++figures_.corners_stopped;
    return;
  }
  b.start_blend_plan = std::move(blend_plan);
  a.end_u = blend->incoming_u;
  a.end_point = blend->curve.start();
  b.start_u = blend->outgoing_u;
  b.start_point = blend->curve.end();
  ++figures_.corners_blended;
  const double fitted_share = (a.fitted || b.fitted) ? 0.5 * a.joint_tolerance_mm : 0.0;
  note_deviation(blend->deviation_mm + fitted_share, a.joint_tolerance_mm);
  front_blend_ = std::move(blend);
}

void SmoothingStream::note_deviation(double deviation_mm, double tolerance_mm) {
  figures_.max_deviation_mm = std::fmax(figures_.max_deviation_mm, deviation_mm);
  figures_.largest_tolerance_mm = std::fmax(figures_.largest_tolerance_mm, tolerance_mm);
  figures_.max_deviation_share = std::fmax(figures_.max_deviation_share, deviation_mm / tolerance_mm);
}

// 3. The smoothed job: each item cut to what the blends left, then its blend.
void SmoothingStream::write_item(const Item& item, const Item* next) {
  const std::size_t number = items_made_ - items_.size();
  const auto [first, last] = events_at_item_.equal_range(number);
  for (auto e = first; e != last; ++e) {
    out_.events[e->second].before_segment = written_;
    event_at(written_);
  }
  events_at_item_.erase(first, last);
  if (const auto piece = written_piece(item.segment, item.start_u, item.end_u, item.start_point, item.end_point)) {
    emit(*piece, item.source);
  }
  if (next != nullptr && front_blend_) {
    emit(front_blend_->curve, next->source);
  }
}

void SmoothingStream::emit(const PathSegment& segment, std::size_t source) {
  if (unlabelled_joints_.erase(written_) != 0) event_labels_[written_] = source;
  last_source_ = source;
  ++written_;
  if (downstream_) {
    downstream_(segment, source);
    return;
  }
  out_.segments.push_back(segment);
  out_.source_index.push_back(source);
}

Job SmoothingStream::finish(Job rest, SmoothingReport* report) {
  figures_.segments_before = pushed_;
  if (smoothing_on(options_) && pushed_ > 0) {
    make_items(true);
    write_items(true);
    // Events after the last segment (or past the job's end) stay after it.
    for (const auto& [index, position] : events_at_segment_) out_.events[position].before_segment = written_;
    for (const auto& [item, position] : events_at_item_) out_.events[position].before_segment = written_;
    if (!events_at_segment_.empty() || !events_at_item_.empty()) event_at(written_);
    events_at_segment_.clear();
    events_at_item_.clear();
  }
  // Joints at or past the end: the label after the last segment's.
  for (const std::size_t joint : unlabelled_joints_) event_labels_[joint] = written_ == 0 ? 0 : last_source_ + 1;
  unlabelled_joints_.clear();
  figures_.segments_after = written_;
  if (report != nullptr) *report = figures_;
  out_.version = rest.version;
  out_.name = std::move(rest.name);
  out_.sources = std::move(rest.sources);
  out_.source_lines = std::move(rest.source_lines);
  out_.source_lines_from = rest.source_lines_from;
  return std::move(out_);
}

}  // namespace curvestep::host::smoothing
