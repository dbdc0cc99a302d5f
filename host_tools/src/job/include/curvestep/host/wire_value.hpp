// SPDX-License-Identifier: MIT
// Weights and feeds on the Q16.16 grid, as the wire carries them: one rounding, with one set of
// errors, for every importer (job files, G-code, SVG), so the simulator sees what a device receives.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include <curvestep/core/error.hpp>

namespace curvestep::host {

/// What is rounded: it names the value in a problem and picks the code of a value rounding to 0.
enum class WireQuantity : std::uint8_t { Weight, Feed };

/// A weight or feed rounded for the wire, or why it cannot travel.
struct WireValue {
  double value = 0;                   ///< the nearest Q16.16 value, as a double (when there is no problem)
  std::string problem;                ///< empty, or the cause: "weight 40000 is outside the Q16.16 range (at most 32767.99998)"
  Error code = Error::FixedOverflow;  ///< the problem's code (meaningless without a problem)
  /// True if the value can travel.
  [[nodiscard]] explicit operator bool() const noexcept { return problem.empty(); }
};

/// `value` rounded to the nearest Q16.16 value (ties away from zero, as Q16_16::from_double).
/// Problems: a value outside Q16.16 (or not finite) is FixedOverflow; a positive value that rounds
/// to 0 is NonPositiveWeight for a weight, InvalidArgument for a feed. Zero and negative values are
/// rounded without complaint (the callers check signs with their own messages). `name` names the
/// value in the problem ("feed (mm/s)"); empty: "weight" or "feed".
[[nodiscard]] WireValue round_for_wire(double value, WireQuantity quantity, std::string_view name = {});

}  // namespace curvestep::host
