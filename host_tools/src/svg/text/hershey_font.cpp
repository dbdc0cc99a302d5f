// SPDX-License-Identifier: MIT
// The Hershey Roman simplex font decoded from its James Hurt encoding (hershey_font.hpp).
#include "hershey_font.hpp"

#include <array>
#include <cstddef>
#include <string_view>

namespace curvestep::host::svg {
namespace {

constexpr char32_t first_code = 32;
constexpr std::string_view encoded_glyphs[] = {
#include "hershey_roman_simplex.inc"
};
constexpr std::size_t glyph_count = std::size(encoded_glyphs);

/// A coordinate character's value: character - 'R'.
double value(char c) { return static_cast<double>(c - 'R'); }

/// "HYLFL[ RL[X[" -> bearings -10, 7 and the strokes (-6,-12)-(-6,9), (-6,9)-(6,9).
HersheyGlyph decode(std::string_view encoded) {
  HersheyGlyph glyph;
  glyph.left = value(encoded[0]);
  glyph.right = value(encoded[1]);
  bool pen_up = true;
  for (std::size_t i = 2; i + 1 < encoded.size(); i += 2) {
    if (encoded[i] == ' ' && encoded[i + 1] == 'R') {
      pen_up = true;
      continue;
    }
    if (pen_up) glyph.strokes.emplace_back();
    pen_up = false;
    glyph.strokes.back().push_back({value(encoded[i]), value(encoded[i + 1])});
  }
  return glyph;
}

const std::array<HersheyGlyph, glyph_count>& decoded_glyphs() {
  static const std::array<HersheyGlyph, glyph_count> glyphs = [] {
    std::array<HersheyGlyph, glyph_count> out;
    for (std::size_t i = 0; i < glyph_count; ++i) out[i] = decode(encoded_glyphs[i]);
    return out;
  }();
  return glyphs;
}

}  // namespace

const HersheyGlyph* roman_simplex_glyph(char32_t code) {
  if (code < first_code || code - first_code >= glyph_count) return nullptr;
  return &decoded_glyphs()[code - first_code];
}

}  // namespace curvestep::host::svg
