// SPDX-License-Identifier: MIT
// Probe: forward differencing (plain, rational, adaptive), flattening and arc-length tables in Q16.16 and float.
#include <curvestep/core.hpp>

#include "probe.hpp"

namespace curvestep::probe {
namespace {

template <Scalar S>
void exercise_sampling(S quarter) {
  using P = Vec2<S>;
  const S one = from_int<S>(1);
  const S two = one + one;
  const auto cubic = Bezier<S, 2, 5>::create({P{{S{}, S{}}}, P{{one, two}}, P{{two, one}}, P{{two + one, S{}}}});
  if (!cubic) return;
  const auto& c = cubic.value();
  if (auto fd = ForwardDifference<S, 2>::create(c, 1000)) {
    auto stepper = fd.value();
    while (!stepper.finished()) stepper.step();
    sink = sink + static_cast<std::int32_t>(to_double(stepper.point()[0]) * 1000);
  }
  const auto arc = circular_arc<S, 5>(P{{S{}, S{}}}, P{{one, S{}}}, P{{S{}, one}}, ArcDirection::CounterClockwise, quarter);
  if (arc) {
    if (auto rfd = RationalForwardDifference<S, 2>::create(arc.value(), 100)) {
      auto stepper = rfd.value();
      while (!stepper.finished()) stepper.step();
      sink = sink + static_cast<std::int32_t>(to_double(stepper.point()[1]) * 1000);
    }
    std::array<P, 64> polyline{};
    if (auto n = flatten_into(arc.value(), constant<S>(0.01), std::span<P>(polyline))) sink = sink + static_cast<std::int32_t>(n.value());
  }
  if (auto afd = AdaptiveForwardDifference<S, 2>::create(c, 6)) {
    auto stepper = afd.value();
    while (!stepper.finished()) stepper.step_within(0.05, 0.2);
    sink = sink + static_cast<std::int32_t>(stepper.level());
  }
  std::array<P, 128> polyline{};
  if (auto n = flatten_into(c, constant<S>(0.01), std::span<P>(polyline))) sink = sink + static_cast<std::int32_t>(n.value());
  if (auto table = ArcLengthTable<Bezier<S, 2, 5>, 32>::create(c, constant<S>(0.01))) {
    if (auto t = table.value().parameter_at(one)) sink = sink + static_cast<std::int32_t>(to_double(t.value()) * 1000);
  }
}

}  // namespace

void probe_sampling() {
  exercise_sampling<Q16_16>(Q16_16::constant(0.25));
  exercise_sampling<float>(static_cast<float>(sink) * 1e-9f + 0.25f);
}

}  // namespace curvestep::probe
