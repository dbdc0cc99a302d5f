// SPDX-License-Identifier: MIT
#include <curvestep/host/readable_job.hpp>

namespace curvestep::host {

ReadableJob readable(const Job& job) {
  ReadableJob out;
  out.outline = &job;
  out.segments = job.segments.size();
  const auto label = [&job](std::size_t k) { return job.source_index.empty() ? k : job.source_index[k]; };
  out.file_segments = out.segments == 0 ? 0 : label(out.segments - 1) + 1;
  for (const JobEvent& event : job.events) {
    const std::size_t joint = event.before_segment;
    out.event_labels[joint] = joint < out.segments ? label(joint) : out.file_segments;
  }
  out.read = [&job] { return std::make_unique<JobSegments>(job); };
  return out;
}

}  // namespace curvestep::host
