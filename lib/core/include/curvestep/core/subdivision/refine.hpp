// SPDX-License-Identifier: MIT
// One step of mask-based polygon refinement (closed, finite and pseudo-finite ends), no heap.
//
// New vertex p_i = Σ_k m_{i − a·k} P_k (see subdivision_mask.hpp), old vertex k at position a·k.
// Boundary handling (seed 001 §8.3):
//   * Closed:       P_{k+N} = P_k; N old vertices give exactly a·N new ones, p_0 … p_{aN−1}.
//   * Finite:       only new vertices whose whole stencil (its non-zero taps) lies on existing
//                   vertices P_0 … P_K are produced; vertices are lost at the ends. The longest
//                   contiguous run is returned (the four-point scheme also has isolated p_0 = P_0
//                   and p_{aK} = P_K, which are not part of a polygon and are dropped).
//   * PseudoFinite: P_k = P_0 for k < 0 and P_k = P_K for k > K (endpoint replication). The new
//                   polygon runs from the last vertex still equal to P_0 to the first equal to P_K,
//                   so the end points stay fixed and repeated refinement converges to an open curve.
// The result says which p_i were written: first_index and count. Each new vertex is an exact
// integer combination of at most ⌈L/a⌉ old vertices rounded once (Fixed), so dyadic masks on
// Q16.16 data are exact; schemes with negative weights (four-point) can leave the hull of the
// data, which is checked (FixedOverflow, index = new vertex). Work: O(count · L).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>

#include <curvestep/core/detail/exact_combination.hpp>
#include <curvestep/core/geometry/vec.hpp>
#include <curvestep/core/subdivision/subdivision_mask.hpp>

namespace curvestep {

/// How the ends of the polygon are treated.
enum class Boundary : std::uint8_t {
  Closed,        ///< cyclic polygon
  Finite,        ///< open; new vertices only where the full stencil exists
  PseudoFinite,  ///< open; end points replicated infinitely
};

/// Which new vertices a refinement step produced: p_first_index … p_{first_index + count − 1}.
struct RefinedRange {
  std::int64_t first_index = 0;  ///< i of the first new vertex (in the p_i numbering)
  std::size_t count = 0;         ///< number of new vertices written
};

namespace detail {

/// Floor division for a positive divisor.
[[nodiscard]] constexpr std::int64_t floor_divide_positive(std::int64_t n, std::int64_t d) noexcept {
  const std::int64_t q = n / d;
  return (n % d != 0 && n < 0) ? q - 1 : q;
}

/// Smallest and largest old index k touched by the non-zero taps of p_i.
struct TapSpan {
  std::int64_t lowest = 0;
  std::int64_t highest = 0;
};
[[nodiscard]] constexpr TapSpan tap_span(const SubdivisionMask& mask, std::int64_t i) noexcept {
  const auto a = static_cast<std::int64_t>(mask.arity());
  TapSpan span{std::numeric_limits<std::int64_t>::max(), std::numeric_limits<std::int64_t>::min()};
  for (std::int64_t s = mask.first_index(); s <= mask.last_index(); ++s) {
    if (mask.numerator(s) == 0 || (i - s) % a != 0) continue;
    const std::int64_t k = (i - s) / a;
    if (k < span.lowest) span.lowest = k;
    if (k > span.highest) span.highest = k;
  }
  return span;
}

/// The range of new vertices produced for an open polygon with old vertices 0..last.
[[nodiscard]] constexpr RefinedRange refined_open_range(const SubdivisionMask& mask, std::int64_t last, Boundary boundary) noexcept {
  const auto a = static_cast<std::int64_t>(mask.arity());
  const std::int64_t from = mask.first_index() - a;
  const std::int64_t to = a * last + mask.last_index() + a;
  if (boundary == Boundary::PseudoFinite) {
    std::int64_t low = from;
    std::int64_t high = to;
    for (std::int64_t i = from; i <= to; ++i) {
      if (tap_span(mask, i).highest <= 0) low = i;
    }
    for (std::int64_t i = to; i >= from; --i) {
      if (tap_span(mask, i).lowest >= last) high = i;
    }
    return RefinedRange{low, high >= low ? static_cast<std::size_t>(high - low + 1) : 0};
  }
  RefinedRange best{};
  std::int64_t run_start = 0;
  std::size_t run = 0;
  for (std::int64_t i = from; i <= to; ++i) {
    const TapSpan taps = tap_span(mask, i);
    if (taps.lowest >= 0 && taps.highest <= last) {
      if (run == 0) run_start = i;
      ++run;
      if (run > best.count) best = RefinedRange{run_start, run};
    } else {
      run = 0;
    }
  }
  return best;
}

}  // namespace detail

/// Number and position of the new vertices one step produces for `vertex_count` old vertices.
/// TooFewPoints for an empty closed polygon or fewer than 2 open vertices.
[[nodiscard]] constexpr Result<RefinedRange> refined_range(const SubdivisionMask& mask, std::size_t vertex_count,
                                                           Boundary boundary) noexcept {
  if (mask.length() == 0) return fail(Error::InvalidMask);
  if (boundary == Boundary::Closed) {
    if (vertex_count == 0) return fail(Error::TooFewPoints, 0);
    return RefinedRange{0, mask.arity() * vertex_count};
  }
  if (vertex_count < 2) return fail(Error::TooFewPoints, vertex_count);
  return detail::refined_open_range(mask, static_cast<std::int64_t>(vertex_count) - 1, boundary);
}

/// One refinement step of `polygon` into `output`. BufferTooSmall (index = vertices needed) if
/// output is short, TooFewPoints, InvalidMask for a default-constructed mask, FixedOverflow /
/// NotFinite (index = position in output) if a new vertex leaves the range.
/// Contract: output does not overlap polygon.
template <Scalar S, std::size_t Dim>
[[nodiscard]] constexpr Result<RefinedRange> refine(const SubdivisionMask& mask, std::span<const Vec<S, Dim>> polygon,
                                                    Boundary boundary, std::span<Vec<S, Dim>> output) noexcept {
  CURVESTEP_TRY(const RefinedRange range, refined_range(mask, polygon.size(), boundary));
  if (output.size() < range.count) return fail(Error::BufferTooSmall, range.count);
  const auto a = static_cast<std::int64_t>(mask.arity());
  const auto n = static_cast<std::int64_t>(polygon.size());
  std::array<Vec<S, Dim>, SubdivisionMask::max_length> taps{};
  std::array<std::int64_t, SubdivisionMask::max_length> weights{};
  for (std::size_t out = 0; out < range.count; ++out) {
    const std::int64_t i = range.first_index + static_cast<std::int64_t>(out);
    std::size_t used = 0;
    for (std::int64_t s = mask.first_index(); s <= mask.last_index(); ++s) {
      if (mask.numerator(s) == 0 || (i - s) % a != 0) continue;
      std::int64_t k = (i - s) / a;
      if (boundary == Boundary::Closed) {
        k = k - n * detail::floor_divide_positive(k, n);
      } else if (k < 0) {
        k = 0;
      } else if (k >= n) {
        k = n - 1;
      }
      taps[used] = polygon[static_cast<std::size_t>(k)];
      weights[used] = mask.numerator(s);
      ++used;
    }
    const auto vertex = detail::exact_combination<S, Dim>(std::span<const Vec<S, Dim>>(taps.data(), used),
                                                          std::span<const std::int64_t>(weights.data(), used), mask.denominator());
    if (!vertex) return fail(vertex.error(), out);
    output[out] = vertex.value();
  }
  return range;
}

}  // namespace curvestep
