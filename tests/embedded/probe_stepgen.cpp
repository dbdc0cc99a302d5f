// SPDX-License-Identifier: MIT
// Probe: step positions, the step-rate checks and the step generator in Q16.16 and float.
#include <array>
#include <span>

#include <curvestep/core/motion/step_generator.hpp>
#include <curvestep/core/motion/step_output.hpp>

#include "probe.hpp"

namespace curvestep::probe {
namespace {

template <Scalar S>
void exercise_step_generator(S step) {
  MachineLimits limits;
  limits.axes[0].steps_per_mm = 80;
  limits.axes[1].steps_per_mm = 80;
  limits.axes[2].steps_per_mm = 400;
  const auto config = StepConfig::create(limits, StepTiming{});
  if (!config) return;
  std::array<Setpoint<S>, 4> job{};
  for (std::size_t i = 0; i < job.size(); ++i) {
    job[i].tick = i;
    job[i].position[0] = job[i > 0 ? i - 1 : 0].position[0] + step;
    job[i].position[1] = S{} - job[i].position[0];
  }
  if (auto report = measure_step_rate(std::span<const Setpoint<S>>(job), config.value())) {
    sink = sink + static_cast<std::int32_t>(report.value().peak_steps_per_tick[0]);
  }
  if (check_step_rate(std::span<const Setpoint<S>>(job), config.value())) sink = sink + 1;
  if (check_machine_step_rate(limits)) sink = sink + 1;
  StepGenerator generator(config.value());
  if (!generator.reset(job[0])) return;
  StepBatch<64> batch;
  CountingStepOutput counter;
  for (std::size_t i = 1; i < job.size(); ++i) {
    if (!generator.advance(job[i], batch)) return;
    play(batch, counter);
    sink = sink + static_cast<std::int32_t>(batch.size());
  }
  sink = sink + static_cast<std::int32_t>(counter.count(0)) + generator.count(1);
  if (auto steps = position_in_steps(step, config.value().scale(2))) sink = sink + steps.value();
}

}  // namespace

void probe_stepgen() {
  exercise_step_generator<Q16_16>(Q16_16::from_raw(static_cast<std::int32_t>(sink) + 3000));
  exercise_step_generator<float>(static_cast<float>(sink) * 1e-9f + 0.04f);
}

}  // namespace curvestep::probe
