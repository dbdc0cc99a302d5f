// SPDX-License-Identifier: MIT
// SVG path data, transform lists and number lists (SVG 1.1 grammar), and elliptical arcs as conics.
#include "svg_geometry.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>
#include <system_error>

#include <curvestep/host/csv.hpp>

namespace curvestep::host::svg {
namespace {

constexpr double half_pi = std::numbers::pi / 2;

bool is_space(char c) noexcept { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f'; }
bool is_digit(char c) noexcept { return c >= '0' && c <= '9'; }

/// Reads numbers, flags and separators from an attribute value.
class Scanner {
 public:
  explicit Scanner(std::string_view text) : text_(text) {}

  [[nodiscard]] bool at_end() const noexcept { return position_ >= text_.size(); }
  [[nodiscard]] char peek() const noexcept { return at_end() ? '\0' : text_[position_]; }
  [[nodiscard]] std::size_t position() const noexcept { return position_; }
  void advance() noexcept { ++position_; }

  void skip_space() noexcept {
    while (!at_end() && is_space(peek())) ++position_;
  }
  /// Whitespace with at most one comma.
  void skip_separator() noexcept {
    skip_space();
    if (peek() == ',') {
      ++position_;
      skip_space();
    }
  }
  [[nodiscard]] bool number_follows() const noexcept {
    const char c = peek();
    return is_digit(c) || c == '.' || c == '-' || c == '+';
  }

  [[noreturn]] void fail(const std::string& message) const { throw SyntaxError(position_ + 1, message); }

  /// The text at the current position, for messages ("NaN", "x", "end of data").
  [[nodiscard]] std::string what_is_here() const {
    if (at_end()) return "the end of the data";
    std::size_t end = position_;
    while (end < text_.size() && end - position_ < 12 && !is_space(text_[end]) && text_[end] != ',') ++end;
    if (end == position_) end = position_ + 1;
    return "\"" + std::string(text_.substr(position_, end - position_)) + "\"";
  }

  /// number ::= sign? (digits ('.' digits?)? | '.' digits) (('e'|'E') sign? digits)?
  double number(const char* what = "a number") {
    const std::size_t begin = position_;
    std::size_t i = position_;
    if (i < text_.size() && (text_[i] == '+' || text_[i] == '-')) ++i;
    std::size_t digits = 0;
    while (i < text_.size() && is_digit(text_[i])) ++i, ++digits;
    if (i < text_.size() && text_[i] == '.') {
      std::size_t j = i + 1;
      std::size_t fraction = 0;
      while (j < text_.size() && is_digit(text_[j])) ++j, ++fraction;
      if (digits + fraction > 0) {
        i = j;
        digits += fraction;
      }
    }
    if (digits == 0) fail(std::string("expected ") + what + ", got " + what_is_here());
    if (i < text_.size() && (text_[i] == 'e' || text_[i] == 'E')) {
      std::size_t j = i + 1;
      if (j < text_.size() && (text_[j] == '+' || text_[j] == '-')) ++j;
      if (j < text_.size() && is_digit(text_[j])) {
        while (j < text_.size() && is_digit(text_[j])) ++j;
        i = j;
      }
    }
    std::string_view token = text_.substr(begin, i - begin);
    const std::string_view digits_text = token.front() == '+' ? token.substr(1) : token;
    double value = 0;
    const auto [end, error] = std::from_chars(digits_text.data(), digits_text.data() + digits_text.size(), value);
    if (error == std::errc::result_out_of_range) {
      const auto exponent = token.find_first_of("eE");
      if (exponent != std::string_view::npos && token[exponent + 1] == '-') {
        value = 0;  // underflow: a number too small to represent is zero for any drawing
      } else {
        fail("the number " + std::string(token) + " is too large");
      }
    } else if (error != std::errc() || end != digits_text.data() + digits_text.size()) {
      fail("malformed number \"" + std::string(token) + "\"");
    }
    if (!std::isfinite(value)) fail("the number " + std::string(token) + " is too large");
    position_ = i;
    return value;
  }

  /// An arc flag: the single character 0 or 1.
  bool flag(const char* what) {
    const char c = peek();
    if (c != '0' && c != '1') fail(std::string("expected the ") + what + " (0 or 1), got " + what_is_here());
    ++position_;
    return c == '1';
  }

 private:
  std::string_view text_;
  std::size_t position_ = 0;
};

Point2 operator+(Point2 p, Point2 q) noexcept { return {p.x + q.x, p.y + q.y}; }
Point2 reflect(Point2 control, Point2 about) noexcept { return {2 * about.x - control.x, 2 * about.y - control.y}; }

/// Signed angle from u to v in (-π, π].
double angle_between(Point2 u, Point2 v) noexcept { return std::atan2(u.x * v.y - u.y * v.x, u.x * v.x + u.y * v.y); }

/// cos and sin of an angle in degrees, exact for multiples of 90°.
Point2 cos_sin_degrees(double degrees) noexcept {
  const double turns = degrees / 90;
  if (turns == std::floor(turns) && std::fabs(turns) < 1e15) {
    const auto quarter = static_cast<long long>(std::fmod(turns, 4.0)) & 3;
    constexpr Point2 table[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    return table[quarter];
  }
  const double radians = degrees * std::numbers::pi / 180;
  return {std::cos(radians), std::sin(radians)};
}

class PathParser {
 public:
  explicit PathParser(std::string_view data) : scan_(data) {}

  /// The subpaths up to the first error, and that error (SVG's rule: render up to the error).
  PathData parse_until_error() {
    PathData result;
    try {
      result.subpaths = parse();
    } catch (const SyntaxError& error) {
      result.error = error;
      result.subpaths = std::move(subpaths_);
    }
    return result;
  }

  std::vector<Subpath> parse() {
    char command = 0;
    while (true) {
      scan_.skip_space();
      if (scan_.at_end()) break;
      const char c = scan_.peek();
      const std::size_t position = scan_.position() + 1;  // the command letter, or the first number of a repetition
      if (std::string_view("MmLlHhVvCcSsQqTtAaZz").find(c) != std::string_view::npos) {
        if (subpaths_.empty() && c != 'M' && c != 'm') {
          scan_.fail(std::string("path data must begin with a moveto (M or m), got \"") + c + "\"");
        }
        command = c;
        scan_.advance();
        scan_.skip_space();
      } else if (command == 0) {
        scan_.fail("path data must begin with a moveto (M or m), got " + scan_.what_is_here());
      } else if (!scan_.number_follows()) {
        scan_.fail("expected a path command or a number, got " + scan_.what_is_here());
      } else if (command == 'Z' || command == 'z') {
        scan_.fail("closepath (Z) takes no numbers, got " + scan_.what_is_here());
      }
      const std::size_t subpaths_before = subpaths_.size();
      const std::size_t pieces_before = subpaths_.empty() ? 0 : subpaths_.back().pieces.size();
      execute(command);
      mark_new_pieces(subpaths_before, pieces_before, position);
      // Further argument sets repeat the command; after a moveto they are linetos.
      if (command == 'M') command = 'L';
      if (command == 'm') command = 'l';
      scan_.skip_space();
      if (scan_.peek() == ',') {
        scan_.advance();
        scan_.skip_space();
        if (!scan_.number_follows()) scan_.fail("a comma must be followed by a number, got " + scan_.what_is_here());
      }
    }
    return std::move(subpaths_);
  }

 private:
  /// Records `position` in the pieces added since there were `subpaths_before` subpaths and the
  /// last one had `pieces_before` pieces.
  void mark_new_pieces(std::size_t subpaths_before, std::size_t pieces_before, std::size_t position) {
    for (std::size_t s = subpaths_before == 0 ? 0 : subpaths_before - 1; s < subpaths_.size(); ++s) {
      auto& pieces = subpaths_[s].pieces;
      for (std::size_t i = s + 1 == subpaths_before ? pieces_before : 0; i < pieces.size(); ++i) pieces[i].position = position;
    }
  }

  Point2 pair(bool relative) {
    const double x = scan_.number("a coordinate");
    scan_.skip_separator();
    const double y = scan_.number("a coordinate");
    return relative ? current_ + Point2{x, y} : Point2{x, y};
  }

  double coordinate() { return scan_.number("a coordinate"); }

  Subpath& drawing() {
    if (subpaths_.empty() || subpaths_.back().closed) {
      subpaths_.push_back(Subpath{current_, {}, false});  // after Z: a new subpath at the same point
    }
    return subpaths_.back();
  }

  void curve(PieceKind kind, std::initializer_list<Point2> points) {
    Piece piece;
    piece.kind = kind;
    piece.count = points.size();
    std::size_t i = 0;
    bool moves = false;
    for (const auto& p : points) {
      piece.points[i++] = p;
      if (!(p == *points.begin())) moves = true;
    }
    if (moves) drawing().pieces.push_back(piece);
    else drawing();
  }

  void execute(char command) {
    const bool relative = command >= 'a' && command <= 'z';
    const char upper = static_cast<char>(relative ? command - 'a' + 'A' : command);
    Point2 control_out{};
    bool cubic_control = false;
    bool quadratic_control = false;
    switch (upper) {
      case 'M': {
        const Point2 to = pair(relative);
        subpaths_.push_back(Subpath{to, {}, false});
        current_ = to;
        break;
      }
      case 'L': {
        const Point2 to = pair(relative);
        append_line(drawing(), to);
        current_ = to;
        break;
      }
      case 'H': {
        const double x = coordinate();
        const Point2 to{relative ? current_.x + x : x, current_.y};
        append_line(drawing(), to);
        current_ = to;
        break;
      }
      case 'V': {
        const double y = coordinate();
        const Point2 to{current_.x, relative ? current_.y + y : y};
        append_line(drawing(), to);
        current_ = to;
        break;
      }
      case 'C':
      case 'S': {
        Point2 c1;
        if (upper == 'C') {
          c1 = pair(relative);
          scan_.skip_separator();
        } else {
          c1 = previous_cubic_ ? reflect(last_control_, current_) : current_;
        }
        const Point2 c2 = pair(relative);
        scan_.skip_separator();
        const Point2 to = pair(relative);
        curve(PieceKind::Cubic, {current_, c1, c2, to});
        control_out = c2;
        cubic_control = true;
        current_ = to;
        break;
      }
      case 'Q':
      case 'T': {
        Point2 c1;
        if (upper == 'Q') {
          c1 = pair(relative);
          scan_.skip_separator();
        } else {
          c1 = previous_quadratic_ ? reflect(last_control_, current_) : current_;
        }
        const Point2 to = pair(relative);
        curve(PieceKind::Quadratic, {current_, c1, to});
        control_out = c1;
        quadratic_control = true;
        current_ = to;
        break;
      }
      case 'A': {
        const double rx = scan_.number("the x radius");
        scan_.skip_separator();
        const double ry = scan_.number("the y radius");
        scan_.skip_separator();
        const double rotation = scan_.number("the x-axis rotation");
        scan_.skip_separator();
        const bool large = scan_.flag("large-arc flag");
        scan_.skip_separator();
        const bool sweep = scan_.flag("sweep flag");
        scan_.skip_separator();
        const Point2 to = pair(relative);
        try {
          append_elliptical_arc(drawing(), current_, rx, ry, rotation, large, sweep, to);
        } catch (const std::overflow_error& error) {
          scan_.fail(error.what());
        }
        current_ = to;
        break;
      }
      case 'Z': {
        if (!subpaths_.empty() && !subpaths_.back().closed) {
          Subpath& open = subpaths_.back();
          append_line(open, open.start);
          open.closed = true;
          current_ = open.start;
        }
        break;
      }
      default: scan_.fail("unknown command");
    }
    previous_cubic_ = cubic_control;
    previous_quadratic_ = quadratic_control;
    last_control_ = control_out;
  }

  Scanner scan_;
  std::vector<Subpath> subpaths_;
  Point2 current_{};
  Point2 last_control_{};
  bool previous_cubic_ = false;
  bool previous_quadratic_ = false;
};

}  // namespace

Affine operator*(const Affine& l, const Affine& r) noexcept {
  return {l.a * r.a + l.c * r.b, l.b * r.a + l.d * r.b, l.a * r.c + l.c * r.d,
          l.b * r.c + l.d * r.d, l.a * r.e + l.c * r.f + l.e, l.b * r.e + l.d * r.f + l.f};
}

Point2 end_point(const Subpath& subpath) noexcept {
  if (subpath.pieces.empty()) return subpath.start;
  const Piece& last = subpath.pieces.back();
  return last.points[last.count - 1];
}

void append_line(Subpath& subpath, Point2 to) {
  const Point2 from = end_point(subpath);
  if (from == to) return;
  Piece piece;
  piece.kind = PieceKind::Line;
  piece.count = 2;
  piece.points[0] = from;
  piece.points[1] = to;
  subpath.pieces.push_back(piece);
}

void append_quarter(Subpath& subpath, Point2 center, Point2 u, Point2 v) {
  Piece piece;
  piece.kind = PieceKind::Conic;
  piece.count = 3;
  piece.points[0] = end_point(subpath);
  piece.points[1] = center + u + v;
  piece.points[2] = center + v;
  piece.weight = std::numbers::sqrt2 / 2;
  subpath.pieces.push_back(piece);
}

void append_elliptical_arc(Subpath& subpath, Point2 from, double rx, double ry, double rotation_deg, bool large_arc,
                           bool sweep, Point2 to) {
  if (from == to) return;  // F.6.2: an arc with equal end points is omitted
  rx = std::fabs(rx);
  ry = std::fabs(ry);
  if (rx == 0 || ry == 0) {  // F.6.2: a zero radius makes a straight line
    append_line(subpath, to);
    return;
  }
  const Point2 cs = cos_sin_degrees(std::fmod(rotation_deg, 360.0));
  const double cos_phi = cs.x;
  const double sin_phi = cs.y;
  // F.6.5 step 1: the half chord in the ellipse's axes.
  const double hx = (from.x - to.x) / 2;
  const double hy = (from.y - to.y) / 2;
  const double x1 = cos_phi * hx + sin_phi * hy;
  const double y1 = -sin_phi * hx + cos_phi * hy;
  // F.6.6: radii too small to span the chord grow uniformly until they just do.
  const double lambda = (x1 / rx) * (x1 / rx) + (y1 / ry) * (y1 / ry);
  if (lambda > 1) {
    const double grow = std::sqrt(lambda);
    rx *= grow;
    ry *= grow;
  }
  // Step 2: the centre in the ellipse's axes. F.6.5.2 divided through by rx² ry² (X = x1'/rx,
  // Y = y1'/ry), so that large radii do not overflow: c' = ±sqrt((1 - X² - Y²)/(X² + Y²)) (rx Y, -ry X).
  const double x_unit = x1 / rx;
  const double y_unit = y1 / ry;
  const double chord_squared = x_unit * x_unit + y_unit * y_unit;
  if (!(chord_squared > 0)) {  // radii so large against the chord that the small arc is its chord
    if (!large_arc) {
      append_line(subpath, to);
      return;
    }
  }
  double factor = std::sqrt(std::max(0.0, 1 - chord_squared) / chord_squared);
  if (large_arc == sweep) factor = -factor;
  const double cx1 = factor * rx * y_unit;
  const double cy1 = -factor * ry * x_unit;
  // Step 3: the centre in user space.
  const Point2 center{cos_phi * cx1 - sin_phi * cy1 + (from.x + to.x) / 2, sin_phi * cx1 + cos_phi * cy1 + (from.y + to.y) / 2};
  // Step 4: start angle and sweep.
  const Point2 u{(x1 - cx1) / rx, (y1 - cy1) / ry};
  const Point2 v{(-x1 - cx1) / rx, (-y1 - cy1) / ry};
  const double theta1 = angle_between({1, 0}, u);
  double delta = angle_between(u, v);
  if (!sweep && delta > 0) delta -= 2 * std::numbers::pi;
  if (sweep && delta < 0) delta += 2 * std::numbers::pi;
  if (!std::isfinite(cx1) || !std::isfinite(cy1) || !std::isfinite(delta)) {
    throw std::overflow_error("the arc's ellipse is too large to compute (radii " + format_number(rx) + " and " +
                              format_number(ry) + " for a chord of " + format_number(2 * std::hypot(hx, hy)) + ")");
  }
  // The ellipse as the affine image of the unit circle.
  const Affine ellipse{cos_phi * rx, sin_phi * rx, -sin_phi * ry, cos_phi * ry, center.x, center.y};
  const auto pieces = static_cast<std::size_t>(std::ceil(std::fabs(delta) / half_pi - 1e-9));
  const std::size_t count = std::clamp<std::size_t>(pieces, 1, 4);
  const double step = delta / static_cast<double>(count);
  const double weight = std::cos(step / 2);
  Point2 start = end_point(subpath);
  for (std::size_t k = 0; k < count; ++k) {
    const double a = theta1 + step * static_cast<double>(k);
    const double middle = a + step / 2;
    Piece piece;
    piece.kind = PieceKind::Conic;
    piece.count = 3;
    piece.weight = weight;
    piece.points[0] = start;
    piece.points[1] = ellipse.apply({std::cos(middle) / weight, std::sin(middle) / weight});
    piece.points[2] = k + 1 == count ? to : ellipse.apply({std::cos(a + step), std::sin(a + step)});
    subpath.pieces.push_back(piece);
    start = piece.points[2];
  }
}

std::vector<Subpath> parse_path_data(std::string_view data) { return PathParser(data).parse(); }

PathData parse_path_data_until_error(std::string_view data) { return PathParser(data).parse_until_error(); }

Length parse_length(std::string_view text) {
  Scanner scan(text);
  scan.skip_space();
  Length length;
  length.value = scan.number();
  while (!scan.at_end() && (std::isalpha(static_cast<unsigned char>(scan.peek())) != 0 || scan.peek() == '%')) {
    length.unit += scan.peek();
    scan.advance();
  }
  scan.skip_space();
  if (!scan.at_end()) scan.fail("unexpected " + scan.what_is_here() + " after the length");
  return length;
}

std::vector<double> parse_number_list(std::string_view text) {
  NumberList list = parse_number_list_until_error(text);
  if (list.error) throw *list.error;
  return std::move(list.numbers);
}

NumberList parse_number_list_until_error(std::string_view text) {
  NumberList list;
  Scanner scan(text);
  try {
    scan.skip_space();
    while (!scan.at_end()) {
      list.numbers.push_back(scan.number());
      const std::size_t before = scan.position();
      scan.skip_separator();
      if (scan.at_end() && scan.position() != before && text.substr(before).find(',') != std::string_view::npos) {
        scan.fail("the list ends with a comma");
      }
    }
  } catch (const SyntaxError& error) {
    list.error = error;
  }
  return list;
}

Affine parse_transform(std::string_view text) {
  Scanner scan(text);
  Affine result;
  scan.skip_separator();
  while (!scan.at_end()) {
    const std::size_t name_start = scan.position();
    std::string name;
    while (!scan.at_end() && ((scan.peek() >= 'a' && scan.peek() <= 'z') || (scan.peek() >= 'A' && scan.peek() <= 'Z'))) {
      name += scan.peek();
      scan.advance();
    }
    if (name.empty()) scan.fail("expected a transform (matrix, translate, scale, rotate, skewX or skewY), got " + scan.what_is_here());
    if (name != "matrix" && name != "translate" && name != "scale" && name != "rotate" && name != "skewX" && name != "skewY") {
      throw SyntaxError(name_start + 1, "unknown transform \"" + name + "\" (expected matrix, translate, scale, rotate, skewX or skewY)");
    }
    scan.skip_space();
    if (scan.peek() != '(') scan.fail("expected \"(\" after " + name + ", got " + scan.what_is_here());
    scan.advance();
    std::vector<double> args;
    scan.skip_space();
    while (scan.peek() != ')') {
      if (scan.at_end()) scan.fail("missing \")\" after the arguments of " + name);
      if (!args.empty()) scan.skip_separator();
      args.push_back(scan.number());
      scan.skip_space();
    }
    const std::size_t close = scan.position();
    scan.advance();
    const std::size_t n = args.size();
    auto count_error = [&](const char* expected) {
      throw SyntaxError(close + 1, name + " takes " + expected + " numbers, got " + std::to_string(n));
    };
    Affine m;
    if (name == "matrix") {
      if (n != 6) count_error("6");
      m = {args[0], args[1], args[2], args[3], args[4], args[5]};
    } else if (name == "translate") {
      if (n != 1 && n != 2) count_error("1 or 2");
      m.e = args[0];
      m.f = n == 2 ? args[1] : 0;
    } else if (name == "scale") {
      if (n != 1 && n != 2) count_error("1 or 2");
      m.a = args[0];
      m.d = n == 2 ? args[1] : args[0];
    } else if (name == "rotate") {
      if (n != 1 && n != 3) count_error("1 or 3");
      const Point2 cs = cos_sin_degrees(std::fmod(args[0], 360.0));
      const Affine rotation{cs.x, cs.y, -cs.y, cs.x, 0, 0};
      if (n == 3) {
        m = Affine{1, 0, 0, 1, args[1], args[2]} * rotation * Affine{1, 0, 0, 1, -args[1], -args[2]};
      } else {
        m = rotation;
      }
    } else {
      if (n != 1) count_error("1");
      const Point2 cs = cos_sin_degrees(std::fmod(args[0], 360.0));
      if (cs.x == 0) throw SyntaxError(close + 1, name + "(" + std::to_string(args[0]) + "): the skew angle must not be 90°");
      const double slope = cs.y / cs.x;
      if (name == "skewX") m.c = slope;
      else m.b = slope;
    }
    result = result * m;
    scan.skip_separator();
  }
  return result;
}

}  // namespace curvestep::host::svg
