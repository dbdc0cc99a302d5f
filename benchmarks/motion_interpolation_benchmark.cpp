// SPDX-License-Identifier: MIT
// Per-tick cost of MotionController::next_setpoint: chunked forward differencing against the exact
// per-tick evaluation (set_max_chunk_ticks(1)) on a job of curves, as JSON.
//
// Usage: motion_interpolation_benchmark [--rate HZ] [--repetitions R] [--method chunked|exact]
// The job (the same segments every time): a gentle 400 mm cubic, an S of two tight cubics, a
// line–arc–line chain, a rational quarter circle and a two-turn helix, joined by lines, run on a
// 3-axis machine (a_max 2000, j_max 50000, feed 50, tolerance 0.01) at --rate Hz (default 1000)
// with Q16.16 setpoints, as a firmware would. Each repetition queues the job on a fresh controller
// (not timed) and then times only the tick loop (bench_ticks_<method>), so both figures are the
// per-tick work including each segment's start (arc-length table and profile). Both methods run in
// the same process and the JSON gives their ratio; it also gives each method's exact
// evaluations and the largest deviation of the chunked double setpoints from the exact ones.
// benchmarks/run_motion_callgrind.sh counts instructions inside bench_ticks_chunked and
// bench_ticks_exact in one valgrind run.
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include <curvestep/core/motion/motion_controller.hpp>

namespace {

using namespace curvestep;

MachinePoint mp(double x, double y, double z = 0) { return MachinePoint{{x, y, z}}; }

std::vector<PathSegment> curve_job() {
  std::vector<PathSegment> job;
  auto cubic = [&](MachinePoint a, MachinePoint b, MachinePoint c, MachinePoint d) {
    const std::array<MachinePoint, 4> pts{a, b, c, d};
    job.push_back(PathSegment::make_bezier(pts).value());
  };
  auto line = [&](MachinePoint a, MachinePoint b) { job.push_back(PathSegment::make_line(a, b).value()); };
  cubic(mp(0, 0), mp(130, 60), mp(270, -60), mp(400, 0));
  cubic(mp(400, 0), mp(420, 40), mp(440, -40), mp(460, 0));
  cubic(mp(460, 0), mp(480, 40), mp(500, -40), mp(520, 0));
  line(mp(520, 0), mp(540, 0));
  job.push_back(PathSegment::make_arc(mp(540, 0), mp(540, 20), mp(540, 10), ArcDirection::CounterClockwise, 0, 1e-6).value());
  line(mp(540, 20), mp(520, 20));
  const std::array<MachinePoint, 3> quarter{mp(520, 20), mp(520, 30), mp(510, 30)};
  const std::array<double, 3> weights{1, std::sqrt(0.5), 1};
  job.push_back(PathSegment::make_rational_bezier(quarter, weights).value());
  line(mp(510, 30), mp(505, 30));
  job.push_back(PathSegment::make_arc(mp(505, 30, 0), mp(505, 30, 4), mp(500, 30), ArcDirection::Clockwise, 1, 1e-9).value());
  return job;
}

MachineLimits benchmark_machine(double rate) {
  MachineLimits m;
  m.v_max_mm_per_s = 200;
  m.a_max_mm_per_s2 = 2000;
  m.j_max_mm_per_s3 = 50000;
  m.feed_mm_per_s = 50;
  m.tolerance_mm = 0.01;
  m.rate_hz = rate;
  m.junction_deviation_mm = 0.05;
  return m;
}

template <class S>
using Controller = MotionController<S, 32, 16, 64>;

template <class S>
void queue_job(Controller<S>& c, const MachineLimits& machine, std::uint32_t max_chunk) {
  if (!c.configure(machine) || !c.set_max_chunk_ticks(max_chunk)) std::abort();
  const auto job = curve_job();
  for (std::size_t i = 0; i < job.size(); ++i) {
    if (!c.try_push(job[i], static_cast<std::uint32_t>(i))) std::abort();
  }
  c.end_of_job();
  if (!c.start()) std::abort();
}

template <class S>
std::int64_t fold(const Setpoint<S>& sp) {
  if constexpr (FixedPoint<S>) {
    return static_cast<std::int64_t>(sp.position[0].raw()) + sp.position[1].raw() + sp.position[2].raw();
  } else {
    return static_cast<std::int64_t>(sp.position[0] + sp.position[1] + sp.position[2]);
  }
}

/// The timed part: every tick of a started controller; returns a checksum, counts the ticks.
template <class S>
std::int64_t run_ticks(Controller<S>& c, std::uint64_t& ticks) {
  std::int64_t sum = 0;
  while (!c.finished()) {
    const auto sp = c.next_setpoint();
    if (!sp) std::abort();
    sum += fold(sp.value());
    ++ticks;
  }
  return sum;
}

}  // namespace

