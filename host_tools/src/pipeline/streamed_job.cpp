// SPDX-License-Identifier: MIT
// A job simulated without holding it: the two passes of streamed_job.hpp.
#include <curvestep/host/streamed_job.hpp>

#include <algorithm>
#include <condition_variable>
#include <malloc.h>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <utility>

#include <curvestep/host/simulator.hpp>
#include <curvestep/host/swept_extent.hpp>

namespace curvestep::host {
namespace {

/// std::runtime_error naming `job_file` unless its stamp is still `stamp`: a streamed job is read
/// again for each pass (and each pass checks it as it reads).
void require_unchanged(const std::filesystem::path& job_file, const FileStamp& stamp) {
  if (file_stamp(job_file) != stamp) {
    throw std::runtime_error(job_file.string() +
                             ": the file changed while the job ran (its size or modification time is not the first "
                             "read's): it is read again for each pass, so it must stay as it was checked");
  }
}

/// The second pass: prepare_job_streamed in a thread, its smoothed segments through a bounded queue.
class ThreadedSegments final : public SegmentSource {
 public:
  ThreadedSegments(std::filesystem::path job_file, MachineFile machine_file, MachineLimits machine, JobPipelineOptions options,
                   std::optional<FileStamp> expected) {
    reader_ = std::thread([this, job_file = std::move(job_file), machine_file = std::move(machine_file), machine, options = std::move(options),
                           expected] {
      try {
        const auto check_unchanged = [&] {
          if (expected) require_unchanged(job_file, *expected);
        };
        check_unchanged();
        std::size_t pushed = 0;
        (void)prepare_job_streamed(job_file, machine_file, machine, options, [&](const PathSegment& segment, std::size_t source) {
          if (++pushed % 64 == 0) check_unchanged();
          push(segment, source);
        });
        check_unchanged();
      } catch (const Cancelled&) {
        // the run ended first (it failed, or was abandoned)
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex_);
        error_ = std::current_exception();
      }
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        done_ = true;
      }
      changed_.notify_all();
    });
  }

  ThreadedSegments(const ThreadedSegments&) = delete;
  ThreadedSegments& operator=(const ThreadedSegments&) = delete;

  ~ThreadedSegments() override {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      cancelled_ = true;
    }
    changed_.notify_all();
    reader_.join();
  }

  const PathSegment* next(std::size_t& source) override {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return !queue_.empty() || done_; });
    if (queue_.empty()) {
      if (error_) std::rethrow_exception(error_);
      return nullptr;
    }
    current_.emplace(std::move(queue_.front()));
    queue_.pop_front();
    lock.unlock();
    changed_.notify_all();
    source = current_->second;
    return &current_->first;
  }

 private:
  struct Cancelled {};  ///< thrown through the load to end the thread

  void push(const PathSegment& segment, std::size_t source) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return queue_.size() < streamed_segments_queued || cancelled_; });
    if (cancelled_) throw Cancelled{};
    queue_.emplace_back(segment, source);
    lock.unlock();
    changed_.notify_all();
  }

  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::pair<PathSegment, std::size_t>> queue_;  // guarded by mutex_, as the three below
  bool done_ = false;
  bool cancelled_ = false;
  std::exception_ptr error_;
  std::optional<std::pair<PathSegment, std::size_t>> current_;  ///< the segment next() returned (the run's thread only)
  std::thread reader_;  ///< last: started once the rest is made
};

}  // namespace

