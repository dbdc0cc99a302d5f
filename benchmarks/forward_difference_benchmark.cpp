// SPDX-License-Identifier: MIT
// Setpoints per second of a 3-axis cubic: forward differencing vs de Casteljau vs Horner, as JSON.
//
// Usage: forward_difference_benchmark [--steps N] [--repetitions R] [--method NAME]
// Each method evaluates the same cubic at t = k/N for k = 0..N, R times, and folds every
// coordinate into a checksum so nothing is optimised away. The JSON also gives the largest
// deviation from a long-double de Casteljau over all points: the library's steppers and, for
// comparison, naive float forward differencing (seeded once, never re-seeded). Forward differencing includes its
// create() (the seed) and every re-seed. --method runs one method only (for callgrind:
// benchmarks/run_callgrind.sh counts the instructions inside the function bench_<method>).
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <curvestep/core/curve/bezier.hpp>
#include <curvestep/core/curve/power_basis.hpp>
#include <curvestep/core/sampling/forward_difference.hpp>

namespace {

using namespace curvestep;

template <class S>
Bezier<S, 3, 3> benchmark_curve() {
  // The 1000 mm acceptance cubic of tests/core/sampling/forward_difference_test.cpp.
  const auto v = [](double x, double y, double z) { return vec_from_doubles<S, 3>({x, y, z}).value(); };
  return Bezier<S, 3, 3>::create({v(0, 0, 0), v(250, 400, 30), v(750, -400, 60), v(1000, 0, 100)}).value();
}

template <class S>
std::int64_t fold(const Vec<S, 3>& p) {
  if constexpr (FixedPoint<S>) {
    return static_cast<std::int64_t>(p[0].raw()) + p[1].raw() + p[2].raw();
  } else {
    return static_cast<std::int64_t>(p[0] + p[1] + p[2]);
  }
}

template <class S>
std::int64_t run_forward_difference(std::uint32_t steps) {
  auto fd = ForwardDifference<S, 3, 3>::create(benchmark_curve<S>(), steps).value();
  std::int64_t sum = fold(fd.point());
  while (!fd.finished()) {
    fd.step();
    sum += fold(fd.point());
  }
  return sum;
}

template <class S>
S parameter_step(std::uint32_t steps) {
  return from_double<S>(1.0 / static_cast<double>(steps)).value();
}

template <class S>
std::int64_t run_de_casteljau(std::uint32_t steps) {
  const auto curve = benchmark_curve<S>();
  const S h = parameter_step<S>(steps);
  const S one = from_int<S>(1);
  S t{};
  std::int64_t sum = 0;
  for (std::uint32_t k = 0; k <= steps; ++k) {
    sum += fold(curve.point_at(one < t ? one : t));
    t += h;
  }
  return sum;
}

template <class S>
std::int64_t run_horner(std::uint32_t steps) {
  const auto power = to_power_basis(benchmark_curve<S>()).value();
  const S h = parameter_step<S>(steps);
  const S one = from_int<S>(1);
  S t{};
  std::int64_t sum = 0;
  for (std::uint32_t k = 0; k <= steps; ++k) {
    sum += fold(power.evaluate(one < t ? one : t));
    t += h;
  }
  return sum;
}

/// p(k/N) of the benchmark curve in long double (the accuracy reference).
std::array<long double, 3> reference(std::uint32_t k, std::uint32_t steps) {
  const auto curve = benchmark_curve<double>();
  std::array<std::array<long double, 3>, 4> w{};
  for (std::size_t i = 0; i < 4; ++i) {
    for (std::size_t a = 0; a < 3; ++a) w[i][a] = curve[i][a];
  }
  const long double t = static_cast<long double>(k) / steps;
  for (std::size_t r = 1; r <= 3; ++r) {
    for (std::size_t i = 0; i + r <= 3; ++i) {
      for (std::size_t a = 0; a < 3; ++a) w[i][a] = (1 - t) * w[i][a] + t * w[i + 1][a];
    }
  }
  return w[0];
}

template <class P>
long double deviation(const P& p, const std::array<long double, 3>& exact) {
  long double m = 0;
  for (std::size_t a = 0; a < 3; ++a) m = std::fmax(m, std::fabs(static_cast<long double>(to_double(p[a])) - exact[a]));
  return m;
}

/// Largest deviation of the library's stepper from the reference over all N+1 points (mm).
template <class S>
double stepper_error(std::uint32_t steps) {
  auto fd = ForwardDifference<S, 3, 3>::create(benchmark_curve<S>(), steps).value();
  long double worst = deviation(fd.point(), reference(0, steps));
  while (!fd.finished()) {
    fd.step();
    worst = std::fmax(worst, deviation(fd.point(), reference(fd.index(), steps)));
  }
  return static_cast<double>(worst);
}

/// The same for naive float forward differencing: seeded once from the power form, never
/// re-seeded, every addition in float (what the library avoids).
double naive_float_error(std::uint32_t steps) {
  const auto power = to_power_basis(benchmark_curve<double>()).value();
  const double h = 1.0 / steps;
  std::array<std::array<float, 4>, 3> d{};
  for (std::size_t a = 0; a < 3; ++a) {
    const double a1 = power.coefficients[1][a], a2 = power.coefficients[2][a], a3 = power.coefficients[3][a];
    d[a] = {static_cast<float>(power.coefficients[0][a]), static_cast<float>(a1 * h + a2 * h * h + a3 * h * h * h),
            static_cast<float>(2 * a2 * h * h + 6 * a3 * h * h * h), static_cast<float>(6 * a3 * h * h * h)};
  }
  long double worst = 0;
  for (std::uint32_t k = 0;; ++k) {
    const auto exact = reference(k, steps);
    for (std::size_t a = 0; a < 3; ++a) worst = std::fmax(worst, std::fabs(static_cast<long double>(d[a][0]) - exact[a]));
    if (k == steps) break;
    for (auto& axis : d) {
      axis[0] += axis[1];
      axis[1] += axis[2];
      axis[2] += axis[3];
    }
  }
  return static_cast<double>(worst);
}

}  // namespace

