// SPDX-License-Identifier: MIT
// A job read whole, handed to a JobSink as a streamed load would hand it (job.hpp).
#include <curvestep/host/job.hpp>

#include <utility>

namespace curvestep::host {

Job feed_job(Job job, JobSink& sink) {
  for (JobEvent& event : job.events) sink.event(std::move(event));
  const bool per_joint = job.blend_tolerance_mm.size() == job.segments.size();
  for (std::size_t k = 0; k < job.segments.size(); ++k) {
    const std::size_t source = k < job.source_index.size() ? job.source_index[k] : 0;
    sink.segment(job.segments[k], source, per_joint ? std::optional<double>(job.blend_tolerance_mm[k]) : std::nullopt);
  }
  Job rest;
  rest.version = job.version;
  rest.name = std::move(job.name);
  rest.sources = std::move(job.sources);
  rest.source_lines = std::move(job.source_lines);
  rest.source_lines_from = job.source_lines_from;
  return rest;
}

}  // namespace curvestep::host