StreamedJobPlan plan_streamed_job(const std::filesystem::path& job_file, const MachineFile& machine_file, const MachineLimits& machine,
                                  const JobPipelineOptions& options) {
  // glibc raises its mmap threshold when large blocks are freed (this pass's), after which the
  // second pass's growing vectors come from the heap and fragment it: 137 instead of 101 MB for
  // 10 MB of G-code. The default threshold, fixed, keeps both passes' peaks the whole job's.
  ::mallopt(M_MMAP_THRESHOLD, 128 * 1024);
  StreamedJobPlan plan;
  plan.streamed = true;
  plan.file = file_stamp(job_file);
  bool outside = false;  // a smoothed segment leaves the travel
  plan.prepared = prepare_job_streamed(job_file, machine_file, machine, options, [&](const PathSegment& segment, std::size_t source) {
    ++plan.segments;
    plan.file_segments = source + 1;
    plan.approximate_length_mm += approximate_length(segment);
    outside = outside || !within_travel(segment, machine_file.travel);
    if (segment.rapid()) {
      auto& ranges = plan.rapid_sources;
      if (!ranges.empty() && source <= ranges.back().second + 1) {
        ranges.back().second = std::max(ranges.back().second, source);
      } else {
        ranges.emplace_back(source, source);
      }
    }
  });
  require_unchanged(job_file, plan.file);
  if (outside) {
    // Its message names the file's line, which the streamed load does not keep: the whole job's
    // check_travel (a third read, holding the job, on this error only) throws it.
    (void)prepare_job(job_file, machine_file, machine, options);
    throw std::logic_error(job_file.string() + ": a smoothed segment leaves the travel, but the whole job's travel check passed");
  }
  ::malloc_trim(0);  // what this pass's load freed, back to the system before the second one
  return plan;
}

bool StreamedJobPlan::rapid_source(std::size_t source) const noexcept {
  // The first range ending at or after `source`.
  const auto found = std::lower_bound(rapid_sources.begin(), rapid_sources.end(), source,
                                      [](const std::pair<std::size_t, std::size_t>& range, std::size_t s) { return range.second < s; });
  return found != rapid_sources.end() && found->first <= source;
}

std::unique_ptr<SegmentSource> stream_segments(const std::filesystem::path& job_file, const MachineFile& machine_file,
                                               const MachineLimits& machine, const JobPipelineOptions& options,
                                               std::optional<FileStamp> expected) {
  return std::make_unique<ThreadedSegments>(job_file, machine_file, machine, options, expected);
}

FileStamp file_stamp(const std::filesystem::path& path) {
  std::error_code error;
  FileStamp stamp;
  stamp.size = std::filesystem::file_size(path, error);
  if (!error) stamp.modified = std::filesystem::last_write_time(path, error);
  if (error) throw std::runtime_error(path.string() + ": cannot read the file (" + error.message() + ")");
  return stamp;
}

StreamedJobPlan plan_job(const std::filesystem::path& job_file, const MachineFile& machine_file, const MachineLimits& machine,
                         const JobPipelineOptions& options) {
  if (!options.optimize && is_streamed(job_file, machine_file)) return plan_streamed_job(job_file, machine_file, machine, options);
  StreamedJobPlan plan;
  plan.prepared = prepare_job(job_file, machine_file, machine, options);
  plan.segments = plan.prepared.job.segments.size();
  return plan;
}

ReadableJob readable(const StreamedJobPlan& plan, const std::filesystem::path& job_file, const MachineFile& machine_file,
                     const MachineLimits& machine, const JobPipelineOptions& options) {
  if (!plan.streamed) return readable(plan.prepared.job);
  ReadableJob out;
  out.outline = &plan.prepared.job;
  out.segments = plan.segments;
  out.file_segments = plan.file_segments;
  out.approximate_length_mm = plan.approximate_length_mm;
  out.event_labels = plan.prepared.event_labels;
  out.read = [job_file, &machine_file, machine, options, stamp = plan.file] {
    return stream_segments(job_file, machine_file, machine, options, stamp);
  };
  return out;
}

SimulationSummary simulate_streamed_job(const StreamedJobPlan& plan, const std::filesystem::path& job_file, const MachineFile& machine_file,
                                        const MachineLimits& machine, const JobPipelineOptions& options, const SimulationOptions& simulation,
                                        const SetpointSink& sink) {
  if (!plan.streamed) return simulate_stream(plan.prepared.job, plan.prepared.machine, simulation, sink);
  return simulate_stream(readable(plan, job_file, machine_file, machine, options), plan.prepared.machine, simulation, sink);
}

}  // namespace curvestep::host