// C linkage and no inlining give callgrind plain names to toggle collection on.
extern "C" {
__attribute__((noinline)) std::int64_t bench_forward_difference_q16_16(std::uint32_t s) { return run_forward_difference<Q16_16>(s); }
__attribute__((noinline)) std::int64_t bench_forward_difference_float(std::uint32_t s) { return run_forward_difference<float>(s); }
__attribute__((noinline)) std::int64_t bench_de_casteljau_q16_16(std::uint32_t s) { return run_de_casteljau<Q16_16>(s); }
__attribute__((noinline)) std::int64_t bench_de_casteljau_float(std::uint32_t s) { return run_de_casteljau<float>(s); }
__attribute__((noinline)) std::int64_t bench_horner_q16_16(std::uint32_t s) { return run_horner<Q16_16>(s); }
__attribute__((noinline)) std::int64_t bench_horner_float(std::uint32_t s) { return run_horner<float>(s); }
}

namespace {

struct Method {
  const char* name;
  std::int64_t (*run)(std::uint32_t);
};

constexpr Method methods[] = {
    {"forward_difference_q16_16", bench_forward_difference_q16_16},
    {"forward_difference_float", bench_forward_difference_float},
    {"de_casteljau_q16_16", bench_de_casteljau_q16_16},
    {"de_casteljau_float", bench_de_casteljau_float},
    {"horner_q16_16", bench_horner_q16_16},
    {"horner_float", bench_horner_float},
};
constexpr std::size_t method_count = sizeof(methods) / sizeof(methods[0]);

}  // namespace

int main(int argc, char** argv) {
  std::uint32_t steps = 100000;
  int repetitions = 20;
  const char* only = nullptr;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--steps") == 0) steps = static_cast<std::uint32_t>(std::strtoul(argv[i + 1], nullptr, 10));
    else if (std::strcmp(argv[i], "--repetitions") == 0) repetitions = std::atoi(argv[i + 1]);
    else if (std::strcmp(argv[i], "--method") == 0) only = argv[i + 1];
  }
  if (steps == 0 || repetitions <= 0) {
    std::fprintf(stderr, "usage: %s [--steps N>0] [--repetitions R>0] [--method NAME]\n", argv[0]);
    return 2;
  }
  std::array<double, method_count> rate{};
  std::int64_t checksum = 0;
  for (std::size_t m = 0; m < method_count; ++m) {
    if (only != nullptr && std::strcmp(only, methods[m].name) != 0) continue;
    const auto start = std::chrono::steady_clock::now();
    for (int r = 0; r < repetitions; ++r) checksum += methods[m].run(steps);
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    rate[m] = static_cast<double>(steps + 1) * repetitions / elapsed.count();
  }
  if (only != nullptr) {
    std::printf("{\"method\": \"%s\", \"steps\": %u, \"checksum\": %lld}\n", only, steps, static_cast<long long>(checksum));
    return 0;
  }
  std::printf("{\n  \"curve\": \"3-axis cubic (0,0,0) (250,400,30) (750,-400,60) (1000,0,100) mm\",\n");
  std::printf("  \"steps\": %u,\n  \"repetitions\": %d,\n  \"setpoints_per_second\": {\n", steps, repetitions);
  for (std::size_t m = 0; m < method_count; ++m) {
    std::printf("    \"%s\": %.0f%s\n", methods[m].name, rate[m], m + 1 < method_count ? "," : "");
  }
  std::printf("  },\n  \"ratios\": {\n");
  std::printf("    \"forward_difference_q16_16_over_de_casteljau_q16_16\": %.2f,\n", rate[0] / rate[2]);
  std::printf("    \"forward_difference_float_over_de_casteljau_float\": %.2f,\n", rate[1] / rate[3]);
  std::printf("    \"forward_difference_q16_16_over_horner_q16_16\": %.2f,\n", rate[0] / rate[4]);
  std::printf("    \"forward_difference_float_over_horner_float\": %.2f\n", rate[1] / rate[5]);
  std::printf("  },\n  \"max_error_mm\": {\n");
  std::printf("    \"forward_difference_q16_16\": %.3g,\n", stepper_error<Q16_16>(steps));
  std::printf("    \"forward_difference_float\": %.3g,\n", stepper_error<float>(steps));
  std::printf("    \"naive_float_forward_difference\": %.3g\n", naive_float_error(steps));
  std::printf("  },\n  \"checksum\": %lld\n}\n", static_cast<long long>(checksum));
  return 0;
}
