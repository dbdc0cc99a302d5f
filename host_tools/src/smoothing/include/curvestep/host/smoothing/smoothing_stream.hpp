// SPDX-License-Identifier: MIT
// Path smoothing fed one programmed segment at a time (path_smoothing.hpp says what it does). It
// holds only what is not decided yet: the run of short lines being collected (and its fit) and the
// piece whose corner with the next one is open; everything before goes out at once. smooth_job()
// is this stream fed a whole job, so a streamed load (job_pipeline.hpp) and a job read whole are
// smoothed into the same segments bit for bit, while memory follows the longest line run instead
// of the job.
#pragma once

#include <cstddef>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include <curvestep/core/motion/segment_plan.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/smoothing/corner_blend.hpp>
#include <curvestep/host/smoothing/line_run_fit.hpp>
#include <curvestep/host/smoothing/path_smoothing.hpp>

namespace curvestep::host::smoothing {

class SmoothingStream final : public JobSink {
 public:
  /// Receives each smoothed segment and its Job::source_index entry as soon as it is decided.
  using SegmentHandler = std::function<void(const PathSegment& segment, std::size_t source)>;

  /// `downstream` (may be empty): where the smoothed segments go instead of the job finish()
  /// returns (whose segments and source_index then stay empty; its events are kept and numbered
  /// as always, in the smoothed segments' order).
  explicit SmoothingStream(const SmoothingOptions& options, SegmentHandler downstream = {});

  /// An event of the programmed job; its before_segment is renumbered to the smoothed job's. It
  /// must come before the segment it precedes.
  void event(JobEvent event) override;
  /// The next programmed segment (JobSink).
  void segment(const PathSegment& segment, std::size_t source, std::optional<double> blend_tolerance_mm) override;
  /// The job ended: `rest` (what the load returned: name, version, sources) with the smoothed
  /// segments, their source indices and the events. With tolerance 0 the job as pushed, blend
  /// tolerances included. `report` (optional) receives the figures. Call once.
  [[nodiscard]] Job finish(Job rest, SmoothingReport* report = nullptr);
  /// After finish(): for each joint of the smoothed job that has events (JobEvent::before_segment),
  /// the file segment index of the smoothed segment after it (Job::source_index[joint]), or, past
  /// the last segment, the last one's + 1 (0 for a job without segments): the labels of the event
  /// timeline (link::to_wire_events), known without holding source_index.
  [[nodiscard]] const std::map<std::size_t, std::size_t>& event_labels() const noexcept { return event_labels_; }

  /// One piece of the path between smoothing steps.
  struct Item {
    PathSegment segment;
    std::size_t source = 0;         ///< Job::source_index of the programmed segment it comes from
    double length_mm = 0;           ///< arc length (before any cut)
    bool fitted = false;            ///< part of a fitted run
    bool run_inside_next = false;   ///< the joint to the next item is inside a fitted run (smooth)
    double joint_tolerance_mm = 0;  ///< tolerance at the joint to the next item (0: keep the joint)
    double start_u = 0;             ///< cut by the blend before it
    double end_u = 1;               ///< cut by the blend after it
    MachinePoint start_point{};
    MachinePoint end_point{};
    /// The planner's view of `segment` (plan_segment; inner nullopt: it refuses it), made by the
    /// first blend decision that needs it and reused by the second (the item is the outgoing
    /// neighbour of one corner, then the incoming one of the next). Valid while `segment` is
    /// unchanged: a blend cuts an item only through start_u/end_u (the piece is made when written),
    /// so the plan is always of the whole segment, as blend decisions judge it.
    std::optional<std::optional<SegmentPlan>> plan;
    /// The planner's view of the blend before this item (when a blend cut its start): the joint
    /// from that blend into what the next blend leaves of this item caps the speed there too.
    std::optional<SegmentPlan> start_blend_plan;
  };