extern "C" {
__attribute__((noinline)) std::int64_t bench_ticks_chunked(void* c, std::uint64_t* ticks) {
  return run_ticks(*static_cast<Controller<Q16_16>*>(c), *ticks);
}
__attribute__((noinline)) std::int64_t bench_ticks_exact(void* c, std::uint64_t* ticks) {
  return run_ticks(*static_cast<Controller<Q16_16>*>(c), *ticks);
}
}

namespace {

struct Measured {
  double seconds = 0;
  std::uint64_t ticks = 0;
  std::uint64_t exact_evaluations = 0;
  std::uint64_t stepped_ticks = 0;
  std::int64_t checksum = 0;
};

Measured measure(const MachineLimits& machine, bool chunked, int repetitions) {
  Measured m;
  static Controller<Q16_16> controller;  // ~40 KiB: not on the stack
  for (int r = 0; r < repetitions; ++r) {
    controller.reset();
    queue_job(controller, machine, chunked ? HermiteChunk::max_ticks : 1);
    const auto start = std::chrono::steady_clock::now();
    m.checksum += chunked ? bench_ticks_chunked(&controller, &m.ticks) : bench_ticks_exact(&controller, &m.ticks);
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    m.seconds += elapsed.count();
    m.exact_evaluations += controller.interpolator_stats().exact_evaluations;
    m.stepped_ticks += controller.interpolator_stats().stepped_ticks;
  }
  return m;
}

/// Largest per-axis deviation of the chunked double setpoints from the exact ones.
double deviation(const MachineLimits& machine) {
  static Controller<double> a;
  static Controller<double> b;
  a.reset();
  b.reset();
  queue_job(a, machine, HermiteChunk::max_ticks);
  queue_job(b, machine, 1);
  double worst = 0;
  while (!a.finished() && !b.finished()) {
    const auto pa = a.next_setpoint();
    const auto pb = b.next_setpoint();
    if (!pa || !pb) std::abort();
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      worst = std::fmax(worst, std::fabs(pa.value().position[axis] - pb.value().position[axis]));
    }
  }
  if (a.finished() != b.finished()) std::abort();
  return worst;
}

}  // namespace

int main(int argc, char** argv) {
  double rate = 1000;
  int repetitions = 5;
  const char* only = nullptr;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--rate") == 0) rate = std::strtod(argv[i + 1], nullptr);
    else if (std::strcmp(argv[i], "--repetitions") == 0) repetitions = std::atoi(argv[i + 1]);
    else if (std::strcmp(argv[i], "--method") == 0) only = argv[i + 1];
  }
  const MachineLimits machine = benchmark_machine(rate);
  if (!machine.validate() || repetitions <= 0 ||
      (only != nullptr && std::strcmp(only, "chunked") != 0 && std::strcmp(only, "exact") != 0)) {
    std::fprintf(stderr, "usage: %s [--rate 100..100000] [--repetitions R>0] [--method chunked|exact]\n", argv[0]);
    return 2;
  }
  const auto runs = static_cast<std::uint64_t>(repetitions);
  const bool run_chunked = only == nullptr || std::strcmp(only, "chunked") == 0;
  const bool run_exact = only == nullptr || std::strcmp(only, "exact") == 0;
  const Measured chunked = run_chunked ? measure(machine, true, repetitions) : Measured{};
  const Measured exact = run_exact ? measure(machine, false, repetitions) : Measured{};
  auto per_tick_ns = [](const Measured& m) { return m.ticks == 0 ? 0.0 : 1e9 * m.seconds / static_cast<double>(m.ticks); };
  std::printf("{\n  \"job\": \"400 mm cubic, S of two cubics, line-arc-line, rational quarter circle, 2-turn helix (%zu segments)\",\n",
              curve_job().size());
  std::printf("  \"rate_hz\": %.0f,\n  \"repetitions\": %d,\n", rate, repetitions);
  std::printf("  \"ticks_per_run\": %llu,\n", static_cast<unsigned long long>((run_chunked ? chunked.ticks : exact.ticks) / runs));
  std::printf("  \"ns_per_tick\": {\"chunked\": %.1f, \"exact\": %.1f},\n", per_tick_ns(chunked), per_tick_ns(exact));
  std::printf("  \"exact_evaluations_per_run\": {\"chunked\": %llu, \"exact\": %llu},\n",
              static_cast<unsigned long long>(chunked.exact_evaluations / runs),
              static_cast<unsigned long long>(exact.exact_evaluations / runs));
  std::printf("  \"stepped_ticks_per_run\": %llu,\n", static_cast<unsigned long long>(chunked.stepped_ticks / runs));
  if (run_chunked && run_exact) {
    std::printf("  \"exact_over_chunked_time\": %.2f,\n", per_tick_ns(exact) / per_tick_ns(chunked));
    std::printf("  \"max_deviation_mm\": %.3g,\n", deviation(machine));
    std::printf("  \"same_checksum\": %s,\n", chunked.checksum == exact.checksum ? "true" : "false");
  }
  std::printf("  \"checksum\": %lld\n}\n", static_cast<long long>(chunked.checksum + exact.checksum));
  return 0;
}
