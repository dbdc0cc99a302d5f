// SPDX-License-Identifier: MIT
// `curvestep sim JOB --machine MACHINE.json [--rate HZ] [--lookahead N] [-o setpoints.csv] [--report report.html]`:
// replays a job through the firmware's motion code and prints what the machine would do.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <sstream>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

#include <curvestep/host/job_file.hpp>
#include <curvestep/host/link/event_timeline.hpp>
#include <curvestep/host/link/wire.hpp>
#include <curvestep/host/csv.hpp>
#include <curvestep/host/job.hpp>
#include <curvestep/host/machine_file.hpp>
#include <curvestep/host/printable.hpp>
#include <curvestep/host/report.hpp>
#include <curvestep/host/simulator.hpp>
#include <curvestep/host/smoothing/path_smoothing.hpp>
#include <curvestep/host/streamed_job.hpp>

#include "command_registry.hpp"
#include "job_pipeline_options.hpp"
#include "rate_option.hpp"

namespace curvestep::host {
namespace {

struct SimOptions {
  std::string job;
  std::string machine;
  double rate_hz = 0;
  long long lookahead = static_cast<long long>(SimulationOptions::max_lookahead);
  bool lookahead_given = false;  ///< without --lookahead: the count window 16 extended by distance
  std::string output;
  std::string report;
  bool double_precision = false;
  std::vector<std::string> holds;  ///< --hold-at T[:R], seconds
  std::vector<std::string> overrides;  ///< --override-at T:F[:R], seconds and percent
  JobPipelineOptions pipeline;
};

/// A number >= 0 in `part` of `option`'s value `text` (the error names both and `what`).
double parse_non_negative(const std::string& option, const std::string& text, const std::string& part, const char* what) {
  std::size_t used = 0;
  double value = -1;
  try {
    value = std::stod(part, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != part.size() || !(value >= 0) || !std::isfinite(value)) {
    throw std::runtime_error(option + " " + text + ": " + what + " must be a number >= 0");
  }
  return value;
}

/// `--hold-at T[:R]`: a feed hold before the setpoint at T seconds (index T × rate, rounded), standing
/// R seconds (default 0) once stopped, then resume (FeedHoldEvent).
FeedHoldEvent parse_hold(const std::string& text, double rate_hz) {
  const auto colon = text.find(':');
  const auto seconds = [&](const std::string& part, const char* what) {
    return static_cast<std::uint64_t>(std::llround(parse_non_negative("--hold-at", text, part, what) * rate_hz));
  };
  FeedHoldEvent hold;
  hold.tick = seconds(text.substr(0, colon), "the hold time T (seconds)");
  if (colon != std::string::npos) hold.standing_ticks = seconds(text.substr(colon + 1), "the standing time R (seconds)");
  return hold;
}

/// `--override-at T:F[:R]`: feed override F % and rapid override R % (default 100) set before the
/// setpoint at T seconds (index T × rate, rounded) (FeedOverrideEvent).
FeedOverrideEvent parse_override(const std::string& text, double rate_hz) {
  const auto first = text.find(':');
  if (first == std::string::npos) throw std::runtime_error("--override-at " + text + ": expected T:F[:R] (seconds, feed %, rapid %)");
  const auto second = text.find(':', first + 1);
  const auto percent = [&](const std::string& part, const char* what) {
    const double value = parse_non_negative("--override-at", text, part, what);
    if (value != std::floor(value) || value > 65535) throw std::runtime_error("--override-at " + text + ": " + what + " must be a whole number");
    return static_cast<std::uint16_t>(value);
  };
  FeedOverrideEvent event;
  event.tick = static_cast<std::uint64_t>(std::llround(parse_non_negative("--override-at", text, text.substr(0, first), "the time T (seconds)") * rate_hz));
  event.value.feed_percent = percent(text.substr(first + 1, second == std::string::npos ? std::string::npos : second - first - 1),
                                     "the feed override F (percent)");
  if (second != std::string::npos) event.value.rapid_percent = percent(text.substr(second + 1), "the rapid override R (percent)");
  if (!event.value.valid()) {
    throw std::runtime_error("--override-at " + text + ": " + override_range_text());
  }
  return event;
}

/// The job's machine events as summary lines (count, pen moves counted, then up to 8 others with where they happen).
std::string format_events(const Job& job) {
  if (job.events.empty()) return {};
  static const char* names[] = {"dwell", "pause", "program end", "spindle on", "spindle off", "spindle speed", "mist",
                                "flood", "coolant off", "tool change", "output", "pen up", "pen down", "layer change", "message"};
  std::ostringstream out;
  out << "  job events:          " << job.events.size()
      << " (in program order; G4, M0/M1, M6 and pen changes between layers stop the motion, G4 rests its P seconds)\n";
  // Pen moves come in their hundreds on plotter art: counted, so that the layer changes show.
  std::size_t pen_up = 0;
  std::size_t pen_down = 0;
  for (const JobEvent& e : job.events) {
    pen_up += e.kind == JobEventKind::PenUp ? 1 : 0;
    pen_down += e.kind == JobEventKind::PenDown ? 1 : 0;
  }
  if (pen_up + pen_down > 0) out << "                       pen up " << pen_up << " times, pen down " << pen_down << " times\n";
  std::size_t shown = 0;
  for (const JobEvent& e : job.events) {
    if (e.kind == JobEventKind::PenUp || e.kind == JobEventKind::PenDown) continue;
    if (++shown > 8) {
      out << "                       ...\n";
      break;
    }
    out << "                       " << names[static_cast<std::size_t>(e.kind)];
    if (e.kind == JobEventKind::Message) {
      out << " \"" << printable(e.text) << "\"";
    } else if (!e.text.empty()) {
      out << " (" << e.text << ")";
    }
    if (e.kind == JobEventKind::Dwell) out << " " << e.value << " s";
    if (e.kind == JobEventKind::SpindleOn || e.kind == JobEventKind::SpindleSpeed) out << " " << e.value << " rev/min";
    if (e.kind == JobEventKind::ToolChange) out << " tool " << e.value;
    out << " before segment " << e.before_segment;
    if (e.line != 0) out << ", line " << e.line;
    out << "\n";
  }
  return out.str();
}

/// The event timeline: where a device calls its board hooks (up to 40 lines, pen moves included).
std::string format_timeline(const link::SimulatedEventTimeline& timeline) {
  if (timeline.events().empty()) return {};
  std::ostringstream out;
  out << "  event timeline:      (the board hooks a device calls, logged the same; a dwell is a rest in the motion, not a hook)\n";
  for (std::size_t k = 0; k < timeline.setpoints().size(); ++k) {
    if (k == 40) {
      out << "                       ... " << timeline.setpoints().size() - k << " more\n";
      break;
    }
    out << "                       " << link::event_line(timeline.events()[k], timeline.setpoints()[k]) << "\n";
  }
  return out.str();
}

/// Exit status for a job the machine cannot run within its limits.
constexpr int exit_limits_exceeded = 3;

int run_sim(const SimOptions& o) {
  const bool replay_window = o.lookahead_given;
  if (o.lookahead < 1 || o.lookahead > static_cast<long long>(SimulationOptions::max_lookahead)) {
    throw std::runtime_error("--lookahead: must be between 1 and " + std::to_string(SimulationOptions::max_lookahead) + " segments");
  }
  const MachineFile machine_file = load_machine_file(o.machine);
  MachineLimits file_limits = machine_file.limits;
  if (o.rate_hz > 0) {
    file_limits.rate_hz = o.rate_hz;
    if (auto valid = file_limits.validate(); !valid) throw std::runtime_error("--rate: must be between 100 and 100000 Hz");
  }
  // A streamed job is read twice (more for --report) and never held (streamed_job.hpp): memory
  // independent of its length. A pen drawing (or --optimize) is prepared whole.
  const StreamedJobPlan plan = plan_job(o.job, machine_file, file_limits, o.pipeline);
  const bool streamed = plan.streamed;
  const PreparedJob& prepared = plan.prepared;
  const Job& job = prepared.job;
  const MachineLimits& machine = prepared.machine;
  const smoothing::SmoothingReport& smoothing_report = prepared.smoothing;
  SimulationOptions options;
  if (replay_window) {
    options.lookahead = static_cast<std::size_t>(o.lookahead);
  } else {
    options.lookahead_distance_mm = lookahead_distance_for(machine);
  }
  options.fixed_point = !o.double_precision;
  for (const auto& text : o.holds) options.holds.push_back(parse_hold(text, machine.rate_hz));
  for (const auto& text : o.overrides) options.overrides.push_back(parse_override(text, machine.rate_hz));
  options.progress = make_terminal_progress();  // a bar with ETA on a terminal, quiet otherwise
  // The setpoints go to the CSV as they are made and are kept nowhere; the HTML report runs the
  // simulation again for its plots (write_html_report_streamed).
  // One simulation of the job: pulled from a new read of the file when streamed.
  const auto simulate_job = [&](const SimulationOptions& with, const SetpointSink& sink) {
    return simulate_streamed_job(plan, o.job, machine_file, file_limits, o.pipeline, with, sink);
  };
  SimulationResult result;
  link::SimulatedEventTimeline timeline(
      link::to_wire_events(job, machine.rate_hz, readable(plan, o.job, machine_file, file_limits, o.pipeline).event_labels));
  std::uint64_t last_index = 0;
  const auto run = [&](const SetpointSink& sink) {
    const SetpointSink both = [&](const SetpointRecord& r) {
      if (sink) sink(r);
      timeline.on_setpoint(r);
      last_index = r.index;
    };
    result.summary = simulate_job(options, both);
    timeline.finish(last_index);
  };
  if (o.output.empty()) {
    run({});
  } else {
    try {
      write_output(o.output, [&](std::ostream& out) {
        write_setpoints_csv_header(out);
        run([&out](const SetpointRecord& r) { write_setpoint_csv_line(out, r); });
      });
    } catch (...) {
      std::error_code ignored;
      std::filesystem::remove(o.output, ignored);  // no half-written CSV left behind by a refused job
      throw;
    }
  }
  finish_terminal_progress();
  if (!o.report.empty()) {
    ReportInput report;
    report.job = &job;
    report.machine = &machine;
    report.result = &result;
    report.fixed_point = !o.double_precision;
    report.title = o.job;
    report.extra_rows = smoothing::smoothing_rows(smoothing_report);
    if (streamed) {
      report.path_segments = plan.segments;
      report.rapid_source = [&plan](std::size_t source) { return plan.rapid_source(source); };
    }
    SimulationOptions replay_options = options;
    replay_options.progress = nullptr;
    write_html_report_streamed(o.report, report, [&](const SetpointSink& sink) { (void)simulate_job(replay_options, sink); });
  }
  std::cout << "curvestep sim " << o.job << " (" << (o.double_precision ? "double" : "Q16.16");
  if (replay_window) std::cout << ", look-ahead " << options.lookahead;
  std::cout << ")\n"
            << format_summary(result.summary, machine) << smoothing::format_smoothing(smoothing_report) << format_events(job)
            << format_timeline(timeline);
  for (const FeedHoldEvent& hold : options.holds) {
    std::cout << "  feed hold:           before setpoint " << hold.tick << ", standing " << hold.standing_ticks
              << " ticks once stopped, then resumed\n";
  }
  for (const FeedOverrideEvent& event : options.overrides) {
    std::cout << "  override:            before setpoint " << event.tick << ", feed " << event.value.feed_percent << " %, rapid "
              << event.value.rapid_percent << " %\n";
  }
  for (const auto& note : prepared.notes) std::cout << "  note: " << note << "\n";
  if (!o.output.empty()) std::cout << "  wrote " << o.output << "\n";
  if (!o.report.empty()) std::cout << "  wrote " << o.report << "\n";
  return result.summary.violations.empty() ? 0 : exit_limits_exceeded;
}

}  // namespace

namespace {

void add_sim_command(CLI::App& app) {
  auto options = std::make_shared<SimOptions>();
  auto* sim = app.add_subcommand("sim", "Replay a job exactly as the firmware would run it and report the motion");
  sim->add_option("job", options->job, job_file_help())->required()->check(CLI::ExistingFile);
  sim->add_option("--machine,-m", options->machine, "Machine file (.json)")->required()->check(CLI::ExistingFile);
  sim->add_option("--rate", options->rate_hz, "Setpoint rate in Hz (100..100000), overriding the machine file")
      ->check(rate_hz_check());
  auto* lookahead_option = sim->add_option("--lookahead", options->lookahead,
                  "Look-ahead window in segments (1..16). The setpoints depend on it: give a device's window to reproduce "
                  "its stream bit for bit. Without it: 16 segments, extended to cover twice the braking distance "
                  "from v_max (up to 256 segments) (docs/motion.md, \"Look-ahead and determinism\")");
  sim->add_option("-o,--output", options->output, "Write the setpoints as CSV (t,x,y,z,v,index; index = the setpoint's tick from the start)");
  sim->add_option("--report", options->report, "Write a self-contained HTML report (path, speed/acceleration/jerk, summary). Like the rest of sim it holds "
                  "none of the job's path: it reads the job file again for each pass (docs/robustness.md, \"Memory of a run\")");
  sim->add_flag("--double", options->double_precision, "Write double-precision setpoints instead of Q16.16");
  sim->add_option("--hold-at", options->holds,
                  "Feed hold at T seconds (before setpoint T x rate), resume R seconds after the machine stands (default 0); "
                  "repeatable. `curvestep stream` prints the --hold-at that replays its holds bit for bit")
      ->type_name("T[:R]");
  sim->add_option("--override-at", options->overrides,
                  "Feed override F % (10..200) and rapid override R % (10..100, default 100) set at T seconds (before "
                  "setpoint T x rate); it takes effect where the plan is at zero acceleration (docs/motion.md). Repeatable, "
                  "or comma-separated. `curvestep stream` prints the --override-at that replays its overrides bit for bit")
      ->type_name("T:F[:R]")
      ->delimiter(',');
  add_job_pipeline_options(sim, options->pipeline);
  sim->callback([options, lookahead_option] {
    options->lookahead_given = lookahead_option->count() > 0;
    const int status = run_sim(*options);
    if (status != 0) throw CLI::RuntimeError(status);
  });
}

const RegisterCommand registered{40, add_sim_command};

}  // namespace

}  // namespace curvestep::host
