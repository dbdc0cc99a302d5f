// SPDX-License-Identifier: MIT
// Internal: <text> and its <tspan>s laid out in the single-stroke Hershey font (hershey_font.hpp) as
// polylines in the text element's user space; the walk maps them like any other shape.
//
// Layout (left to right, one line per text chunk):
// * a glyph's point (hx, hy) lands at (pen.x + (hx - left)·s, pen.y + (hy - 9)·s) with s = font-size / 32
//   (pen.y is the baseline); the pen then advances by (right - left)·s;
// * `x`, `y` (first value of the list) set the pen and start a new text chunk; `dx`, `dy` (first value)
//   move it; every tspan may have its own, and its own font-size (inherited, with units);
// * `text-anchor` (inherited; the value where the chunk starts): `middle` shifts the chunk by half its
//   advance to the left, `end` by all of it;
// * white space as SVG's default: newlines dropped, tabs as spaces, runs of spaces collapsed, leading
//   and trailing ones removed; `xml:space="preserve"` keeps every space (newlines and tabs as spaces);
// * a character the font lacks is drawn as nothing and advances like a space; one warning per file
//   (missing_glyphs_note) names the first element with one and counts each character.
// font-family, font-weight, letter-spacing and the rest are not read (the first font-family gets one note).
#pragma once

#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <tinyxml2.h>

#include "../svg_css.hpp"
#include "../svg_diagnostics.hpp"
#include "../svg_geometry.hpp"
#include "../svg_lengths.hpp"

namespace curvestep::host::svg {

/// Lays out the text elements of one document.
class TextLayout {
 public:
  TextLayout(Diagnostics& diagnostics, const StyleSheet& styles) : diagnostics_(diagnostics), styles_(styles) {}

  /// The strokes of `text` (a <text> element whose computed font-size is in `lengths` and whose
  /// computed visibility is `visible`) in its user space.
  [[nodiscard]] std::vector<Subpath> strokes(const tinyxml2::XMLElement& text, const LengthContext& lengths, bool visible);

  /// After the last text: one warning for every character the font lacks, at the first element
  /// that had one (a text in many scripts gave hundreds of lines before).
  void missing_glyphs_note();

 private:
  /// What a text-content element passes to its children.
  struct Style {
    LengthContext lengths;       ///< font_size: the element's computed font-size
    std::string anchor = "start";
    bool visible = true;
    bool preserve = false;       ///< xml:space="preserve"
  };
  void element(const tinyxml2::XMLElement& element, const Style& style);
  void characters(const tinyxml2::XMLElement& owner, const char* text, const Style& style);
  void glyph(const tinyxml2::XMLElement& owner, char32_t code, const Style& style);
  /// Starts a text chunk at the pen (after shifting the one before by its anchor).
  void start_chunk(const std::string& anchor);
  void finish_chunk();
  /// The first value of a length list attribute, if present.
  [[nodiscard]] std::optional<double> first_length(const tinyxml2::XMLElement& element, const char* attribute,
                                                   const LengthContext& lengths, LengthAxis axis) const;

  Diagnostics& diagnostics_;
  const StyleSheet& styles_;
  bool family_noted_ = false;
  /// Characters the font lacks, in the order first met, and how often each was met.
  std::vector<std::pair<char32_t, std::size_t>> missing_;
  std::set<const tinyxml2::XMLElement*> missing_owners_;
  const tinyxml2::XMLElement* first_missing_owner_ = nullptr;
  std::size_t missing_place_ = 0;  ///< the warning's place (Diagnostics::reserve_warning)
  // The text being laid out:
  std::vector<Subpath> out_;
  Point2 pen_;
  std::size_t chunk_begin_ = 0;  ///< first subpath of the current chunk
  double chunk_x_ = 0;           ///< pen x where the chunk started
  std::string chunk_anchor_;
  bool any_character_ = false;   ///< a character was placed (for collapsing leading spaces)
  bool pending_space_ = false;   ///< a collapsed space waiting for a following character
  const tinyxml2::XMLElement* pending_owner_ = nullptr;
  Style pending_style_;
};

}  // namespace curvestep::host::svg
