// SPDX-License-Identifier: MIT
// The job pipeline of every machine-moving command (job_pipeline.hpp).
#include <curvestep/host/job_pipeline.hpp>

#include <cctype>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <curvestep/host/job_file.hpp>
#include <curvestep/host/pen_moves.hpp>
#include <curvestep/host/smoothing/smoothing_stream.hpp>
#include <curvestep/host/swept_extent.hpp>

namespace curvestep::host {
namespace {

bool is_svg(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".svg";
}

}  // namespace

MachineLimits step_rate_aware(const MachineLimits& machine, std::vector<std::string>* notes) {
  MachineLimits out = machine;
  const char* names[] = {"x", "y", "z"};
  const double fastest = std::fmax(machine.v_max_mm_per_s, machine.rapid_mm_per_s);
  for (std::size_t axis = 0; axis < motion_axes; ++axis) {
    AxisLimits& a = out.axes[axis];
    if (!(a.steps_per_mm > 0) || !(machine.max_step_rate_hz > 0)) continue;
    const double steppable = step_rate_share * machine.max_step_rate_hz / a.steps_per_mm;
    const double current = a.v_max_mm_per_s > 0 ? a.v_max_mm_per_s : fastest;
    if (steppable < current) {
      a.v_max_mm_per_s = steppable;
      if (notes != nullptr) {
        std::ostringstream line;
        line << "axis " << names[axis] << " planned at most " << steppable << " mm/s (max_step_rate " << machine.max_step_rate_hz
             << " steps/s at " << a.steps_per_mm << " steps/mm; --strict-step-rate refuses instead)";
        notes->push_back(line.str());
      }
    }
  }
  return out;
}

JobPipelineOptions without_drawing_options(const JobPipelineOptions& options) {
  JobPipelineOptions machine_only;
  machine_only.blend_tolerance_mm = options.blend_tolerance_mm;
  machine_only.strict_step_rate = options.strict_step_rate;
  machine_only.subroutine_path = options.subroutine_path;
  return machine_only;
}

JobFileOptions job_file_options(const JobPipelineOptions& options) {
  JobFileOptions file;
  file.optimize = options.optimize;
  file.strict_svg = options.strict_svg;
  file.layers = options.layers;
  file.gcode.subroutine_path.assign(options.subroutine_path.begin(), options.subroutine_path.end());
  if (!options.page.empty()) file.page.page = parse_page_size(options.page);
  file.page.landscape = options.landscape;
  file.page.center = options.center;
  file.page.fit = options.fit;
  if (!options.margin.empty()) file.page.margin_mm = parse_page_length(options.margin);
  file.page.rotate_deg = options.rotate_deg;
  if ((options.landscape || !options.margin.empty()) && options.page.empty()) {
    throw std::invalid_argument("--landscape and --margin need --page");
  }
  return file;
}

namespace {

/// A dwell this long is more likely milliseconds written where a dwell's P (G4, G82, G89) takes seconds.
constexpr double suspicious_dwell_s = 60.0;

/// A note for the job's longest dwell, if any is over suspicious_dwell_s: G4 P is in seconds
/// (LinuxCNC, grbl), but some posts (for controls set to milliseconds) write P1000 for one second.
void note_long_dwells(const Job& job, std::vector<std::string>& notes) {
  const JobEvent* longest = nullptr;
  std::size_t count = 0;
  for (const auto& event : job.events) {
    if (event.kind != JobEventKind::Dwell || !(event.value > suspicious_dwell_s)) continue;
    ++count;
    if (longest == nullptr || event.value > longest->value) longest = &event;
  }
  if (longest == nullptr) return;
  std::ostringstream line;
  line << count << (count == 1 ? " dwell" : " dwells") << " over " << suspicious_dwell_s << " s, the longest " << longest->value << " s";
  if (longest->line != 0) line << " (line " << longest->line << ")";
  line << ": a dwell's P (G4, G82, G89) is in seconds (LinuxCNC, grbl); if the post meant milliseconds, as some controls "
          "are set, the program dwells 1000 times too long";
  notes.push_back(line.str());
}

/// The streamed load: the file hands each segment to smoothing as it is read, and smoothing hands
/// each smoothed segment to `downstream` (empty: into the job).
PreparedJob load_streamed(const std::filesystem::path& job_file, const JobFileOptions& file_options, const MachineLimits& machine,
                          double machine_blend_tolerance_mm, const JobPipelineOptions& options,
                          smoothing::SmoothingStream::SegmentHandler downstream) {
  PreparedJob prepared;
  const double tolerance_mm = smoothing::tolerance_in_force(machine_blend_tolerance_mm, options.blend_tolerance_mm);
  std::vector<std::string> rate_notes;
  prepared.machine = options.strict_step_rate ? machine : step_rate_aware(machine, &rate_notes);
  smoothing::SmoothingStream stream(smoothing::options_for(prepared.machine, tolerance_mm), std::move(downstream));
  Job rest = load_job_file(job_file, file_options, &prepared.notes, stream);
  prepared.job = stream.finish(std::move(rest), &prepared.smoothing);
  prepared.event_labels = stream.event_labels();
  prepared.notes.insert(prepared.notes.end(), rate_notes.begin(), rate_notes.end());
  note_long_dwells(prepared.job, prepared.notes);
  return prepared;
}

PreparedJob prepare(const std::filesystem::path& job_file, const JobFileOptions& file_options, const MachineLimits& machine,
                    double machine_blend_tolerance_mm, const JobPipelineOptions& options, const std::optional<PenModel>& pen) {
  if (!(pen && is_svg(job_file))) return load_streamed(job_file, file_options, machine, machine_blend_tolerance_mm, options, {});
  PreparedJob prepared;
  const double tolerance_mm = smoothing::tolerance_in_force(machine_blend_tolerance_mm, options.blend_tolerance_mm);
  Job programmed = load_job_file(job_file, file_options, &prepared.notes);
  {  // plotter art: the pen moves become part of the motion
    PenMovesReport report;
    programmed = add_pen_moves(programmed, *pen, &report);
    check_swept_extent(programmed);
    std::ostringstream line;
    if (pen->servo) {
      line << "pen: a servo on " << pen->line << ", " << pen->settle_s << " s to settle after each move (a dwell)";
    } else {
      line << "pen: " << report.lifts << " lifts to z " << pen->up_mm << " mm (rapid), " << report.lowers << " moves down to z "
           << pen->down_mm << " mm at " << pen->feed_mm_per_s << " mm/s";
    }
    prepared.notes.push_back(line.str());
  }
  prepared.machine = options.strict_step_rate ? machine : step_rate_aware(machine, &prepared.notes);
  prepared.job = smoothing::smooth_for_machine(std::move(programmed), prepared.machine, tolerance_mm, &prepared.smoothing);
  note_long_dwells(prepared.job, prepared.notes);
  return prepared;
}

}  // namespace

PreparedJob prepare_job(const std::filesystem::path& job_file, const MachineLimits& machine, double machine_blend_tolerance_mm,
                        const JobPipelineOptions& options, const std::optional<PenModel>& pen) {
  return prepare(job_file, job_file_options(options), machine, machine_blend_tolerance_mm, options, pen);
}

GcodeOptions gcode_options(const MachineFile& machine_file) {
  GcodeOptions gcode;
  for (const auto& [number, tool] : machine_file.tools) {
    gcode.tool_length_mm[number] = tool.length_mm;
    if (tool.diameter_mm) gcode.tool_diameter_mm[number] = *tool.diameter_mm;
  }
  if (machine_file.g28_position) gcode.g28_position = *machine_file.g28_position;
  if (machine_file.g30_position) gcode.g30_position = *machine_file.g30_position;
  return gcode;
}

namespace {

JobFileOptions file_options_for(const JobPipelineOptions& options, const MachineFile& machine_file) {
  JobFileOptions file_options = job_file_options(options);
  GcodeOptions gcode = gcode_options(machine_file);
  gcode.subroutine_path = std::move(file_options.gcode.subroutine_path);
  file_options.gcode = std::move(gcode);
  return file_options;
}

}  // namespace

bool is_streamed(const std::filesystem::path& job_file, const MachineFile& machine_file) {
  return !(machine_file.pen && is_svg(job_file));
}

PreparedJob prepare_job_streamed(const std::filesystem::path& job_file, const MachineFile& machine_file, const MachineLimits& machine,
                                 const JobPipelineOptions& options, smoothing::SmoothingStream::SegmentHandler downstream) {
  if (!is_streamed(job_file, machine_file)) throw std::logic_error("prepare_job_streamed: an SVG drawing with a pen is not streamed");
  JobFileOptions file_options = file_options_for(options, machine_file);
  file_options.gcode.keep_source_lines = false;  // the downstream keeps nothing per segment either
  return load_streamed(job_file, file_options, machine, machine_file.blend_tolerance_mm, options,
                       std::move(downstream));
}

PreparedJob prepare_job(const std::filesystem::path& job_file, const MachineFile& machine_file, const MachineLimits& machine,
                        const JobPipelineOptions& options) {
  PreparedJob prepared =
      prepare(job_file, file_options_for(options, machine_file), machine, machine_file.blend_tolerance_mm, options, machine_file.pen);
  check_travel(prepared.job, machine_file.travel, machine_file.name);
  return prepared;
}

}  // namespace curvestep::host
