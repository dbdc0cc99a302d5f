// SPDX-License-Identifier: MIT
// <text> and <tspan> laid out in the Hershey font (svg_text.hpp).
#include "svg_text.hpp"

#include <algorithm>
#include <cstdio>
#include <string_view>

#include "../svg_attributes.hpp"
#include "hershey_font.hpp"

namespace curvestep::host::svg {
namespace {

/// The code points of UTF-8 text (a malformed byte is U+FFFD).
std::u32string decode_utf8(std::string_view text) {
  std::u32string out;
  for (std::size_t i = 0; i < text.size();) {
    const auto lead = static_cast<unsigned char>(text[i]);
    const std::size_t length = lead < 0x80 ? 1 : (lead >> 5) == 0x6 ? 2 : (lead >> 4) == 0xE ? 3 : (lead >> 3) == 0x1E ? 4 : 0;
    char32_t code = length == 1 ? lead : length == 2 ? lead & 0x1F : length == 3 ? lead & 0x0F : lead & 0x07;
    bool valid = length != 0 && i + length <= text.size();
    for (std::size_t k = 1; valid && k < length; ++k) {
      const auto next = static_cast<unsigned char>(text[i + k]);
      valid = (next & 0xC0) == 0x80;
      code = (code << 6) | (next & 0x3F);
    }
    out.push_back(valid ? code : U'\uFFFD');
    i += valid ? length : 1;
  }
  return out;
}

/// A code point as UTF-8.
std::string encode_utf8(char32_t code) {
  std::string out;
  if (code < 0x80) {
    out += static_cast<char>(code);
  } else if (code < 0x800) {
    out += static_cast<char>(0xC0 | (code >> 6));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else if (code < 0x10000) {
    out += static_cast<char>(0xE0 | (code >> 12));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (code >> 18));
    out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  }
  return out;
}

/// "U+00E9".
std::string code_point_name(char32_t code) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "U+%04X", static_cast<unsigned>(code));
  return buffer;
}

}  // namespace

std::optional<double> TextLayout::first_length(const tinyxml2::XMLElement& element, const char* attribute,
                                               const LengthContext& lengths, LengthAxis axis) const {
  const char* raw = element.Attribute(attribute);
  if (raw == nullptr) return std::nullopt;
  const std::string list = trim(raw);
  const std::string first = list.substr(0, list.find_first_of(" \t\r\n,"));
  if (first.empty()) return std::nullopt;
  return length_value(diagnostics_, element, attribute, first, lengths, axis);
}

std::vector<Subpath> TextLayout::strokes(const tinyxml2::XMLElement& text, const LengthContext& lengths, bool visible) {
  if (!family_noted_) {
    // font-family is inherited: the text's own, else the nearest ancestor's (Batik sets it on the root).
    for (const tinyxml2::XMLNode* node = &text; node != nullptr && node->ToElement() != nullptr; node = node->Parent()) {
      const std::string family = styles_.property(*node->ToElement(), "font-family");
      if (family.empty() || family == "inherit") continue;
      family_noted_ = true;
      diagnostics_.warn(text, "font-family " + family + " is not used: text is drawn in the " + roman_simplex_name +
                                  " single-stroke font (noted once per file)");
      break;
    }
  }
  out_.clear();
  pen_ = {};
  any_character_ = false;
  pending_space_ = false;
  Style style;
  style.lengths = lengths;
  style.visible = visible;
  // text-anchor is inherited: the nearest ancestor that sets it (through <use>: the referenced element's).
  for (const auto* node = text.Parent(); node != nullptr && node->ToElement() != nullptr; node = node->Parent()) {
    if (const std::string anchor = styles_.property(*node->ToElement(), "text-anchor"); !anchor.empty() && anchor != "inherit") {
      style.anchor = anchor;
      break;
    }
  }
  chunk_begin_ = 0;
  chunk_x_ = 0;
  chunk_anchor_ = "start";
  element(text, style);
  finish_chunk();
  return std::move(out_);
}

void TextLayout::element(const tinyxml2::XMLElement& element, const Style& inherited) {
  Style style = inherited;  // its font-size computed by the caller
  if (const std::string anchor = styles_.property(element, "text-anchor"); !anchor.empty() && anchor != "inherit") {
    style.anchor = anchor;
  }
  if (const std::string visibility = styles_.property(element, "visibility"); !visibility.empty() && visibility != "inherit") {
    style.visible = visibility == "visible";
  }
  if (const char* space = element.Attribute("xml:space")) style.preserve = std::string_view(space) == "preserve";
  const auto x = first_length(element, "x", style.lengths, LengthAxis::X);
  const auto y = first_length(element, "y", style.lengths, LengthAxis::Y);
  if (x || y) {
    finish_chunk();
    pen_ = {x.value_or(pen_.x), y.value_or(pen_.y)};
    start_chunk(style.anchor);
  } else if (out_.empty() && !any_character_) {
    chunk_anchor_ = style.anchor;  // the chunk starting at the text's origin
  }
  pen_.x += first_length(element, "dx", style.lengths, LengthAxis::X).value_or(0);
  pen_.y += first_length(element, "dy", style.lengths, LengthAxis::Y).value_or(0);
  for (const auto* node = element.FirstChild(); node != nullptr; node = node->NextSibling()) {
    if (const auto* text = node->ToText()) {
      characters(element, text->Value(), style);
      continue;
    }
    const auto* child = node->ToElement();
    if (child == nullptr) continue;
    const std::string name = local_name(*child);
    if (name == "title" || name == "desc" || name == "metadata") continue;
    if (name != "tspan" && name != "a") {
      diagnostics_.warn(*child, "is not drawn (inside <text> only <tspan> and <a> are read)");
      continue;
    }
    if (styles_.property(*child, "display") == "none") continue;
    Style inner = style;
    inner.lengths.font_size =
        font_size(diagnostics_, *child, styles_.property(*child, "font-size"), style.lengths.font_size, style.lengths);
    this->element(*child, inner);
  }
}

