// SPDX-License-Identifier: MIT
// Fuzz harness: the motion planner and interpolator (MotionController) fed with random but
// valid-looking jobs.
//
// The input chooses machine limits (mostly sensible, sometimes any bit pattern), a scale for the
// coordinates, and up to 6 segments that chain end to start: lines, arcs (random centre, turns),
// Béziers (random control points), rational Béziers (random weights) and B-splines with random
// clamped knot vectors (interior knots up to full multiplicity) cut into Bézier pieces. Every
// PathSegment::make_* result that is an error is skipped. Then configure, try_push, end_of_job,
// start and a bounded number of ticks, with an optional feed hold and resume on the way.
// Properties:
//   * no crash, sanitizer report or contract violation (MotionController is noexcept: its only
//     way to report a problem is a Result error, and then its state is Fault with that error);
//   * every setpoint position is finite and within the range of the position scalar;
//   * when the controller finishes, the last setpoint is the last segment's end point (quantised);
//   * setpoint ticks count up by one;
//   * no jump: consecutive setpoints are at most v_max / rate apart, times step_margin, plus the
//     rounding of two Q16.16 positions (issue 19, item 1: a rational curve the controller's
//     arc-length table could not follow moved 0.5-0.9 mm in one tick at v_max 200 and 1000 Hz).
//     Rational Béziers the job loaders refuse (host::table_speed_factor above
//     host::max_table_speed_factor) are left out, as a loaded job never has them;
//     CURVESTEP_FUZZ_ALL_RATIONALS=1 keeps them, which shows the check catching the jump.
// CURVESTEP_FUZZ_PRINT_JOB=1 prints the job and limits an input makes.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>

#include <curvestep/core/bspline/bezier_extraction.hpp>
#include <curvestep/core/bspline/bspline.hpp>
#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/core/motion/motion_controller.hpp>

#include <curvestep/host/parameter_speed.hpp>

#include "fuzz_support.hpp"

