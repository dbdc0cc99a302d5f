// SPDX-License-Identifier: MIT
#include <curvestep/host/simulator.hpp>

#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include <curvestep/core/error_text.hpp>
#include <curvestep/core/motion/motion_controller.hpp>
#include <curvestep/host/csv.hpp>

namespace curvestep::host {
namespace {

constexpr std::size_t queue_capacity = 32;
constexpr std::size_t lookahead = 16;

std::string failure_text(const Job& job, const Failure& f) {
  std::ostringstream s;
  s << job.name << ": ";
  if (f.index != no_index) s << "segment " << f.index << ": ";
  s << describe(f.code) << " (" << error_name(f.code) << ")";
  return s.str();
}

/// Runs both a double and a Q16.16 controller in lockstep: the same plan, two output scalars.
class LockstepRun {
 public:
  LockstepRun(const Job& job, const MachineLimits& machine) : job_(job) {
    check(exact_.configure(machine), "machine");
    check(fixed_.configure(machine), "machine");
  }

  void fill() {
    while (next_ < job_.segments.size() && !exact_.queue_full() && !fixed_.queue_full()) {
      const auto index = static_cast<std::uint32_t>(job_.source_index.empty() ? next_ : job_.source_index[next_]);
      auto pushed = exact_.try_push(job_.segments[next_], index);
      if (!pushed && pushed.error() == Error::QueueFull) return;  // a cusp split needs more room: later
      check(pushed, index);
      check(fixed_.try_push(job_.segments[next_], index), index);
      ++next_;
    }
    if (next_ == job_.segments.size()) {
      exact_.end_of_job();
      fixed_.end_of_job();
    }
  }

  void start() {
    check(exact_.start(), no_index);
    check(fixed_.start(), no_index);
  }

  [[nodiscard]] bool finished() const { return exact_.finished(); }
  [[nodiscard]] double progress() const { return static_cast<double>(next_) / static_cast<double>(job_.segments.size()); }

  /// One tick of both; returns the exact and the fixed setpoint.
  std::pair<Setpoint<double>, Setpoint<Q16_16>> step() {
    auto e = exact_.next_setpoint();
    auto f = fixed_.next_setpoint();
    if (!e) throw std::runtime_error(failure_text(job_, e.failure()));
    if (!f) throw std::runtime_error(failure_text(job_, f.failure()));
    return {e.value(), f.value()};
  }

 private:
  void check(const Result<void>& r, std::size_t index) const {
    if (!r) {
      Failure f = r.failure();
      if (f.index == no_index) f.index = static_cast<std::uint16_t>(index > no_index ? no_index : index);
      throw std::runtime_error(failure_text(job_, f));
    }
  }
  void check(const Result<void>& r, const char* what) const {
    if (!r) throw std::runtime_error(job_.name + ": " + what + ": " + std::string(describe(r.error())));
  }

