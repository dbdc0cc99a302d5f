// SPDX-License-Identifier: MIT
#include <curvestep/host/simulator.hpp>

#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <curvestep/core/error_text.hpp>
#include <curvestep/core/motion/motion_controller.hpp>
#include <curvestep/core/motion/step_generator.hpp>
#include <curvestep/host/csv.hpp>
#include <curvestep/host/piece_planner.hpp>
#include <curvestep/host/position_differences.hpp>

#include "lockstep_run.hpp"

namespace curvestep::host {

using detail::check_request;
using detail::ExactController;
using detail::FixedController;
using detail::LockstepRun;

std::string override_range_text() {
  return "the feed override must be " + std::to_string(FeedOverride::min_feed_percent) + ".." +
         std::to_string(FeedOverride::max_feed_percent) + " % and the rapid override " +
         std::to_string(FeedOverride::min_rapid_percent) + ".." + std::to_string(FeedOverride::max_rapid_percent) + " %";
}

namespace detail {

void check_request(const MachineLimits& machine, const SimulationOptions& options) {
  if (auto valid = machine.validate(); !valid) {
    throw std::runtime_error("machine: " + std::string(describe(valid.error())));
  }
  if (options.lookahead < 1 || options.lookahead > SimulationOptions::max_lookahead) {
    throw std::runtime_error("lookahead: must be between 1 and " + std::to_string(SimulationOptions::max_lookahead) + " segments, not " +
                             std::to_string(options.lookahead));
  }
  for (std::size_t k = 1; k < options.overrides.size(); ++k) {
    if (options.overrides[k].tick < options.overrides[k - 1].tick) {
      throw std::runtime_error("--override-at: the overrides must come in time order (setpoint " +
                               std::to_string(options.overrides[k].tick) + " after setpoint " +
                               std::to_string(options.overrides[k - 1].tick) + ")");
    }
  }
  for (const FeedOverrideEvent& event : options.overrides) {
    if (!event.value.valid()) {
      throw std::runtime_error("--override-at: feed " + std::to_string(event.value.feed_percent) + " %, rapid " +
                               std::to_string(event.value.rapid_percent) + " %: " + override_range_text());
    }
  }
  for (std::size_t k = 1; k < options.holds.size(); ++k) {
    if (options.holds[k].tick <= options.holds[k - 1].tick) {
      throw std::runtime_error("--hold-at: the holds must come in time order (setpoint " + std::to_string(options.holds[k].tick) +
                               " after setpoint " + std::to_string(options.holds[k - 1].tick) + ")");
    }
  }
}

}  // namespace detail

double approximate_length(const PathSegment& segment) {
  if (segment.kind() == SegmentKind::Arc) {
    const double along = segment.arc_radius() * segment.arc_sweep_rad();
    const double rise = segment.end()[2] - segment.start()[2];
    return std::sqrt(along * along + rise * rise);
  }
  constexpr int samples = 16;
  double total = 0;
  MachinePoint previous = segment.start();
  for (int k = 1; k <= samples; ++k) {
    const MachinePoint next = segment.point(static_cast<double>(k) / samples);
    double d2 = 0;
    for (std::size_t axis = 0; axis < motion_axes; ++axis) d2 += (next[axis] - previous[axis]) * (next[axis] - previous[axis]);
    total += std::sqrt(d2);
    previous = next;
  }
  return total;
}

namespace {

/// The path's length for progress (approximate_length of each segment). Only the fraction shown
/// to the user depends on it.
double path_length(const Job& job) {
  double total = 0;
  for (const PathSegment& segment : job.segments) total += approximate_length(segment);
  return total;
}

void note_violation(SimulationSummary& s, const char* what, double measured, double limit, const char* unit) {
  if (limit > 0 && measured > limit * 1.01) {
    std::ostringstream line;
    line << what << " " << measured << " " << unit << " exceeds the limit " << limit << " " << unit;
    s.violations.push_back(line.str());
  }
}

}  // namespace

namespace {

/// The run's setpoints to `sink` and their summary. `total_length`: the path's approximate length
/// (progress only).
SimulationSummary summarize(LockstepRun<ExactController, FixedController>& run, const MachineLimits& machine,
                            const SimulationOptions& options, double total_length, const SetpointSink& sink) {
  SimulationSummary s;
  const double dt = 1.0 / machine.rate_hz;
  // Peaks from the exact (double) positions, one setpoint apart, as they come (position_differences.hpp,
  // the implementation the report's motion profile uses too): memory independent of the job's length.
  RunningDifferences differences;
  std::array<double, motion_axes> peak_axis_speed{};
  std::size_t reported = 0;
  run.run([&](const auto& setpoints) {
    const auto& [exact, fixed] = setpoints;
    SetpointRecord r;
    r.time_s = static_cast<double>(exact.tick) * dt;
    r.index = exact.tick;
    r.speed_mm_per_s = exact.speed_mm_per_s;
    r.segment = exact.segment;
    double quantisation = 0;
    for (std::size_t axis = 0; axis < 3; ++axis) {
      r.raw_q16[axis] = fixed.position[axis].raw();
      r.position_mm[axis] = options.fixed_point ? fixed.position[axis].to_double() : exact.position[axis];
      const double d = fixed.position[axis].to_double() - exact.position[axis];
      quantisation += d * d;
    }
    if (options.fixed_point) s.max_quantisation_mm = std::fmax(s.max_quantisation_mm, std::sqrt(quantisation));
    const SampleDifferences d = differences.push({exact.position[0], exact.position[1], exact.position[2]});
    s.distance_mm += d.first;
    s.peak_speed_mm_per_s = std::fmax(s.peak_speed_mm_per_s, d.first / dt);
    s.peak_acceleration_mm_per_s2 = std::fmax(s.peak_acceleration_mm_per_s2, d.second / (dt * dt));
    s.peak_jerk_mm_per_s3 = std::fmax(s.peak_jerk_mm_per_s3, d.third / (dt * dt * dt));
    s.max_chord_deviation_mm = std::fmax(s.max_chord_deviation_mm, d.second / 8);
    for (std::size_t axis = 0; axis < 3; ++axis) peak_axis_speed[axis] = std::fmax(peak_axis_speed[axis], d.axis_first[axis] / dt);
    s.duration_s = r.time_s;
    if (sink) sink(r);
    if (options.progress && differences.count() - reported >= 20000) {
      reported = differences.count();
      options.progress(total_length > 0 ? std::fmin(s.distance_mm / total_length, 0.999) : 0.0);
    }
  });
  run.check_holds_done();
  if (options.progress) options.progress(1.0);
  s.setpoints = differences.count();
  for (std::size_t axis = 0; axis < 3; ++axis) s.peak_step_rate_hz[axis] = peak_axis_speed[axis] * machine.axes[axis].steps_per_mm;
  note_violation(s, "peak speed", s.peak_speed_mm_per_s, machine.v_max_mm_per_s, "mm/s");
  note_violation(s, "peak acceleration", s.peak_acceleration_mm_per_s2, machine.a_max_mm_per_s2, "mm/s^2");
  if (machine.jerk_limited) note_violation(s, "peak jerk", s.peak_jerk_mm_per_s3, machine.j_max_mm_per_s3, "mm/s^3");
  note_violation(s, "chord deviation", s.max_chord_deviation_mm, machine.tolerance_mm, "mm");
  // The driver limit, judged by the core's rule (step_generator.hpp: |v_axis| × steps/mm above
  // max_step_rate_hz). It names the first axis over the limit; the next call looks past it.
  const char* axis_names[] = {"x", "y", "z"};
  std::array<double, motion_axes> unchecked = peak_axis_speed;
  for (auto verdict = check_step_rate(unchecked, machine); !verdict && verdict.where() < motion_axes;
       verdict = check_step_rate(unchecked, machine)) {
    const std::size_t axis = verdict.where();
    std::ostringstream line;
    if (verdict.error() == Error::StepRateTooHigh) {
      line << "axis " << axis_names[axis] << " needs " << s.peak_step_rate_hz[axis] << " steps/s, more than max_step_rate "
           << machine.max_step_rate_hz;
    } else {
      line << "axis " << axis_names[axis] << ": " << describe(verdict.error());
    }
    s.violations.push_back(line.str());
    unchecked[axis] = 0;
  }
  return s;
}

}  // namespace

SimulationSummary simulate_stream(const Job& job, const MachineLimits& machine, const SimulationOptions& options,
                                  const SetpointSink& sink) {
  check_request(machine, options);
  LockstepRun<ExactController, FixedController> run(job, machine, options, options.holds);
  // Progress is the distance travelled over the path's length (segments queued over the total
  // would say "done" at once for a job that fits the queue).
  return summarize(run, machine, options, options.progress ? path_length(job) : 0.0, sink);
}

SimulationSummary simulate_stream(StreamedJob job, const MachineLimits& machine, const SimulationOptions& options,
                                  const SetpointSink& sink) {
  check_request(machine, options);
  LockstepRun<ExactController, FixedController> run(job.outline->name, job.segments,
                                                    joint_stops(job.outline->events, job.segments, job.outline->name, machine.rate_hz),
                                                    std::move(job.source), machine, options, options.holds);
  return summarize(run, machine, options, job.approximate_length_mm, sink);
}

SimulationSummary simulate_stream(const ReadableJob& job, const MachineLimits& machine, const SimulationOptions& options,
                                  const SetpointSink& sink) {
  return simulate_stream(StreamedJob{job.outline, job.segments, job.approximate_length_mm, job.read()}, machine, options, sink);
}

SimulationResult simulate(const Job& job, const MachineLimits& machine, const SimulationOptions& options) {
  SimulationResult result;
  result.summary = simulate_stream(job, machine, options, [&result](const SetpointRecord& r) { result.setpoints.push_back(r); });
  return result;
}

double lookahead_distance_for(const MachineLimits& machine) {
  const ProfileLimits limits{machine.v_max_mm_per_s, machine.a_max_mm_per_s2, machine.j_max_mm_per_s3, machine.jerk_limited};
  return 2 * speed_change_distance(machine.v_max_mm_per_s, 0, limits);
}

std::vector<PlannedPiece> plan_pieces(const Job& job, const MachineLimits& machine, const SimulationOptions& options) {
  PiecePlanner planner(job, machine, options);
  std::vector<PlannedPiece> pieces;
  while (auto piece = planner.next_piece()) pieces.push_back(*piece);
  return pieces;
}

void write_setpoints_csv_header(std::ostream& out) { out << "t,x,y,z,v,index\n"; }

void write_setpoint_csv_line(std::ostream& out, const SetpointRecord& r) {
  out << format_number(r.time_s) << ',' << format_number(r.position_mm[0]) << ',' << format_number(r.position_mm[1]) << ','
      << format_number(r.position_mm[2]) << ',' << format_number(r.speed_mm_per_s) << ',' << r.index << '\n';
}

void write_setpoints_csv(std::ostream& out, const std::vector<SetpointRecord>& setpoints) {
  write_setpoints_csv_header(out);
  for (const auto& r : setpoints) write_setpoint_csv_line(out, r);
}

std::string format_summary(const SimulationSummary& s, const MachineLimits& machine) {
  std::ostringstream out;
  out << std::setprecision(6);
  out << "  setpoints:           " << s.setpoints << " at " << machine.rate_hz << " Hz\n"
      << "  duration:            " << s.duration_s << " s\n"
      << "  distance:            " << s.distance_mm << " mm\n"
      << "  peak speed:          " << s.peak_speed_mm_per_s << " mm/s (limit " << machine.v_max_mm_per_s << ")\n"
      << "  peak acceleration:   " << s.peak_acceleration_mm_per_s2 << " mm/s^2 (limit " << machine.a_max_mm_per_s2 << ")\n"
      << "  peak jerk:           " << s.peak_jerk_mm_per_s3 << " mm/s^3 (limit " << machine.j_max_mm_per_s3 << ")\n"
      << "  max deviation:       " << (s.max_quantisation_mm + s.max_chord_deviation_mm) * 1000 << " um (Q16.16 "
      << s.max_quantisation_mm * 1000 << " um + chord " << s.max_chord_deviation_mm * 1000 << " um; tolerance "
      << machine.tolerance_mm * 1000 << " um)\n";
  if (s.violations.empty()) {
    out << "  limit violations:    none\n";
  } else {
    for (const auto& v : s.violations) out << "  LIMIT VIOLATION:     " << v << "\n";
  }
  return out.str();
}

}  // namespace curvestep::host
