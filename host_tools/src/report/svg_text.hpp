// SPDX-License-Identifier: MIT
// Helpers shared by the SVG and HTML writers: escaping, number text, tick steps, colours.
#pragma once

#include <string>
#include <string_view>

namespace curvestep::host::report_detail {

/// `text` made printable() (control characters and invalid UTF-8 as \xNN), then &, <, >, " and ' as entities.
[[nodiscard]] std::string escape(std::string_view text);

/// A pixel coordinate with two decimals ("12.35").
[[nodiscard]] std::string pixel(double value);

/// A figure with `digits` significant digits ("%.*g").
[[nodiscard]] std::string figure(double value, int digits = 4);

/// The largest 1, 2 or 5 × 10^k not above `limit` (limit > 0).
[[nodiscard]] double nice_step_below(double limit);

/// The colour (#rrggbb) of `fraction` in 0..1 on a perceptually ordered dark-blue → yellow scale.
[[nodiscard]] std::string speed_colour(double fraction);

/// The colour (#rrggbb) of segment `index` (ten distinct colours, repeating).
[[nodiscard]] std::string segment_colour(std::size_t index);

}  // namespace curvestep::host::report_detail
