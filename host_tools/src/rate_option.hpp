// SPDX-License-Identifier: MIT
// The --rate option's check, shared by the commands that take one (sim, gpio).
#pragma once

#include <cmath>
#include <limits>
#include <string>

#include <CLI/CLI.hpp>

#include <curvestep/host/printable.hpp>

namespace curvestep::host {

/// Lowest and highest tick rate a command accepts (the core's MachineLimits::validate() range).
inline constexpr double min_rate_hz = 100;
inline constexpr double max_rate_hz = 100000;

/// Refuses a --rate that is not a finite number from 100 to 100000 Hz (nan, 0 and negative values
/// included) instead of leaving it to look like "not given".
inline CLI::Validator rate_hz_check() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::size_t used = 0;
        double value = std::numeric_limits<double>::quiet_NaN();
        try {
          value = std::stod(text, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used != text.size() || !std::isfinite(value) || value < min_rate_hz || value > max_rate_hz) {
          return "must be a number from 100 to 100000 Hz, got \"" + quoted_excerpt(text) + "\"";
        }
        return {};
      },
      "HZ", "tick rate");
}

}  // namespace curvestep::host