namespace {

using namespace curvestep;
using curvestep::fuzz::InputReader;

constexpr std::size_t max_segments = 24;
constexpr std::uint64_t max_ticks = 4000;

/// How far a setpoint may be from the previous one, as a multiple of v_max / rate: the loaders let
/// the arc-length table run up to max_table_speed_factor faster than planned on a rational curve;
/// the rest is the table's cubic error on polynomial curves.
constexpr double step_margin = curvestep::host::max_table_speed_factor + 0.01;

/// Rational Béziers the loaders would refuse are kept only when CURVESTEP_FUZZ_ALL_RATIONALS is set.
bool keep_all_rationals() {
  static const bool keep = std::getenv("CURVESTEP_FUZZ_ALL_RATIONALS") != nullptr;
  return keep;
}

/// How the runs ended (printed at exit when CURVESTEP_FUZZ_STATS is set): how deep the fuzzer gets.
struct Outcomes {
  std::uint64_t refused_limits = 0, nothing_queued = 0, faulted = 0, out_of_ticks = 0, finished = 0;
  ~Outcomes() {
    if (std::getenv("CURVESTEP_FUZZ_STATS") == nullptr) return;
    std::fprintf(stderr, "planner outcomes: limits refused %llu, nothing queued %llu, Result fault %llu, tick budget %llu, finished %llu\n",
                 static_cast<unsigned long long>(refused_limits), static_cast<unsigned long long>(nothing_queued),
                 static_cast<unsigned long long>(faulted), static_cast<unsigned long long>(out_of_ticks),
                 static_cast<unsigned long long>(finished));
  }
};
Outcomes outcomes;

struct Job {
  std::array<PathSegment, max_segments> segments{};
  std::size_t count = 0;
  void add(const Result<PathSegment>& s, double feed) {
    if (!s || count == max_segments) return;
    if (s.value().kind() == SegmentKind::RationalBezier && !keep_all_rationals() &&
        !(curvestep::host::table_speed_factor(s.value()) <= curvestep::host::max_table_speed_factor)) {
      return;  // the loaders refuse it: "the weights vary too strongly"
    }
    segments[count] = s.value();
    segments[count].set_feed_mm_per_s(feed);
    ++count;
  }
};

MachineLimits read_limits(InputReader& in, double scale) {
  MachineLimits m;
  m.v_max_mm_per_s = scale * in.in_range(1, 200);
  m.a_max_mm_per_s2 = scale * in.in_range(20, 20000);
  m.j_max_mm_per_s3 = scale * in.in_range(200, 1000000);
  m.feed_mm_per_s = scale * in.in_range(1, 200);
  m.rapid_mm_per_s = in.u8() < 128 ? 0 : scale * in.in_range(0.2, 50);
  m.tolerance_mm = scale * in.in_range(1e-5, 1e-2);
  m.rate_hz = in.in_range(100, 400);
  m.junction_deviation_mm = scale * in.in_range(0, 1e-2);
  m.jerk_limited = (in.u8() & 1) != 0;
  for (auto& axis : m.axes) {
    const std::uint8_t mode = in.u8();
    if (mode & 1) axis.v_max_mm_per_s = scale * in.in_range(0.2, 50);
    if (mode & 2) axis.a_max_mm_per_s2 = scale * in.in_range(2, 5000);
    if (mode & 4) axis.steps_per_mm = in.in_range(1, 1000);
  }
  // Sometimes one field gets any bit pattern: configure must refuse what validate refuses.
  const std::uint8_t wild = in.u8();
  if (wild >= 240) {
    const double v = in.any_double();
    switch (wild % 8) {
      case 0: m.v_max_mm_per_s = v; break;
      case 1: m.a_max_mm_per_s2 = v; break;
      case 2: m.j_max_mm_per_s3 = v; break;
      case 3: m.feed_mm_per_s = v; break;
      case 4: m.tolerance_mm = v; break;
      case 5: m.rate_hz = v; break;
      case 6: m.junction_deviation_mm = v; break;
      default: m.rapid_mm_per_s = v; break;
    }
  }
  return m;
}

MachinePoint read_point(InputReader& in, double scale) {
  return MachinePoint{{scale * in.in_range(-1, 1), scale * in.in_range(-1, 1), (in.u8() & 1) ? scale * in.in_range(-1, 1) : 0.0}};
}

void add_bspline(InputReader& in, Job& job, const MachinePoint& start, double scale, double feed) {
  constexpr std::size_t max_degree = 7;
  constexpr std::size_t max_points = 12;
  using Spline = BSpline<double, 3, max_degree, max_points>;
  const std::size_t degree = 1 + in.u8() % 5;
  const std::size_t count = degree + 1 + in.u8() % (max_points - degree);
  std::array<MachinePoint, max_points> points{};
  points[0] = start;
  for (std::size_t i = 1; i < count; ++i) points[i] = read_point(in, scale);
  // Clamped: degree+1 zeros, interior knots from the input (sorted), degree+1 ones.
  std::array<double, max_points + max_degree + 1> knots{};
  const std::size_t knot_count = count + degree + 1;
  for (std::size_t i = 0; i < knot_count; ++i) {
    if (i <= degree) knots[i] = 0;
    else if (i >= count) knots[i] = 1;
    else knots[i] = (in.u8() % 8) / 8.0;  // coarse values, so multiplicities happen
  }
  for (std::size_t i = degree + 1; i < count; ++i) {
    for (std::size_t j = i; j > degree + 1 && knots[j - 1] > knots[j]; --j) std::swap(knots[j - 1], knots[j]);
  }
  const auto spline = Spline::create(std::span<const MachinePoint>(points.data(), count),
                                     std::span<const double>(knots.data(), knot_count), degree);
  if (!spline) return;
  (void)for_each_bezier(spline.value(), [&](const BezierSpan<double, 3, max_degree>& piece) {
    const auto control = piece.curve.control_points();
    job.add(PathSegment::make_bezier(std::span<const MachinePoint>(control.data(), control.size())), feed);
  });
}

Job read_job(InputReader& in, double scale) {
  Job job;
  MachinePoint at = read_point(in, scale);
  const std::size_t wanted = 1 + in.u8() % 6;
  for (std::size_t k = 0; k < wanted && !in.empty(); ++k) {
    const std::uint8_t kind = in.u8();
    const double feed = (kind & 0x80) ? scale * in.in_range(1, 200) : 0.0;
    const std::size_t before = job.count;
    switch (kind % 5) {
      case 0: job.add(PathSegment::make_line(at, read_point(in, scale)), feed); break;
      case 1: {
        const MachinePoint centre = read_point(in, scale);
        MachinePoint end = read_point(in, scale);
        // Put the end on the start's circle, mostly, so the radii agree.
        const double r = std::hypot(at[0] - centre[0], at[1] - centre[1]);
        const double angle = in.in_range(-3.2, 3.2);
        if (in.u8() < 224) end = MachinePoint{{centre[0] + r * std::cos(angle), centre[1] + r * std::sin(angle), end[2]}};
        const auto direction = (in.u8() & 1) ? ArcDirection::Clockwise : ArcDirection::CounterClockwise;
        job.add(PathSegment::make_arc(at, end, centre, direction, in.u8() % 3, scale * 1e-3), feed);
        break;
      }
      case 2:
      case 3: {
        const std::size_t n = 2 + in.u8() % 7;
        std::array<MachinePoint, 8> control{};
        std::array<double, 8> weights{};
        control[0] = at;
        for (std::size_t i = 1; i < n; ++i) {
          // Sometimes repeat the previous point: coincident control points and cusps.
          control[i] = in.u8() < 40 ? control[i - 1] : read_point(in, scale);
        }
        for (std::size_t i = 0; i < n; ++i) weights[i] = in.u8() < 8 ? in.any_double() : in.in_range(0.05, 20);
        const std::span<const MachinePoint> points(control.data(), n);
        if (kind % 5 == 2) job.add(PathSegment::make_bezier(points), feed);
        else job.add(PathSegment::make_rational_bezier(points, std::span<const double>(weights.data(), n)), feed);
        break;
      }
      default: add_bspline(in, job, at, scale, feed); break;
    }
    if (job.count > before) {
      if (in.u8() < 16) job.segments[job.count - 1].set_rapid(true);
      at = job.segments[job.count - 1].end();
    }
  }
  return job;
}

template <Scalar S>
void check_position(const Setpoint<S>& sp) {
  for (const S& c : sp.position) {
    if constexpr (FixedPoint<S>) {
      (void)c;  // every bit pattern of a Fixed is a finite value inside its range
    } else {
      CURVESTEP_FUZZ_ASSERT(std::isfinite(c));
    }
  }
}

/// The largest distance between consecutive setpoints the limits allow (see step_margin), plus the
/// rounding of both positions to the scalar's grid (√3·2^-17 mm each for Q16.16).
template <Scalar S>
double max_step_mm(const MachineLimits& limits) {
  const double rounding = FixedPoint<S> ? 2 * std::sqrt(3.0) * 0x1p-17 : 1e-9 * limits.v_max_mm_per_s / limits.rate_hz;
  return step_margin * limits.v_max_mm_per_s / limits.rate_hz + rounding;
}

template <Scalar S>
double distance_mm(const Setpoint<S>& a, const Setpoint<S>& b) {
  double sum = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    const double d = to_double(a.position[i]) - to_double(b.position[i]);
    sum += d * d;
  }
  return std::sqrt(sum);
}

