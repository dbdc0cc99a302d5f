// SPDX-License-Identifier: MIT
// A smoothed job's segments handed out one at a time, so that a planner can pull them as it needs
// them instead of holding the job (the simulator's LockstepRun; a streamed load, streamed_job.hpp).
#pragma once

#include <cstddef>

#include <curvestep/core/motion/path_segment.hpp>
#include <curvestep/host/job.hpp>

namespace curvestep::host {

class SegmentSource {
 public:
  virtual ~SegmentSource() = default;
  /// The job's next segment (valid until the next call) and its Job::source_index entry in
  /// `source`; nullptr after the last one.
  virtual const PathSegment* next(std::size_t& source) = 0;
};

/// The segments of a job held whole (Job::source_index, or the segment's own index without one).
class JobSegments final : public SegmentSource {
 public:
  explicit JobSegments(const Job& job) : job_(job) {}
  const PathSegment* next(std::size_t& source) override {
    if (next_ == job_.segments.size()) return nullptr;
    source = job_.source_index.empty() ? next_ : job_.source_index[next_];
    return &job_.segments[next_++];
  }

 private:
  const Job& job_;
  std::size_t next_ = 0;
};

}  // namespace curvestep::host
