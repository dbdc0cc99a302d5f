// SPDX-License-Identifier: MIT
// SubdivisionMask: the integer mask of a stationary, uniform subdivision scheme, validated.
//
// A scheme of arity a maps old vertices P_k (placed at positions j = a·k) to new vertices
//   p_i = Σ_k m_{i − a·k} · P_k,   i ∈ ℤ                      (seed 001 §8.3, eq. 23)
// The mask m is stored as integer numerators over one positive denominator, so that a new vertex
// is an exact integer combination rounded once (Fixed) — dyadic masks are exact in Q16.16.
// Index convention (seed 001): a mask of length L holds m_f … m_{f+L−1} with f = −⌊L/2⌋, i.e.
// odd lengths are centred (m_i = m_{−i} for a symmetric scheme) and even lengths satisfy
// m_{i−1} = m_{−i}. The a stencils are the residues i mod a; every stencil is an affine
// combination, so its numerators must sum to the denominator (the necessary condition for
// convergence; seed 001 §8.4). A mask violating that is rejected with Error::InvalidMask.
// The four schemes of seed 001: cubic B-spline [1,4,6,4,1]/8 (C2), Chaikin [1,3,3,1]/4 (C1),
// ternary quadratic [1,3,6,7,6,3,1]/9 (C1, see erratum E2), four-point [−1,0,9,16,9,0,−1]/16
// (interpolating, C1, reproduces cubics).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <span>

#include <curvestep/core/result.hpp>

namespace curvestep {

/// A validated subdivision mask: arity, integer numerators m_f..m_{f+L-1} and a denominator.
class SubdivisionMask {
 public:
  static constexpr std::size_t max_length = 15;  ///< longest mask stored
  static constexpr std::size_t max_arity = 8;    ///< largest arity accepted (the seed uses 2 and 3)

  /// An empty, invalid mask (use create()).
  constexpr SubdivisionMask() = default;

  /// Validates and stores a mask. InvalidArgument (index 0) for arity outside 2..max_arity,
  /// CapacityExceeded (index = length) above max_length, InvalidMask for an empty mask, a
  /// non-positive denominator (index = length) or a stencil whose numerators do not sum to the
  /// denominator (index = the stencil's residue i mod a).
  [[nodiscard]] static constexpr Result<SubdivisionMask> create(std::size_t arity, std::span<const std::int32_t> numerators,
                                                                std::int32_t denominator) noexcept {
    if (arity < 2 || arity > max_arity) return fail(Error::InvalidArgument, 0);
    if (numerators.empty()) return fail(Error::InvalidMask, 0);
    if (numerators.size() > max_length) return fail(Error::CapacityExceeded, numerators.size());
    if (denominator <= 0) return fail(Error::InvalidMask, numerators.size());
    SubdivisionMask mask;
    mask.arity_ = arity;
    mask.length_ = numerators.size();
    mask.denominator_ = denominator;
    for (std::size_t i = 0; i < numerators.size(); ++i) mask.numerators_[i] = numerators[i];
    for (std::size_t residue = 0; residue < arity; ++residue) {
      if (mask.stencil_sum(residue) != denominator) return fail(Error::InvalidMask, residue);
    }
    return mask;
  }

  /// Convenience: create(arity, {n...}, denominator).
  [[nodiscard]] static constexpr Result<SubdivisionMask> create(std::size_t arity, std::initializer_list<std::int32_t> numerators,
                                                                std::int32_t denominator) noexcept {
    return create(arity, std::span<const std::int32_t>(numerators.begin(), numerators.size()), denominator);
  }

  /// a: 2 for binary, 3 for ternary schemes.
  [[nodiscard]] constexpr std::size_t arity() const noexcept { return arity_; }
  /// L, the number of stored numerators.
  [[nodiscard]] constexpr std::size_t length() const noexcept { return length_; }
  /// The common denominator of the mask entries.
  [[nodiscard]] constexpr std::int32_t denominator() const noexcept { return denominator_; }
  /// f = −⌊L/2⌋, the index of the first stored entry.
  [[nodiscard]] constexpr std::int64_t first_index() const noexcept { return -static_cast<std::int64_t>(length_ / 2); }
  /// f + L − 1, the index of the last stored entry.
  [[nodiscard]] constexpr std::int64_t last_index() const noexcept {
    return first_index() + static_cast<std::int64_t>(length_) - 1;
  }
  /// The numerator of m_index (0 outside the stored range).
  [[nodiscard]] constexpr std::int32_t numerator(std::int64_t index) const noexcept {
    if (index < first_index() || index > last_index()) return 0;
    return numerators_[static_cast<std::size_t>(index - first_index())];
  }
  /// Σ_k numerator(residue − a·k): the stencil of new vertices i ≡ residue (mod a).
  [[nodiscard]] constexpr std::int64_t stencil_sum(std::size_t residue) const noexcept {
    std::int64_t sum = 0;
    for (std::int64_t index = first_index(); index <= last_index(); ++index) {
      const std::int64_t shifted = index - static_cast<std::int64_t>(residue);
      if (shifted % static_cast<std::int64_t>(arity_) == 0) sum += numerator(index);
    }
    return sum;
  }

 private:
  std::array<std::int32_t, max_length> numerators_{};
  std::size_t arity_ = 2;
  std::size_t length_ = 0;
  std::int32_t denominator_ = 1;
};

/// Uniform cubic B-spline scheme (Lane–Riesenfeld), binary, [1,4,6,4,1]/8; limit C2.
[[nodiscard]] constexpr SubdivisionMask cubic_bspline_mask() noexcept {
  return SubdivisionMask::create(2, {1, 4, 6, 4, 1}, 8).value();
}
/// Chaikin's corner cutting, binary, [1,3,3,1]/4; limit: the uniform quadratic B-spline, C1.
[[nodiscard]] constexpr SubdivisionMask chaikin_mask() noexcept { return SubdivisionMask::create(2, {1, 3, 3, 1}, 4).value(); }
/// Ternary quadratic scheme, [1,3,6,7,6,3,1]/9; limit: the uniform quadratic B-spline, C1.
[[nodiscard]] constexpr SubdivisionMask ternary_quadratic_mask() noexcept {
  return SubdivisionMask::create(3, {1, 3, 6, 7, 6, 3, 1}, 9).value();
}
/// Dubuc / Dyn–Levin–Gregory four-point scheme, binary, [−1,0,9,16,9,0,−1]/16: interpolating, C1.
[[nodiscard]] constexpr SubdivisionMask four_point_mask() noexcept {
  return SubdivisionMask::create(2, {-1, 0, 9, 16, 9, 0, -1}, 16).value();
}

}  // namespace curvestep
