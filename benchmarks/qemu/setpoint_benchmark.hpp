// SPDX-License-Identifier: MIT
// Bare-metal setpoint benchmark: forward differencing and de Casteljau per 3-axis cubic setpoint,
// each bracketed by calls to curvestep_bench_mark(id) so that an instruction trace (QEMU
// -singlestep -d exec,nochain) counts exactly the instructions executed between the marks
// (benchmarks/qemu/count_instructions.py). No timer is read: the figures are instruction counts.
//
// Curve: the 1000 mm acceptance cubic of benchmarks/forward_difference_benchmark.cpp (same
// per-point work: the point is folded into a checksum that is printed, so nothing is optimised away).
// Regions (id = 20 * scalar index + k): k = 1/2 empty region (the marks' own overhead),
// k = 3/4 forward differencing, first steady_steps setpoints (step + point, no re-seed while
// steady_steps < reseed_interval), k = 5/6 the remaining setpoints (re-seeds included), k = 7/8 de
// Casteljau (point_at per setpoint, t advanced by h), k = 9/10 step() alone and k = 11/12 step()
// plus point() stored to a volatile sink (no checksum fold), both over steady_steps fresh steps:
// they split the steady cost into its parts.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <type_traits>

#include <curvestep/boards/stm32/text.hpp>
#include <curvestep/core/curve/bezier.hpp>
#include <curvestep/core/sampling/forward_difference.hpp>

extern "C" void curvestep_bench_mark(std::uint32_t id);

namespace curvestep::bench {

inline constexpr std::uint32_t forward_difference_steps = 4096;  ///< setpoints of the forward-difference region
inline constexpr std::uint32_t steady_steps = 1024;              ///< setpoints of the steady (no re-seed) region
inline constexpr std::uint32_t de_casteljau_points = 512;        ///< setpoints of the de Casteljau region

/// The benchmark cubic in scalar S.
template <class S>
Bezier<S, 3, 3> benchmark_curve() noexcept {
  const auto v = [](double x, double y, double z) { return vec_from_doubles<S, 3>({x, y, z}).value(); };
  return Bezier<S, 3, 3>::create({v(0, 0, 0), v(250, 400, 30), v(750, -400, 60), v(1000, 0, 100)}).value();
}

/// Folds a point into the checksum (raw units in fixed point, truncated millimetres in float).
template <class S>
std::int64_t fold(const Vec<S, 3>& p) noexcept {
  if constexpr (FixedPoint<S>) {
    return static_cast<std::int64_t>(p[0].raw()) + p[1].raw() + p[2].raw();
  } else {
    return static_cast<std::int64_t>(p[0] + p[1] + p[2]);
  }
}

/// Runs the three regions for scalar S; `say` writes text to the console.
template <class S, class Say>
void run(std::uint32_t index, std::string_view label, Say&& say) noexcept {
  const auto put = [&](char c) { say(std::string_view(&c, 1)); };
  curvestep_bench_mark(20 * index + 1);
  curvestep_bench_mark(20 * index + 2);

  auto fd = ForwardDifference<S, 3, 3>::create(benchmark_curve<S>(), forward_difference_steps).value();
  std::int64_t fd_sum = 0;
  curvestep_bench_mark(20 * index + 3);
  for (std::uint32_t k = 0; k < steady_steps; ++k) {
    fd.step();
    fd_sum += fold(fd.point());
  }
  curvestep_bench_mark(20 * index + 4);
  curvestep_bench_mark(20 * index + 5);
  for (std::uint32_t k = steady_steps; k < forward_difference_steps; ++k) {
    fd.step();
    fd_sum += fold(fd.point());
  }
  curvestep_bench_mark(20 * index + 6);

  const auto curve = benchmark_curve<S>();
  const S h = from_double<S>(1.0 / de_casteljau_points).value();
  S t{};
  std::int64_t dc_sum = 0;
  curvestep_bench_mark(20 * index + 7);
  for (std::uint32_t k = 0; k < de_casteljau_points; ++k) {
    t += h;
    dc_sum += fold(curve.point_at(t));
  }
  curvestep_bench_mark(20 * index + 8);

  auto step_only = ForwardDifference<S, 3, 3>::create(benchmark_curve<S>(), forward_difference_steps).value();
  curvestep_bench_mark(20 * index + 9);
  for (std::uint32_t k = 0; k < steady_steps; ++k) step_only.step();
  curvestep_bench_mark(20 * index + 10);
  auto with_point = ForwardDifference<S, 3, 3>::create(benchmark_curve<S>(), forward_difference_steps).value();
  using Stored = std::conditional_t<FixedPoint<S>, std::int32_t, float>;
  static volatile Stored sink[3];
  curvestep_bench_mark(20 * index + 11);
  for (std::uint32_t k = 0; k < steady_steps; ++k) {
    with_point.step();
    const auto p = with_point.point();
    for (std::size_t axis = 0; axis < 3; ++axis) {
      if constexpr (FixedPoint<S>) {
        sink[axis] = p[axis].raw();
      } else {
        sink[axis] = p[axis];
      }
    }
  }
  curvestep_bench_mark(20 * index + 12);
  fd_sum += fold(step_only.point()) + fold(with_point.point());

  say("bench ");
  say(label);
  say(" index=");
  stm32::put_decimal(put, index);
  say(" fd_steps=");
  stm32::put_decimal(put, forward_difference_steps);
  say(" steady_steps=");
  stm32::put_decimal(put, steady_steps);
  say(" reseed_interval=");
  stm32::put_decimal(put, fd.reseed_interval());
  say(" fd_checksum=");
  stm32::put_signed(put, fd_sum);
  say(" dc_points=");
  stm32::put_decimal(put, de_casteljau_points);
  say(" dc_checksum=");
  stm32::put_signed(put, dc_sum);
  say("\r\n");
}

}  // namespace curvestep::bench
