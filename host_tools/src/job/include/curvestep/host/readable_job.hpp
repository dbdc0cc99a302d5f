// SPDX-License-Identifier: MIT
// A smoothed job that a consumer reads as often as it needs instead of holding it: its outline
// (name and events), the count of its segments and a new read of them from the start for each pass.
// `curvestep stream` uploads a G-code program this way (streamed_job.hpp reads the file again for
// each pass); a job held whole is read from memory (readable()).
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <memory>

#include <curvestep/host/job.hpp>
#include <curvestep/host/segment_source.hpp>

namespace curvestep::host {

struct ReadableJob {
  const Job* outline = nullptr;  ///< name and events (their before_segment numbers the smoothed segments); no segments needed
  std::size_t segments = 0;      ///< how many each read gives
  std::size_t file_segments = 0;  ///< the file segment labels (Job::source_index) are below this
  /// The sum of approximate_length(segment) over its segments, for a simulation's progress; 0 when
  /// not known (readable() of a job held whole: its simulation reports progress only at the end).
  double approximate_length_mm = 0;
  /// For each joint with events, the file segment label of the segment after it, or past the last
  /// segment the last one's + 1 (SmoothingStream::event_labels).
  std::map<std::size_t, std::size_t> event_labels;
  std::function<std::unique_ptr<SegmentSource>()> read;  ///< the segments from the first, each call a new read
};

/// `job`, held whole, as a ReadableJob reading it from memory; `job` must outlive it.
[[nodiscard]] ReadableJob readable(const Job& job);

}  // namespace curvestep::host
