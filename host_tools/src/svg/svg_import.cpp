// SPDX-License-Identifier: MIT
// SVG documents (tinyxml2) -> machine-space subpaths -> a host Job, optionally reordered.
//
// Coordinates: user space is mapped to millimetres with y down by the root viewport (width,
// height, viewBox, preserveAspectRatio; user units are px = 1/96 in without a viewBox), then
// flipped to machine coordinates with y up about the page's bottom edge: y_machine = H - y_mm, H the
// page height in mm (y_machine = -y_mm when the page has no height), so the page's bottom-left
// corner is the machine origin. Each element's affine map is that root map ∘ the transforms of its
// ancestors and its own; pieces are mapped point by point (exact for Béziers and rational Béziers).
//
// Wire grid: the wire carries coordinates, weights and feeds as Q16.16, so all three are rounded
// to the nearest Q16.16 value here, by the same Q16_16::from_double the job loader and the G-code
// importer use (docs/job_format.md, "Weights and feeds"): the simulator then sees the job exactly
// as a device receives it. An arc's middle weight is cos(δ/2) with δ ≤ 90°, so it lies in
// [√2/2, 1] and rounds by at most 2^-17; the weight √2/2 of quarter arcs becomes 46341/65536.
#include <curvestep/host/svg_import.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <utility>

#include <tinyxml2.h>

#include <curvestep/core/error_text.hpp>
#include <curvestep/core/fixed/fixed.hpp>
#include <curvestep/host/csv.hpp>
#include <curvestep/host/printable.hpp>
#include <curvestep/host/wire_value.hpp>

#include "svg_geometry.hpp"

