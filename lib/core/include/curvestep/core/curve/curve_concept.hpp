// SPDX-License-Identifier: MIT
// ParametricCurve: what the analysis algorithms (curvature, arc length, sampling) need of a curve.
#pragma once

#include <cstddef>

#include <curvestep/core/result.hpp>
#include <curvestep/core/scalar.hpp>

namespace curvestep {

/// A curve with a scalar type, a point type, a point on its domain and derivatives of any order.
template <class C>
concept ParametricCurve = requires(const C& curve, typename C::scalar_type t, std::size_t order) {
  typename C::scalar_type;
  typename C::Point;
  { curve.evaluate(t) } -> std::same_as<Result<typename C::Point>>;
  { curve.derivative_at(t, order) } -> std::same_as<Result<typename C::Point>>;
};

}  // namespace curvestep
