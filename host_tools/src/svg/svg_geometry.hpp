// SPDX-License-Identifier: MIT
// Internal: SVG path data, transform lists and number lists parsed into pieces in user space.
//
// Elliptical arcs (SVG 1.1 implementation notes F.6.5/F.6.6): the endpoint form (x1,y1, rx,ry, φ,
// large-arc, sweep, x2,y2) is converted to the centre form (c, θ1, Δθ), radii too small for the
// chord being scaled by √Λ first. The ellipse is E(θ) = c + R(φ) diag(rx, ry) (cos θ, sin θ): the
// affine image of the unit circle. A unit-circle arc of sweep δ ≤ 90° is exactly the rational
// quadratic with end points on the circle, middle point (cos m, sin m)/cos(δ/2) (m the middle
// angle) and middle weight cos(δ/2); rational Béziers are affine invariant (map the control points,
// keep the weights), so the same construction mapped by c + R(φ) diag(rx, ry) is the exact
// elliptical arc. Δθ is split into ⌈|Δθ|/90°⌉ equal pieces; the last piece ends at (x2,y2) exactly.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace curvestep::host::svg {

/// A point in some 2D coordinate system.
struct Point2 {
  double x = 0;  ///< x
  double y = 0;  ///< y
  friend bool operator==(const Point2&, const Point2&) = default;
};

/// The affine map (x, y) -> (a x + c y + e, b x + d y + f), SVG's matrix(a b c d e f).
struct Affine {
  double a = 1, b = 0, c = 0, d = 1, e = 0, f = 0;
  /// The image of p.
  [[nodiscard]] Point2 apply(Point2 p) const noexcept { return {a * p.x + c * p.y + e, b * p.x + d * p.y + f}; }
};

/// left ∘ right: apply `right` first.
[[nodiscard]] Affine operator*(const Affine& left, const Affine& right) noexcept;

/// The kinds of pieces a subpath is made of.
enum class PieceKind { Line, Quadratic, Cubic, Conic };

/// One piece: 2 (line), 3 (quadratic, conic) or 4 (cubic) control points.
struct Piece {
  PieceKind kind = PieceKind::Line;   ///< what the points mean
  std::array<Point2, 4> points{};     ///< control points, `count` of them
  std::size_t count = 2;              ///< number of control points
  double weight = 1;                  ///< middle weight of a conic (end weights are 1)
  std::size_t position = 0;           ///< 1-based character of the path command that made it (0: not from path data)
};

/// A subpath: connected pieces from `start`.
struct Subpath {
  Point2 start;               ///< first point
  std::vector<Piece> pieces;  ///< connected pieces
  bool closed = false;        ///< ended with Z
};

/// Malformed text: `position` is the 1-based character in the attribute value.
class SyntaxError : public std::runtime_error {
 public:
  SyntaxError(std::size_t position, const std::string& message) : std::runtime_error(message), position_(position) {}
  /// 1-based character of the problem in the attribute value.
  [[nodiscard]] std::size_t position() const noexcept { return position_; }

 private:
  std::size_t position_;
};

/// Path data (the "d" attribute) -> subpaths in user space. SyntaxError on malformed data.
[[nodiscard]] std::vector<Subpath> parse_path_data(std::string_view data);

/// Path data read up to its first error (SVG's error rule).
struct PathData {
  std::vector<Subpath> subpaths;     ///< every complete command before the error
  std::optional<SyntaxError> error;  ///< the first error, if any
};

/// Path data -> the subpaths of the commands before the first error, and that error.
[[nodiscard]] PathData parse_path_data_until_error(std::string_view data);

/// A transform list ("translate(10) rotate(45 5 5)") -> its affine map. SyntaxError if malformed.
[[nodiscard]] Affine parse_transform(std::string_view text);

/// Numbers separated by whitespace and/or commas (points, viewBox). SyntaxError if malformed.
[[nodiscard]] std::vector<double> parse_number_list(std::string_view text);

/// A number list read up to its first error.
struct NumberList {
  std::vector<double> numbers;       ///< the numbers before the error
  std::optional<SyntaxError> error;  ///< the first error, if any
};

/// Numbers -> those before the first error, and that error.
[[nodiscard]] NumberList parse_number_list_until_error(std::string_view text);

/// A length attribute: a number and its unit text ("", "mm", "%", ...).
struct Length {
  double value = 0;   ///< the number
  std::string unit;   ///< the unit as written, empty for user units
};

/// "12.5mm" -> {12.5, "mm"}; surrounding whitespace allowed. SyntaxError if malformed.
[[nodiscard]] Length parse_length(std::string_view text);

/// Appends the SVG arc from `from` (the subpath's current point) to `to` as conics (or a line if
/// a radius is zero); nothing if from == to. std::overflow_error if the centre cannot be computed.
void append_elliptical_arc(Subpath& subpath, Point2 from, double rx, double ry, double rotation_deg, bool large_arc,
                           bool sweep, Point2 to);

/// Appends the quarter of the ellipse about `center` from center + u to center + v (u, v conjugate
/// semi-axes): the conic with middle point center + u + v and weight √2/2.
void append_quarter(Subpath& subpath, Point2 center, Point2 u, Point2 v);

/// Appends a line to `to` unless it ends where the subpath currently ends.
void append_line(Subpath& subpath, Point2 to);

/// The point where the subpath currently ends.
[[nodiscard]] Point2 end_point(const Subpath& subpath) noexcept;

}  // namespace curvestep::host::svg