/// The no-jump property; a violation prints the figures before it is reported.
template <Scalar S>
void check_step(const Setpoint<S>& from, const Setpoint<S>& to, double max_step, const MachineLimits& limits) {
  const double step_mm = distance_mm(from, to);
  if (step_mm <= max_step) return;
  std::fprintf(stderr,
               "planner: setpoint %llu (segment %u, planned %.6g mm/s) moved %.6g mm in one tick from segment %u (%.6g mm/s), "
               "at most %.6g allowed (v_max %.6g mm/s, rate %.6g Hz)\n",
               static_cast<unsigned long long>(to.tick), static_cast<unsigned>(to.segment), to.speed_mm_per_s, step_mm,
               static_cast<unsigned>(from.segment), from.speed_mm_per_s, max_step, limits.v_max_mm_per_s, limits.rate_hz);
  CURVESTEP_FUZZ_ASSERT(step_mm <= max_step);
}

template <Scalar S>
void run(InputReader& in, const MachineLimits& limits, const Job& job) {
  static MotionController<S, 16, 8> controller;  // large: keep it off the stack
  controller = MotionController<S, 16, 8>{};
  if (!controller.configure(limits)) {
    CURVESTEP_FUZZ_ASSERT(!limits.validate());
    ++outcomes.refused_limits;
    return;
  }
  CURVESTEP_FUZZ_ASSERT(limits.validate().has_value());
  std::size_t pushed = 0;
  PathSegment last{};
  for (std::size_t i = 0; i < job.count; ++i) {
    const auto r = controller.try_push(job.segments[i], static_cast<std::uint32_t>(i));
    if (!r) {
      if (r.error() == Error::QueueFull) break;
      continue;  // a segment the planner refuses (DegenerateCurve, ...) is left out
    }
    last = job.segments[i];
    ++pushed;
  }
  if (pushed == 0) {
    ++outcomes.nothing_queued;
    return;
  }
  controller.end_of_job();
  CURVESTEP_FUZZ_ASSERT(controller.start().has_value());
  const std::uint64_t hold_at = in.u8() < 64 ? in.u16() : max_ticks;
  Setpoint<S> sp{};
  const double max_step = max_step_mm<S>(limits);
  std::uint64_t expected_tick = 0;
  for (std::uint64_t tick = 0; tick < max_ticks; ++tick) {
    if (tick == hold_at) controller.hold();
    if (controller.state() == ControllerState::Held) CURVESTEP_FUZZ_ASSERT(controller.resume().has_value());
    const auto next = controller.next_setpoint();
    if (!next) {
      CURVESTEP_FUZZ_ASSERT(controller.state() == ControllerState::Fault);
      CURVESTEP_FUZZ_ASSERT(controller.fault().code == next.error());
      ++outcomes.faulted;
      return;
    }
    if (expected_tick > 0) check_step(sp, next.value(), max_step, limits);
    sp = next.value();
    CURVESTEP_FUZZ_ASSERT(sp.tick == expected_tick);
    ++expected_tick;
    check_position(sp);
    CURVESTEP_FUZZ_ASSERT(std::isfinite(sp.speed_mm_per_s) && sp.speed_mm_per_s >= 0);
    if (controller.finished()) break;
  }
  if (!controller.finished()) {  // a long job: the tick budget ran out first
    ++outcomes.out_of_ticks;
    return;
  }
  ++outcomes.finished;
  const auto end = vec_from_doubles<S, 3>(to_doubles(last.end()));
  CURVESTEP_FUZZ_ASSERT(end.has_value());
  for (std::size_t a = 0; a < 3; ++a) CURVESTEP_FUZZ_ASSERT(sp.position[a] == end.value()[a]);
}