  const Job& job_;
  std::size_t next_ = 0;
  MotionController<double, queue_capacity, lookahead> exact_;
  MotionController<Q16_16, queue_capacity, lookahead> fixed_;
};

void note_violation(SimulationSummary& s, const char* what, double measured, double limit, const char* unit) {
  if (limit > 0 && measured > limit * 1.01) {
    std::ostringstream line;
    line << what << " " << measured << " " << unit << " exceeds the limit " << limit << " " << unit;
    s.violations.push_back(line.str());
  }
}

}  // namespace

SimulationResult simulate(const Job& job, const MachineLimits& machine, const SimulationOptions& options) {
  if (job.segments.empty()) throw std::runtime_error(job.name + ": the job has no segments");
  if (auto valid = machine.validate(); !valid) {
    throw std::runtime_error("machine: " + std::string(describe(valid.error())));
  }
  SimulationResult result;
  LockstepRun run(job, machine);
  run.fill();
  run.start();
  const double dt = 1.0 / machine.rate_hz;
  std::vector<std::array<double, 3>> exact_positions;
  std::size_t reported = 0;
  while (!run.finished()) {
    run.fill();
    const auto [exact, fixed] = run.step();
    SetpointRecord r;
    r.time_s = static_cast<double>(exact.tick) * dt;
    r.speed_mm_per_s = exact.speed_mm_per_s;
    r.segment = exact.segment;
    double quantisation = 0;
    for (std::size_t axis = 0; axis < 3; ++axis) {
      r.raw_q16[axis] = fixed.position[axis].raw();
      r.position_mm[axis] = options.fixed_point ? fixed.position[axis].to_double() : exact.position[axis];
      const double d = fixed.position[axis].to_double() - exact.position[axis];
      quantisation += d * d;
    }
    if (options.fixed_point) result.summary.max_quantisation_mm = std::fmax(result.summary.max_quantisation_mm, std::sqrt(quantisation));
    exact_positions.push_back({exact.position[0], exact.position[1], exact.position[2]});
    result.setpoints.push_back(r);
    if (options.progress && result.setpoints.size() - reported >= 20000) {
      reported = result.setpoints.size();
      options.progress(run.progress());
    }
  }
  if (options.progress) options.progress(1.0);

  SimulationSummary& s = result.summary;
  s.setpoints = result.setpoints.size();
  s.duration_s = result.setpoints.back().time_s;
  for (std::size_t i = 1; i < exact_positions.size(); ++i) {
    double v2 = 0, a2 = 0, j2 = 0;
    std::array<double, 3> axis_speed{};
    for (std::size_t axis = 0; axis < 3; ++axis) {
      const auto p = [&](std::size_t k) { return exact_positions[k][axis]; };
      const double d1 = p(i) - p(i - 1);
      v2 += d1 * d1;
      axis_speed[axis] = std::fabs(d1) / dt;
      if (i >= 2) {
        const double d2 = p(i) - 2 * p(i - 1) + p(i - 2);
        a2 += d2 * d2;
      }
      if (i >= 3) {
        const double d3 = p(i) - 3 * p(i - 1) + 3 * p(i - 2) - p(i - 3);
        j2 += d3 * d3;
      }
    }
    s.distance_mm += std::sqrt(v2);
    s.peak_speed_mm_per_s = std::fmax(s.peak_speed_mm_per_s, std::sqrt(v2) / dt);
    s.peak_acceleration_mm_per_s2 = std::fmax(s.peak_acceleration_mm_per_s2, std::sqrt(a2) / (dt * dt));
    s.peak_jerk_mm_per_s3 = std::fmax(s.peak_jerk_mm_per_s3, std::sqrt(j2) / (dt * dt * dt));
    s.max_chord_deviation_mm = std::fmax(s.max_chord_deviation_mm, std::sqrt(a2) / 8);
    for (std::size_t axis = 0; axis < 3; ++axis) {
      s.peak_step_rate_hz[axis] = std::fmax(s.peak_step_rate_hz[axis], axis_speed[axis] * machine.axes[axis].steps_per_mm);
    }
  }
  note_violation(s, "peak speed", s.peak_speed_mm_per_s, machine.v_max_mm_per_s, "mm/s");
  note_violation(s, "peak acceleration", s.peak_acceleration_mm_per_s2, machine.a_max_mm_per_s2, "mm/s^2");
  if (machine.jerk_limited) note_violation(s, "peak jerk", s.peak_jerk_mm_per_s3, machine.j_max_mm_per_s3, "mm/s^3");
  note_violation(s, "chord deviation", s.max_chord_deviation_mm, machine.tolerance_mm, "mm");
  const char* axis_names[] = {"x", "y", "z"};
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if (s.peak_step_rate_hz[axis] > machine.max_step_rate_hz) {
      std::ostringstream line;
      line << "axis " << axis_names[axis] << " needs " << s.peak_step_rate_hz[axis] << " steps/s, more than max_step_rate "
           << machine.max_step_rate_hz;
      s.violations.push_back(line.str());
    }
  }
  return result;
}

void write_setpoints_csv(std::ostream& out, const std::vector<SetpointRecord>& setpoints) {
  out << "t,x,y,z,v\n";
  for (const auto& r : setpoints) {
    out << format_number(r.time_s) << ',' << format_number(r.position_mm[0]) << ',' << format_number(r.position_mm[1]) << ','
        << format_number(r.position_mm[2]) << ',' << format_number(r.speed_mm_per_s) << '\n';
  }
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