 private:
  /// A programmed segment waiting for its line run to end: a line that may join a run by its ends
  /// (88 bytes: a run of a million lines is held in 88 MB), any other segment whole.
  struct Pending {
    std::unique_ptr<PathSegment> other;  ///< nullptr: a fittable line (fittable_line), kept as start, end, feed
    MachinePoint start{};
    MachinePoint end{};
    double feed_mm_per_s = 0;
    std::size_t source = 0;
    std::size_t index = 0;              ///< its index in the programmed job
    double joint_tolerance_mm = 0;      ///< of the joint into it (0: keep it)
    double deflection_cos = 1;          ///< of the joint into it (tangent after · tangent before)
    [[nodiscard]] bool fittable() const noexcept { return other == nullptr; }
    /// The segment as pushed (a line made again from its ends: make_line is exact).
    [[nodiscard]] PathSegment segment() const;
  };

  /// The tolerance of the joint into `segment` (after previous_), 0 if it must stay.
  [[nodiscard]] double joint_tolerance(const PathSegment& segment, std::optional<double> blend_tolerance_mm) const;
  /// Step 1: turns the pending segments into items as far as their runs are decided (all at the end).
  void make_items(bool at_end);
  void add_item(const PathSegment& segment, std::size_t source, bool fitted);
  /// Whether the corner into pending_[k] (k >= 1, a line) is a jog: one of its two lines is at most
  /// a quarter of the tolerance long. A jog joins a run whatever its angle.
  [[nodiscard]] bool jog_below_tolerance(std::size_t k) const;
  /// The first `count` pending lines (a run) fitted, or nullopt.
  [[nodiscard]] std::optional<LineRunFit> fit_lines(std::size_t count) const;
  /// The longest prefix of the run of pending lines, of at most `longest` lines, that fits, with
  /// its length (at least 3 lines); nullopt if none does. For a run that cannot be fitted whole (a
  /// noisy one, or one with a feature inside): the rest is looked at after it.
  [[nodiscard]] std::optional<std::pair<LineRunFit, std::size_t>> fit_longest_prefix(std::size_t longest) const;
  /// Steps 2 and 3: blends the corner after the first item and writes it out, while it has a next one.
  void write_items(bool at_end);
  void decide_corner(Item& a, Item& b);
  /// Counts a blend's or a fit's deviation from the programmed path where `tolerance_mm` is in force.
  void note_deviation(double deviation_mm, double tolerance_mm);
  void write_item(const Item& item, const Item* next);
  /// The next smoothed segment: to downstream_, or into out_.
  void emit(const PathSegment& segment, std::size_t source);

  SmoothingOptions options_;
  double cos_max_run_deflection_ = 1;
  SmoothingReport figures_;
  Job out_;
  SegmentHandler downstream_;
  std::size_t written_ = 0;  ///< smoothed segments emitted so far
  std::size_t pushed_ = 0;
  std::optional<PathSegment> previous_;
  std::deque<Pending> pending_;
  std::size_t verified_run_ = 0;  ///< pending_[0 .. verified_run_) are known to form one run
  std::size_t failed_run_lines_ = 0;  ///< pending_[0 .. failed_run_lines_) are part of a run whose whole fit failed
  std::deque<Item> items_;
  std::optional<CornerBlend> front_blend_;  ///< the blend after items_[0], once decided
  std::size_t items_made_ = 0;    ///< items made so far (items_.front() is number items_made_ - items_.size())
  /// Events waiting for their programmed segment's first item, and for that item's output index
  /// (values: positions in out_.events).
  std::multimap<std::size_t, std::size_t> events_at_segment_;
  std::multimap<std::size_t, std::size_t> events_at_item_;
  /// Joints of the smoothed job whose events are numbered but whose segment is not emitted yet.
  std::set<std::size_t> unlabelled_joints_;
  std::map<std::size_t, std::size_t> event_labels_;  ///< event_labels()
  std::size_t last_source_ = 0;                      ///< of the last segment emitted
  /// An event of the smoothed job is at `joint`: its label comes with the segment emitted there.
  void event_at(std::size_t joint) { unlabelled_joints_.insert(joint); }
};

}  // namespace curvestep::host::smoothing
