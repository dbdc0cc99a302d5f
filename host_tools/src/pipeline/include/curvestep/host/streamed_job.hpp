// SPDX-License-Identifier: MIT
// A job simulated without holding it (`curvestep sim` without --report, issue 19): the file is
// read twice through the streamed load and smoothing of prepare_job_streamed (job_pipeline.hpp).
// The first pass keeps no segment and finds everything a run needs before its first setpoint:
// every load, range and travel error (no job starts that is refused later), the smoothing report,
// the events, the segment count and the path's length; the second reads the file again in a
// thread while the run pulls the segments through a bounded queue (StreamedJob, simulator.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <curvestep/host/job.hpp>
#include <curvestep/host/job_pipeline.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/readable_job.hpp>
#include <curvestep/host/segment_source.hpp>
#include <curvestep/host/simulator.hpp>

namespace curvestep::host {

/// What tells one read of a job file from another: its size and modification time. A streamed job
/// is read again for each pass, so it must not change while it runs.
struct FileStamp {
  std::uintmax_t size = 0;
  std::filesystem::file_time_type modified{};
  friend bool operator==(const FileStamp&, const FileStamp&) = default;
};
/// The stamp of `path` now; std::runtime_error naming the file if it cannot be read.
[[nodiscard]] FileStamp file_stamp(const std::filesystem::path& path);

/// What the first pass over a streamed job found (or, `streamed` false, the job prepared whole).
struct StreamedJobPlan {
  bool streamed = false;  ///< false: prepared.job holds the whole smoothed job (plan_job)
  /// The prepared job without its segments, source_index and sources (the second pass's load has
  /// them): name, version, events (few: they are kept) and the event timeline's labels
  /// (PreparedJob::event_labels, one per joint with events). Nothing per segment.
  PreparedJob prepared;
  FileStamp file;                    ///< the job file as the first pass read it (a streamed job)
  std::size_t segments = 0;          ///< smoothed segments
  double approximate_length_mm = 0;  ///< approximate_length summed over them (progress)
  /// The file segments whose smoothed segments are rapids, as ranges [first, last] (one per run of
  /// consecutive rapids: a plot draws them apart).
  std::vector<std::pair<std::size_t, std::size_t>> rapid_sources;
  std::size_t file_segments = 0;     ///< the last smoothed segment's file segment + 1 (ReadableJob::file_segments)
  /// True if file segment `source` is a rapid.
  [[nodiscard]] bool rapid_source(std::size_t source) const noexcept;
};

/// Pass 1: prepare_job(job_file, machine_file, machine, options) keeping no segment, with the
/// travel check of every smoothed segment (check_travel). Throws what prepare_job throws, the
/// same errors. The job must be is_streamed.
[[nodiscard]] StreamedJobPlan plan_streamed_job(const std::filesystem::path& job_file, const MachineFile& machine_file,
                                                const MachineLimits& machine, const JobPipelineOptions& options);

/// What a command runs: plan_streamed_job when the job is streamed (is_streamed, and not
/// options.optimize, which needs the whole drawing), else the job prepared whole (prepare_job).
/// readable() and simulate_streamed_job() take either.
[[nodiscard]] StreamedJobPlan plan_job(const std::filesystem::path& job_file, const MachineFile& machine_file, const MachineLimits& machine,
                                       const JobPipelineOptions& options);

/// Pass 2: the smoothed segments of the same load, read again in a thread (at most
/// streamed_segments_queued ahead of the run). The thread's errors (the first pass's, as the code
/// is the same) are thrown by next(); destroying the source stops the thread. With `expected`
/// (StreamedJobPlan::file), a file whose stamp differs before, during (every 64 segments) or after
/// the read ends it with std::runtime_error naming the file.
[[nodiscard]] std::unique_ptr<SegmentSource> stream_segments(const std::filesystem::path& job_file, const MachineFile& machine_file,
                                                             const MachineLimits& machine, const JobPipelineOptions& options,
                                                             std::optional<FileStamp> expected = std::nullopt);

/// simulate_stream of the job `plan` describes (plan_job of the same arguments): a streamed job as
/// its readable() (its segments pulled from a new read of the file, each call reads it again), a job
/// held whole from memory.
[[nodiscard]] SimulationSummary simulate_streamed_job(const StreamedJobPlan& plan, const std::filesystem::path& job_file,
                                                      const MachineFile& machine_file, const MachineLimits& machine,
                                                      const JobPipelineOptions& options, const SimulationOptions& simulation,
                                                      const SetpointSink& sink);

/// The job `plan` describes as a ReadableJob: a streamed job's read() reads the file again
/// (stream_segments), a job held whole is read from memory.
/// The plan and the machine file must outlive it (the path, limits and options are copied).
[[nodiscard]] ReadableJob readable(const StreamedJobPlan& plan, const std::filesystem::path& job_file, const MachineFile& machine_file,
                                   const MachineLimits& machine, const JobPipelineOptions& options);

/// How many smoothed segments the reading thread may be ahead of the run (about 0.5 KB each).
inline constexpr std::size_t streamed_segments_queued = 256;

}  // namespace curvestep::host