/// The job and limits an input makes (CURVESTEP_FUZZ_PRINT_JOB=1), for reading a finding.
void print_job(const Job& job, const MachineLimits& limits) {
  for (std::size_t i = 0; i < job.count; ++i) {
    const PathSegment& s = job.segments[i];
    std::fprintf(stderr, "segment %zu: kind %d, length %.6g mm, feed %.6g, rapid %d\n", i, static_cast<int>(s.kind()),
                 std::hypot(s.end()[0] - s.start()[0], s.end()[1] - s.start()[1], s.end()[2] - s.start()[2]), s.feed_mm_per_s(), s.rapid() ? 1 : 0);
    if (s.kind() == SegmentKind::RationalBezier) {
      const auto points = s.rational().control_points();
      for (std::size_t k = 0; k < points.size(); ++k) std::fprintf(stderr, "  (%.6g, %.6g, %.6g) w %.6g\n", points[k][0], points[k][1], points[k][2], s.rational().weight(k));
      std::fprintf(stderr, "  table speed factor %.6g\n", curvestep::host::table_speed_factor(s));
    }
  }
  std::fprintf(stderr, "limits: v_max %g a_max %g j_max %g feed %g tol %g rate %g jerk %d\n", limits.v_max_mm_per_s, limits.a_max_mm_per_s2,
               limits.j_max_mm_per_s3, limits.feed_mm_per_s, limits.tolerance_mm, limits.rate_hz, limits.jerk_limited ? 1 : 0);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  curvestep::contract_handler = curvestep::fuzz::report_contract;
  InputReader in(data, size);
  const std::uint8_t mode = in.u8();
  static constexpr std::array<double, 4> scales{1, 50, 1000, 30000};
  const double scale = scales[mode % 4];
  const MachineLimits limits = read_limits(in, scale);
  const Job job = read_job(in, scale);
  if (std::getenv("CURVESTEP_FUZZ_PRINT_JOB") != nullptr) print_job(job, limits);
  if ((mode & 4) != 0) run<double>(in, limits, job);
  else run<Q16_16>(in, limits, job);
  return 0;
}
