// SPDX-License-Identifier: MIT
// Probe: Bézier, rational Bézier, arcs, composite curves, curvature and arc length in Q16.16 and float.
#include <curvestep/core.hpp>

#include "probe.hpp"

namespace curvestep::probe {
namespace {

template <Scalar S>
void exercise_curves(S quarter) {
  using P = Vec2<S>;
  const S one = from_int<S>(1);
  const auto cubic = Bezier<S, 2, 7>::create({P{{S{}, S{}}}, P{{one, one + one}}, P{{one + one, one}}, P{{one + one + one, S{}}}});
  if (!cubic) return;
  const auto& c = cubic.value();
  sink = sink + static_cast<std::int32_t>(to_double(c.point_at(quarter)[0]) * 1000);
  if (auto h = c.split(quarter)) sink = sink + static_cast<std::int32_t>(h.value().left.degree());
  if (auto e = c.elevated()) sink = sink + static_cast<std::int32_t>(e.value().degree());
  if (auto k = curvature(c, quarter)) sink = sink + static_cast<std::int32_t>(to_double(k.value()) * 1000);
  if (auto l = arc_length(c, S{}, one, constant<S>(0.01))) sink = sink + static_cast<std::int32_t>(to_double(l.value()));
  if (auto p = to_power_basis(c)) sink = sink + static_cast<std::int32_t>(p.value().degree);
  const auto arc = circular_arc<S>(P{{S{}, S{}}}, P{{one, S{}}}, P{{S{}, one}}, ArcDirection::CounterClockwise, constant<S>(0.01));
  if (arc) sink = sink + static_cast<std::int32_t>(to_double(arc.value().point_at(quarter)[1]) * 1000);
  CompositeBezier<S, 2, 7, 16> path;
  if (path.try_append(c, one)) {
    if (auto p = path.evaluate(quarter)) sink = sink + static_cast<std::int32_t>(to_double(p.value()[0]));
  }
}

}  // namespace

void probe_core_curves() {
  exercise_curves<Q16_16>(Q16_16::constant(0.25));
  exercise_curves<float>(static_cast<float>(sink) * 1e-9f + 0.25f);
}

}  // namespace curvestep::probe