void TextLayout::characters(const tinyxml2::XMLElement& owner, const char* text, const Style& style) {
  for (const char32_t raw : decode_utf8(text)) {
    if (raw == U'\n' || raw == U'\r') {
      if (!style.preserve) continue;
    }
    const bool space = raw == U' ' || raw == U'\t' || raw == U'\n' || raw == U'\r';
    if (space && !style.preserve) {
      if (any_character_ && !pending_space_) {
        pending_space_ = true;
        pending_owner_ = &owner;
        pending_style_ = style;
      }
      continue;
    }
    if (pending_space_) {
      pending_space_ = false;
      glyph(*pending_owner_, U' ', pending_style_);
    }
    glyph(owner, space ? U' ' : raw, style);
  }
}

void TextLayout::glyph(const tinyxml2::XMLElement& owner, char32_t code, const Style& style) {
  any_character_ = true;
  const double scale = style.lengths.font_size / hershey_units_per_em;
  const HersheyGlyph* found = roman_simplex_glyph(code);
  if (found == nullptr) {
    const auto seen = std::find_if(missing_.begin(), missing_.end(), [code](const auto& entry) { return entry.first == code; });
    if (seen == missing_.end()) {
      missing_.emplace_back(code, 1);
    } else {
      ++seen->second;
    }
    if (first_missing_owner_ == nullptr) {
      first_missing_owner_ = &owner;
      missing_place_ = diagnostics_.reserve_warning();  // the summary comes where the first is met
    }
    missing_owners_.insert(&owner);
    found = roman_simplex_glyph(U' ');
  } else if (style.visible) {
    for (const auto& stroke : found->strokes) {
      if (stroke.size() < 2) continue;
      const auto place = [&](Point2 p) {
        return Point2{pen_.x + (p.x - found->left) * scale, pen_.y + (p.y - hershey_baseline) * scale};
      };
      Subpath subpath{place(stroke.front()), {}, false};
      for (std::size_t i = 1; i < stroke.size(); ++i) append_line(subpath, place(stroke[i]));
      if (!subpath.pieces.empty()) out_.push_back(std::move(subpath));
    }
  }
  pen_.x += found->advance() * scale;
}

void TextLayout::missing_glyphs_note() {
  if (first_missing_owner_ == nullptr) return;
  constexpr std::size_t listed = 8;
  std::size_t total = 0;
  std::string list;
  for (std::size_t i = 0; i < missing_.size(); ++i) {
    const auto& [code, count] = missing_[i];
    total += count;
    if (i >= listed) continue;
    list += (i == 0 ? "" : ", ") + ("\"" + encode_utf8(code) + "\" (" + code_point_name(code) + ")") +
            (count > 1 ? " x" + std::to_string(count) : "");
  }
  if (missing_.size() > listed) list += " and " + std::to_string(missing_.size() - listed) + " other distinct characters";
  const bool one = total == 1;
  std::string message = "has " + std::string(one ? "the character " : "characters ") + list + ", which the " + roman_simplex_name +
                        " font has no glyph for: " + (one ? "drawn as a gap" : "each drawn as a gap") + " the width of a space";
  if (missing_owners_.size() > 1) {
    message += " (" + std::to_string(total) + " characters in " + std::to_string(missing_owners_.size()) + " elements, the first here)";
  }
  diagnostics_.warn_in(missing_place_, *first_missing_owner_, message);
}

void TextLayout::start_chunk(const std::string& anchor) {
  chunk_begin_ = out_.size();
  chunk_x_ = pen_.x;
  chunk_anchor_ = anchor;
}

void TextLayout::finish_chunk() {
  pending_space_ = false;  // trailing white space is removed
  const double advance = pen_.x - chunk_x_;
  const double shift = chunk_anchor_ == "end" ? -advance : chunk_anchor_ == "middle" ? -advance / 2 : 0;
  if (shift == 0) return;
  for (std::size_t i = chunk_begin_; i < out_.size(); ++i) {
    Subpath& subpath = out_[i];
    subpath.start.x += shift;
    for (Piece& piece : subpath.pieces) {
      for (std::size_t k = 0; k < piece.count; ++k) piece.points[k].x += shift;
    }
  }
}

}  // namespace curvestep::host::svg
