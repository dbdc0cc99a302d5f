// SPDX-License-Identifier: MIT
// The rotation of a coordinate system about Z (LinuxCNC's G10 L2 R, degrees counter-clockwise).
//
// LinuxCNC turns the program's XY (after adding the G92 offset) by the angle of the coordinate
// system in use, then adds the system's offset: machine = R(program + G92) + G5x (emccanon.cc
// rotate_and_offset). Z never turns. This type holds the angle with its cosine and sine, so a
// block's points turn with one multiplication each; an angle of 0 turns nothing, exactly.
#pragma once

#include <cmath>
#include <numbers>

#include <curvestep/core/geometry/vec.hpp>

namespace curvestep::gcode {

/// A turn of the XY plane about Z by `degrees` (counter-clockwise seen from +Z).
class XyRotation {
 public:
  using Point = Vec<double, 3>;

  constexpr XyRotation() noexcept = default;
  /// No trigonometry for 0 (the usual case: every block of an unrotated program asks).
  explicit XyRotation(double degrees) noexcept : degrees_(degrees) {
    if (degrees_ != 0) {
      cos_ = std::cos(radians());
      sin_ = std::sin(radians());
    }
  }

  [[nodiscard]] constexpr double degrees() const noexcept { return degrees_; }
  [[nodiscard]] constexpr double radians() const noexcept { return degrees_ * (std::numbers::pi / 180.0); }
  /// No turn at all (then `turned` and `turned_back` return their argument unchanged).
  [[nodiscard]] constexpr bool none() const noexcept { return degrees_ == 0; }

  /// `p` with its X and Y turned by the angle; Z kept.
  [[nodiscard]] constexpr Point turned(const Point& p) const noexcept {
    if (none()) return p;
    return Point{{p[0] * cos_ - p[1] * sin_, p[0] * sin_ + p[1] * cos_, p[2]}};
  }
  /// `p` with its X and Y turned back by the angle (the inverse of `turned`); Z kept.
  [[nodiscard]] constexpr Point turned_back(const Point& p) const noexcept {
    if (none()) return p;
    return Point{{p[0] * cos_ + p[1] * sin_, -p[0] * sin_ + p[1] * cos_, p[2]}};
  }

 private:
  double degrees_ = 0;
  double cos_ = 1;
  double sin_ = 0;
};

}  // namespace curvestep::gcode