namespace curvestep::host {
namespace {

using svg::Affine;
using svg::Piece;
using svg::PieceKind;
using svg::Point2;
using svg::Subpath;
using svg::SyntaxError;

constexpr double mm_per_inch = 25.4;
constexpr double mm_per_px = mm_per_inch / 96;

/// Millimetres per unit, for the absolute units SVG knows.
std::optional<double> mm_per_unit(const std::string& unit) {
  if (unit.empty() || unit == "px") return mm_per_px;
  if (unit == "mm") return 1.0;
  if (unit == "cm") return 10.0;
  if (unit == "in") return mm_per_inch;
  if (unit == "pt") return mm_per_inch / 72;
  if (unit == "pc") return mm_per_inch / 6;
  if (unit == "Q") return 0.25;
  return std::nullopt;
}

/// One drawn piece in machine coordinates (mm, on the Q16.16 grid).
struct MachinePiece {
  SegmentType type = SegmentType::Line;
  std::vector<MachinePoint> points;
  std::vector<double> weights;  ///< rational pieces only
};

/// One pen-down stretch.
struct DrawnSubpath {
  std::vector<MachinePiece> pieces;
  std::size_t line = 0;  ///< line of the element in the file
  [[nodiscard]] const MachinePoint& start() const { return pieces.front().points.front(); }
  [[nodiscard]] const MachinePoint& end() const { return pieces.back().points.back(); }
  [[nodiscard]] bool closed() const { return start() == end(); }
  void reverse() {
    std::reverse(pieces.begin(), pieces.end());
    for (auto& piece : pieces) {
      std::reverse(piece.points.begin(), piece.points.end());
      std::reverse(piece.weights.begin(), piece.weights.end());
    }
  }
};

double distance(const MachinePoint& a, const MachinePoint& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

std::string trim(std::string_view text) {
  std::size_t begin = 0;
  std::size_t end = text.size();
  while (begin < end && std::isspace(static_cast<unsigned char>(text[begin])) != 0) ++begin;
  while (end > begin && std::isspace(static_cast<unsigned char>(text[end - 1])) != 0) --end;
  return std::string(text.substr(begin, end - begin));
}

/// The element name without an "svg:" prefix.
std::string local_name(const tinyxml2::XMLElement& element) {
  std::string name = element.Name();
  if (name.rfind("svg:", 0) == 0) name = name.substr(4);
  return name;
}

/// Plain words for tinyxml2's error ids.
std::string xml_error_text(tinyxml2::XMLError error) {
  switch (error) {
    case tinyxml2::XML_ERROR_EMPTY_DOCUMENT: return "the file is empty";
    case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT: return "an end tag does not match its start tag";
    case tinyxml2::XML_ERROR_PARSING_ELEMENT: return "malformed element (an unclosed tag or a missing end tag)";
    case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE: return "malformed attribute (attribute values need quotes)";
    case tinyxml2::XML_ERROR_PARSING_TEXT: return "malformed text";
    case tinyxml2::XML_ERROR_PARSING_CDATA: return "malformed CDATA section";
    case tinyxml2::XML_ERROR_PARSING_COMMENT: return "malformed comment";
    case tinyxml2::XML_ERROR_PARSING_DECLARATION: return "malformed declaration";
    case tinyxml2::XML_ERROR_PARSING_UNKNOWN: return "malformed <!...> construct";
    default: return "malformed XML";
  }
}

class SvgReader {
 public:
  SvgReader(std::string_view text, std::string name, const SvgOptions& options)
      : text_(text), name_(std::move(name)), options_(options) {}

  SvgImport read() {
    document_.Parse(text_.data(), text_.size());
    if (document_.Error()) {
      std::string detail;
      if (const char* raw = document_.ErrorStr()) {
        const std::string all = raw;
        const auto colon = all.find(": ", all.find("Line number="));
        if (all.find("Line number=") != std::string::npos && colon != std::string::npos) detail = " (" + all.substr(colon + 2) + ")";
      }
      fail_at(static_cast<std::size_t>(std::max(document_.ErrorLineNum(), 0)), "", "invalid XML: " + xml_error_text(document_.ErrorID()) + detail);
    }
    const tinyxml2::XMLElement* root = document_.RootElement();
    if (root == nullptr) fail_at(1, "", "invalid XML: no root element");
    if (local_name(*root) != "svg") fail(*root, "", "the root element is <" + std::string(root->Name()) + ">, expected <svg>");
    index_ids(*root);
    const Affine root_map = root_viewport(*root);
    visit_children(*root, root_map);
    if (drawn_.empty()) fail(*root, "", "the drawing has no paths or shapes to draw");
    return build();
  }

 private:
  // ---- errors ------------------------------------------------------------------------------
  [[noreturn]] void fail_at(std::size_t line, const std::string& field, const std::string& message, Error code = Error::InvalidJob) const {
    SourceLocation location;
    location.file = name_;
    location.line = line;
    location.field = field;
    throw LoadError(std::move(location), message, code);
  }

  static std::string label(const tinyxml2::XMLElement& element) {
    std::string text = "<" + std::string(element.Name());
    if (const char* id = element.Attribute("id")) text += " id=\"" + std::string(id) + "\"";
    return text + ">";
  }

  static std::string field(const tinyxml2::XMLElement& element, const char* attribute) {
    std::string text = label(element);
    if (attribute != nullptr && *attribute != '\0') text += " \"" + std::string(attribute) + "\"";
    return text;
  }

  [[noreturn]] void fail(const tinyxml2::XMLElement& element, const char* attribute, const std::string& message,
                         Error code = Error::InvalidJob) const {
    fail_at(static_cast<std::size_t>(element.GetLineNum()), field(element, attribute), message, code);
  }

  [[noreturn]] void fail_syntax(const tinyxml2::XMLElement& element, const char* attribute, const SyntaxError& error) const {
    fail(element, attribute, "at character " + std::to_string(error.position()) + ": " + error.what());
  }

  void warn(const tinyxml2::XMLElement& element, const std::string& message) {
    warnings_.push_back(name_ + ":" + std::to_string(element.GetLineNum()) + ": " + label(element) + " " + message);
  }

  // ---- attributes --------------------------------------------------------------------------
  /// A length attribute in user units (absolute units converted at 96 px per inch); `fallback` if absent.
  double length(const tinyxml2::XMLElement& element, const char* attribute, double fallback) const {
    const char* raw = element.Attribute(attribute);
    if (raw == nullptr) return fallback;
    svg::Length value;
    try {
      value = svg::parse_length(raw);
    } catch (const SyntaxError& error) {
      fail_syntax(element, attribute, error);
    }
    if (value.unit.empty()) return value.value;
    const auto scale = mm_per_unit(value.unit);
    if (!scale) {
      fail(element, attribute, "unsupported unit \"" + value.unit + "\" (use px, mm, cm, in, pt, pc, Q or none)");
    }
    return value.value * *scale / mm_per_px;
  }

  /// A length that must not be negative; nullopt when absent.
  std::optional<double> size(const tinyxml2::XMLElement& element, const char* attribute) const {
    if (element.Attribute(attribute) == nullptr) return std::nullopt;
    if (trim(element.Attribute(attribute)) == "auto") return std::nullopt;
    const double value = length(element, attribute, 0);
    if (value < 0) fail(element, attribute, "must not be negative, got " + std::string(element.Attribute(attribute)));
    return value;
  }

  /// The value of a presentation property from the style attribute or the attribute itself.
  static std::string property(const tinyxml2::XMLElement& element, const std::string& name) {
    if (const char* style = element.Attribute("style")) {
      std::string_view rest = style;
      while (!rest.empty()) {
        const auto end = rest.find(';');
        const std::string_view declaration = rest.substr(0, end);
        const auto colon = declaration.find(':');
        if (colon != std::string_view::npos && trim(declaration.substr(0, colon)) == name) {
          return trim(declaration.substr(colon + 1));
        }
        if (end == std::string_view::npos) break;
        rest.remove_prefix(end + 1);
      }
    }
    if (const char* value = element.Attribute(name.c_str())) return trim(value);
    return {};
  }

  // ---- the viewport ------------------------------------------------------------------------
  /// A root width or height in mm; nullopt when absent or relative (%).
  std::optional<double> page_size_mm(const tinyxml2::XMLElement& root, const char* attribute) const {
    const char* raw = root.Attribute(attribute);
    if (raw == nullptr || trim(raw) == "auto") return std::nullopt;
    svg::Length value;
    try {
      value = svg::parse_length(raw);
    } catch (const SyntaxError& error) {
      fail_syntax(root, attribute, error);
    }
    if (value.unit == "%") return std::nullopt;
    const auto scale = mm_per_unit(value.unit);
    if (!scale) fail(root, attribute, "unsupported unit \"" + value.unit + "\" (use px, mm, cm, in, pt, pc or Q)");
    if (!(value.value > 0)) fail(root, attribute, "the page " + std::string(attribute) + " must be positive, got " + std::string(raw));
    return value.value * *scale;
  }

  /// The map from the viewBox (or px) to a viewport of width x height (in the target units),
  /// following preserveAspectRatio.
  Affine viewbox_map(const tinyxml2::XMLElement& element, const std::vector<double>& box, double width, double height) const {
    const double sx = width / box[2];
    const double sy = height / box[3];
    std::string aspect = trim(element.Attribute("preserveAspectRatio") ? element.Attribute("preserveAspectRatio") : "");
    if (aspect.rfind("defer", 0) == 0) aspect = trim(aspect.substr(5));
    std::string align = aspect.substr(0, aspect.find(' '));
    const std::string mode = aspect.find(' ') == std::string::npos ? "meet" : trim(aspect.substr(aspect.find(' ')));
    if (align.empty()) align = "xMidYMid";
    if (align == "none") return Affine{sx, 0, 0, sy, -box[0] * sx, -box[1] * sy};
    if (align.size() != 8 || align[0] != 'x' || align[4] != 'Y' || (mode != "meet" && mode != "slice")) {
      fail(element, "preserveAspectRatio", "expected none or x(Min|Mid|Max)Y(Min|Mid|Max) [meet|slice], got \"" + aspect + "\"");
    }
    const double s = mode == "meet" ? std::min(sx, sy) : std::max(sx, sy);
    auto offset = [&](const std::string& where, double room) {
      if (where == "Min") return 0.0;
      if (where == "Mid") return room / 2;
      if (where == "Max") return room;
      fail(element, "preserveAspectRatio", "expected Min, Mid or Max in \"" + align + "\"");
    };
    const double tx = offset(align.substr(1, 3), width - box[2] * s);
    const double ty = offset(align.substr(5, 3), height - box[3] * s);
    return Affine{s, 0, 0, s, tx - box[0] * s, ty - box[1] * s};
  }

  std::optional<std::vector<double>> view_box(const tinyxml2::XMLElement& element) const {
    const char* raw = element.Attribute("viewBox");
    if (raw == nullptr) return std::nullopt;
    std::vector<double> box;
    try {
      box = svg::parse_number_list(raw);
    } catch (const SyntaxError& error) {
      fail_syntax(element, "viewBox", error);
    }
    if (box.size() != 4) fail(element, "viewBox", "expected 4 numbers (min-x min-y width height), got " + std::to_string(box.size()));
    if (!(box[2] > 0 && box[3] > 0)) fail(element, "viewBox", "width and height must be positive");
    return box;
  }

  /// User space of the root -> machine mm, y up.
  Affine root_viewport(const tinyxml2::XMLElement& root) const {
    auto width = page_size_mm(root, "width");
    auto height = page_size_mm(root, "height");
    const auto box = view_box(root);
    Affine to_mm{mm_per_px, 0, 0, mm_per_px, 0, 0};
    if (box) {
      const double aspect = (*box)[3] / (*box)[2];
      if (!width && height) width = *height / aspect;
      if (width && !height) height = *width * aspect;
      if (!width) width = (*box)[2] * mm_per_px;
      if (!height) height = (*box)[3] * mm_per_px;
      to_mm = viewbox_map(root, *box, *width, *height);
    }
    const Affine flip = height ? Affine{1, 0, 0, -1, 0, *height} : Affine{1, 0, 0, -1, 0, 0};
    return flip * with_transform(root, to_mm);
  }

  Affine with_transform(const tinyxml2::XMLElement& element, const Affine& parent) const {
    const char* raw = element.Attribute("transform");
    if (raw == nullptr) return parent;
    try {
      return parent * svg::parse_transform(raw);
    } catch (const SyntaxError& error) {
      fail_syntax(element, "transform", error);
    }
  }

  // ---- the element tree --------------------------------------------------------------------
  void visit_children(const tinyxml2::XMLElement& parent, const Affine& map) {
    for (const auto* child = parent.FirstChildElement(); child != nullptr; child = child->NextSiblingElement()) {
      visit(*child, map);
    }
  }

  void visit(const tinyxml2::XMLElement& element, const Affine& parent_map) {
    // Nested <use> fans out geometrically (a 1.3 KB file drew billions of elements): bound the total.
    if (!active_uses_.empty() && ++expanded_elements_ > max_svg_expanded_elements) {
      const tinyxml2::XMLElement& outer = *active_uses_.front();
      fail(outer, outer.Attribute("href") != nullptr ? "href" : "xlink:href",
           "<use> references expand to more than " + std::to_string(max_svg_expanded_elements) +
               " elements (the limit for SVG files)");
    }
    const std::string full_name = element.Name();
    if (full_name.find(':') != std::string::npos && full_name.rfind("svg:", 0) != 0) return;  // editor metadata
    const std::string name = local_name(element);
    static constexpr const char* not_rendered[] = {"defs", "symbol", "clipPath", "mask", "marker", "pattern", "linearGradient",
                                                   "radialGradient", "style", "title", "desc", "metadata", "script", "filter"};
    for (const char* skip : not_rendered) {
      if (name == skip) return;
    }
    if (property(element, "display") == "none") return;
    if (name == "g" || name == "a" || name == "switch") {
      visit_children(element, with_transform(element, parent_map));
      return;
    }
    if (name == "svg") {  // a nested viewport: x, y and its own viewBox
      Affine map = with_transform(element, parent_map) * Affine{1, 0, 0, 1, length(element, "x", 0), length(element, "y", 0)};
      if (const auto box = view_box(element)) {
        const auto width = size(element, "width");
        const auto height = size(element, "height");
        map = map * viewbox_map(element, *box, width.value_or((*box)[2]), height.value_or((*box)[3]));
      }
      visit_children(element, map);
      return;
    }
    const Affine map = with_transform(element, parent_map);
    std::vector<Subpath> subpaths;
    if (name == "path") {
      const char* data = element.Attribute("d");
      if (data == nullptr) return;  // no d: nothing to draw
      try {
        subpaths = svg::parse_path_data(data);
      } catch (const SyntaxError& error) {
        fail_syntax(element, "d", error);
      }
    } else if (name == "rect") {
      subpaths = rect(element);
    } else if (name == "circle" || name == "ellipse") {
      subpaths = ellipse(element, name == "circle");
    } else if (name == "line") {
      Subpath line{{length(element, "x1", 0), length(element, "y1", 0)}, {}, false};
      svg::append_line(line, {length(element, "x2", 0), length(element, "y2", 0)});
      subpaths.push_back(line);
    } else if (name == "polyline" || name == "polygon") {
      subpaths = poly(element, name == "polygon");
    } else if (name == "use") {
      use(element, map);
      return;
    } else if (name == "text" || name == "image" || name == "foreignObject") {
      warn(element, name == "text" ? "is not drawn (convert text to paths first)" : "is not drawn");
      return;
    } else {
      warn(element, "is not drawn (unknown element)");
      return;
    }
    add(element, name == "path" ? "d" : "", map, subpaths);
  }

  void index_ids(const tinyxml2::XMLElement& element) {
    if (const char* id = element.Attribute("id")) ids_.emplace(id, &element);
    for (const auto* child = element.FirstChildElement(); child != nullptr; child = child->NextSiblingElement()) index_ids(*child);
  }

  /// <use>: the referenced element (or a symbol's children) drawn at x, y under the use's transform.
  void use(const tinyxml2::XMLElement& element, const Affine& map) {
    const char* attribute = element.Attribute("href") != nullptr ? "href" : "xlink:href";
    const char* raw = element.Attribute(attribute);
    if (raw == nullptr) return;  // nothing referenced: nothing drawn
    const std::string reference = trim(raw);
    if (reference.empty() || reference.front() != '#') {
      fail(element, attribute,
           "only references into the same file (\"#id\") are supported, got \"" + quoted_excerpt(reference) + "\"");
    }
    const auto found = ids_.find(reference.substr(1));
    if (found == ids_.end()) fail(element, attribute, "no element has id \"" + quoted_excerpt(reference.substr(1)) + "\"");
    const tinyxml2::XMLElement& target = *found->second;
    if (std::find(active_uses_.begin(), active_uses_.end(), &element) != active_uses_.end() || active_uses_.size() > 64) {
      fail(element, attribute, "the reference \"" + quoted_excerpt(reference) + "\" refers back to itself");
    }
    active_uses_.push_back(&element);
    const Affine placed = map * Affine{1, 0, 0, 1, length(element, "x", 0), length(element, "y", 0)};
    if (local_name(target) == "symbol") {
      Affine inner = with_transform(target, placed);
      if (const auto box = view_box(target)) {
        const auto width = size(element, "width");
        const auto height = size(element, "height");
        inner = inner * viewbox_map(target, *box, width.value_or((*box)[2]), height.value_or((*box)[3]));
      }
      visit_children(target, inner);
    } else {
      visit(target, placed);
    }
    active_uses_.pop_back();
  }

  std::vector<Subpath> rect(const tinyxml2::XMLElement& element) const {
    const double x = length(element, "x", 0);
    const double y = length(element, "y", 0);
    const double w = size(element, "width").value_or(0);
    const double h = size(element, "height").value_or(0);
    if (w == 0 || h == 0) return {};  // not rendered
    auto rx = size(element, "rx");
    auto ry = size(element, "ry");
    if (!rx) rx = ry;
    if (!ry) ry = rx;
    const double r_x = std::min(rx.value_or(0), w / 2);
    const double r_y = std::min(ry.value_or(0), h / 2);
    Subpath outline;
    if (r_x == 0 || r_y == 0) {
      outline.start = {x, y};
      svg::append_line(outline, {x + w, y});
      svg::append_line(outline, {x + w, y + h});
      svg::append_line(outline, {x, y + h});
      svg::append_line(outline, {x, y});
    } else {
      outline.start = {x + r_x, y};
      svg::append_line(outline, {x + w - r_x, y});
      svg::append_quarter(outline, {x + w - r_x, y + r_y}, {0, -r_y}, {r_x, 0});
      svg::append_line(outline, {x + w, y + h - r_y});
      svg::append_quarter(outline, {x + w - r_x, y + h - r_y}, {r_x, 0}, {0, r_y});
      svg::append_line(outline, {x + r_x, y + h});
      svg::append_quarter(outline, {x + r_x, y + h - r_y}, {0, r_y}, {-r_x, 0});
      svg::append_line(outline, {x, y + r_y});
      svg::append_quarter(outline, {x + r_x, y + r_y}, {-r_x, 0}, {0, -r_y});
    }
    outline.closed = true;
    return {outline};
  }

  std::vector<Subpath> ellipse(const tinyxml2::XMLElement& element, bool circle) const {
    const double cx = length(element, "cx", 0);
    const double cy = length(element, "cy", 0);
    double rx = 0;
    double ry = 0;
    if (circle) {
      rx = ry = size(element, "r").value_or(0);
    } else {
      auto a = size(element, "rx");
      auto b = size(element, "ry");
      if (!a) a = b;
      if (!b) b = a;
      rx = a.value_or(0);
      ry = b.value_or(0);
    }
    if (rx == 0 || ry == 0) return {};  // not rendered
    // Starts at (cx + rx, cy) and runs through (cx, cy + ry): positive angles in user space.
    Subpath outline{{cx + rx, cy}, {}, true};
    const Point2 c{cx, cy};
    svg::append_quarter(outline, c, {rx, 0}, {0, ry});
    svg::append_quarter(outline, c, {0, ry}, {-rx, 0});
    svg::append_quarter(outline, c, {-rx, 0}, {0, -ry});
    svg::append_quarter(outline, c, {0, -ry}, {rx, 0});
    return {outline};
  }

  std::vector<Subpath> poly(const tinyxml2::XMLElement& element, bool closed) const {
    const char* raw = element.Attribute("points");
    if (raw == nullptr) return {};
    std::vector<double> numbers;
    try {
      numbers = svg::parse_number_list(raw);
    } catch (const SyntaxError& error) {
      fail_syntax(element, "points", error);
    }
    if (numbers.size() % 2 != 0) {
      fail(element, "points", "expected pairs of coordinates, got an odd count (" + std::to_string(numbers.size()) + " numbers)");
    }
    if (numbers.empty()) return {};
    Subpath outline{{numbers[0], numbers[1]}, {}, closed};
    for (std::size_t i = 2; i < numbers.size(); i += 2) svg::append_line(outline, {numbers[i], numbers[i + 1]});
    if (closed) svg::append_line(outline, outline.start);
    return {outline};
  }

  // ---- machine space -----------------------------------------------------------------------
  MachinePoint machine_point(const tinyxml2::XMLElement& element, const Affine& map, Point2 user) const {
    const Point2 mm = map.apply(user);
    MachinePoint p{};
    const double values[2] = {mm.x, mm.y};
    for (std::size_t axis = 0; axis < 2; ++axis) {
      const auto q = Q16_16::from_double(values[axis]);
      if (!std::isfinite(values[axis])) {
        fail(element, "",
             "the point (" + format_number(user.x) + ", " + format_number(user.y) +
                 ") in user units has no finite image (an arc or a transform too large for double precision)",
             Error::NotFinite);
      }
      if (!q) {
        fail(element, "",
             "the point (" + format_number(user.x) + ", " + format_number(user.y) + ") in user units lands at (" +
                 format_number(mm.x) + ", " + format_number(mm.y) + ") mm, outside the Q16.16 range (-32768 to 32768 mm)",
             Error::FixedOverflow);
      }
      p[axis] = q.value().to_double();
    }
    return p;
  }

  /// A conic's middle weight on the Q16.16 grid, as the wire carries it; the job loader's errors
  /// for a weight out of range or rounding to 0, at the element (and the path command) of the piece.
  double wire_weight(const tinyxml2::XMLElement& element, const char* attribute, const Piece& piece) const {
    const double weight = piece.weight;
    std::string cause;
    Error code = Error::NonPositiveWeight;
    if (!(weight > 0) || !std::isfinite(weight)) {
      cause = "weight " + format_number(weight) + " is not a finite positive number";
      if (!std::isfinite(weight)) code = Error::NotFinite;
    } else {
      auto rounded = round_for_wire(weight, WireQuantity::Weight);
      if (rounded) return rounded.value;
      cause = std::move(rounded.problem);
      code = rounded.code;
    }
    const Point2 from = piece.points[0];
    const Point2 to = piece.points[piece.count - 1];
    const std::string where = piece.position > 0 ? "at character " + std::to_string(piece.position) + ": " : "";
    fail(element, attribute,
         where + "the arc from (" + format_number(from.x) + ", " + format_number(from.y) + ") to (" + format_number(to.x) + ", " +
             format_number(to.y) + ") in user units: " + cause,
         code);
  }

  void add(const tinyxml2::XMLElement& element, const char* attribute, const Affine& map, const std::vector<Subpath>& subpaths) {
    for (const auto& subpath : subpaths) {
      DrawnSubpath drawn;
      drawn.line = static_cast<std::size_t>(element.GetLineNum());
      for (const auto& piece : subpath.pieces) {
        MachinePiece out;
        for (std::size_t i = 0; i < piece.count; ++i) out.points.push_back(machine_point(element, map, piece.points[i]));
        if (std::all_of(out.points.begin(), out.points.end(), [&](const MachinePoint& p) { return p == out.points.front(); })) {
          continue;  // vanished on the Q16.16 grid
        }
        switch (piece.kind) {
          case PieceKind::Line: out.type = SegmentType::Line; break;
          case PieceKind::Quadratic:
          case PieceKind::Cubic: out.type = SegmentType::Bezier; break;
          case PieceKind::Conic:
            out.type = SegmentType::RationalBezier;
            out.weights = {1.0, wire_weight(element, attribute, piece), 1.0};
            break;
        }
        drawn.pieces.push_back(std::move(out));
      }
      if (!drawn.pieces.empty()) drawn_.push_back(std::move(drawn));
    }
  }

  // ---- the job -----------------------------------------------------------------------------
  static double travel(const MachinePoint& from, const std::vector<DrawnSubpath>& order) {
    double total = 0;
    MachinePoint at = from;
    for (const auto& subpath : order) {
      total += distance(at, subpath.start());
      at = subpath.end();
    }
    return total;
  }

  /// Greedy nearest neighbour: always draw next the subpath whose start (or, for an open one,
  /// end) is nearest; ties keep document order.
  std::size_t optimise(const MachinePoint& from) {
    std::vector<DrawnSubpath> ordered;
    std::vector<bool> used(drawn_.size(), false);
    MachinePoint at = from;
    std::size_t reversed = 0;
    for (std::size_t n = 0; n < drawn_.size(); ++n) {
      std::size_t best = 0;
      bool best_reversed = false;
      double best_distance = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < drawn_.size(); ++i) {
        if (used[i]) continue;
        const double forward = distance(at, drawn_[i].start());
        if (forward < best_distance) {
          best = i;
          best_distance = forward;
          best_reversed = false;
        }
        if (!drawn_[i].closed()) {
          const double backward = distance(at, drawn_[i].end());
          if (backward < best_distance) {
            best = i;
            best_distance = backward;
            best_reversed = true;
          }
        }
      }
      used[best] = true;
      ordered.push_back(drawn_[best]);
      if (best_reversed) {
        ordered.back().reverse();
        ++reversed;
      }
      at = ordered.back().end();
    }
    drawn_ = std::move(ordered);
    return reversed;
  }

  void push(Job& job, SourceSegment source, PathSegment segment) {
    source.first_piece = job.segments.size();
    source.breaks = {0.0, 1.0};
    job.source_index.push_back(job.sources.size());
    job.segments.push_back(segment);
    job.sources.push_back(std::move(source));
  }

  /// The feed option on the Q16.16 grid (0: the machine default), with the job loader's errors.
  double wire_feed() const {
    const double feed = options_.feed_mm_per_s;
    if (feed == 0) return 0;
    const SourceLocation location{name_, 0, 0, std::nullopt, "", "feed"};
    if (!(feed > 0) || !std::isfinite(feed)) {
      throw LoadError(location, "feed " + format_number(feed) + " must be a finite number > 0 (or 0 for the machine default)",
                      Error::InvalidArgument);
    }
    const auto rounded = round_for_wire(feed, WireQuantity::Feed);
    if (!rounded) throw LoadError(location, rounded.problem, rounded.code);
    return rounded.value;
  }

  SvgImport build() {
    SvgImport result;
    MachinePoint start{};
    for (std::size_t axis = 0; axis < motion_axes; ++axis) {
      const auto q = Q16_16::from_double(options_.start[axis]);
      if (!q) throw LoadError(SourceLocation{name_, 0, 0, std::nullopt, "", "start"}, "the start point is outside the Q16.16 range", Error::FixedOverflow);
      start[axis] = q.value().to_double();
    }
    const double feed = wire_feed();
    result.travel_document_mm = travel(start, drawn_);
    if (options_.optimize) result.reversed_count = optimise(start);
    result.travel_mm = travel(start, drawn_);
    result.subpath_count = drawn_.size();
    result.warnings = std::move(warnings_);

    Job& job = result.job;
    job.version = 1;
    job.name = name_;
    MachinePoint at = start;
    for (const auto& subpath : drawn_) {
      if (!(subpath.start() == at)) {
        auto move = PathSegment::make_line(at, subpath.start());
        move.value().set_rapid(true);
        SourceSegment source;
        source.type = SegmentType::Rapid;
        source.line = subpath.line;
        source.points = {at, subpath.start()};
        source.degree = 1;
        push(job, std::move(source), move.value());
      }
      for (const auto& piece : subpath.pieces) {
        Result<PathSegment> made = piece.type == SegmentType::Line ? PathSegment::make_line(piece.points[0], piece.points[1])
                                   : piece.type == SegmentType::Bezier ? PathSegment::make_bezier(piece.points)
                                                                       : PathSegment::make_rational_bezier(piece.points, piece.weights);
        if (!made) {
          fail_at(subpath.line, "", "a piece of this element cannot be used: " + std::string(describe(made.error())), made.error());
        }
        made.value().set_feed_mm_per_s(feed);
        SourceSegment source;
        source.type = piece.type;
        source.line = subpath.line;
        source.points = piece.points;
        source.weights = piece.weights;
        source.degree = piece.points.size() - 1;
        source.feed_mm_per_s = feed;
        push(job, std::move(source), made.value());
      }
      at = subpath.end();
    }
    return result;
  }

  std::string_view text_;
  std::string name_;
  SvgOptions options_;
  tinyxml2::XMLDocument document_;
  std::vector<DrawnSubpath> drawn_;
  std::vector<std::string> warnings_;
  std::map<std::string, const tinyxml2::XMLElement*> ids_;
  std::vector<const tinyxml2::XMLElement*> active_uses_;
  std::size_t expanded_elements_ = 0;  ///< elements visited through <use>, all uses together
};

}  // namespace

SvgImport parse_svg(std::string_view text, std::string name, const SvgOptions& options) {
  return SvgReader(text, std::move(name), options).read();
}

SvgImport load_svg(const std::filesystem::path& path, const SvgOptions& options) {
  return parse_svg(read_text_file(path), path.string(), options);
}

Job import_svg(const std::filesystem::path& path, const SvgOptions& options) { return load_svg(path, options).job; }

Job parse_svg_job(std::string_view text, std::string name, const SvgOptions& options) {
  return parse_svg(text, std::move(name), options).job;
}

}  // namespace curvestep::host
