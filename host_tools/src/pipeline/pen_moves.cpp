// SPDX-License-Identifier: MIT
// Plotter pen up/down as motion (pen_moves.hpp).
#include <curvestep/host/pen_moves.hpp>

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace curvestep::host {
namespace {

/// `segment` with every control point at height z (x, y and everything else bit for bit).
PathSegment at_height(const PathSegment& segment, double z) {
  if (segment.kind() == SegmentKind::Arc) throw std::invalid_argument("pen moves: arcs are not expected in a drawing job");
  CompactSegment c = segment.compact();
  for (std::size_t i = 0; i <= c.degree; ++i) c.values[3 * i + 2] = z;
  Result<PathSegment> made = PathSegment::expand(c);
  if (!made) throw std::invalid_argument("pen moves: a segment cannot be moved to the pen height");
  return made.value();
}

class PenJob {
 public:
  PenJob(const Job& job, const PenModel& pen) : in_(job), pen_(pen) {
    out_.version = job.version;
    out_.name = job.name;
    at_ = job.segments.front().start();
  }

  Job run(PenMovesReport* report) {
    const std::size_t n = in_.segments.size();
    std::size_t next_event = 0;
    for (std::size_t k = 0; k <= n; ++k) {
      for (; next_event < in_.events.size() && in_.events[next_event].before_segment <= k; ++next_event) {
        const JobEvent& event = in_.events[next_event];
        if (event.kind == JobEventKind::LayerChange) lift();  // the pen comes off for a pen change
        add_event(event);
      }
      if (k == n) break;
      const PathSegment& segment = in_.segments[k];
      SourceSegment source = in_.sources.at(in_.source_index.at(k));
      if (segment.rapid()) {
        lift();
      } else {
        lower();
      }
      const double blend = in_.blend_tolerance_mm.size() == n ? in_.blend_tolerance_mm[k] : 0;
      if (pen_.servo) {  // the servo moves the pen: the path keeps its z
        push(segment, std::move(source), blend);
        continue;
      }
      const double z = segment.rapid() ? pen_.up_mm : pen_.down_mm;
      for (auto& p : source.points) p[2] = z;
      push(at_height(segment, z), std::move(source), blend);
    }
    lift();
    if (report != nullptr) *report = report_;
    if (!in_.blend_tolerance_mm.empty()) out_.blend_tolerance_mm = std::move(blend_);
    return std::move(out_);
  }

 private:
  void add_event(JobEvent event) {
    event.before_segment = out_.segments.size();
    out_.events.push_back(std::move(event));
  }

  /// A PenUp/PenDown event; `pulse_us`: a servo's pulse width for it (0 for a pen on z).
  void pen_event(JobEventKind kind, double pulse_us = 0) {
    JobEvent event;
    event.kind = kind;
    event.value = pulse_us;
    add_event(std::move(event));
  }

  /// A servo pen's move: its event, carrying the servo's pulse width for it in whole microseconds
  /// (the board's PWM resolution: docs/boards.md, "Machine outputs"), then a dwell of the settle
  /// time (an exact stop there).
  void servo_move(JobEventKind kind) {
    pen_event(kind, std::nearbyint(kind == JobEventKind::PenDown ? pen_.down_pulse_us : pen_.up_pulse_us));
    JobEvent settle;
    settle.kind = JobEventKind::Dwell;
    settle.value = pen_.settle_s;
    settle.text = "pen settle";
    add_event(std::move(settle));
  }

  void push(const PathSegment& segment, SourceSegment source, double blend) {
    source.first_piece = out_.segments.size();
    source.breaks = {0.0, 1.0};
    out_.source_index.push_back(out_.sources.size());
    out_.segments.push_back(segment);
    out_.sources.push_back(std::move(source));
    blend_.push_back(blend);
    at_ = segment.end();
  }

  /// A straight z move from where the pen is to `z` (a rapid up, or a line down at the pen's feed).
  void move_to_height(double z, bool rapid) {
    const MachinePoint to{{at_[0], at_[1], z}};
    Result<PathSegment> made = PathSegment::make_line(at_, to);
    if (!made) throw std::invalid_argument("pen moves: the pen move cannot be made");
    made.value().set_rapid(rapid);
    made.value().set_feed_mm_per_s(rapid ? 0 : pen_.feed_mm_per_s);
    SourceSegment source;
    source.type = rapid ? SegmentType::Rapid : SegmentType::Line;
    source.points = {at_, to};
    source.degree = 1;
    source.feed_mm_per_s = made.value().feed_mm_per_s();
    push(made.value(), std::move(source), -1);  // exact stop at both ends
  }

  void lift() {
    if (pen_.servo) {
      if (known_up_) return;  // unknown at the start: lifted once to be sure
      servo_move(JobEventKind::PenUp);
      known_up_ = true;
      lowered_ = false;
      return;
    }
    if (!lowered_ && at_[2] == pen_.up_mm) return;
    pen_event(JobEventKind::PenUp);
    if (at_[2] != pen_.up_mm) {
      move_to_height(pen_.up_mm, true);
      ++report_.lifts;
    }
    lowered_ = false;
  }

  void lower() {
    if (lowered_) return;
    if (pen_.servo) {
      servo_move(JobEventKind::PenDown);
      lowered_ = true;
      known_up_ = false;
      return;
    }
    if (at_[2] != pen_.down_mm) {
      move_to_height(pen_.down_mm, false);
      ++report_.lowers;
    }
    pen_event(JobEventKind::PenDown);  // after the move: smoothing keeps the touch-down corner sharp
    lowered_ = true;
  }

  const Job& in_;
  const PenModel& pen_;
  Job out_;
  std::vector<double> blend_;
  MachinePoint at_{};
  bool lowered_ = false;  ///< the pen is known to be on the paper
  bool known_up_ = false; ///< a servo pen is known to be lifted
  PenMovesReport report_;
};

}  // namespace

Job add_pen_moves(const Job& job, const PenModel& pen, PenMovesReport* report) {
  if (job.segments.empty()) return job;
  if (job.source_index.size() != job.segments.size()) throw std::invalid_argument("pen moves: the job has no source per segment");
  for (std::size_t k = 0; k < job.segments.size(); ++k) {
    if (job.sources.at(job.source_index[k]).piece_count() > 1) {
      throw std::invalid_argument("pen moves: expects one segment per source (a drawing job)");
    }
  }
  return PenJob(job, pen).run(report);
}

}  // namespace curvestep::host
