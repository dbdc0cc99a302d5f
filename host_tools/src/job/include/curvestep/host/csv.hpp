// SPDX-License-Identifier: MIT
// CSV output of points: shortest round-trip number text, header x,y,z.
#pragma once

#include <functional>
#include <ostream>
#include <span>
#include <string>

#include <curvestep/core/motion/path_segment.hpp>

namespace curvestep::host {

/// Shortest text that reads back as the same double ("0.90625", "1e+09", "0").
[[nodiscard]] std::string format_number(double value);

/// Writes "x,y,z" and one line per point.
void write_points_csv(std::ostream& out, std::span<const MachinePoint> points);

/// Runs `write` on the file `path`, or on standard output when `path` is empty. Throws
/// std::runtime_error naming the file if it cannot be opened or written.
void write_output(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace curvestep::host
